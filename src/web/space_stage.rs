//! The spatial stage: an arm in space drawn in perspective on the same 2-D
//! canvas as the plane's (no WebGL: a handful of capsules and spheres is
//! a painter's job). The floor's grid and the shadows on it are the depth
//! cues; the links (capsules of the chain's radius, outlined), the joints
//! and the spheres are painted far to near; then the path, the trail, the
//! target and the reference point, an axis cross and the caption. A slice
//! atlas's map lies on its plane under the arm ([`SliceLayer`]).

use std::cmp::Ordering;

use web_sys::CanvasRenderingContext2d;

use super::style::{
    rgba, ACCENT, ARM, AXIS, DANGER, FONT, FORCE, FORCE_SCALE, GHOST, GHOST_ALPHA, GRID, INK,
    LAYER_ALPHA, MAX_FORCE, MUTED, PAPER, POST, TEAL, VELOCITY, VELOCITY_SCALE,
};
use super::surface::{dash, disc, text, Surface};
use crate::atlas::space::Plane;
use crate::atlas::{Class, Grid};
use crate::error::Result;
use crate::kinematics::sin_cos;
use crate::session::space::{Projection, SpaceHandle, SpaceSession, NEAR};
use crate::space::manipulability::velocity_ellipsoid;
use crate::space::Vec3;

/// Half the floor grid's side (m) and its spacing.
const FLOOR_HALF: f64 = 1.0;
const FLOOR_STEP: f64 = 0.1;

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

    fn draw(&self, ctx: &CanvasRenderingContext2d, proj: &Projection) {
        let g = &self.grid;
        let [u0, u1, v0, v1] = g.region;
        let (du, dv) = ((u1 - u0) / (g.n - 1) as f64, (v1 - v0) / (g.n - 1) as f64);
        ctx.set_global_alpha(LAYER_ALPHA);
        for j in 0..g.n {
            for i in 0..g.n {
                let class = Class::ALL[usize::from(self.classes[j * g.n + i])];
                let (u, v) = (g.x(i), g.y(j));
                let corners = [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
                    .map(|(a, b)| self.plane.point(u + a * du, v + b * dv));
                ctx.set_fill_style_str(class.colour());
                if polygon(ctx, proj, &corners) {
                    ctx.fill();
                }
            }
        }
        ctx.set_global_alpha(1.0);
    }
}

