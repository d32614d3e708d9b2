//! A quadratic program with velocity dampers, the modern reactive
//! controller (NEO, Haviland and Corke 2021; the collision-avoidance limits
//! of mink and dm_robotics). Decision variables `theta_dot` (n) and a task
//! slack `s` (`m`: 2 for a hand in the plane, 3 in space; one program for
//! every arm model):
//!
//! minimise `(1/2) |theta_dot - v|^2 + (w/2) |s|^2`
//! subject to `J theta_dot + s = Xdot` (the commanded task velocity, the
//! feedback term included) and the rows `G theta_dot <= h` of every
//! constraint of [`constraints::ALL`], one file each: the velocity dampers
//! (`constraints/damper.rs`) and the joint-rate limit
//! (`constraints/rate_limit.rs`).
//!
//! This file is the program they are assembled into. `v` is the paper's
//! area vector (eq. 14 with its gain `lambda`; `lambda = 0` gives the
//! minimum-norm rates, NEO's setting without its manipulability term). With
//! no row binding the solution is `v + J^T (J J^T + I / w)^-1 (Xdot - J v)`:
//! eq. (5) with damped least squares, `delta = 1 / w`. The scene's `delta`
//! and the damping schedule add to that damping (`1 / w` becomes
//! `1 / w + delta`), so the task slack grows near singular poses as in the
//! other methods.
//!
//! Eliminating `s = Xdot - J theta_dot` leaves `n` variables:
//! `H = I + w' J^T J`, `g = v + w' J^T Xdot`, `w' = 1 / (1 / w + delta)`,
//! solved by [`crate::qp::solve`] (Goldfarb-Idnani, rows `A x >= b`, so
//! `A = -G`, `b = -h`) only when the unconstrained solution breaks a row.
//!
//! Where no rate satisfies every row (an arm already inside `d_s` of
//! obstacles on both sides), every bound is relaxed to `max(h, 0)`: no link
//! may approach an obstacle, none is required to move away; the rate
//! limit's bounds `h = L > 0` are unchanged. `theta_dot = 0` satisfies that,
//! so the relaxed program is feasible; the step's note (and the run's
//! summary) say when it was needed. The solver's rates are checked against
//! every row before they are taken (`solve_relaxing`, for every arm): on
//! nearly opposite damper rows (an arm between two obstacles that face
//! each other across a link, `tests/constraints.rs`) the dual active-set
//! method can lose its digits and return rates that break one; the program
//! is relaxed then as where it is infeasible, and where the relaxed one's
//! rates break a row too the arm holds still.

pub mod constraints;

use super::influence::{INFLUENCE, STOP_DISTANCE};
use super::paper::{obstacle_vector, V, DELTA, LAMBDA};
use super::{Context, Entry, Group, Method, MethodInfo, Needs, Note, Rule};
use crate::planner::Planned;
use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::model::{Model, Scene as _};
use crate::qp as solver;
use crate::scene::{Param, Scale};
use crate::space::{Chain, PoseChain};
use constraints::{Constraint, Rows};
use constraints::{
    DAMPER_GAIN, LIMIT_GAIN, LIMIT_INFLUENCE, LIMIT_STOP, RATE_LIMIT, SELF_DAMPER_GAIN,
    SELF_INFLUENCE, SELF_STOP_DISTANCE,
};

/// Weight `w` of the task slack: with no row binding the rates are eq. (5)
/// with damped least squares, `delta = 1 / w`. Below 1 the task hardly
/// counts; above 1e12 `1 / w` drowns in the rounding of `J J^T`.
pub static SLACK_WEIGHT: Param = Param {
    name: "slack_weight",
    flag: "--slack-weight",
    label: "Slack weight w",
    what: "slack weight w",
    #[cfg(feature = "cli")]
    help: "Weight w of the task slack (qp)",
    unit: "",
    bounds: (1.0, 1e12),
    default: 1e6,
    slider: (2.0, 8.0, 0.5),
    scale: Scale::Log,
    count: false,
    below: None,
    above: None,
};

