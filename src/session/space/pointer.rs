//! The pointer and the keys on the spatial stage: what is under the
//! pointer (the target or a sphere, the nearest to the eye where they
//! overlap), dragging it in the plane through it that faces the camera (so
//! it stays under the pointer: on that plane the perspective map is a
//! scaling), the orbit and the zoom, and the arrow keys, which move the
//! selected item in that same plane.

use super::{Camera, Projection, SpaceSession, DISTANCE, PITCH};
use crate::error::{finite, Result};
use crate::scene::SpacePath;
use crate::session::{FINE_NUDGE, NUDGE};
use crate::space::{add, scale, sub, Vec3};

/// How far one orbit key turns the view (rad): 15 degrees.
pub const KEY_ORBIT: f64 = std::f64::consts::PI / 12.0;
/// The target's handle radius on the canvas (CSS px).
const TARGET_PX: f64 = 9.0;

/// What the pointer holds or the keys move.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpaceHandle {
    /// The end of the hand's line.
    Target,
    /// Sphere `i`.
    Sphere(usize),
}

impl SpaceHandle {
    /// `"target"` or `"sphere 2"` (counted from 1), as the page says it.
    pub fn describe(self) -> String {
        match self {
            SpaceHandle::Target => "target".into(),
            SpaceHandle::Sphere(i) => format!("sphere {}", i + 1),
        }
    }
}

/// A drag in progress: what is held, the depth of the plane it moves in
/// and the offset from the pointer's point on that plane to its centre.
#[derive(Debug, Clone, Copy)]
pub(super) struct Drag {
    grab: Grab,
    depth: f64,
    offset: Vec3,
}

/// What a drag holds: the target or a sphere, or an elbow (joint `k`'s
/// origin, pulled in the null space: `self_motion.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Grab {
    Item(SpaceHandle),
    Elbow(usize),
}

impl SpaceSession {
    /// The camera.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// The camera's projection onto a `width` x `height` canvas.
    pub fn projection(&self, width: f64, height: f64) -> Projection {
        self.camera.projection(width, height)
    }

    /// Turns the view (rad); see [`Camera::orbit`].
    pub fn orbit(&mut self, d_yaw: f64, d_pitch: f64) -> Result<()> {
        self.camera.orbit(d_yaw, d_pitch)
    }

    /// Zooms in by `factor` (out below 1); returns the factor applied.
    pub fn zoom(&mut self, factor: f64) -> Result<f64> {
        self.camera.zoom(factor)
    }

    /// Sets the view: `yaw` and `pitch` (rad, the pitch within [`PITCH`])
    /// and the distance (m, within [`DISTANCE`]); refused, changing
    /// nothing, on a non-finite number.
    pub fn set_view(&mut self, yaw: f64, pitch: f64, distance: f64) -> Result<()> {
        finite("view yaw", yaw)?;
        finite("view pitch", pitch)?;
        crate::error::positive("view distance", distance)?;
        self.camera.yaw = yaw.rem_euclid(std::f64::consts::TAU);
        self.camera.pitch = pitch.clamp(PITCH[0], PITCH[1]);
        self.camera.distance = distance.clamp(DISTANCE[0], DISTANCE[1]);
        Ok(())
    }

    /// Back to the preset's view.
    pub fn reset_view(&mut self) {
        self.camera = self.home;
    }

    /// Where `handle` is (m), if it exists.
    pub fn handle_centre(&self, handle: SpaceHandle) -> Option<Vec3> {
        match handle {
            SpaceHandle::Target => Some(self.scene.target),
            SpaceHandle::Sphere(i) => self.scene.obstacles.get(i).map(|s| s.centre),
        }
    }

