//! The paper's numerical approach: eqs. (17)-(18) with the exact obstacle
//! vector `v` of eqs. (14)-(16) (Figs. 3 and 8).

use super::paper::{self, Phi, V, DELTA, LAMBDA, SIGN_SMOOTHING};
use super::{Entry, Group, Method, MethodInfo, Needs};
use crate::arm::Arm;
use crate::space::{Chain, PoseChain};

/// Numerical (`numerical`).
pub const NUMERICAL: Method = Method::new(&ENTRY);

static ENTRY: Entry = Entry {
    info: MethodInfo {
        name: "numerical",
        label: "Numerical",
        description: "Φ and v computed exactly",
        group: Group::Paper,
        paper_figures: Some([3, 8]),
        networks: Needs::NOTHING,
        avoids: true,
        weighting: true,
        limits: false,
        colour: "#000000",
        params: &[&LAMBDA, &DELTA, &SIGN_SMOOTHING],
    },
    rule: |n| paper::rule::<Arm, 2>(n, NUMERICAL, V::Exact, Phi::Exact),
    space: Some(|n| paper::rule::<Chain, 3>(n, NUMERICAL, V::Exact, Phi::Exact)),
    pose: Some(|n| paper::rule::<PoseChain, 6>(n, NUMERICAL, V::Exact, Phi::Exact)),
};
