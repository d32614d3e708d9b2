//! The paper's Case 2: `Phi` exact, `v` by the `v` network, eq. (18)
//! (Figs. 5 and 10).

use super::area::{self, Scratch};
use super::route;
use super::{Context, Entry, Group, Method, MethodInfo, Needs, Note, Rule};
use crate::error::Result;
use crate::kinematics::Pose;
use crate::scene::Param;

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
        colour: "#2ca02c",
        params: &[Param::Lambda, Param::Delta],
    },
    rule: |n| Box::new(Case2(Scratch::new(n))),
};

#[derive(Clone)]
struct Case2(Scratch);

impl Rule for Case2 {
    fn theta_dot(
        &mut self,
        cx: &Context<'_>,
        pose: &Pose,
        xdot: [f64; 2],
        out: &mut [f64],
    ) -> Result<Note> {
        let s = &mut self.0;
        area::learned(CASE2, cx, pose, &mut s.g, &mut s.v)?;
        route::exact(cx, pose, xdot, &s.v, out)
    }

    fn null_space(&mut self, cx: &Context<'_>, pose: &Pose, v: &mut [f64]) -> Result<bool> {
        area::learned(CASE2, cx, pose, &mut self.0.g, v)?;
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule> {
        Box::new(self.clone())
    }
}
