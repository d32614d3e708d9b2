//! The spatial stage: what the page's 3-D view draws of an arm in space
//! ([`SceneView`], numbers read from the core for the three.js renderer in
//! `www/view/`, which computes no position of its own), and the 2-D overlay
//! on the canvas above it: the target's handle and the reference point,
//! the keyboard's ring, an axis cross and the caption. The overlay and the
//! 3-D camera share the session's one [`Projection`] (the renderer's
//! camera is built from [`SceneView::camera`]), so what the pointer picks
//! is where it is drawn. A slice atlas's map lies on its plane
//! ([`SliceLayer`], [`LayerView`]).

use serde::Serialize;
use web_sys::CanvasRenderingContext2d;

use super::style::{DANGER, FONT, FORCE_SCALE, INK, MAX_FORCE, MUTED, TEAL, VELOCITY_SCALE};
use super::surface::{dash, disc, text, Surface};
use crate::atlas::space::Plane;
use crate::atlas::{Class, Grid};
use crate::error::Result;
use crate::session::space::{Projection, SelfNear, SpaceHandle, SpaceSession, NEAR};
use crate::space::manipulability::velocity_ellipsoid;
use crate::space::rotation::Mat3;
use crate::space::Vec3;

/// Half the floor grid's side (m) and its spacing.
const FLOOR_HALF: f64 = 1.0;
const FLOOR_STEP: f64 = 0.1;
/// The chords of a circle path's outline per lap.
const OUTLINE_CHORDS: usize = 96;

/// A slice atlas shown on its plane: the grid of sphere centres on it and
/// one class per cell (rows from the plane's `v0`, each from `u0`; the
/// order of `atlasClasses()`).
pub struct SliceLayer {
    plane: Plane,
    grid: Grid,
    classes: Vec<u8>,
}

impl SliceLayer {
    /// A checked layer: the grid valid, one known class per cell.
    pub fn new(plane: Plane, grid: Grid, classes: Vec<u8>) -> Result<Self> {
        Class::check_map(&grid, &classes, "slice atlas classes")?;
        Ok(Self {
            plane,
            grid,
            classes,
        })
    }

    /// The cell under canvas pixel `(x, y)`: the pointer's ray met with
    /// the plane, then the grid's nearest point, if any lies within half a
    /// cell.
    pub fn cell_at(&self, proj: &Projection, x: f64, y: f64) -> Option<usize> {
        let (eye, dir) = proj.ray(x, y);
        let (u, v) = self.plane.coordinates(self.plane.hit(eye, dir)?);
        self.grid.nearest([u, v])
    }

    /// The centre of cell `k` in the world, if there is such a cell.
    pub fn cell_point(&self, k: usize) -> Option<Vec3> {
        (k < self.grid.cells()).then(|| {
            let [u, v] = self.grid.point(k);
            self.plane.point(u, v)
        })
    }

    /// The cells as the 3-D view draws them: four corners a cell (`x, y,
    /// z` each, counter-clockwise on the plane) and its class's colour.
    pub fn view(&self) -> LayerView {
        let g = &self.grid;
        let [u0, u1, v0, v1] = g.region;
        let (du, dv) = ((u1 - u0) / (g.n - 1) as f64, (v1 - v0) / (g.n - 1) as f64);
        let mut corners = Vec::with_capacity(g.cells() * 12);
        let mut colours = Vec::with_capacity(g.cells());
        for j in 0..g.n {
            for i in 0..g.n {
                let class = Class::ALL[usize::from(self.classes[j * g.n + i])];
                let (u, v) = (g.x(i), g.y(j));
                for (a, b) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)] {
                    corners.extend(self.plane.point(u + a * du, v + b * dv));
                }
                colours.push(class.colour());
            }
        }
        LayerView { corners, colours }
    }
}

/// A slice atlas as the 3-D view draws it ([`SliceLayer::view`]).
#[derive(Debug, Serialize)]
pub struct LayerView {
    /// Four corners a cell, `x, y, z` each (m), rows from the plane's `v0`.
    pub corners: Vec<f64>,
    /// One colour a cell, its class's.
    pub colours: Vec<&'static str>,
}

/// The legend's switches of the drawing in space: the velocity and the
/// force ellipsoid at the hand (the plane's `ellipse` and `force`).
#[derive(Debug, Clone, Copy, Default)]
pub struct Shown {
    /// The velocity ellipsoid `{J theta_dot : |theta_dot| <= 1}`.
    pub velocity: bool,
    /// The force ellipsoid `{f : |J^T f| <= 1}`.
    pub force: bool,
}