/// The QP with velocity dampers (`qp`).
pub const QP: Method = Method::new(&ENTRY);

static ENTRY: Entry = Entry {
    info: MethodInfo {
        name: "qp",
        label: "QP with dampers",
        description: "min |θ̇ − v|² + w|s|² with a velocity damper on every close link (NEO)",
        group: Group::Beyond,
        paper_figures: None,
        networks: Needs::NOTHING,
        avoids: true,
        weighting: false,
        limits: false,
        colour: "#17becf",
        // The program's own and its constraints' (tests/constraints.rs
        // checks that every constraint's are here).
        params: &[
            &LAMBDA,
            &INFLUENCE,
            &STOP_DISTANCE,
            &DAMPER_GAIN,
            &SELF_INFLUENCE,
            &SELF_STOP_DISTANCE,
            &SELF_DAMPER_GAIN,
            &SLACK_WEIGHT,
            &RATE_LIMIT,
            &LIMIT_INFLUENCE,
            &LIMIT_STOP,
            &LIMIT_GAIN,
            &DELTA,
        ],
    },
    rule: rule::<Arm, 2>,
    space: Some(rule::<Chain, 3>),
    pose: Some(rule::<PoseChain, 6>),
};

/// The program's scratch space, sized for an `n`-joint arm and grown
/// (once) when more rows appear than ever before.
#[derive(Clone)]
struct Qp<A: Model<M>, const M: usize> {
    /// The constraints of [`constraints::ALL`], each with its scratch space.
    constraints: Vec<Box<dyn Constraint<A, M>>>,
    /// Their rows at the current pose, in the order of the constraints.
    rows: Rows,
    /// The area vector `v`, and one obstacle's gradient.
    v: Vec<f64>,
    g: Vec<f64>,
    /// `H` (row-major `n x n`) and the linear term.
    h: Vec<f64>,
    lin: Vec<f64>,
    /// The rows as the solver takes them, `A x >= b`: `A = -G`, `b = -h`.
    a: Vec<f64>,
    b: Vec<f64>,
    ws: solver::Workspace,
}

/// The rule of `qp` for an `n`-joint arm.
fn rule<A: Planned<M>, const M: usize>(n: usize) -> Box<dyn Rule<A, M>> {
    // Dampers for the model's pairs, the joint-limit dampers and the rate
    // limits.
    let m = A::most_pairs(n) + 2 * n + 2 * n;
    Box::new(Qp::<A, M> {
        constraints: constraints::ALL
            .iter()
            .map(|c| A::constraint(c)(n))
            .collect(),
        rows: Rows::with_capacity(n, m),
        v: vec![0.0; n],
        g: vec![0.0; n],
        h: vec![0.0; n * n],
        lin: vec![0.0; n],
        a: Vec::with_capacity(m * n),
        b: Vec::with_capacity(m),
        ws: solver::Workspace::with_capacity(n, m),
    })
}

/// `a^T Z b` for `Z`'s diagonal `z`, summed left to right from the first
/// product (the order of the written-out `a0 b0 + a1 b1 (+ a2 b2)`; with
/// `z = 1`, exactly `a . b`).
#[inline]
fn dot(a: &[f64], z: &[f64], b: &[f64]) -> f64 {
    let mut sum = a[0] * z[0] * b[0];
    for ((x, zk), y) in a.iter().zip(z).zip(b).skip(1) {
        sum += x * zk * y;
    }
    sum
}

