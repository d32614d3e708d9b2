//! The paper's Case 1: `Phi` by the `Phi` network, `v` exact, eq. (21)
//! (Figs. 4 and 9).

use super::paper::{self, Phi, V, DELTA, LAMBDA, REFINE, SIGN_SMOOTHING};
use super::{Entry, Group, Method, MethodInfo, Needs};
use crate::arm::Arm;
use crate::space::{Chain, PoseChain};

/// Case 1 (`case1`).
pub const CASE1: Method = Method::new(&ENTRY);

static ENTRY: Entry = Entry {
    info: MethodInfo {
        name: "case1",
        label: "Case 1",
        description: "Φ by a network, v exact",
        group: Group::Paper,
        paper_figures: Some([4, 9]),
        networks: Needs {
            phi: true,
            v: false,
        },
        avoids: true,
        weighting: true,
        limits: false,
        colour: "#1f77b4",
        params: &[&LAMBDA, &DELTA, &SIGN_SMOOTHING, &REFINE],
    },
    rule: |n| paper::rule::<Arm, 2>(n, CASE1, V::Exact, Phi::Network),
    space: Some(|n| paper::rule::<Chain, 3>(n, CASE1, V::Exact, Phi::Network)),
    pose: Some(|n| paper::rule::<PoseChain, 6>(n, CASE1, V::Exact, Phi::Network)),
};