/// The camera the 3-D view draws with: at `eye`, looking at `focus`, `z`
/// up, `fov` its vertical field of view (rad) on the canvas it was made
/// for, `near` the nearest depth drawn (m).
#[derive(Debug, Serialize)]
pub struct CameraView {
    pub eye: Vec3,
    pub focus: Vec3,
    pub fov: f64,
    pub near: f64,
}

/// An ellipsoid at the hand: its principal axes (unit vectors, rows) and
/// half-lengths (m, at the drawing's scale).
#[derive(Debug, Serialize)]
pub struct EllipsoidView {
    pub axes: [Vec3; 3],
    pub half: [f64; 3],
}

/// Everything the 3-D view draws of a session at the time shown, read
/// from the core: points are `[x, y, z]` (m), in the world's frame.
#[derive(Debug, Serialize)]
pub struct SceneView {
    pub camera: CameraView,
    /// The links' capsules' radius (m).
    pub radius: f64,
    /// The base, on the floor under the first joint.
    pub base: Vec3,
    /// Each link's segment, its two ends.
    pub links: Vec<[Vec3; 2]>,
    /// The joints' and the hand's points.
    pub joints: Vec<Vec3>,
    /// Each joint's frame in the world (from joint 1): its axes `x, y, z`
    /// as columns, then its origin (12 numbers); a robot's visuals are
    /// placed on them.
    pub frames: Vec<[f64; 12]>,
    /// The spheres, `[x, y, z, r]`.
    pub spheres: Vec<[f64; 4]>,
    /// Whether a link is inside a sphere now.
    pub collision: bool,
    /// The path's outline from the hand's start.
    pub path: Vec<Vec3>,
    /// Where the hand has been, up to the time shown.
    pub trail: Vec<Vec3>,
    /// The numerical ghost's points, when a learned method runs.
    pub ghost: Option<Vec<Vec3>>,
    /// The hand now.
    pub hand: Vec3,
    /// The velocity ellipsoid at the hand (half-lengths `sigma_i` at 1/4
    /// scale), when switched on.
    pub velocity: Option<EllipsoidView>,
    /// The force ellipsoid (`1 / sigma_i` at 1/10 scale, at most 0.6 m),
    /// when switched on.
    pub force: Option<EllipsoidView>,
    /// The target: the end of the hand's line.
    pub target: Vec3,
    /// The target's orientation (a rotation matrix by rows) where the
    /// task is the hand's pose: the view draws its frame and the gizmo
    /// turns it.
    pub target_rotation: Option<Mat3>,
    /// The hand's orientation now (by rows): its frame is drawn for the
    /// pose task.
    pub hand_rotation: Mat3,
    /// The checked pairs of capsules within `self_influence` of each
    /// other: the segment between their closest points and the distance.
    pub self_near: Vec<SelfNear>,
    /// Half the floor grid's side and its spacing (m).
    pub floor: [f64; 2],
    /// What the keys move (the gizmo's item): `target` or `sphere 2`.
    pub selected: String,
    /// Counts the slice atlas layers shown (0: none yet); the view asks
    /// for [`LayerView`] when it changes.
    pub layer: u32,
}

/// What the 3-D view draws of `s`; `layer` is the revision of the slice
/// atlas shown (0 none), `shown` the ellipsoids switched on.
pub fn view(s: &SpaceSession, width: f64, height: f64, layer: u32, shown: Shown) -> SceneView {
    let proj = s.projection(width, height);
    let scene = s.scene();
    let chain = &scene.arm;
    let pose = s.pose();
    let base = chain.base().1;
    let ellipsoid = (shown.velocity || shown.force).then(|| velocity_ellipsoid(pose.jjt()));
    let scaled = |on: bool, f: &dyn Fn(f64) -> f64| {
        ellipsoid.filter(|_| on).map(|(axes, sigma)| EllipsoidView {
            axes,
            half: sigma.map(f),
        })
    };
    SceneView {
        camera: CameraView {
            eye: proj.eye(),
            focus: s.camera().focus,
            fov: proj.vertical_fov(),
            near: NEAR,
        },
        radius: chain.radius(),
        base: [base[0], base[1], 0.0],
        links: chain
            .segments()
            .iter()
            .map(|g| {
                let (a, b) = pose.segment(g);
                [a, b]
            })
            .collect(),
        joints: pose.points().to_vec(),
        frames: (0..pose.dof())
            .map(|i| {
                let ([x, y, z], o) = (pose.frame(i), pose.joint_origin(i));
                [
                    x[0], x[1], x[2], y[0], y[1], y[2], z[0], z[1], z[2], o[0], o[1], o[2],
                ]
            })
            .collect(),
        spheres: scene
            .obstacles
            .iter()
            .map(|o| [o.centre[0], o.centre[1], o.centre[2], o.radius])
            .collect(),
        collision: s.state().collision,
        path: s
            .samples()
            .first()
            .map(|first| scene.path.outline(first.ee, scene.target, OUTLINE_CHORDS))
            .unwrap_or_default(),
        trail: s.played().iter().map(|p| p.ee).collect(),
        ghost: s.ghost().map(|g| g.points().to_vec()),
        hand: pose.hand(),
        velocity: scaled(shown.velocity, &|s| VELOCITY_SCALE * s),
        force: scaled(shown.force, &|s| (FORCE_SCALE / s).min(MAX_FORCE)),
        target: scene.target,
        target_rotation: s.target_rotation(),
        hand_rotation: s.hand_rotation(),
        self_near: s.self_near(),
        floor: [FLOOR_HALF, FLOOR_STEP],
        selected: s.selected().describe(),
        layer,
    }
}

