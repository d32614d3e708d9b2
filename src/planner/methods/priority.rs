//! Task priority with an obstacle-avoidance point (Maciejewski and Klein
//! 1985): the task first, with the minimum-norm rates `J^+ Xdot`; then,
//! within what the task leaves free, the point closest to an obstacle moves
//! away along the normal:
//!
//! `theta_dot = J^+ Xdot + [J_o (I - J^+ J)]^+ (xdot_o - J_o J^+ Xdot)`,
//!
//! with `J^+ = J^T (J J^T + delta I)^-1` (damped least squares, the scene's
//! `delta` plus the schedule's), `J_o = n^T J_p` the `1 x n` row of the
//! closest link-obstacle pair over all links and obstacles
//! ([`crate::clearance`]), and the escape speed
//! `xdot_o = v_e (d_i - c) / (d_i - d_s)` while its clearance `c` is below
//! the influence distance `d_i`: zero at `d_i`, the escape speed `v_e` at
//! the stop distance `d_s`, more below it (the profile of a velocity
//! damper, as an equality). The pseudoinverse of the row
//! `b = J_o (I - J^+ J)` is damped, `b^T / (b b^T + mu)` with
//! [`ROW_DAMPING`] `= mu`, so it stays bounded where `b` vanishes (the
//! escape direction needs the task's own joints). With no pair within
//! `d_i` the rates are `J^+ Xdot`, the route without avoidance.

use crate::space::Chain;
use crate::model::Model;
use super::influence::{INFLUENCE, STOP_DISTANCE};
use super::paper::DELTA;
use super::{Context, Entry, Group, Method, MethodInfo, Needs, Note, Rule};
use crate::clearance::Pairs;
use crate::error::Result;
use crate::ik;
use crate::kinematics::{jjt, Pose};
use crate::scene::{Param, Scale};
use crate::space::linalg::solve_spd3;
use crate::space::{SpacePairs, SpacePose};

