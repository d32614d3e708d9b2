//! The spatial stage's camera: a perspective view that orbits a focus
//! point (yaw about the vertical `z` axis, pitch above the floor) at a
//! distance, and the projection it gives a canvas ([`Projection`]): world
//! to pixel with depth, and back from a pixel onto the plane through a
//! point that faces the camera, which is where a dragged item moves.
//! Plain geometry, tested natively; the page's module draws and hit-tests
//! through the one [`Projection`] of a frame.

use crate::error::{finite, Result};
// The kinematics' own sine and cosine: libm's would add 7 KB to the page's module.
use crate::kinematics::sin_cos;
use crate::space::{cross, dot, norm, scale, sub, Vec3};

/// The pitch the user may choose (rad): from slightly below the floor's
/// plane to looking straight down.
pub const PITCH: [f64; 2] = [-0.35, 1.5];
/// The distance from the focus the user may choose (m).
pub const DISTANCE: [f64; 2] = [0.6, 8.0];
/// The vertical field of view across the canvas's shorter side (rad).
pub const FIELD_OF_VIEW: f64 = 0.7;
/// The nearest depth drawn (m): what is closer to the eye is left out.
pub const NEAR: f64 = 0.05;

/// Where the camera is: it looks at `focus` from `distance` away, from
/// the direction `yaw` about `z` and `pitch` above the floor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Angle about the vertical axis, from `+x` toward `+y` (rad).
    pub yaw: f64,
    /// Elevation above the floor's plane (rad).
    pub pitch: f64,
    /// Distance from the eye to the focus (m).
    pub distance: f64,
    /// The point looked at (m).
    pub focus: Vec3,
}

impl Camera {
    /// The view of a preset's task: the arm and its line from the front
    /// and a little to the side and above, with `focus` in the middle.
    pub fn looking_at(focus: Vec3, distance: f64) -> Self {
        Self {
            yaw: 0.45,
            pitch: 0.32,
            distance: distance.clamp(DISTANCE[0], DISTANCE[1]),
            focus,
        }
    }

    /// Turns the view by `d_yaw` about the vertical and `d_pitch` up or
    /// down (rad), the pitch kept within [`PITCH`]; refused, changing
    /// nothing, on a non-finite angle.
    pub fn orbit(&mut self, d_yaw: f64, d_pitch: f64) -> Result<()> {
        finite("orbit angle", d_yaw)?;
        finite("orbit angle", d_pitch)?;
        self.yaw = (self.yaw + d_yaw).rem_euclid(std::f64::consts::TAU);
        self.pitch = (self.pitch + d_pitch).clamp(PITCH[0], PITCH[1]);
        Ok(())
    }

    /// Moves the eye `factor` times closer (`factor > 1` zooms in), within
    /// [`DISTANCE`]; returns the factor applied.
    pub fn zoom(&mut self, factor: f64) -> Result<f64> {
        crate::error::positive("zoom factor", factor)?;
        let before = self.distance;
        self.distance = (self.distance / factor).clamp(DISTANCE[0], DISTANCE[1]);
        Ok(before / self.distance)
    }

    /// The eye's position (m).
    pub fn eye(&self) -> Vec3 {
        let (sy, cy) = sin_cos(self.yaw);
        let (sp, cp) = sin_cos(self.pitch);
        let d = self.distance;
        [
            self.focus[0] + d * cp * cy,
            self.focus[1] + d * cp * sy,
            self.focus[2] + d * sp,
        ]
    }

    /// The projection onto a `width` x `height` canvas (CSS px).
    pub fn projection(&self, width: f64, height: f64) -> Projection {
        let eye = self.eye();
        let f = unit(sub(self.focus, eye));
        // Right: the forward direction crossed with up; at a vertical view
        // (never reached within PITCH) the yaw's own right.
        let r = {
            let r = cross(f, [0.0, 0.0, 1.0]);
            if norm(r) > 1e-9 {
                unit(r)
            } else {
                let (sy, cy) = sin_cos(self.yaw);
                [sy, -cy, 0.0]
            }
        };
        let u = cross(r, f);
        let (s, c) = sin_cos(0.5 * FIELD_OF_VIEW);
        let focal = 0.5 * width.min(height).max(1.0) * c / s;
        Projection {
            eye,
            right: r,
            up: u,
            forward: f,
            focal,
            centre: [0.5 * width, 0.5 * height],
        }
    }
}

fn unit(v: Vec3) -> Vec3 {
    let n = norm(v).max(1e-300);
    scale(v, 1.0 / n)
}

/// A camera's map between the world and a canvas (CSS px, `y` down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    eye: Vec3,
    right: Vec3,
    up: Vec3,
    forward: Vec3,
    /// Pixels per metre at a depth of one metre.
    focal: f64,
    centre: [f64; 2],
}

impl Projection {
    /// The depth of `p` along the view (m; [`NEAR`] or less: not drawn).
    #[inline]
    pub fn depth(&self, p: Vec3) -> f64 {
        dot(sub(p, self.eye), self.forward)
    }

    /// `p` on the canvas, `[x, y, depth]`; a point at or behind [`NEAR`]
    /// is placed as if at [`NEAR`] (callers skip it by its depth).
    #[inline]
    pub fn project(&self, p: Vec3) -> [f64; 3] {
        let q = sub(p, self.eye);
        let z = dot(q, self.forward);
        let k = self.focal / z.max(NEAR);
        [
            self.centre[0] + k * dot(q, self.right),
            self.centre[1] - k * dot(q, self.up),
            z,
        ]
    }

    /// Pixels per metre at depth `z`.
    #[inline]
    pub fn pixels_per_metre(&self, z: f64) -> f64 {
        self.focal / z.max(NEAR)
    }

    /// The world point at canvas pixel `(x, y)` on the plane that faces the
    /// camera at depth `z`: [`Projection::project`]'s inverse there.
    pub fn unproject(&self, x: f64, y: f64, z: f64) -> Vec3 {
        let z = z.max(NEAR);
        let a = (x - self.centre[0]) * z / self.focal;
        let b = -(y - self.centre[1]) * z / self.focal;
        [0, 1, 2].map(|i| self.eye[i] + z * self.forward[i] + a * self.right[i] + b * self.up[i])
    }

    /// The ray through canvas pixel `(x, y)`: the eye and the direction
    /// (not of unit length) to the pixel's point one metre deep.
    pub fn ray(&self, x: f64, y: f64) -> (Vec3, Vec3) {
        (self.eye, sub(self.unproject(x, y, 1.0), self.eye))
    }

    /// The camera's right and up directions (unit vectors): the plane the
    /// arrow keys move the selected item in.
    pub fn screen_axes(&self) -> (Vec3, Vec3) {
        (self.right, self.up)
    }

    /// The direction the camera looks in (unit vector).
    pub fn forward(&self) -> Vec3 {
        self.forward
    }

    /// The eye's position (m).
    pub fn eye(&self) -> Vec3 {
        self.eye
    }

    /// The vertical field of view (rad) of a pinhole camera with this
    /// projection on its canvas (whose centre is the image's): what a 3-D
    /// renderer's perspective camera, placed at the eye and looking along
    /// [`Projection::forward`] with `z` up, needs to draw every point where
    /// [`Projection::project`] puts it.
    pub fn vertical_fov(&self) -> f64 {
        2.0 * (self.centre[1] / self.focal).atan()
    }
}
