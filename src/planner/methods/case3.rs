//! The paper's Case 3: both `Phi` and `v` by the networks, eq. (21)
//! (Figs. 6 and 11).

use super::paper::{self, Phi, V, DELTA, LAMBDA, REFINE};
use super::{Entry, Group, Method, MethodInfo, Needs};
use crate::arm::Arm;
use crate::space::{Chain, PoseChain};

/// Case 3 (`case3`).
pub const CASE3: Method = Method::new(&ENTRY);

static ENTRY: Entry = Entry {
    info: MethodInfo {
        name: "case3",
        label: "Case 3",
        description: "Φ and v by networks",
        group: Group::Paper,
        paper_figures: Some([6, 11]),
        networks: Needs {
            phi: true,
            v: true,
        },
        avoids: true,
        weighting: true,
        limits: false,
        colour: "#ff7f0e",
        params: &[&LAMBDA, &DELTA, &REFINE],
    },
    rule: |n| paper::rule::<Arm, 2>(n, CASE3, V::Network, Phi::Network),
    space: Some(|n| paper::rule::<Chain, 3>(n, CASE3, V::Network, Phi::Network)),
    pose: Some(|n| paper::rule::<PoseChain, 6>(n, CASE3, V::Network, Phi::Network)),
};
