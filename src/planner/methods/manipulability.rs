//! Manipulability (Yoshikawa 1985) by gradient projection (Liégeois 1977):
//! eq. (5) with `v = k_m grad w`, `w = sqrt(det(J J^T))`, which keeps the
//! arm away from singular poses (a stretched or folded arm has `w = 0`).
//! The gradient is analytic ([`Pose::manipulability_gradient_into`],
//! checked against finite differences on random arms of 2-6 links); `w` is
//! floored at 1e-6 m^2, where a singular pose leaves it undefined. It
//! avoids no obstacle: it is the field's second classic criterion, beside
//! the paper's. In space (below): the same gain, with
//! `w` of the hand's `3 x n` Jacobian ([`crate::space::manipulability`]).

use super::paper::DELTA;
use super::space::{SpaceContext, SpaceRule};
use super::{projection, Context, Entry, Group, Method, MethodInfo, Needs};
use crate::kinematics::Pose;
use crate::scene::{Param, Scale};
use crate::space::manipulability::manipulability_gradient_into;
use crate::space::SpacePose;

/// Gain `k_m` of the manipulability gradient.
pub static MANIPULABILITY_GAIN: Param = Param {
    name: "manipulability_gain",
    flag: "--manipulability-gain",
    label: "Manipulability gain km",
    what: "manipulability gain k_m",
    #[cfg(feature = "cli")]
    help: "Gain k_m of the manipulability gradient (manipulability)",
    unit: "",
    bounds: (0.0, 1000.0),
    default: 0.5,
    slider: (0.0, 5.0, 0.1),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// Gradient projection on the manipulability (`manipulability`).
pub const MANIPULABILITY: Method = Method::new(&ENTRY);

static ENTRY: Entry = Entry {
    info: MethodInfo {
        name: "manipulability",
        label: "Manipulability",
        description: "v climbs Yoshikawa's manipulability √det(J Jᵀ), eq. (5)",
        group: Group::Beyond,
        paper_figures: None,
        networks: Needs::NOTHING,
        avoids: false,
        weighting: true,
        limits: false,
        colour: "#e377c2",
        params: &[&MANIPULABILITY_GAIN, &DELTA],
    },
    rule: |n| projection::rule(n, gradient),
    space: Some(space_rule),
};

/// `v = k_m grad w`.
fn gradient(cx: &Context<'_>, pose: &Pose, v: &mut [f64]) {
    pose.manipulability_gradient_into(1e-6, v);
    let gain = cx.scene.param(&MANIPULABILITY_GAIN);
    v.iter_mut().for_each(|x| *x *= gain);
}

// ---- In space ----------------------------------------------------------
//
// `manipulability` in space: gradient projection (eq. 5) with
// `v = k_m grad w`, `w = sqrt(det(J J^T))` of the hand's `3 x n`
// Jacobian (Yoshikawa 1985), its gradient analytic
// ([`crate::space::manipulability::manipulability_gradient_into`]), `w`
// floored at 1e-6 m^3 as in the plane. The gain is the planar method's
// [`MANIPULABILITY_GAIN`].

/// The spatial rule for an `n`-joint chain.
pub(in crate::planner::methods) fn space_rule(n: usize) -> Box<dyn SpaceRule> {
    projection::space_rule(n, space_gradient)
}

/// `v = k_m grad w`.
fn space_gradient(cx: &SpaceContext<'_>, pose: &SpacePose, v: &mut [f64]) {
    manipulability_gradient_into(pose, 1e-6, v);
    let gain = cx.scene.param(&MANIPULABILITY_GAIN);
    v.iter_mut().for_each(|x| *x *= gain);
}
