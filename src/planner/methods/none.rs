//! No provision for obstacle avoidance: `v = 0` in eqs. (17)-(18), the
//! minimum-norm joint rates of the task alone (the paper's Figs. 2 and 7).

use super::paper::{self, Phi, V, DELTA};
use super::{Entry, Group, Method, MethodInfo, Needs};
use crate::arm::Arm;
use crate::space::{Chain, PoseChain};

/// No avoidance (`none`).
pub const NO_AVOIDANCE: Method = Method::new(&ENTRY);

static ENTRY: Entry = Entry {
    info: MethodInfo {
        name: "none",
        label: "No avoidance",
        description: "v = 0, no obstacle avoidance",
        group: Group::Paper,
        paper_figures: Some([2, 7]),
        networks: Needs::NOTHING,
        avoids: false,
        weighting: true,
        limits: false,
        colour: "#d62728",
        params: &[&DELTA],
    },
    rule: |n| paper::rule::<Arm, 2>(n, NO_AVOIDANCE, V::Zero, Phi::Exact),
    space: Some(|n| paper::rule::<Chain, 3>(n, NO_AVOIDANCE, V::Zero, Phi::Exact)),
    pose: Some(|n| paper::rule::<PoseChain, 6>(n, NO_AVOIDANCE, V::Zero, Phi::Exact)),
};