    /// The item under canvas pixel `(x, y)` within `slop` px, the nearest
    /// to the eye where several are.
    pub fn handle_at(&self, proj: &Projection, x: f64, y: f64, slop: f64) -> Option<SpaceHandle> {
        let target = std::iter::once((SpaceHandle::Target, self.scene.target, 0.0));
        let spheres = self
            .scene
            .obstacles
            .iter()
            .enumerate()
            .map(|(i, s)| (SpaceHandle::Sphere(i), s.centre, s.radius));
        target
            .chain(spheres)
            .filter_map(|(h, c, r)| {
                let [px, py, z] = proj.project(c);
                let reach = match h {
                    SpaceHandle::Target => TARGET_PX,
                    SpaceHandle::Sphere(_) => r * proj.pixels_per_metre(z),
                } + slop.max(0.0);
                (z > super::NEAR && (px - x).hypot(py - y) <= reach).then_some((h, z))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(h, _)| h)
    }

    /// Grabs the item under `(x, y)`, if any (and selects it).
    pub fn pointer_down(
        &mut self,
        proj: &Projection,
        x: f64,
        y: f64,
        slop: f64,
    ) -> Option<SpaceHandle> {
        if !(x.is_finite() && y.is_finite()) {
            return None;
        }
        let handle = self.handle_at(proj, x, y, slop)?;
        let centre = self.handle_centre(handle)?;
        self.hold(proj, x, y, Grab::Item(handle), centre);
        self.selected = handle;
        Some(handle)
    }

    /// Grabs the elbow under `(x, y)`, if any ([`SpaceSession::elbow_at`];
    /// after the target and the spheres, which [`SpaceSession::pointer_down`]
    /// grabs first): a drag then moves the arm in the null space, the
    /// elbow toward the pointer in the plane through it facing the camera.
    /// Returns the joint (from 0).
    pub fn grab_elbow(&mut self, proj: &Projection, x: f64, y: f64, slop: f64) -> Option<usize> {
        let k = self.elbow_at(proj, x, y, slop)?;
        let centre = self.pose().joint_origin(k);
        self.hold(proj, x, y, Grab::Elbow(k), centre);
        Some(k)
    }

    fn hold(&mut self, proj: &Projection, x: f64, y: f64, grab: Grab, centre: Vec3) {
        let depth = proj.depth(centre);
        let offset = sub(centre, proj.unproject(x, y, depth));
        self.drag = Some(Drag {
            grab,
            depth,
            offset,
        });
    }

    /// Moves the item held to under `(x, y)`, in its plane facing the
    /// camera; a place the scene refuses (a sphere over the base, say)
    /// leaves it where it was and the drag goes on. Refused on a
    /// non-finite pixel.
    pub fn pointer_move(&mut self, proj: &Projection, x: f64, y: f64) -> Result<()> {
        finite("pointer x", x)?;
        finite("pointer y", y)?;
        let Some(d) = self.drag else {
            return Ok(());
        };
        let to = add(proj.unproject(x, y, d.depth), d.offset);
        // A place or a pose refused leaves things as they were; the drag goes on.
        let _ = match d.grab {
            Grab::Item(h) => self.place(h, to),
            Grab::Elbow(k) => self.drag_joint(k, to),
        };
        Ok(())
    }

    /// The polyline drawn by a pointer over canvas pixels `stroke` (flat
    /// `[x0, y0, x1, y1, ...]`), on the plane through the hand's start
    /// that faces the camera, thinned as a drawn planar path is
    /// ([`SpacePath::drawn`]); refused on a non-finite pixel. (Not made
    /// the scene's path: [`SpaceSession::set_path`] does that.)
    pub fn drawn_path(&self, proj: &Projection, stroke: &[f64]) -> Result<SpacePath> {
        let depth = proj.depth(self.scene.start());
        let mut world = Vec::with_capacity(stroke.len() / 2);
        for p in stroke.chunks_exact(2) {
            finite("stroke x", p[0])?;
            finite("stroke y", p[1])?;
            world.push(proj.unproject(p[0], p[1], depth));
        }
        Ok(SpacePath::drawn(&world))
    }

    /// Lets go of the item held.
    pub fn pointer_up(&mut self) {
        self.drag = None;
    }

    /// The item held, if any (not an elbow: [`SpaceSession::dragging_elbow`]).
    pub fn dragging(&self) -> Option<SpaceHandle> {
        match self.drag?.grab {
            Grab::Item(h) => Some(h),
            Grab::Elbow(_) => None,
        }
    }

    /// The elbow held (its joint, from 0), if one is.
    pub fn dragging_elbow(&self) -> Option<usize> {
        match self.drag?.grab {
            Grab::Elbow(k) => Some(k),
            Grab::Item(_) => None,
        }
    }

    fn place(&mut self, handle: SpaceHandle, to: Vec3) -> Result<()> {
        let to = to.map(|v| (v * 1e4).round() / 1e4);
        match handle {
            SpaceHandle::Target => self.set_target(to),
            SpaceHandle::Sphere(i) => self.move_sphere(i, to),
        }
    }

    /// What the keys move (the target when the selected sphere is gone).
    pub fn selected(&self) -> SpaceHandle {
        match self.selected {
            SpaceHandle::Sphere(i) if i >= self.scene.obstacles.len() => SpaceHandle::Target,
            h => h,
        }
    }

    /// Selects the next item (`forward`) or the one before: the target,
    /// then the spheres, and round again.
    pub fn select_next(&mut self, forward: bool) -> SpaceHandle {
        let n = 1 + self.scene.obstacles.len();
        let at = match self.selected() {
            SpaceHandle::Target => 0,
            SpaceHandle::Sphere(i) => i + 1,
        };
        let next = if forward {
            (at + 1) % n
        } else {
            (at + n - 1) % n
        };
        self.selected = if next == 0 {
            SpaceHandle::Target
        } else {
            SpaceHandle::Sphere(next - 1)
        };
        self.selected
    }

    /// Moves the selected item by `(dx, dy)` steps of [`NUDGE`] (or
    /// [`FINE_NUDGE`] when `fine`) metres along the camera's right and up:
    /// in the plane facing the camera, as a drag would.
    pub fn nudge(&mut self, proj: &Projection, dx: f64, dy: f64, fine: bool) -> Result<()> {
        finite("nudge", dx)?;
        finite("nudge", dy)?;
        let h = self.selected();
        let step = if fine { FINE_NUDGE } else { NUDGE };
        let (r, u) = proj.screen_axes();
        let c = self.handle_centre(h).unwrap_or(self.scene.target);
        self.place(h, add(c, add(scale(r, dx * step), scale(u, dy * step))))
    }
}
