//! The scene's gains and switches, for the planner and the ghost: the
//! methods' parameters, the damping schedule, the joint weighting of eq. (7),
//! the floor and post as obstacles, and the closed-loop gain.

use super::Session;
use crate::error::Result;
use crate::ik::DampingSchedule;
use crate::planner::methods::LAMBDA;
use crate::scene::{JointWeighting, Param};

impl Session {
    /// Sets `lambda`, the gain of the obstacle vector (eq. 14).
    pub fn set_lambda(&mut self, lambda: f64) -> Result<()> {
        self.set_param(&LAMBDA, lambda)
    }

    /// Sets a parameter of the methods ([`Param`]), for the planner and the
    /// ghost; refused, changing nothing, when out of its bounds.
    pub fn set_param(&mut self, param: &'static Param, value: f64) -> Result<()> {
        self.twin.apply(|p| p.set_param(param, value))?;
        self.after_change();
        Ok(())
    }

    /// Switches the damping schedule on or off.
    pub fn set_damping(&mut self, on: bool) -> Result<()> {
        self.twin
            .apply(|p| p.set_damping(on.then(DampingSchedule::default)))?;
        self.after_change();
        Ok(())
    }

    /// How the methods of eq. (5) use the joint limits (eq. 7's `W`), for
    /// the planner and the ghost.
    pub fn set_weighting(&mut self, weighting: JointWeighting) {
        let _ = self.twin.apply(|p| {
            p.set_weighting(weighting);
            Ok(())
        });
        self.after_change();
    }

    /// Whether the floor and the post are obstacles, for both planners.
    pub fn set_floor(&mut self, floor: bool) {
        let _ = self.twin.apply(|p| {
            p.set_floor(floor);
            Ok(())
        });
        self.after_change();
    }

    /// Closed-loop gain `K` (1/s), for the planner and the ghost.
    pub fn set_feedback(&mut self, gain: f64) -> Result<()> {
        self.twin.apply(|p| p.set_feedback_gain(gain))?;
        self.after_change();
        Ok(())
    }
}
