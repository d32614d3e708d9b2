//! The QP with velocity dampers in space: the program of `methods/qp`
//! (its module documentation has the formulas) with the hand's `3 x n`
//! Jacobian, the area vector of the criterion in space
//! ([`crate::space::criterion`]) and the spatial rows of every constraint
//! of [`constraints::ALL`] (each constraint's file: the dampers of the
//! capsule pairs and the floor, the joint-limit dampers, the rate limit).
//!
//! With no row binding, `theta_dot = v + J^T (J J^T + I / w')^-1 (Xdot -
//! J v)`, eq. (18) with `m = 3`; where one binds, the task slack
//! `s = Xdot - J theta_dot` (3 entries) eliminated,
//! `H = I + w' J^T J`, `g = v + w' J^T Xdot`, `w' = 1 / (1 / w + delta)`,
//! solved by [`crate::qp::solve`] over `A = -G`, `b = -h`; where no rate
//! satisfies every row, every bound relaxed to `max(h, 0)`.
//!
//! One check the planar program does not make: the rates must keep every
//! row (to [`ROW_TOLERANCE`]). The dual active-set method loses its digits
//! on nearly opposite active rows (a forearm squeezed between two spheres;
//! the planar program's known case, `tests/constraints.rs`) and can return
//! rates that break one. Such a solution is not taken: the program is
//! relaxed as where it is infeasible, and where the relaxed one's solution
//! breaks a row too the arm holds still, `theta_dot = 0`, which keeps every
//! relaxed row. Both are relaxed steps.

use super::super::paper::{DELTA, LAMBDA, SIGN_SMOOTHING};
use super::super::qp::constraints::{self, Rows, SpaceConstraint};
use super::super::qp::SLACK_WEIGHT;
use super::super::Note;
use super::{eq18, SpaceContext, SpaceRule};
use crate::error::{Error, Result};
use crate::qp as solver;
use crate::space::{criterion, SpacePairs, SpacePose};

/// The spatial program's scratch space, sized for an `n`-joint chain and
/// grown (once) when more rows appear than ever before.
#[derive(Clone)]
struct SpaceQp {
    constraints: Vec<Box<dyn SpaceConstraint>>,
    rows: Rows,
    /// The area vector `v`.
    v: Vec<f64>,
    /// `H` (row-major `n x n`) and the linear term.
    h: Vec<f64>,
    lin: Vec<f64>,
    /// The rows as the solver takes them, `A x >= b`.
    a: Vec<f64>,
    b: Vec<f64>,
    ws: solver::Workspace,
}

/// The rule of `qp` for an `n`-joint chain.
pub(in crate::planner::methods) fn rule(n: usize) -> Box<dyn SpaceRule> {
    // Every damper a chain can have, the joint-limit dampers and the
    // rate limits: the rows never grow.
    let m = SpacePairs::most(n) + 2 * n + 2 * n;
    Box::new(SpaceQp {
        constraints: constraints::ALL.iter().map(|c| (c.space)(n)).collect(),
        rows: Rows::with_capacity(n, m),
        v: vec![0.0; n],
        h: vec![0.0; n * n],
        lin: vec![0.0; n],
        a: Vec::with_capacity(m * n),
        b: Vec::with_capacity(m),
        ws: solver::Workspace::with_capacity(n, m),
    })
}

/// How far rates may break a row, relative to `1 + |h|`, before the
/// program refuses them.
pub const ROW_TOLERANCE: f64 = 1e-7;

/// Why a solve was not taken.
enum Refused {
    /// No rate keeps every row, or the solver's rates break one.
    Unsolved,
    /// Anything else (a dimension mismatch): an error.
    Error(Error),
}

impl SpaceQp {
    /// Solves the program over the current rows into `out` and checks the
    /// rates keep them.
    fn solve(&mut self, out: &mut [f64]) -> std::result::Result<(), Refused> {
        self.a.clear();
        self.a.extend(self.rows.g().iter().map(|g| -g));
        self.b.clear();
        self.b.extend(self.rows.h().iter().map(|h| -h));
        match solver::solve(&mut self.ws, &self.h, &self.lin, &self.a, &self.b, out) {
            Ok(_) => {}
            Err(Error::Infeasible { .. } | Error::QpFailed { .. }) => {
                return Err(Refused::Unsolved)
            }
            Err(e) => return Err(Refused::Error(e)),
        }
        let kept = self.rows.iter().all(|(row, h)| {
            let rate: f64 = row.iter().zip(out.iter()).map(|(g, t)| g * t).sum();
            rate <= h + ROW_TOLERANCE * (1.0 + h.abs())
        });
        if kept {
            Ok(())
        } else {
            Err(Refused::Unsolved)
        }
    }
}

impl SpaceRule for SpaceQp {
    fn theta_dot(
        &mut self,
        cx: &SpaceContext<'_>,
        pose: &SpacePose,
        xdot: [f64; 3],
        out: &mut [f64],
    ) -> Result<Note> {
        let n = pose.dof();
        let s = cx.scene;
        criterion::null_space_vector_into(
            &s.chain,
            pose,
            s.spheres.iter().map(|sp| sp.centre),
            s.param(&LAMBDA),
            s.param(&SIGN_SMOOTHING),
            &mut self.v,
        );
        let damping = 1.0 / s.param(&SLACK_WEIGHT) + s.param(&DELTA) + cx.scheduled_delta(pose);
        // The unconstrained minimum: eq. (18) with m = 3.
        eq18(pose, xdot, &self.v, damping, out)?;
        self.rows.clear(n);
        for constraint in &mut self.constraints {
            constraint.rows(cx, pose, &mut self.rows)?;
        }
        if !self.rows.broken_by(out) {
            return Ok(Note::default());
        }
        // H = I + w' J^T J, g = v + w' J^T Xdot over J's three rows.
        let w = 1.0 / damping;
        let jac = pose.jacobian();
        for (r, jr) in jac.chunks_exact(3).enumerate() {
            for (c, jc) in jac.chunks_exact(3).enumerate() {
                let jtj = jr[0] * jc[0] + jr[1] * jc[1] + jr[2] * jc[2];
                self.h[r * n + c] = f64::from(u8::from(r == c)) + w * jtj;
            }
            let jtx = jr[0] * xdot[0] + jr[1] * xdot[1] + jr[2] * xdot[2];
            self.lin[r] = self.v[r] + w * jtx;
        }
        let relaxed = Note {
            relaxed: true,
            ..Note::default()
        };
        match self.solve(out) {
            Ok(()) => return Ok(Note::default()),
            Err(Refused::Error(e)) => return Err(e),
            Err(Refused::Unsolved) => {}
        }
        // No capsule may approach; none must move away (theta_dot = 0 is
        // feasible).
        self.rows.h_mut().iter_mut().for_each(|h| *h = h.max(0.0));
        match self.solve(out) {
            Ok(()) => Ok(relaxed),
            Err(Refused::Error(e)) => Err(e),
            Err(Refused::Unsolved) => {
                out.iter_mut().for_each(|t| *t = 0.0);
                Ok(relaxed)
            }
        }
    }

    fn boxed_clone(&self) -> Box<dyn SpaceRule> {
        Box::new(self.clone())
    }
}
