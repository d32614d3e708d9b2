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
//! `d_i` the rates are `J^+ Xdot`, the route without avoidance. In space
//! `J` is the hand's `3 x n` Jacobian and the closest pair a capsule's
//! ([`crate::space::SpacePairs`]): one rule for every arm.

use super::influence::{INFLUENCE, STOP_DISTANCE};
use super::paper::DELTA;
use super::{Context, Entry, Group, Method, MethodInfo, Needs, Note, Rule};
use crate::arm::Arm;
use crate::error::Result;
use crate::model::{closest, Clearance, Model, Scene as _};
use crate::scene::{Param, Scale};
use crate::space::{Chain, PoseChain};

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
    rule: rule::<Arm, 2>,
    space: Some(rule::<Chain, 3>),
    pose: Some(rule::<PoseChain, 6>),
};

/// The rule's scratch space.
#[derive(Clone)]
struct Priority<A: Model<M>, const M: usize> {
    pairs: A::Pairs,
    /// `v = 0` for the first level's route.
    zero: Vec<f64>,
    /// `J_o`, then `b = J_o (I - J^+ J)`.
    jo: Vec<f64>,
}

/// The rule of `priority` for an `n`-joint arm.
fn rule<A: Model<M>, const M: usize>(n: usize) -> Box<dyn Rule<A, M>> {
    Box::new(Priority::<A, M> {
        pairs: A::pairs(n),
        zero: vec![0.0; n],
        jo: vec![0.0; n],
    })
}

impl<A: Model<M>, const M: usize> Rule<A, M> for Priority<A, M> {
    fn theta_dot(
        &mut self,
        cx: &Context<'_, A, M>,
        pose: &A::Pose,
        xdot: [f64; M],
        out: &mut [f64],
    ) -> Result<Note> {
        let s = cx.scene;
        let delta = s.value(&DELTA) + cx.scheduled_delta(pose);
        let jac = A::jacobian(pose);
        // The task: J^+ Xdot.
        A::eq18(pose, xdot, &self.zero, delta, out)?;
        let influence = s.value(&INFLUENCE);
        A::update_pairs(s, pose, influence, &mut self.pairs);
        let Some(pair) = closest(A::pair_list(&self.pairs)).copied() else {
            return Ok(Note::default());
        };
        pair.row_into(pose, &mut self.jo);
        let escape = s.value(&ESCAPE_SPEED) * (influence - pair.clearance())
            / (influence - s.value(&STOP_DISTANCE));
        // J_o J^+ = (J_o J^T) (J J^T + delta I)^-1, a 1 x M row.
        let mut p = [0.0; M];
        for (col, joi) in jac.chunks_exact(M).zip(&self.jo) {
            for (pr, c) in p.iter_mut().zip(col) {
                *pr += joi * c;
            }
        }
        let jo_pinv = A::solve_jjt(pose, delta, p)?;
        // What the task's rates already do to the clearance: J_o J^+ Xdot.
        let done: f64 = self.jo.iter().zip(out.iter()).map(|(j, t)| j * t).sum();
        // b = J_o - (J_o J^+) J.
        for (bi, col) in self.jo.iter_mut().zip(jac.chunks_exact(M)) {
            *bi -= dot(&jo_pinv, col);
        }
        let bb: f64 = self.jo.iter().map(|b| b * b).sum();
        let scale = (escape - done) / (bb + ROW_DAMPING);
        for (o, b) in out.iter_mut().zip(&self.jo) {
            *o += scale * b;
        }
        Ok(Note::default())
    }

    fn boxed_clone(&self) -> Box<dyn Rule<A, M>> {
        Box::new(self.clone())
    }
}

/// `a . b` summed left to right from the first product (the order the
/// written-out `a0 b0 + a1 b1 (+ a2 b2)` has).
#[inline]
fn dot<const M: usize>(a: &[f64; M], b: &[f64]) -> f64 {
    let mut sum = a[0] * b[0];
    for r in 1..M {
        sum += a[r] * b[r];
    }
    sum
}
