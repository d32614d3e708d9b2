//! `jointrange` in space: gradient projection (eq. 5) with the planar
//! method's quadratic criterion `w = -(1 / 2n) sum_i ((theta_i - mid_i) /
//! (hi_i - lo_i))^2` over the chain's limits (dimension-free: the planar
//! [`range_gradient_into`]), gain [`JOINT_RANGE_GAIN`]; `v = 0` for a
//! chain without limits.

use super::super::jointrange::{range_gradient_into, JOINT_RANGE_GAIN};
use super::{projection, SpaceContext, SpaceRule};
use crate::space::SpacePose;

/// The spatial rule for an `n`-joint chain.
pub(in crate::planner::methods) fn rule(n: usize) -> Box<dyn SpaceRule> {
    projection::rule(n, gradient)
}

/// `v = k_r grad w` (zero for a chain without limits).
fn gradient(cx: &SpaceContext<'_>, pose: &SpacePose, v: &mut [f64]) {
    let scene = cx.scene;
    range_gradient_into(
        scene.chain.joint_limits(),
        scene.param(&JOINT_RANGE_GAIN),
        pose.theta(),
        v,
    );
}
