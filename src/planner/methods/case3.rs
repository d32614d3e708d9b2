//! The paper's Case 3: both `Phi` and `v` by the networks, eq. (21)
//! (Figs. 6 and 11).

use super::area::{self, Scratch};
use super::route;
use super::{Context, Entry, Group, Method, MethodInfo, Needs, Note, Rule};
use crate::error::Result;
use crate::kinematics::Pose;
use crate::scene::Param;

/// Case 3 (`case3`).
pub const CASE3: Method = Method::new(&ENTRY);

static ENTRY: Entry = Entry {
    info: MethodInfo {
        name: "case3",
        label: "Case 3",
        description: "Φ and v by networks",
        group: Group::Paper,
        paper_figures: Some([6, 11]),
        networks: Needs { phi: true, v: true },
        avoids: true,
        colour: "#ff7f0e",
        params: &[Param::Lambda, Param::Delta],
    },
    rule: |n| Box::new(Case3(Scratch::new(n))),
};

#[derive(Clone)]
struct Case3(Scratch);

impl Rule for Case3 {
    fn theta_dot(
        &mut self,
        cx: &Context<'_>,
        pose: &Pose,
        xdot: [f64; 2],
        out: &mut [f64],
    ) -> Result<Note> {
        let s = &mut self.0;
        area::learned(CASE3, cx, pose, &mut s.g, &mut s.v)?;
        route::learned(CASE3, cx, pose, xdot, &s.v, &mut s.phi, out)
    }

    fn null_space(&mut self, cx: &Context<'_>, pose: &Pose, v: &mut [f64]) -> Result<bool> {
        area::learned(CASE3, cx, pose, &mut self.0.g, v)?;
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule> {
        Box::new(self.clone())
    }
}
