//! Self-motion in the page in space, as in the plane
//! (`crate::session::self_motion`): an elbow dragged on the stage (in the
//! plane through it that faces the camera), or the slider for a keyboard,
//! moves the arm in the null space of its `3 x n` Jacobian while the hand
//! holds still ([`crate::planner::self_motion`], one integrator for every
//! arm). The new pose becomes the run's start, paused at `t = 0`.

use super::{Projection, SpaceSession};
use crate::error::Result;
use crate::planner::self_motion::SelfMotion;
use crate::session::self_motion::DRAG_STEPS;
use crate::space::{norm, Vec3};

/// An elbow's handle radius on the canvas (CSS px).
const ELBOW_PX: f64 = 8.0;

impl SpaceSession {
    /// Moves the arm in the null space: elbow `joint` (its origin
    /// `P(joint)`, `1 <= joint < n`) pulled toward `to`, the hand held
    /// where it is. The pose becomes the run's start; refused, changing
    /// nothing, for a joint that is not an elbow, a singular pose or a pose
    /// outside the joints' limits.
    pub fn drag_joint(&mut self, joint: usize, to: Vec3) -> Result<()> {
        self.move_in_null_space(joint, Some(to), 0.0)
    }

    /// Moves the arm along joint `joint`'s self-motion by `amount` rad of
    /// joint-space arc (the page's slider; the sign chooses the way), the
    /// hand held where it is; refused as [`SpaceSession::drag_joint`] is.
    pub fn self_motion(&mut self, joint: usize, amount: f64) -> Result<()> {
        self.move_in_null_space(joint, None, amount)
    }

    fn move_in_null_space(&mut self, joint: usize, to: Option<Vec3>, amount: f64) -> Result<()> {
        let chain = &self.scene.arm;
        let mut theta = self.pose.theta().to_vec();
        let hold = self.pose.hand();
        let mut motion = SelfMotion::new(chain);
        match to {
            Some(to) => motion.drag(chain, &mut theta, joint, to, hold, DRAG_STEPS)?,
            None => motion.along(chain, &mut theta, joint, amount, hold)?,
        }
        if let Some(l) = chain.joint_limits() {
            l.check("the pose after the self-motion", &theta)?;
        }
        let mut scene = self.scene.clone();
        scene.theta0 = theta;
        scene.validate()?;
        self.scene = scene;
        self.running = false;
        self.index = 0;
        self.recompute();
        Ok(())
    }

    /// The elbow under canvas pixel `(x, y)` within `slop` px, if any: a
    /// joint's origin that some joint before it moves (the Panda's second
    /// joint sits on its first: it has no self-motion of its own), the
    /// nearest on the canvas, the later joint where two coincide.
    pub fn elbow_at(&self, proj: &Projection, x: f64, y: f64, slop: f64) -> Option<usize> {
        if !(x.is_finite() && y.is_finite()) {
            return None;
        }
        let pose = &self.pose;
        (1..pose.dof())
            .filter(|&k| {
                let p = pose.joint_origin(k);
                (0..k).any(|i| norm(pose.column(i, p)) > 1e-9)
            })
            .filter_map(|k| {
                let [px, py, z] = proj.project(pose.joint_origin(k));
                let d = (px - x).hypot(py - y);
                (z > super::NEAR && d <= ELBOW_PX + slop.max(0.0)).then_some((k, d))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))
            .map(|(k, _)| k)
    }
}
