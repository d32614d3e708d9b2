//! Self-motion in the page: an elbow dragged on the stage, or the slider
//! for a keyboard, moves the arm in the null space while the hand holds
//! still ([`crate::planner::self_motion`]). The new pose becomes the run's
//! start (as a dropped target's line does), paused at `t = 0`.

use super::Session;
use crate::error::Result;
use crate::planner::self_motion::SelfMotion;
use crate::planner::Planner;

/// RK4 steps of the self-motion per pointer move (0.2 s of it).
pub const DRAG_STEPS: usize = 10;

impl Session {
    /// Moves the arm in the null space: elbow `joint` (its position
    /// `P(joint)`, `1 <= joint < n`) pulled toward `to`, the hand held
    /// where it is. The pose becomes the run's start; refused, changing
    /// nothing, for a joint that is not an elbow, a singular pose or a pose
    /// outside the joints' limits.
    pub fn drag_joint(&mut self, joint: usize, to: [f64; 2]) -> Result<()> {
        self.move_in_null_space(joint, Some(to), 0.0)
    }

    /// Moves the arm along joint `joint`'s self-motion by `amount` rad of
    /// joint-space arc (the page's slider; the sign chooses the way),
    /// the hand held where it is; refused as [`Session::drag_joint`] is.
    pub fn self_motion(&mut self, joint: usize, amount: f64) -> Result<()> {
        self.move_in_null_space(joint, None, amount)
    }

    /// Joint `joint` dragged toward `to`, or (none) moved along by `amount`.
    fn move_in_null_space(
        &mut self,
        joint: usize,
        to: Option<[f64; 2]>,
        amount: f64,
    ) -> Result<()> {
        let p = self.planner();
        let mut scene = p.scene().clone();
        let mut theta = p.theta().as_slice().to_vec();
        let hold = p.sample().ee;
        let mut motion = SelfMotion::new(&scene.arm);
        match to {
            Some(to) => motion.drag(&scene.arm, &mut theta, joint, to, hold, DRAG_STEPS)?,
            None => motion.along(&scene.arm, &mut theta, joint, amount, hold)?,
        }
        scene
            .arm
            .check_within_limits("the pose after the self-motion", &theta)?;
        scene.theta0 = theta;
        let planner = Planner::new(scene, p.method(), p.networks().cloned())?;
        self.twin.replace(planner);
        self.own_start = true;
        self.running = false;
        self.backlog = 0.0;
        self.histories.clear();
        self.remember_poses();
        self.record();
        Ok(())
    }
}
