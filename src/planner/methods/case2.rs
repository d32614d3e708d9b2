//! The paper's Case 2: `Phi` exact, `v` by the `v` network, eq. (18)
//! (Figs. 5 and 10).

use super::paper::{self, Phi, V, DELTA, LAMBDA};
use super::{Entry, Group, Method, MethodInfo, Needs};
use crate::arm::Arm;
use crate::space::{Chain, PoseChain};

/// Case 2 (`case2`).
pub const CASE2: Method = Method::new(&ENTRY);

static ENTRY: Entry = Entry {
    info: MethodInfo {
        name: "case2",
        label: "Case 2",
        description: "Φ exact, v by a network",
        group: Group::Paper,
        paper_figures: Some([5, 10]),
        networks: Needs {
            phi: false,
            v: true,
        },
        avoids: true,
        weighting: true,
        limits: false,
        colour: "#2ca02c",
        params: &[&LAMBDA, &DELTA],
    },
    rule: |n| paper::rule::<Arm, 2>(n, CASE2, V::Network, Phi::Exact),
    space: Some(|n| paper::rule::<Chain, 3>(n, CASE2, V::Network, Phi::Exact)),
    pose: Some(|n| paper::rule::<PoseChain, 6>(n, CASE2, V::Network, Phi::Exact)),
};
