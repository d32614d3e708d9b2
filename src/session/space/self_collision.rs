//! Self-collision on the page in space (the command line's
//! `--self-collision`): the chain's capsules checked against each other,
//! every pair but adjacent links and those touching at the zero pose or
//! the start (or, for a robot of the user's, the pairs its chain came
//! with); `distance`, `priority` and `qp` keep them apart, and the view
//! draws each checked pair that comes within `self_influence` as the
//! segment between its closest points.

use super::SpaceSession;
use crate::error::Result;
use crate::planner::methods::SELF_INFLUENCE;
use crate::scene::SpaceScene;
use crate::space::self_pairs::self_contact;
use crate::space::Vec3;

/// A checked pair of capsules near each other: the closest points on
/// their axes and the signed distance between their surfaces (m).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SelfNear {
    /// The closest points, on the first capsule's axis and the second's.
    pub points: [Vec3; 2],
    /// The distance between the surfaces (negative: they overlap).
    pub distance: f64,
}

impl SpaceSession {
    /// Whether the chain's capsules are checked against each other.
    pub fn self_collision(&self) -> bool {
        !self.scene.arm.self_pairs().is_empty()
    }

    /// Checks the chain's capsules against each other (`true`) or not;
    /// refused, changing nothing, where the scene then does not run.
    pub fn set_self_collision(&mut self, on: bool) -> Result<()> {
        let scene = self.with_self_collision(self.scene.clone(), on)?;
        self.apply(scene)
    }

    /// `scene` with its chain's pairs for self-collision set (`on`) or
    /// cleared: the robot's own pairs where its chain came with some,
    /// else every pair but adjacent links and those touching at the zero
    /// pose or the scene's start.
    pub(super) fn with_self_collision(
        &self,
        mut scene: SpaceScene,
        on: bool,
    ) -> Result<SpaceScene> {
        let own = self.robot.task.arm.self_pairs();
        if !on {
            scene.arm.set_self_pairs(Vec::new())?;
        } else if !own.is_empty() {
            scene.arm.set_self_pairs(own.to_vec())?;
        } else {
            let zero = vec![0.0; scene.arm.dof()];
            let start = scene.theta0.clone();
            scene.arm.set_self_pairs(Vec::new())?;
            scene.arm = scene.arm.with_self_collision(&[], &[&zero, &start])?;
        }
        Ok(scene)
    }

    /// The checked pairs within `self_influence` of each other at the pose
    /// shown (what the view draws).
    pub fn self_near(&self) -> Vec<SelfNear> {
        let chain = &self.scene.arm;
        let reach = self.scene.param(&SELF_INFLUENCE);
        chain
            .self_pairs()
            .iter()
            .map(|&[a, b]| self_contact(chain, &self.pose, a, b))
            .filter(|c| c.distance < reach)
            .map(|c| SelfNear {
                points: [c.point_a, c.point_b],
                distance: c.distance,
            })
            .collect()
    }
}
