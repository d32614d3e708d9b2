//! The paper's Case 1: `Phi` by the `Phi` network, `v` exact, eq. (21)
//! (Figs. 4 and 9).

use super::area::{self, Scratch};
use super::route;
use super::{Context, Entry, Group, Method, MethodInfo, Needs, Note, Rule};
use crate::error::Result;
use crate::kinematics::Pose;
use crate::scene::Param;

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
        colour: "#1f77b4",
        params: &[Param::Lambda, Param::Delta],
    },
    rule: |n| Box::new(Case1(Scratch::new(n))),
};

#[derive(Clone)]
struct Case1(Scratch);

impl Rule for Case1 {
    fn theta_dot(
        &mut self,
        cx: &Context<'_>,
        pose: &Pose,
        xdot: [f64; 2],
        out: &mut [f64],
    ) -> Result<Note> {
        let s = &mut self.0;
        area::exact(cx, pose, &mut s.g, &mut s.v);
        route::learned(CASE1, cx, pose, xdot, &s.v, &mut s.phi, out)
    }

    fn null_space(&mut self, cx: &Context<'_>, pose: &Pose, v: &mut [f64]) -> Result<bool> {
        area::exact(cx, pose, &mut self.0.g, v);
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule> {
        Box::new(self.clone())
    }
}
