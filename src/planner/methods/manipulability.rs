//! Manipulability (Yoshikawa 1985) by gradient projection (Liégeois 1977):
//! eq. (5) with `v = k_m grad w`, `w = sqrt(det(J J^T))`, which keeps the
//! arm away from singular poses (a stretched or folded arm has `w = 0`).
//! The gradient is analytic ([`Pose::manipulability_gradient_into`],
//! checked against finite differences on random arms of 2-6 links); `w` is
//! floored at 1e-6 m^2, where a singular pose leaves it undefined. It
//! avoids no obstacle: it is the field's second classic criterion, beside
//! the paper's. In space: the same gain, with `w` of the hand's `3 x n`
//! Jacobian ([`crate::space::manipulability`]), floored at 1e-6 m^3.

use super::paper::DELTA;
use super::{projection, Context, Entry, Group, Method, MethodInfo, Needs};
use crate::arm::Arm;
use crate::model::{Model, Scene as _};
use crate::scene::{Param, Scale};
use crate::space::{Chain, PoseChain};

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
    rule: |n| projection::rule(n, gradient::<Arm, 2>),
    space: Some(|n| projection::rule(n, gradient::<Chain, 3>)),
    pose: Some(|n| projection::rule(n, gradient::<PoseChain, 6>)),
};

/// `v = k_m grad w`.
fn gradient<A: Model<M>, const M: usize>(cx: &Context<'_, A, M>, pose: &A::Pose, v: &mut [f64]) {
    A::manipulability_gradient_into(pose, 1e-6, v);
    let gain = cx.scene.value(&MANIPULABILITY_GAIN);
    v.iter_mut().for_each(|x| *x *= gain);
}
