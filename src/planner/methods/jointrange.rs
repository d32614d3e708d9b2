//! Joint range by gradient projection (Liégeois 1977): eq. (5) with
//! `v = k_r grad w` for the quadratic criterion
//! `w = -(1 / 2n) sum_i ((theta_i - mid_i) / (hi_i - lo_i))^2`
//! (Liégeois' own; Siciliano et al. 2009, eq. 3.57), which pulls each
//! joint toward the middle `mid_i = (lo_i + hi_i) / 2` of its range:
//! `v_i = -k_r (theta_i - mid_i) / (n (hi_i - lo_i)^2)`.
//!
//! Why not `w = -H`, Chan and Dubey's criterion that the weighting uses
//! (`super::weighting`)? `H` grows without bound at a limit, so its
//! gradient, fed to eq. (5) as a velocity, does too: near a limit the rates
//! it asks are unbounded and an RK4 step of 0.1 s overshoots past the
//! limit. The quadratic is bounded and smooth everywhere; the weighting is
//! where the barrier belongs (it divides rates, never multiplies them).
//! An arm without limits has no range to keep to: `v = 0`, and the method
//! is eq. (5) with no secondary task (`none`'s rates). Dimension-free: one
//! rule for every arm.

use super::paper::DELTA;
use super::{projection, Context, Entry, Group, Method, MethodInfo, Needs};
use crate::arm::{Arm, JointLimits};
use crate::model::{Model, Scene as _};
use crate::scene::{Param, Scale};
use crate::space::{Chain, PoseChain};

/// Gain `k_r` of the joint-range gradient.
pub static JOINT_RANGE_GAIN: Param = Param {
    name: "joint_range_gain",
    flag: "--joint-range-gain",
    label: "Joint-range gain kr",
    what: "joint-range gain k_r",
    #[cfg(feature = "cli")]
    help: "Gain k_r of the joint-range gradient (jointrange)",
    unit: "",
    bounds: (0.0, 1000.0),
    default: 10.0,
    slider: (0.0, 50.0, 1.0),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// Gradient projection on the joints' ranges (`jointrange`).
pub const JOINT_RANGE: Method = Method::new(&ENTRY);

static ENTRY: Entry = Entry {
    info: MethodInfo {
        name: "jointrange",
        label: "Joint range",
        description: "v pulls each joint toward the middle of its range, eq. (5)",
        group: Group::Beyond,
        paper_figures: None,
        networks: Needs::NOTHING,
        avoids: false,
        weighting: true,
        limits: true,
        colour: "#bcbd22",
        params: &[&JOINT_RANGE_GAIN, &DELTA],
    },
    rule: |n| projection::rule(n, gradient::<Arm, 2>),
    space: Some(|n| projection::rule(n, gradient::<Chain, 3>)),
    pose: Some(|n| projection::rule(n, gradient::<PoseChain, 6>)),
};

/// `v = k_r grad w` (zero for an arm without limits).
fn gradient<A: Model<M>, const M: usize>(cx: &Context<'_, A, M>, pose: &A::Pose, v: &mut [f64]) {
    let scene = cx.scene;
    range_gradient_into(
        scene.arm().joint_limits(),
        scene.value(&JOINT_RANGE_GAIN),
        A::theta(pose),
        v,
    );
}

/// `v_i = -k_r (theta_i - mid_i) / (n (hi_i - lo_i)^2)` for the angles
/// `theta` into `v`, zero without `limits`.
pub(super) fn range_gradient_into(
    limits: Option<&JointLimits>,
    gain: f64,
    theta: &[f64],
    v: &mut [f64],
) {
    let Some(limits) = limits else {
        v.iter_mut().for_each(|x| *x = 0.0);
        return;
    };
    let n = v.len() as f64;
    for ((vi, &t), &[lo, hi]) in v.iter_mut().zip(theta).zip(limits.ranges()) {
        let range = hi - lo;
        *vi = -gain * (t - 0.5 * (lo + hi)) / (n * range * range);
    }
}
