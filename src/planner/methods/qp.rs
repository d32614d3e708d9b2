//! A quadratic program with velocity dampers, the modern reactive
//! controller (NEO, Haviland and Corke 2021; the collision-avoidance limits
//! of mink and dm_robotics). Decision variables `theta_dot` (n) and a task
//! slack `s` (2):
//!
//! minimise `(1/2) |theta_dot - v|^2 + (w/2) |s|^2`
//! subject to `J theta_dot + s = Xdot` (the commanded task velocity, the
//! feedback term included) and, for every link-obstacle pair closer than
//! the influence distance `d_i` ([`crate::clearance`]), the velocity damper
//! `n^T J_p theta_dot >= -xi (c - d_s) / (d_i - d_s)`.
//!
//! `v` is the paper's area vector (eq. 14 with its gain `lambda`; `lambda = 0`
//! gives the minimum-norm rates, NEO's setting without its manipulability
//! term). With no damper active the solution is
//! `v + J^T (J J^T + I / w)^-1 (Xdot - J v)`: eq. (5) with damped least
//! squares, `delta = 1 / w`. The scene's `delta` and the damping schedule add
//! to that damping (`1 / w` becomes `1 / w + delta`), so the task slack
//! grows near singular poses as in the other methods.
//!
//! Eliminating `s = Xdot - J theta_dot` leaves `n` variables:
//! `H = I + w' J^T J`, `g = v + w' J^T Xdot`, `w' = 1 / (1 / w + delta)`,
//! solved by [`crate::qp::solve`] (Goldfarb-Idnani) only when the
//! unconstrained solution breaks a damper.
//!
//! Where no rate satisfies every damper (an arm already inside `d_s` of
//! obstacles on both sides), the dampers' bounds are relaxed to
//! `min(bound, 0)`: no link may approach an obstacle, none is required to
//! move away. `theta_dot = 0` satisfies that, so the relaxed program always
//! has a solution; the step's note (and the run's summary) say when it was
//! needed.

use super::paper::{obstacle_vector, V};
use super::{Context, Entry, Group, Method, MethodInfo, Needs, Note, Rule};
use crate::clearance::Pairs;
use crate::error::{Error, Result};
use crate::ik;
use crate::kinematics::Pose;
use crate::qp as solver;
use super::influence::{INFLUENCE, STOP_DISTANCE};
use super::paper::{DELTA, LAMBDA};
use crate::scene::{Param, Scale};

/// Damper gain `xi` (m/s): how fast a link may approach an obstacle at the
/// influence distance (NEO's order of magnitude).
pub static DAMPER_GAIN: Param = Param {
    name: "damper_gain",
    flag: "--damper-gain",
    label: "Damper gain ξ",
    what: "damper gain xi",
    help: "Damper gain xi: the approach speed allowed at d_i (qp)",
    unit: "m/s",
    bounds: (1e-3, 100.0),
    default: 1.0,
    slider: (0.1, 5.0, 0.1),
    scale: Scale::Linear,
    count: false,
    below: None,
    above: None,
};

/// Weight `w` of the task slack: with no damper active the rates are
/// eq. (5) with damped least squares, `delta = 1 / w`. Below 1 the task
/// hardly counts; above 1e12 `1 / w` drowns in the rounding of `J J^T`.
pub static SLACK_WEIGHT: Param = Param {
    name: "slack_weight",
    flag: "--slack-weight",
    label: "Slack weight w",
    what: "slack weight w",
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

/// The joints' rate limit (rad/s), as NEO bounds a robot's joint
/// velocities: without it, where a damper and the task pull apart the
/// program buys the task with unbounded rates. The paper's tasks need 0.54.
pub static RATE_LIMIT: Param = Param {
    name: "rate_limit",
    flag: "--rate-limit",
    label: "Joint rate limit",
    what: "joint rate limit",
    help: "Limit of every joint's rate (qp)",
    unit: "rad/s",
    bounds: (1e-3, 1000.0),
    default: 1.5,
    slider: (0.2, 10.0, 0.1),
    scale: Scale::Linear,
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
        colour: "#17becf",
        params: &[
            &LAMBDA,
            &INFLUENCE,
            &STOP_DISTANCE,
            &DAMPER_GAIN,
            &SLACK_WEIGHT,
            &RATE_LIMIT,
            &DELTA,
        ],
    },
    rule: |n| Box::new(Qp::new(n)),
};

