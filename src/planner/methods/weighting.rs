//! Weighted least norm (Chan and Dubey 1995), the paper's own `W` of
//! eq. (7) ("to deal with joint limits"), for the methods built on
//! eq. (5): `none`, `numerical`, Cases 1-3, `distance`, `manipulability`
//! and `jointrange`, when the scene asks for it
//! ([`crate::scene::JointWeighting::Wln`]) and the arm has limits.
//!
//! `W = diag(w_i)`, `w_i = 1 + |dH/dtheta_i|` while `|dH/dtheta_i|` grows
//! (joint `i` moves toward a limit), `w_i = 1` otherwise, with `H` the
//! joint-range criterion ([`crate::arm::JointLimits::range_criterion`]).
//!
//! **Whether `|dH/dtheta_i|` grows.** Chan and Dubey compare its value with
//! the previous control period's. A rule here is a function of the pose
//! (an RK4 step evaluates it at four poses, two at one time), so it asks
//! the derivative instead: `H` is convex in each `theta_i` on its range,
//! so `d|dH/dtheta_i|/dt = |d^2H/dtheta_i^2| sign(dH/dtheta_i) theta_dot_i`,
//! which is positive exactly when `dH/dtheta_i theta_dot_i > 0`: the joint
//! moves away from the middle of its range. `theta_dot` there is first the
//! method's unweighted rate at the same pose (`W = I`), so each stage of a
//! step decides from its own pose, and a stage whose joints all move toward
//! the middle keeps the unweighted rates to the last bit. Weighting some
//! joints moves the others more: a joint that the unweighted rates moved
//! toward the middle may be sent toward its limit by the weighted ones
//! (Task 1 with +-2.0944 rad limits: joint 3 weighted near its lower limit
//! drove joint 2 through its upper one, to 2.93 rad). So the test is
//! repeated on the weighted rates, and every joint they move away from its
//! middle is weighted too, until no further joint is (at most `n` solves:
//! the weighted joints only ever grow in number). A weighted joint then
//! moves less toward its limit (`w_i` grows without bound at it); the
//! weights jump where a joint turns back (a property of the method).
//!
//! Written once for every arm ([`Model`]): what differs is eq. (18)'s
//! solve, which the arm's model gives in both forms.

use super::Context;
use crate::arm::JointLimits;
use crate::error::Result;
use crate::model::{Model, Scene as _};
use crate::scene::JointWeighting;

/// The weights' scratch space: `dH/dtheta` and `W^-1` (`n` entries each).
#[derive(Debug, Clone)]
pub(super) struct JointWeights {
    grad: Vec<f64>,
    winv: Vec<f64>,
}

impl JointWeights {
    /// Room for an `n`-joint arm.
    pub(super) fn new(n: usize) -> Self {
        Self {
            grad: vec![0.0; n],
            winv: vec![1.0; n],
        }
    }

    /// Whether the scene weights the joints at all: weighted least norm on
    /// an arm with limits. When not, [`JointWeights::update`] is never
    /// needed.
    #[inline]
    pub(super) fn active<A: Model<M>, const M: usize>(cx: &Context<'_, A, M>) -> bool {
        !cx.scene.weighting().is_none() && cx.scene.arm().joint_limits().is_some()
    }

    /// `W^-1` at `pose` for the unweighted rates `rates` (see the module
    /// documentation); `false` when every weight is 1 (the rates stand).
    pub(super) fn update<A: Model<M>, const M: usize>(
        &mut self,
        cx: &Context<'_, A, M>,
        pose: &A::Pose,
        rates: &[f64],
    ) -> bool {
        self.update_at(
            cx.scene.weighting(),
            cx.scene.arm().joint_limits(),
            A::theta(pose),
            rates,
        )
    }

    /// [`JointWeights::update`] from what it reads, which knows no arm: the
    /// scene's weighting, the joints' limits, the angles `theta` and the
    /// unweighted rates.
    fn update_at(
        &mut self,
        weighting: JointWeighting,
        limits: Option<&JointLimits>,
        theta: &[f64],
        rates: &[f64],
    ) -> bool {
        if weighting.is_none() {
            return false;
        }
        let Some(limits) = limits else {
            return false;
        };
        limits.range_gradient_into(theta, &mut self.grad);
        self.winv.iter_mut().for_each(|w| *w = 1.0);
        self.widen(rates)
    }

    /// Weights every joint not weighted yet that `rates` move away from the
    /// middle of its range; whether there was one (then the rates are to
    /// be solved again).
    ///
    /// A weight that rounds to 1 (`|dH/dtheta_i|` below an ulp of 1, near
    /// the middle of the range) changes nothing and does not count, so each
    /// `true` weights one more joint for good: at most `n` in a row (a
    /// fuzzed scene at the middles of its ranges looped here for ever while
    /// the test was `w == 1` alone).
    pub(super) fn widen(&mut self, rates: &[f64]) -> bool {
        let mut more = false;
        for ((w, &g), &rate) in self.winv.iter_mut().zip(&self.grad).zip(rates) {
            if *w == 1.0 && g * rate > 0.0 {
                *w = 1.0 / (1.0 + g.abs());
                more |= *w != 1.0;
            }
        }
        more
    }

    /// Eq. (18), `theta_dot = J+ (Xdot - J v) + v` with damping `delta`,
    /// into `out`, through the weighted `J+` where the scene's weighting
    /// asks for it ([`Model::eq18_weighted`]), else the paper's
    /// ([`Model::eq18`]): with the weighting `none`, or while no joint
    /// moves toward a limit, the unweighted rates to the last bit.
    pub(super) fn eq18<A: Model<M>, const M: usize>(
        &mut self,
        cx: &Context<'_, A, M>,
        pose: &A::Pose,
        xdot: [f64; M],
        v: &[f64],
        delta: f64,
        out: &mut [f64],
    ) -> Result<()> {
        A::eq18(pose, xdot, v, delta, out)?;
        let mut again = self.update(cx, pose, out);
        // At most n + 1 solves (see widen); the bound only restates that.
        for _ in 0..=out.len() {
            if !again {
                break;
            }
            A::eq18_weighted(pose, &self.winv, xdot, v, delta, out)?;
            again = self.widen(out);
        }
        Ok(())
    }

    /// `W^-1`, one entry per joint, as [`JointWeights::update`] left it.
    pub(super) fn inverse(&self) -> &[f64] {
        &self.winv
    }
}
