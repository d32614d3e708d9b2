//! Gradient projection (Liégeois 1977) for an arm in space: eq. (5) with
//! `v = k grad w` for a criterion `w` to be increased in the null space,
//! then eq. (18) with `m = 3`, weighted where the scene asks
//! (`super::weighting`). The spatial rule of `manipulability` and
//! `jointrange`; each method's spatial file gives its `v`.

use super::super::paper::DELTA;
use super::weighting::SpaceJointWeights;
use super::{SpaceContext, SpaceRule};
use crate::error::Result;
use crate::planner::methods::Note;
use crate::space::SpacePose;

/// `v = k grad w` at a pose into the slice (`n` entries).
pub(super) type SpaceGradient = fn(&SpaceContext<'_>, &SpacePose, &mut [f64]);

/// The rule: the method's `v`, then eq. (18), with its scratch space.
#[derive(Clone)]
struct SpaceProjection {
    gradient: SpaceGradient,
    v: Vec<f64>,
    weights: SpaceJointWeights,
}

/// The rule for an `n`-joint chain whose `v` is `gradient`.
pub(super) fn rule(n: usize, gradient: SpaceGradient) -> Box<dyn SpaceRule> {
    Box::new(SpaceProjection {
        gradient,
        v: vec![0.0; n],
        weights: SpaceJointWeights::new(n),
    })
}

impl SpaceRule for SpaceProjection {
    fn theta_dot(
        &mut self,
        cx: &SpaceContext<'_>,
        pose: &SpacePose,
        xdot: [f64; 3],
        out: &mut [f64],
    ) -> Result<Note> {
        (self.gradient)(cx, pose, &mut self.v);
        let delta = cx.scene.param(&DELTA) + cx.scheduled_delta(pose);
        self.weights.eq18(cx, pose, xdot, &self.v, delta, out)?;
        Ok(Note::default())
    }

    fn boxed_clone(&self) -> Box<dyn SpaceRule> {
        Box::new(self.clone())
    }
}
