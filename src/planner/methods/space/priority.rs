//! Task priority with an obstacle-avoidance point in space (`priority`,
//! Maciejewski and Klein 1985; the planar method's module documentation):
//!
//! `theta_dot = J^+ Xdot + [J_o (I - J^+ J)]^+ (xdot_o - J_o J^+ Xdot)`,
//!
//! `J^+ = J^T (J J^T + delta I)^-1` with the hand's `3 x n` Jacobian,
//! `J_o = n . J_Q` the row of the closest capsule pair (a sphere's, or the
//! floor's where the scene has one; [`crate::space::SpacePairs`]), the
//! escape speed `xdot_o = v_e (d_i - d) / (d_i - d_s)` while its distance
//! `d` is below `d_i`, and the row's pseudoinverse damped by
//! [`ROW_DAMPING`].

use super::super::influence::{INFLUENCE, STOP_DISTANCE};
use super::super::paper::DELTA;
use super::super::priority::{ESCAPE_SPEED, ROW_DAMPING};
use super::super::Note;
use super::{eq18, SpaceContext, SpaceRule};
use crate::error::Result;
use crate::space::linalg::solve_spd3;
use crate::space::{SpacePairs, SpacePose};

/// The rule's scratch space.
#[derive(Clone)]
struct Priority {
    pairs: SpacePairs,
    /// `v = 0` for the first level's route.
    zero: Vec<f64>,
    /// `J_o`, then `b = J_o (I - J^+ J)`.
    jo: Vec<f64>,
}

/// The rule of `priority` for an `n`-joint chain.
pub(in crate::planner::methods) fn rule(n: usize) -> Box<dyn SpaceRule> {
    Box::new(Priority {
        pairs: SpacePairs::with_capacity(SpacePairs::most(n)),
        zero: vec![0.0; n],
        jo: vec![0.0; n],
    })
}

impl SpaceRule for Priority {
    fn theta_dot(
        &mut self,
        cx: &SpaceContext<'_>,
        pose: &SpacePose,
        xdot: [f64; 3],
        out: &mut [f64],
    ) -> Result<Note> {
        let s = cx.scene;
        let delta = s.param(&DELTA) + cx.scheduled_delta(pose);
        // The task: J^+ Xdot.
        eq18(pose, xdot, &self.zero, delta, out)?;
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

    fn boxed_clone(&self) -> Box<dyn SpaceRule> {
        Box::new(self.clone())
    }
}
