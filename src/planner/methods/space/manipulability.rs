//! `manipulability` in space: gradient projection (eq. 5) with
//! `v = k_m grad w`, `w = sqrt(det(J J^T))` of the hand's `3 x n`
//! Jacobian (Yoshikawa 1985), its gradient analytic
//! ([`crate::space::manipulability::manipulability_gradient_into`]), `w`
//! floored at 1e-6 m^3 as in the plane. The gain is the planar method's
//! [`MANIPULABILITY_GAIN`].

use super::super::manipulability::MANIPULABILITY_GAIN;
use super::{projection, SpaceContext, SpaceRule};
use crate::space::manipulability::manipulability_gradient_into;
use crate::space::SpacePose;

/// The spatial rule for an `n`-joint chain.
pub(in crate::planner::methods) fn rule(n: usize) -> Box<dyn SpaceRule> {
    projection::rule(n, gradient)
}

/// `v = k_m grad w`.
fn gradient(cx: &SpaceContext<'_>, pose: &SpacePose, v: &mut [f64]) {
    manipulability_gradient_into(pose, 1e-6, v);
    let gain = cx.scene.param(&MANIPULABILITY_GAIN);
    v.iter_mut().for_each(|x| *x *= gain);
}
