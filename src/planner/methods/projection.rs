//! Gradient projection (Liégeois 1977): the paper's eq. (5) with
//! `v = k grad w` for a criterion `w` to be increased in the null space,
//! then eq. (18) (weighted where the scene asks, `super::weighting`). The
//! rule of the methods whose `v` is such a gradient and nothing else
//! (`manipulability`, `jointrange`), for every arm; each method's file
//! gives its `v`.

use super::weighting::JointWeights;
use super::{Context, Note, Rule, DELTA};
use crate::error::Result;
use crate::model::{Model, Scene as _};

/// `v = k grad w` at a pose into the slice (`n` entries).
pub(super) type Gradient<A, const M: usize> =
    fn(&Context<'_, A, M>, &<A as Model<M>>::Pose, &mut [f64]);

/// The rule: the method's `v`, then eq. (18), with its scratch space.
#[derive(Clone)]
struct Projection<A: Model<M>, const M: usize> {
    gradient: Gradient<A, M>,
    v: Vec<f64>,
    weights: JointWeights,
}

/// The rule for an `n`-joint arm whose `v` is `gradient`.
pub(super) fn rule<A: Model<M>, const M: usize>(
    n: usize,
    gradient: Gradient<A, M>,
) -> Box<dyn Rule<A, M>> {
    Box::new(Projection {
        gradient,
        v: vec![0.0; n],
        weights: JointWeights::new(n),
    })
}

impl<A: Model<M>, const M: usize> Rule<A, M> for Projection<A, M> {
    fn theta_dot(
        &mut self,
        cx: &Context<'_, A, M>,
        pose: &A::Pose,
        xdot: [f64; M],
        out: &mut [f64],
    ) -> Result<Note> {
        (self.gradient)(cx, pose, &mut self.v);
        let delta = cx.scene.value(&DELTA) + cx.scheduled_delta(pose);
        self.weights.eq18(cx, pose, xdot, &self.v, delta, out)?;
        Ok(Note::default())
    }

    fn null_space(
        &mut self,
        cx: &Context<'_, A, M>,
        pose: &A::Pose,
        v: &mut [f64],
    ) -> Result<bool> {
        (self.gradient)(cx, pose, v);
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule<A, M>> {
        Box::new(self.clone())
    }
}