impl<A: Model<M>, const M: usize> Rule<A, M> for Qp<A, M> {
    fn theta_dot(
        &mut self,
        cx: &Context<'_, A, M>,
        pose: &A::Pose,
        xdot: [f64; M],
        out: &mut [f64],
    ) -> Result<Note> {
        let n = out.len();
        obstacle_vector(QP, V::Exact, cx, pose, &mut self.g, &mut self.v)?;
        let s = cx.scene;
        let damping = 1.0 / s.value(&SLACK_WEIGHT) + s.value(&DELTA) + cx.scheduled_delta(pose);
        // The unconstrained minimum: eq. (5) with damped least squares.
        A::eq18(pose, xdot, &self.v, damping, out)?;
        // Every constraint's rows at this pose.
        self.rows.clear(n);
        for constraint in &mut self.constraints {
            constraint.rows(cx, pose, &mut self.rows)?;
        }
        if !self.rows.broken_by(out) {
            return Ok(Note::default());
        }
        // Some row binds: the program over theta_dot,
        // H = I + w' J^T Z J, g = v + w' J^T Z Xdot (Z = I but for the
        // pose task's orientation rows).
        let w = 1.0 / damping;
        let jac = A::jacobian(pose);
        let z = A::task_weights(pose);
        for (r, jr) in jac.chunks_exact(M).enumerate() {
            for (c, jc) in jac.chunks_exact(M).enumerate() {
                self.h[r * n + c] = f64::from(u8::from(r == c)) + w * dot(jr, &z, jc);
            }
            self.lin[r] = self.v[r] + w * dot(jr, &z, &xdot);
        }
        solve_relaxing(
            &mut self.rows,
            (&self.h, &self.lin),
            (&mut self.a, &mut self.b),
            &mut self.ws,
            out,
        )
    }

    fn null_space(&mut self, cx: &Context<'_, A, M>, pose: &A::Pose, v: &mut [f64]) -> Result<bool> {
        obstacle_vector(QP, V::Exact, cx, pose, &mut self.g, v)?;
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule<A, M>> {
        Box::new(self.clone())
    }
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

/// The program `min (1/2) x^T H x - lin^T x` over the rows `G x <= h` of
/// `rows` (`H`, `lin` given; `A`, `b` the solver's scratch, `A x >= b`),
/// for every arm: solved, and its rates checked against every row (to
/// [`ROW_TOLERANCE`]: the dual active-set method loses its digits on nearly
/// opposite active rows and can return rates that break one). Where no rate
/// keeps the rows, or the solver's rates break one, every bound is relaxed
/// to `max(h, 0)` (no link may approach an obstacle, none must move away)
/// and the program solved again; where that fails too, the arm holds still,
/// `theta_dot = 0`, which keeps every relaxed row. Both are relaxed steps.
fn solve_relaxing(
    rows: &mut Rows,
    (h, lin): (&[f64], &[f64]),
    (a, b): (&mut Vec<f64>, &mut Vec<f64>),
    ws: &mut solver::Workspace,
    out: &mut [f64],
) -> Result<Note> {
    let mut solve = |rows: &Rows, out: &mut [f64]| -> std::result::Result<(), Refused> {
        a.clear();
        a.extend(rows.g().iter().map(|g| -g));
        b.clear();
        b.extend(rows.h().iter().map(|h| -h));
        match solver::solve(ws, h, lin, a, b, out) {
            Ok(_) => {}
            Err(Error::Infeasible { .. } | Error::QpFailed { .. }) => {
                return Err(Refused::Unsolved)
            }
            Err(e) => return Err(Refused::Error(e)),
        }
        let kept = rows.iter().all(|(row, h)| {
            let rate: f64 = row.iter().zip(out.iter()).map(|(g, t)| g * t).sum();
            rate <= h + ROW_TOLERANCE * (1.0 + h.abs())
        });
        if kept {
            Ok(())
        } else {
            Err(Refused::Unsolved)
        }
    };
    match solve(rows, out) {
        Ok(()) => return Ok(Note::default()),
        Err(Refused::Error(e)) => return Err(e),
        Err(Refused::Unsolved) => {}
    }
    rows.h_mut().iter_mut().for_each(|h| *h = h.max(0.0));
    let relaxed = Note {
        relaxed: true,
        ..Note::default()
    };
    match solve(rows, out) {
        Ok(()) => Ok(relaxed),
        Err(Refused::Error(e)) => Err(e),
        Err(Refused::Unsolved) => {
            out.iter_mut().for_each(|t| *t = 0.0);
            Ok(relaxed)
        }
    }
}
