//! No provision for obstacle avoidance: `v = 0` in eqs. (17)-(18), the
//! minimum-norm joint rates of the task alone (the paper's Figs. 2 and 7).

use super::route;
use super::{Context, Entry, Group, Method, MethodInfo, Needs, Note, Rule};
use crate::error::Result;
use crate::kinematics::Pose;
use crate::scene::Param;

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
        colour: "#d62728",
        params: &[Param::Delta],
    },
    rule: |n| Box::new(NoAvoidance { v: vec![0.0; n] }),
};

/// `v = 0`, kept as a buffer so that eq. (18) reads it as any other `v`.
#[derive(Clone)]
struct NoAvoidance {
    v: Vec<f64>,
}

impl Rule for NoAvoidance {
    fn theta_dot(
        &mut self,
        cx: &Context<'_>,
        pose: &Pose,
        xdot: [f64; 2],
        out: &mut [f64],
    ) -> Result<Note> {
        route::exact(cx, pose, xdot, &self.v, out)
    }

    fn null_space(&mut self, _: &Context<'_>, _: &Pose, v: &mut [f64]) -> Result<bool> {
        v.iter_mut().for_each(|x| *x = 0.0);
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule> {
        Box::new(self.clone())
    }
}
