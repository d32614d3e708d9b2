//! The paper's numerical approach: eqs. (17)-(18) with the exact obstacle
//! vector `v` of eqs. (14)-(16) (Figs. 3 and 8).

use super::area::{self, Scratch};
use super::route;
use super::{Context, Entry, Group, Method, MethodInfo, Needs, Note, Rule};
use crate::error::Result;
use crate::kinematics::Pose;
use crate::scene::Param;

/// The numerical route (`numerical`).
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
        colour: "#000000",
        params: &[Param::Lambda, Param::Delta],
    },
    rule: |n| Box::new(Numerical(Scratch::new(n))),
};

#[derive(Clone)]
struct Numerical(Scratch);

impl Rule for Numerical {
    fn theta_dot(
        &mut self,
        cx: &Context<'_>,
        pose: &Pose,
        xdot: [f64; 2],
        out: &mut [f64],
    ) -> Result<Note> {
        let s = &mut self.0;
        area::exact(cx, pose, &mut s.g, &mut s.v);
        route::exact(cx, pose, xdot, &s.v, out)
    }

    fn null_space(&mut self, cx: &Context<'_>, pose: &Pose, v: &mut [f64]) -> Result<bool> {
        area::exact(cx, pose, &mut self.0.g, v);
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule> {
        Box::new(self.clone())
    }
}