/// What is painted in depth order.
enum Item {
    Link(Vec3, Vec3),
    Joint(Vec3),
    Sphere(usize),
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

/// Draws `s` on `surface`; `layer` is a slice atlas to show, `focus` rings
/// the selected item (the drawing has the keyboard), `shown` the
/// ellipsoids switched on.
pub fn draw(
    s: &SpaceSession,
    surface: &Surface,
    layer: Option<&SliceLayer>,
    focus: bool,
    shown: Shown,
) {
    let ctx = &surface.ctx;
    surface.begin();
    let proj = s.projection(surface.width, surface.height);
    let scene = s.scene();
    let chain = &scene.arm;
    let pose = s.pose();
    let r = chain.radius();
    let st = s.state();

    floor(ctx, &proj);
    // The base: a plate on the floor under the first joint.
    let base = chain.base().1;
    let plate: Vec<Vec3> = (0..24)
        .map(|k| {
            let a = k as f64 * std::f64::consts::TAU / 24.0;
            [
                base[0] + 2.0 * r * a.cos(),
                base[1] + 2.0 * r * a.sin(),
                0.0,
            ]
        })
        .collect();
    ctx.set_fill_style_str(&rgba(POST, 0.5));
    if polygon(ctx, &proj, &plate) {
        ctx.fill();
    }
    if let Some(l) = layer {
        l.draw(ctx, &proj);
    }
    // Shadows: the links and the spheres dropped straight onto the floor.
    let shadow = rgba(INK, 0.13);
    ctx.set_stroke_style_str(&shadow);
    ctx.set_fill_style_str(&shadow);
    let links: Vec<(Vec3, Vec3)> = chain.segments().iter().map(|g| pose.segment(g)).collect();
    for &(a, b) in &links {
        let (a0, b0) = ([a[0], a[1], 0.0], [b[0], b[1], 0.0]);
        segment(ctx, &proj, a0, b0, 2.0 * r);
    }
    for sp in &scene.obstacles {
        let c = sp.centre;
        let ring: Vec<Vec3> = (0..24)
            .map(|k| {
                let (sa, ca) = sin_cos(k as f64 * std::f64::consts::TAU / 24.0);
                [c[0] + sp.radius * ca, c[1] + sp.radius * sa, 0.0]
            })
            .collect();
        if polygon(ctx, &proj, &ring) {
            ctx.fill();
        }
    }

    // The path and the trail, under the arm.
    let played = s.played();
    if let Some(first) = s.samples().first() {
        let outline = scene.path.outline(first.ee, scene.target, 96);
        ctx.set_stroke_style_str(MUTED);
        ctx.set_line_width(1.2);
        dash(ctx, &[5.0, 4.0]);
        path(ctx, &proj, outline.iter().copied());
        dash(ctx, &[]);
    }
    ctx.set_stroke_style_str(ACCENT);
    ctx.set_line_width(2.0);
    path(ctx, &proj, played.iter().map(|p| p.ee));

    // The arm and the spheres, far to near.
    let mut items: Vec<(f64, Item)> = links
        .iter()
        .map(|&(a, b)| (0.5 * (proj.depth(a) + proj.depth(b)), Item::Link(a, b)))
        .chain(
            pose.points()
                .iter()
                .map(|&p| (proj.depth(p), Item::Joint(p))),
        )
        .chain(
            scene
                .obstacles
                .iter()
                .enumerate()
                .map(|(i, sp)| (proj.depth(sp.centre), Item::Sphere(i))),
        )
        .collect();
    items.sort_by(|a, b| b.0.partial_cmp(&a.0).unwrap_or(Ordering::Equal));
    // Depth as a cue: the nearest link in full colour, the farthest paler.
    let (near, far) = items
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (z, _)| {
            (lo.min(*z), hi.max(*z))
        });
    let shade = |z: f64| 0.95 - 0.4 * ((z - near) / (far - near).max(1e-9)).clamp(0.0, 1.0);
    let hit = st.collision;
    for (z, item) in &items {
        match *item {
            Item::Link(a, b) => {
                ctx.set_stroke_style_str(INK);
                segment_px(ctx, &proj, a, b, 2.0 * r, 2.0);
                // Over white, so that a paler link hides what is behind it.
                ctx.set_stroke_style_str(PAPER);
                segment_px(ctx, &proj, a, b, 2.0 * r, 0.0);
                ctx.set_stroke_style_str(&rgba(ARM, shade(*z)));
                segment_px(ctx, &proj, a, b, 2.0 * r, 0.0);
                // The link's axis, the stick of the stick-and-capsule drawing.
                ctx.set_stroke_style_str(&rgba(PAPER, 0.35));
                segment_px(ctx, &proj, a, b, 0.0, 1.5);
            }
            Item::Joint(p) => {
                let [x, y, z] = proj.project(p);
                if z > NEAR {
                    ctx.set_fill_style_str(INK);
                    disc(ctx, x, y, (0.3 * r * proj.pixels_per_metre(z)).max(1.5));
                    ctx.fill();
                }
            }
            Item::Sphere(i) => {
                let sp = &scene.obstacles[i];
                let [x, y, z] = proj.project(sp.centre);
                if z > NEAR {
                    let rad = sp.radius * proj.pixels_per_metre(z);
                    ctx.set_fill_style_str(&rgba(DANGER, if hit { 0.55 } else { 0.28 }));
                    disc(ctx, x, y, rad);
                    ctx.fill();
                    ctx.set_stroke_style_str(DANGER);
                    ctx.set_line_width(1.5);
                    ctx.stroke();
                    // A highlight toward the light, for roundness.
                    ctx.set_fill_style_str(&rgba("#ffffff", 0.45));
                    disc(ctx, x - 0.35 * rad, y - 0.35 * rad, 0.25 * rad);
                    ctx.fill();
                }
            }
        }
    }

    // The numerical ghost, on top and thinner, with a white edge (the
    // plane's): where the exact route has the arm at this time.
    if let Some(g) = s.ghost() {
        dash(ctx, &[7.0, 5.0]);
        for (colour, width, alpha) in [(PAPER, 4.5, 0.9), (GHOST, 2.0, GHOST_ALPHA)] {
            ctx.set_global_alpha(alpha);
            ctx.set_stroke_style_str(colour);
            ctx.set_line_width(width);
            path(ctx, &proj, g.points().iter().copied());
        }
        dash(ctx, &[]);
        for &p in g.points().iter().skip(1) {
            let [x, y, z] = proj.project(p);
            if z > NEAR {
                disc(ctx, x, y, 3.0);
                ctx.stroke();
            }
        }
        ctx.set_global_alpha(1.0);
    }

