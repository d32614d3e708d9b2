//! Weighted least norm (Chan and Dubey 1995) for an arm in space: the
//! planar weights of `super::super::weighting` (`W = diag(w_i)`,
//! `w_i = 1 + |dH/dtheta_i|` while joint `i` moves away from the middle of
//! its range, 1 otherwise, the test repeated on the weighted rates until no
//! further joint is weighted) over the chain's limits, and eq. (18) in its
//! weighted form with `m = 3` ([`eq18_weighted`]). Everything but the
//! `3 x 3` solve is dimension-free and is the planar code itself.
//!
//! A spatial rule of a method whose [`MethodInfo::weighting`](super::super::MethodInfo)
//! is true owns one [`SpaceJointWeights`] and calls
//! [`SpaceJointWeights::eq18`] where it would call [`super::eq18`]; a rule
//! with a route of its own (a QP, a task priority) calls
//! [`SpaceJointWeights::update`] with its unweighted rates, then, while it
//! returns `true`, solves again with [`SpaceJointWeights::inverse`] and asks
//! [`SpaceJointWeights::widen`] of the new rates.

use super::super::weighting::JointWeights;
use super::{eq18, eq18_weighted, SpaceContext};
use crate::error::Result;
use crate::scene::SpaceScene;
use crate::space::SpacePose;

/// The spatial weights' scratch space (`n` entries of `dH/dtheta` and of
/// `W^-1`).
#[derive(Debug, Clone)]
pub(in crate::planner::methods) struct SpaceJointWeights(JointWeights);

impl SpaceJointWeights {
    /// Room for an `n`-joint chain.
    pub(in crate::planner::methods) fn new(n: usize) -> Self {
        Self(JointWeights::new(n))
    }

    /// Whether `scene` weights the joints at all: weighted least norm on a
    /// chain with limits.
    #[inline]
    pub(in crate::planner::methods) fn active(scene: &SpaceScene) -> bool {
        !scene.weighting.is_none() && scene.chain.joint_limits().is_some()
    }

    /// `W^-1` at `pose` for the unweighted rates `rates`; `false` when
    /// every weight is 1 (the rates stand).
    pub(in crate::planner::methods) fn update(
        &mut self,
        scene: &SpaceScene,
        pose: &SpacePose,
        rates: &[f64],
    ) -> bool {
        Self::active(scene)
            && self.0.update_at(
                scene.weighting,
                scene.chain.joint_limits(),
                pose.theta(),
                rates,
            )
    }

    /// Weights every joint not weighted yet that `rates` move away from the
    /// middle of its range; whether there was one (solve again).
    #[inline]
    pub(in crate::planner::methods) fn widen(&mut self, rates: &[f64]) -> bool {
        self.0.widen(rates)
    }

    /// `W^-1`, one entry per joint, as the last update or widening left it.
    #[inline]
    pub(in crate::planner::methods) fn inverse(&self) -> &[f64] {
        self.0.inverse()
    }

    /// Eq. (18) with `m = 3` into `out`, weighted where the scene's
    /// weighting asks for it ([`eq18_weighted`]), else [`eq18`]: with the
    /// weighting `none`, or while no joint moves toward a limit, the
    /// unweighted rates to the last bit.
    pub(in crate::planner::methods) fn eq18(
        &mut self,
        cx: &SpaceContext<'_>,
        pose: &SpacePose,
        xdot: [f64; 3],
        v: &[f64],
        delta: f64,
        out: &mut [f64],
    ) -> Result<()> {
        eq18(pose, xdot, v, delta, out)?;
        let mut again = self.update(cx.scene, pose, out);
        // At most n + 1 solves (JointWeights::widen).
        for _ in 0..=out.len() {
            if !again {
                break;
            }
            eq18_weighted(pose, self.inverse(), xdot, v, delta, out)?;
            again = self.widen(out);
        }
        Ok(())
    }
}
