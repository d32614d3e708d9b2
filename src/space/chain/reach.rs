//! How far a chain's hand can be from its first joint: the bound the
//! planner reads to tell an unreachable target.

use super::{norm, Chain};

impl Chain {
    /// An upper bound of the hand's distance from the first joint's
    /// origin: the sum of the rows' and the flange's lengths, and twice
    /// each prismatic joint's longest travel (the first joint's origin
    /// slides with it; unlimited, [`crate::arm::MAX_ANGLE`]).
    pub fn reach(&self) -> f64 {
        if !self.joints.is_empty() {
            let travel = |i: usize| {
                self.joint_limits
                    .as_ref()
                    .map_or(crate::arm::MAX_ANGLE, |l| {
                        let [lo, hi] = l.ranges()[i];
                        lo.abs().max(hi.abs())
                    })
            };
            let slides: f64 = (0..self.joints.len())
                .filter(|&i| self.joints[i].prismatic)
                .map(|i| 2.0 * travel(i))
                .sum();
            return self
                .joints
                .iter()
                .skip(1)
                .map(|j| norm(j.translation))
                .sum::<f64>()
                + norm(self.flange)
                + slides;
        }
        self.rows
            .iter()
            .skip(1)
            .map(|r| r.a.abs() + r.d.abs())
            .sum::<f64>()
            + self.rows[0].a.abs()
            + norm(self.flange)
    }
}