    // The ellipsoids at the hand, each as its three principal ellipses at
    // the plane's scales: the velocity ellipsoid (half-lengths sigma_i, m
    // per rad/s) and the force ellipsoid (1 / sigma_i, the same axes, each
    // at most MAX_FORCE: it is unbounded at a singular pose).
    if shown.velocity || shown.force {
        let (axes, sigma) = velocity_ellipsoid(pose.jjt());
        let hand = pose.hand();
        ctx.set_line_width(1.75);
        let velocity = sigma.map(|s| VELOCITY_SCALE * s);
        let force = sigma.map(|s| (FORCE_SCALE / s).min(MAX_FORCE));
        for (on, colour, half) in [
            (shown.velocity, VELOCITY, velocity),
            (shown.force, FORCE, force),
        ] {
            if !on {
                continue;
            }
            ctx.set_stroke_style_str(colour);
            for (a, b) in [(0, 1), (0, 2), (1, 2)] {
                let ring = (0..=64).map(|k| {
                    let (sin, cos) = sin_cos(k as f64 * std::f64::consts::TAU / 64.0);
                    let (u, w) = (half[a] * cos, half[b] * sin);
                    std::array::from_fn(|i| hand[i] + u * axes[a][i] + w * axes[b][i])
                });
                path(ctx, &proj, ring);
            }
        }
    }

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
            ctx.set_stroke_style_str(INK);
            ctx.set_line_width(1.5);
            dash(ctx, &[3.0, 3.0]);
            disc(ctx, x, y, rad);
            ctx.stroke();
            dash(ctx, &[]);
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

/// The floor's grid around the base, its axes darker.
fn floor(ctx: &CanvasRenderingContext2d, proj: &Projection) {
    let n = (2.0 * FLOOR_HALF / FLOOR_STEP).round() as i32;
    ctx.set_line_width(1.0);
    for k in 0..=n {
        let c = -FLOOR_HALF + f64::from(k) * FLOOR_STEP;
        let axis = c.abs() < 1e-9;
        ctx.set_stroke_style_str(if axis { AXIS } else { GRID });
        path(
            ctx,
            proj,
            [[c, -FLOOR_HALF, 0.0], [c, FLOOR_HALF, 0.0]].into_iter(),
        );
        path(
            ctx,
            proj,
            [[-FLOOR_HALF, c, 0.0], [FLOOR_HALF, c, 0.0]].into_iter(),
        );
    }
}

/// A small axis cross in the bottom left corner: x, y and z as the camera
/// sees them.
fn axes(ctx: &CanvasRenderingContext2d, proj: &Projection, height: f64) {
    let (r, u) = proj.screen_axes();
    let (ox, oy) = (28.0, height - 28.0);
    let font = format!("11px {FONT}");
    for (k, (label, colour)) in [("x", DANGER), ("y", "#2e7d32"), ("z", ARM)]
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

/// Strokes the polyline through world points, breaking it where a point
/// lies behind the eye.
fn path(ctx: &CanvasRenderingContext2d, proj: &Projection, pts: impl Iterator<Item = Vec3>) {
    ctx.begin_path();
    let mut pen = false;
    for p in pts {
        let [x, y, z] = proj.project(p);
        if z <= NEAR {
            pen = false;
            continue;
        }
        if pen {
            ctx.line_to(x, y);
        } else {
            ctx.move_to(x, y);
            pen = true;
        }
    }
    ctx.stroke();
}

/// A segment `a`-`b` as a round-capped stroke `width` metres wide at its
/// mean depth, plus `extra` pixels.
fn segment_px(
    ctx: &CanvasRenderingContext2d,
    proj: &Projection,
    a: Vec3,
    b: Vec3,
    width: f64,
    extra: f64,
) {
    let (pa, pb) = (proj.project(a), proj.project(b));
    if pa[2] <= NEAR || pb[2] <= NEAR {
        return;
    }
    let z = 0.5 * (pa[2] + pb[2]);
    ctx.set_line_width(width * proj.pixels_per_metre(z) + extra);
    ctx.begin_path();
    ctx.move_to(pa[0], pa[1]);
    ctx.line_to(pb[0], pb[1]);
    ctx.stroke();
}

fn segment(ctx: &CanvasRenderingContext2d, proj: &Projection, a: Vec3, b: Vec3, width: f64) {
    segment_px(ctx, proj, a, b, width, 0.0);
}

/// Traces the closed polygon through world points; false (nothing traced)
/// when one lies behind the eye.
fn polygon(ctx: &CanvasRenderingContext2d, proj: &Projection, pts: &[Vec3]) -> bool {
    ctx.begin_path();
    for (i, &p) in pts.iter().enumerate() {
        let [x, y, z] = proj.project(p);
        if z <= NEAR {
            return false;
        }
        if i == 0 {
            ctx.move_to(x, y);
        } else {
            ctx.line_to(x, y);
        }
    }
    ctx.close_path();
    true
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