/// The rule's scratch space, sized for an `n`-joint arm and grown (once)
/// when more dampers appear than ever before.
#[derive(Clone)]
struct Qp {
    pairs: Pairs,
    /// The area vector `v`, and one obstacle's gradient.
    v: Vec<f64>,
    g: Vec<f64>,
    /// `H` (row-major `n x n`) and the linear term.
    h: Vec<f64>,
    lin: Vec<f64>,
    /// Damper rows `n^T J_p` (row-major) and their bounds.
    a: Vec<f64>,
    b: Vec<f64>,
    ws: solver::Workspace,
}

impl Qp {
    fn new(n: usize) -> Self {
        // Dampers for 8 obstacles per link, and the rate limits.
        let m = 8 * n + 2 * n;
        Self {
            pairs: Pairs::with_capacity(m),
            v: vec![0.0; n],
            g: vec![0.0; n],
            h: vec![0.0; n * n],
            lin: vec![0.0; n],
            a: Vec::with_capacity(m * n),
            b: Vec::with_capacity(m),
            ws: solver::Workspace::with_capacity(n, m),
        }
    }
}

impl Rule for Qp {
    fn theta_dot(
        &mut self,
        cx: &Context<'_>,
        pose: &Pose,
        xdot: [f64; 2],
        out: &mut [f64],
    ) -> Result<Note> {
        let n = pose.dof();
        obstacle_vector(QP, V::Exact, cx, pose, &mut self.g, &mut self.v)?;
        let s = cx.scene;
        let (influence, stop) = (s.param(&INFLUENCE), s.param(&STOP_DISTANCE));
        let damper_gain = s.param(&DAMPER_GAIN);
        let damping = 1.0 / s.param(&SLACK_WEIGHT) + s.param(&DELTA) + cx.scheduled_delta(pose);
        let jac = pose.jacobian();
        // The unconstrained minimum: eq. (5) with damped least squares.
        ik::theta_dot_symmetric_into(jac, xdot, &self.v, damping, out)?;
        // The dampers of the pairs within the influence distance.
        self.pairs.update(pose, &s.obstacles, influence);
        self.a.clear();
        self.b.clear();
        let mut broken = false;
        for pair in self.pairs.as_slice() {
            let at = self.a.len();
            self.a.resize(at + n, 0.0);
            pair.rate_row(pose, &mut self.a[at..]);
            let bound = -damper_gain * (pair.clearance - stop) / (influence - stop);
            let rate: f64 = self.a[at..].iter().zip(out.iter()).map(|(r, t)| r * t).sum();
            broken |= rate < bound;
            self.b.push(bound);
        }
        // The joints' rate limits, as rows +-e_i.
        let limit = s.param(&RATE_LIMIT);
        for (i, &rate) in out.iter().enumerate() {
            for sign in [1.0, -1.0] {
                let at = self.a.len();
                self.a.resize(at + n, 0.0);
                self.a[at + i] = sign;
                self.b.push(-limit);
                broken |= sign * rate < -limit;
            }
        }
        if !broken {
            return Ok(Note::default());
        }
        // Some damper binds: the program over theta_dot,
        // H = I + w' J^T J, g = v + w' J^T Xdot.
        let w = 1.0 / damping;
        for r in 0..n {
            let (jr0, jr1) = (jac[2 * r], jac[2 * r + 1]);
            for c in 0..n {
                let jtj = jr0 * jac[2 * c] + jr1 * jac[2 * c + 1];
                self.h[r * n + c] = f64::from(u8::from(r == c)) + w * jtj;
            }
            self.lin[r] = self.v[r] + w * (jr0 * xdot[0] + jr1 * xdot[1]);
        }
        match solver::solve(&mut self.ws, &self.h, &self.lin, &self.a, &self.b, out) {
            Ok(_) => Ok(Note::default()),
            Err(Error::Infeasible { .. }) => {
                // No link may approach; none must move away (see the module
                // documentation): theta_dot = 0 is feasible.
                self.b.iter_mut().for_each(|b| *b = b.min(0.0));
                solver::solve(&mut self.ws, &self.h, &self.lin, &self.a, &self.b, out)?;
                Ok(Note {
                    relaxed: true,
                    ..Note::default()
                })
            }
            Err(e) => Err(e),
        }
    }

    fn null_space(&mut self, cx: &Context<'_>, pose: &Pose, v: &mut [f64]) -> Result<bool> {
        obstacle_vector(QP, V::Exact, cx, pose, &mut self.g, v)?;
        Ok(true)
    }

    fn boxed_clone(&self) -> Box<dyn Rule> {
        Box::new(self.clone())
    }
}