/// The escape speed `v_e` (m/s) of the point closest to an obstacle at
/// the stop distance, chosen on the atlas (`docs/methods.md`).
pub static ESCAPE_SPEED: Param = Param {
    name: "escape_speed",
    flag: "--escape-speed",
    label: "Escape speed",
    what: "escape speed",
    #[cfg(feature = "cli")]
    help: "Escape speed of the point closest to an obstacle at d_s (priority)",
    unit: "m/s",
    bounds: (0.0, 100.0),
    default: 0.1,
    slider: (0.0, 1.0, 0.01),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// The damping `mu` (m^2) of the pseudoinverse of the `1 x n` row
/// `J_o (I - J^+ J)`: its gain is at most `1 / (2 sqrt(mu))`, 16 rad per m.
pub const ROW_DAMPING: f64 = 1e-3;

/// Task priority (`priority`).
pub const PRIORITY: Method = Method::new(&ENTRY);

static ENTRY: Entry = Entry {
    info: MethodInfo {
        name: "priority",
        label: "Task priority",
        description:
            "the task first; the closest point escapes in what it leaves free (Maciejewski–Klein)",
        group: Group::Beyond,
        paper_figures: None,
        networks: Needs::NOTHING,
        avoids: true,
        weighting: false,
        limits: false,
        colour: "#8c564b",
        params: &[&INFLUENCE, &STOP_DISTANCE, &ESCAPE_SPEED, &DELTA],
    },
    rule: |n| {
        Box::new(Priority {
            pairs: Pairs::with_capacity(8 * n),
            zero: vec![0.0; n],
            jo: vec![0.0; n],
        })
    },
    space: Some(space_rule),
};

#[derive(Clone)]
struct Priority {
    pairs: Pairs,
    /// `v = 0` for the first level's route.
    zero: Vec<f64>,
    /// `J_o`, then `b = J_o (I - J^+ J)`.
    jo: Vec<f64>,
}

impl Rule for Priority {
    fn theta_dot(
        &mut self,
        cx: &Context<'_>,
        pose: &Pose,
        xdot: [f64; 2],
        out: &mut [f64],
    ) -> Result<Note> {
        let s = cx.scene;
        let delta = s.param(&DELTA) + cx.scheduled_delta(pose);
        let jac = pose.jacobian();
        // The task: J^+ Xdot.
        ik::theta_dot_symmetric_into(jac, xdot, &self.zero, delta, out)?;
        let influence = s.param(&INFLUENCE);
        self.pairs.update(pose, &s.obstacles, influence);
        if let Some(post) = s.ground() {
            self.pairs.add_ground(pose, post, influence);
        }
        let Some(pair) = self.pairs.closest().copied() else {
            return Ok(Note::default());
        };
        pair.rate_row(pose, &mut self.jo);
        let escape = s.param(&ESCAPE_SPEED) * (influence - pair.clearance)
            / (influence - s.param(&STOP_DISTANCE));
        // J_o J^+ = (J_o J^T) (J J^T + delta I)^-1, a 1 x 2 row.
        let (mut p0, mut p1) = (0.0, 0.0);
        for (col, joi) in jac.chunks_exact(2).zip(&self.jo) {
            p0 += joi * col[0];
            p1 += joi * col[1];
        }
        let [a11, a12, a22] = jjt(jac);
        let jo_pinv = ik::solve_spd2([a11 + delta, a12, a22 + delta], [p0, p1])?;
        // What the task's rates already do to the clearance: J_o J^+ Xdot.
        let done: f64 = self.jo.iter().zip(out.iter()).map(|(j, t)| j * t).sum();
        // b = J_o - (J_o J^+) J.
        for (bi, col) in self.jo.iter_mut().zip(jac.chunks_exact(2)) {
            *bi -= jo_pinv[0] * col[0] + jo_pinv[1] * col[1];
        }
        let bb: f64 = self.jo.iter().map(|b| b * b).sum();
        let scale = (escape - done) / (bb + ROW_DAMPING);
        for (o, b) in out.iter_mut().zip(&self.jo) {
            *o += scale * b;
        }
        Ok(Note::default())
    }

    fn boxed_clone(&self) -> Box<dyn Rule> {
        Box::new(self.clone())
    }
}

// ---- In space ----------------------------------------------------------
//
// Task priority with an obstacle-avoidance point in space (`priority`,
// Maciejewski and Klein 1985; the planar method's module documentation):
//
// `theta_dot = J^+ Xdot + [J_o (I - J^+ J)]^+ (xdot_o - J_o J^+ Xdot)`,
//
// `J^+ = J^T (J J^T + delta I)^-1` with the hand's `3 x n` Jacobian,
// `J_o = n . J_Q` the row of the closest capsule pair (a sphere's, or the
// floor's where the scene has one; [`crate::space::SpacePairs`]), the
// escape speed `xdot_o = v_e (d_i - d) / (d_i - d_s)` while its distance
// `d` is below `d_i`, and the row's pseudoinverse damped by
// [`ROW_DAMPING`].

/// The rule's scratch space.
#[derive(Clone)]
struct PriorityInSpace {
    pairs: SpacePairs,
    /// `v = 0` for the first level's route.
    zero: Vec<f64>,
    /// `J_o`, then `b = J_o (I - J^+ J)`.
    jo: Vec<f64>,
}

/// The rule of `priority` for an `n`-joint chain.
pub(in crate::planner::methods) fn space_rule(n: usize) -> Box<dyn Rule<Chain, 3>> {
    Box::new(PriorityInSpace {
        pairs: SpacePairs::with_capacity(SpacePairs::most(n)),
        zero: vec![0.0; n],
        jo: vec![0.0; n],
    })
}

impl Rule<Chain, 3> for PriorityInSpace {
    fn theta_dot(
        &mut self,
        cx: &Context<'_, Chain, 3>,
        pose: &SpacePose,
        xdot: [f64; 3],
        out: &mut [f64],
    ) -> Result<Note> {
        let s = cx.scene;
        let delta = s.param(&DELTA) + cx.scheduled_delta(pose);
        // The task: J^+ Xdot.
        Chain::eq18(pose, xdot, &self.zero, delta, out)?;
        let influence = s.param(&INFLUENCE);
        self.pairs.update(&s.chain, pose, &s.spheres, influence);
        if s.floor {
            self.pairs.add_floor(&s.chain, pose, influence);
        }
        let Some(pair) = self.pairs.closest().copied() else {
            return Ok(Note::default());
        };
        pair.gradient_into(pose, &mut self.jo);
        let escape = s.param(&ESCAPE_SPEED) * (influence - pair.distance)
            / (influence - s.param(&STOP_DISTANCE));
        let jac = pose.jacobian();
        // J_o J^+ = (J_o J^T) (J J^T + delta I)^-1, a 1 x 3 row.
        let mut p = [0.0; 3];
        for (col, joi) in jac.chunks_exact(3).zip(&self.jo) {
            for r in 0..3 {
                p[r] += joi * col[r];
            }
        }
        let mut a = pose.jjt();
        for (i, row) in a.iter_mut().enumerate() {
            row[i] += delta;
        }
        let jo_pinv = solve_spd3(a, p)?;
        // What the task's rates already do to the distance: J_o J^+ Xdot.
        let done: f64 = self.jo.iter().zip(out.iter()).map(|(j, t)| j * t).sum();
        // b = J_o - (J_o J^+) J.
        for (bi, col) in self.jo.iter_mut().zip(jac.chunks_exact(3)) {
            *bi -= jo_pinv[0] * col[0] + jo_pinv[1] * col[1] + jo_pinv[2] * col[2];
        }
        let bb: f64 = self.jo.iter().map(|b| b * b).sum();
        let scale = (escape - done) / (bb + ROW_DAMPING);
        for (o, b) in out.iter_mut().zip(&self.jo) {
            *o += scale * b;
        }
        Ok(Note::default())
    }

    fn boxed_clone(&self) -> Box<dyn Rule<Chain, 3>> {
        Box::new(self.clone())
    }
}
