//! Gradient projection (Liégeois 1977): the paper's eq. (5) with
//! `v = k grad w` for a criterion `w` to be increased in the null space,
//! then eq. (18) (weighted where the scene asks, `super::weighting`). The
//! rule of the methods whose `v` is such a gradient and nothing else
//! (`manipulability`, `jointrange`); each method's file gives its `v`.

use super::space::{SpaceContext, SpaceRule};
use super::weighting::JointWeights;
use super::weighting::SpaceJointWeights;
use super::{Context, Note, Rule, DELTA};
use crate::error::Result;
use crate::kinematics::Pose;
use crate::space::SpacePose;

/// `v = k grad w` at a pose into the slice (`n` entries).
pub(super) type Gradient = fn(&Context<'_>, &Pose, &mut [f64]);

/// The rule: the method's `v`, then eq. (18), with its scratch space.
#[derive(Clone)]
pub(super) struct Projection {
    gradient: Gradient,
    v: Vec<f64>,
    weights: JointWeights,
}

/// The rule for an `n`-joint arm whose `v` is `gradient`.
pub(super) fn rule(n: usize, gradient: Gradient) -> Box<dyn Rule> {
    Box::new(Projection {
        gradient,
        v: vec![0.0; n],
        weights: JointWeights::new(n),
    })
}

impl Rule for Projection {
    fn theta_dot(
        &mut self,
        cx: &Context<'_>,
        pose: &Pose,
        xdot: [f64; 2],
        out: &mut [f64],
    ) -> Result<Note> {
        (self.gradient)(cx, pose, &mut self.v);
        let delta = cx.scene.param(&DELTA) + cx.scheduled_delta(pose);
        self.weights.eq18(cx, pose, xdot, &self.v, delta, out)?;
        Ok(Note::default())
    }

    fn null_space(&mut self, cx: &Context<'_>, pose: &Pose, v: &mut [f64]) -> Result<bool> {
        (self.gradient)(cx, pose, v);
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule> {
        Box::new(self.clone())
    }
}

// ---- In space ----------------------------------------------------------
//
// Gradient projection (Liégeois 1977) for an arm in space: eq. (5) with
// `v = k grad w` for a criterion `w` to be increased in the null space,
// then eq. (18) with `m = 3`, weighted where the scene asks
// (`super::weighting`). The spatial rule of `manipulability` and
// `jointrange`; each method's spatial file gives its `v`.

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
pub(super) fn space_rule(n: usize, gradient: SpaceGradient) -> Box<dyn SpaceRule> {
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