/// Draws the overlay of `s` on `surface` (transparent where nothing is
/// drawn: the 3-D view shows through): the target's handle and where the
/// hand should be now, the selected item's ring when the drawing has the
/// keyboard (`focus`), an axis cross and the caption.
pub fn draw(s: &SpaceSession, surface: &Surface, focus: bool) {
    let ctx = &surface.ctx;
    surface.begin_clear();
    let proj = s.projection(surface.width, surface.height);
    let scene = s.scene();
    let st = s.state();

    // The target and where the hand should be now.
    marker(ctx, &proj, scene.target, 8.0, TEAL);
    let [x, y, z] = proj.project(st.reference);
    if z > NEAR {
        ctx.set_fill_style_str(MUTED);
        disc(ctx, x, y, 3.5);
        ctx.fill();
    }
    if focus {
        let h = s.selected();
        if let Some(c) = s.handle_centre(h) {
            let [x, y, z] = proj.project(c);
            let rad = match h {
                SpaceHandle::Target => 12.0,
                SpaceHandle::Sphere(i) => {
                    scene.obstacles[i].radius * proj.pixels_per_metre(z) + 4.0
                }
            };
            if z > NEAR {
                ctx.set_stroke_style_str(INK);
                ctx.set_line_width(1.5);
                dash(ctx, &[3.0, 3.0]);
                disc(ctx, x, y, rad);
                ctx.stroke();
                dash(ctx, &[]);
            }
        }
    }
    axes(ctx, &proj, surface.height);
    // The time and the method; on a narrow stage the method's short label
    // (about 7 px a character, clear of the view's button at the right).
    let mut caption = format!("t = {:.1} s   ·   {}", st.t, s.method().title());
    if caption.chars().count() as f64 * 7.0 > surface.width - 120.0 {
        caption = format!("t = {:.1} s · {}", st.t, s.method().label());
    }
    text(
        ctx,
        &format!("12px {FONT}"),
        INK,
        ("left", "top"),
        (10.0, 8.0),
        &caption,
    );
}

/// A small axis cross in the bottom left corner: x, y and z as the camera
/// sees them.
fn axes(ctx: &CanvasRenderingContext2d, proj: &Projection, height: f64) {
    let (r, u) = proj.screen_axes();
    let (ox, oy) = (28.0, height - 28.0);
    let font = format!("11px {FONT}");
    for (k, (label, colour)) in [("x", DANGER), ("y", "#2e7d32"), ("z", super::style::ARM)]
        .iter()
        .enumerate()
    {
        let (dx, dy) = (r[k] * 18.0, -u[k] * 18.0);
        ctx.set_stroke_style_str(colour);
        ctx.set_line_width(2.0);
        ctx.begin_path();
        ctx.move_to(ox, oy);
        ctx.line_to(ox + dx, oy + dy);
        ctx.stroke();
        text(
            ctx,
            &font,
            colour,
            ("center", "middle"),
            (ox + 1.3 * dx, oy + 1.3 * dy),
            label,
        );
    }
}

/// The target: a ring with a cross, `size` px.
fn marker(ctx: &CanvasRenderingContext2d, proj: &Projection, p: Vec3, size: f64, colour: &str) {
    let [x, y, z] = proj.project(p);
    if z <= NEAR {
        return;
    }
    ctx.set_stroke_style_str(colour);
    ctx.set_line_width(2.0);
    disc(ctx, x, y, size);
    ctx.stroke();
    ctx.begin_path();
    ctx.move_to(x - size - 3.0, y);
    ctx.line_to(x + size + 3.0, y);
    ctx.move_to(x, y - size - 3.0);
    ctx.line_to(x, y + size + 3.0);
    ctx.stroke();
}
