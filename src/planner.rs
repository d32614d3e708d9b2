//! The motion planner of section V, steps (a)-(g): a straight-line task at
//! constant speed, joint rates from eq. (18) or eq. (21), integrated by the
//! classical fourth-order Runge-Kutta method.
//!
//! A [`Planner`] holds the state and can be stepped one RK4 step at a time;
//! target, obstacles, mode and gains may change between steps (the browser
//! demo re-plans a new straight line from the current end effector when the
//! user drags the target). [`Planner::run`] integrates a whole scene.

use std::fmt;
use std::str::FromStr;
use std::sync::Arc;

use nalgebra::{DVector, Matrix2xX, MatrixXx2, Vector2};
use serde::{Deserialize, Serialize};

use crate::error::{positive, Error, Result};
use crate::ik::{self, DampingSchedule};
use crate::obstacle::{self, Obstacle};
use crate::scene::{self, Scene};

/// Final end-effector error below which a run counts as having reached its
/// target (5 mm, the acceptance bound for the network cases).
pub const REACH_TOLERANCE: f64 = 5e-3;

/// How `Phi` and `v` are computed (paper section VI).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Mode {
    /// No provision for obstacle avoidance: `v = 0`, eqs. (17)-(18) (Figs. 2, 7).
    None,
    /// Numerical approach: eqs. (17)-(18) with `v` from eq. (14) (Figs. 3, 8).
    Numerical,
    /// Case 1: `Phi` by a network, `v` numerically, eq. (21) (Figs. 4, 9).
    Case1,
    /// Case 2: `Phi` numerically, `v` by a network (Figs. 5, 10).
    Case2,
    /// Case 3: both `Phi` and `v` by networks, eq. (21) (Figs. 6, 11).
    Case3,
}

impl Mode {
    /// All five modes, in the paper's order.
    pub const ALL: [Mode; 5] = [
        Mode::None,
        Mode::Numerical,
        Mode::Case1,
        Mode::Case2,
        Mode::Case3,
    ];

    /// The name used on the command line, in JSON and in the page.
    pub fn name(self) -> &'static str {
        match self {
            Mode::None => "none",
            Mode::Numerical => "numerical",
            Mode::Case1 => "case1",
            Mode::Case2 => "case2",
            Mode::Case3 => "case3",
        }
    }

    /// Whether `Phi` comes from a network (Cases 1 and 3).
    pub fn learned_phi(self) -> bool {
        matches!(self, Mode::Case1 | Mode::Case3)
    }

    /// Whether `v` comes from a network (Cases 2 and 3).
    pub fn learned_v(self) -> bool {
        matches!(self, Mode::Case2 | Mode::Case3)
    }

    /// Whether the mode avoids obstacles at all.
    pub fn avoids(self) -> bool {
        self != Mode::None
    }
}

impl fmt::Display for Mode {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Mode {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        Mode::ALL
            .into_iter()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                Error::InvalidValue(format!(
                    "unknown mode '{s}': use none, numerical, case1, case2 or case3"
                ))
            })
    }
}

/// Learned replacements for `Phi(theta)` (eq. 19) and for the obstacle
/// gradient of eqs. (14)-(15). Implemented by the trained networks.
pub trait Surrogate: Send + Sync {
    /// Learned `Phi(theta)`, an `n x 2` matrix.
    fn phi(&self, theta: &DVector<f64>) -> Result<MatrixXx2<f64>>;
    /// Learned area gradient `g(theta, O)` with `v = (lambda / 4) g`
    /// (see [`obstacle::area_gradient`]).
    fn area_gradient(&self, theta: &DVector<f64>, o: &Vector2<f64>) -> Result<DVector<f64>>;
    /// Whether `theta` lies in the range the `Phi` network was trained on.
    fn phi_in_range(&self, theta: &DVector<f64>) -> bool;
    /// Whether `(theta, O)` lies in the range the `v` network was trained on.
    fn v_in_range(&self, theta: &DVector<f64>, o: &Vector2<f64>) -> bool;
}

/// The straight line being tracked: from `start` at time `t0` to `end` at
/// `t0 + duration`, at constant speed, then holding still at `end`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Line {
    /// End-effector position where the line starts.
    pub start: [f64; 2],
    /// End of the line (the target).
    pub end: [f64; 2],
    /// Time at which the line starts (s).
    pub t0: f64,
    /// Time the line takes (s); a whole number of RK4 steps.
    pub duration: f64,
}

impl Line {
    fn start_v(&self) -> Vector2<f64> {
        Vector2::new(self.start[0], self.start[1])
    }
    fn end_v(&self) -> Vector2<f64> {
        Vector2::new(self.end[0], self.end[1])
    }

    /// Reference point `X_ref(t)` on the line.
    pub fn reference(&self, t: f64) -> Vector2<f64> {
        let s = ((t - self.t0) / self.duration).clamp(0.0, 1.0);
        self.start_v() + s * (self.end_v() - self.start_v())
    }

    /// Constant task velocity `Xdot` while the line runs, zero before and after.
    /// Evaluated at a step's midpoint so that every RK4 stage of a step sees the
    /// same `Xdot`.
    fn velocity_at(&self, t_mid: f64) -> Vector2<f64> {
        if t_mid > self.t0 && t_mid < self.t0 + self.duration {
            (self.end_v() - self.start_v()) / self.duration
        } else {
            Vector2::zeros()
        }
    }
}

/// The state after one integration step (or at the start).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Sample {
    /// Time (s).
    pub t: f64,
    /// Joint angles (rad).
    pub theta: Vec<f64>,
    /// Joint positions `P(0)..P(n)`, `P(0)` first.
    pub joints: Vec<[f64; 2]>,
    /// End effector `X = P(n)`.
    pub ee: [f64; 2],
    /// Straight-line reference point at `t`.
    pub reference: [f64; 2],
    /// Distance from the end effector to the reference.
    pub tracking_error: f64,
    /// Smallest distance from an obstacle centre to a moving link (none without obstacles).
    pub distance: Option<f64>,
    /// Whether a link is inside an obstacle disc now.
    pub collision: bool,
    /// Damping `delta` in force at this pose.
    pub delta: f64,
    /// Manipulability `sqrt(det(J J^T))`.
    pub manipulability: f64,
    /// Whether the state is inside the trained range of the networks this mode uses
    /// (always true for numerical modes).
    pub in_range: bool,
}

/// What a run achieved, over every step since the last reset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Mode of the last step.
    pub mode: Mode,
    /// RK4 steps taken.
    pub steps: usize,
    /// Time reached (s).
    pub t: f64,
    /// Smallest obstacle-centre-to-link distance over all steps (none without obstacles).
    pub min_distance: Option<f64>,
    /// Whether a link entered an obstacle disc at any step.
    pub collided: bool,
    /// Distance from the end effector to the target now.
    pub final_error: f64,
    /// Largest distance from the end effector to the reference.
    pub max_tracking_error: f64,
    /// `final_error <= REACH_TOLERANCE`.
    pub reached: bool,
    /// Whether the target lies in the arm's workspace at all.
    pub target_reachable: bool,
    /// Steps at which a network's input left its trained range.
    pub out_of_range_steps: usize,
    /// Largest damping `delta` used.
    pub max_delta: f64,
    /// Whether the damping schedule was switched on automatically because the
    /// target lies outside the workspace (with `delta = 0` a stretched arm has
    /// unbounded joint rates).
    pub auto_damping: bool,
}

/// A whole run: every sample from `t = 0` to `tf`, and the summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Trajectory {
    /// Mode used.
    pub mode: Mode,
    /// One sample per RK4 step, the initial state first.
    pub steps: Vec<Sample>,
    /// Outcome.
    pub summary: Summary,
}

#[derive(Debug, Clone, Copy)]
struct Stats {
    steps: usize,
    min_distance: Option<f64>,
    collided: bool,
    max_tracking_error: f64,
    out_of_range_steps: usize,
    max_delta: f64,
}

impl Stats {
    fn new() -> Self {
        Self {
            steps: 0,
            min_distance: None,
            collided: false,
            max_tracking_error: 0.0,
            out_of_range_steps: 0,
            max_delta: 0.0,
        }
    }

    fn record(&mut self, s: &Sample) {
        if let Some(d) = s.distance {
            self.min_distance = Some(self.min_distance.map_or(d, |m| m.min(d)));
        }
        self.collided |= s.collision;
        self.max_tracking_error = self.max_tracking_error.max(s.tracking_error);
        if !s.in_range {
            self.out_of_range_steps += 1;
        }
        self.max_delta = self.max_delta.max(s.delta);
    }
}

/// The motion planner: state plus everything needed to take the next step.
#[derive(Clone)]
pub struct Planner {
    scene: Scene,
    mode: Mode,
    networks: Option<Arc<dyn Surrogate>>,
    theta: DVector<f64>,
    step_index: usize,
    t: f64,
    line: Line,
    stats: Stats,
    auto_damping: bool,
}

impl fmt::Debug for Planner {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Planner")
            .field("mode", &self.mode)
            .field("t", &self.t)
            .field("theta", &self.theta.as_slice())
            .field("networks", &self.networks.is_some())
            .finish()
    }
}

impl Planner {
    /// A planner at the scene's start. Network modes need `networks`.
    ///
    /// A target outside the workspace is legal: the damping schedule is then
    /// switched on (and the summary says so), so the arm stretches towards it
    /// with bounded joint rates instead of blowing up.
    pub fn new(mut scene: Scene, mode: Mode, networks: Option<Arc<dyn Surrogate>>) -> Result<Self> {
        scene.validate()?;
        check_networks(mode, &networks)?;
        let auto_damping = needs_auto_damping(&scene);
        if auto_damping {
            scene.damping = Some(DampingSchedule::default());
        }
        let theta = scene.theta0_vector();
        let start = scene.arm.forward(&theta);
        let line = Line {
            start: [start[0], start[1]],
            end: scene.target,
            t0: 0.0,
            duration: scene.tf,
        };
        let mut p = Self {
            scene,
            mode,
            networks,
            theta,
            step_index: 0,
            t: 0.0,
            line,
            stats: Stats::new(),
            auto_damping,
        };
        let s = p.sample();
        p.stats.record(&s);
        Ok(p)
    }

    /// Integrates a whole scene from `t = 0` to `tf` (the paper's runs).
    pub fn run(
        scene: Scene,
        mode: Mode,
        networks: Option<Arc<dyn Surrogate>>,
    ) -> Result<Trajectory> {
        let mut p = Self::new(scene, mode, networks)?;
        let n = p.scene.steps();
        let mut steps = Vec::with_capacity(n + 1);
        steps.push(p.sample());
        for _ in 0..n {
            steps.push(p.step()?);
        }
        Ok(Trajectory {
            mode,
            steps,
            summary: p.summary(),
        })
    }

    /// Back to the scene's start pose at `t = 0`, with a fresh summary.
    pub fn reset(&mut self) {
        let scene = self.scene.clone();
        let networks = self.networks.clone();
        // The scene was validated when it entered the planner.
        if let Ok(mut p) = Self::new(scene, self.mode, networks) {
            p.auto_damping |= self.auto_damping;
            *self = p;
        }
    }

    /// The scene (with any target, obstacle or gain changes applied).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The current mode.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// Current time (s).
    pub fn time(&self) -> f64 {
        self.t
    }

    /// Current joint angles.
    pub fn theta(&self) -> &DVector<f64> {
        &self.theta
    }

    /// The line being tracked.
    pub fn line(&self) -> Line {
        self.line
    }

    /// The networks in use, if any.
    pub fn networks(&self) -> Option<&Arc<dyn Surrogate>> {
        self.networks.as_ref()
    }

    /// Switches mode; network modes need networks.
    pub fn set_mode(&mut self, mode: Mode) -> Result<()> {
        check_networks(mode, &self.networks)?;
        self.mode = mode;
        Ok(())
    }

    /// Installs (or removes) the trained networks.
    pub fn set_networks(&mut self, networks: Option<Arc<dyn Surrogate>>) -> Result<()> {
        check_networks(self.mode, &networks)?;
        self.networks = networks;
        Ok(())
    }

    /// Re-plans: a new straight line from the current end effector to `target`,
    /// starting now and lasting `duration` seconds (rounded up to whole steps).
    pub fn set_target(&mut self, target: [f64; 2], duration: f64) -> Result<()> {
        crate::error::coordinate("target x", target[0])?;
        crate::error::coordinate("target y", target[1])?;
        positive("line duration", duration)?;
        let steps = (duration / self.scene.dt - 1e-9).ceil().max(1.0);
        let x = self.scene.arm.forward(&self.theta);
        self.scene.target = target;
        if needs_auto_damping(&self.scene) {
            self.scene.damping = Some(DampingSchedule::default());
            self.auto_damping = true;
        }
        self.line = Line {
            start: [x[0], x[1]],
            end: target,
            t0: self.t,
            duration: steps * self.scene.dt,
        };
        Ok(())
    }

    /// Replaces the obstacles; takes effect at the next step.
    pub fn set_obstacles(&mut self, obstacles: Vec<Obstacle>) -> Result<()> {
        for ob in &obstacles {
            ob.validate(&self.scene.arm)?;
        }
        self.scene.obstacles = obstacles;
        Ok(())
    }

    /// Sets `lambda`, the gain of the obstacle vector.
    pub fn set_lambda(&mut self, lambda: f64) -> Result<()> {
        scene::validate_lambda(lambda)?;
        self.scene.lambda = lambda;
        Ok(())
    }

    /// Sets the constant damping `delta`.
    pub fn set_delta(&mut self, delta: f64) -> Result<()> {
        scene::validate_delta(delta)?;
        self.scene.delta = delta;
        Ok(())
    }

    /// Switches the damping schedule on (`Some`) or off (`None`).
    pub fn set_damping(&mut self, damping: Option<DampingSchedule>) -> Result<()> {
        if let Some(d) = &damping {
            d.validate()?;
        }
        self.scene.damping = damping;
        Ok(())
    }

    /// Sets the closed-loop gain `K` (0 = open loop, as in the paper).
    pub fn set_feedback_gain(&mut self, gain: f64) -> Result<()> {
        scene::validate_gain(gain, self.scene.dt)?;
        self.scene.feedback_gain = gain;
        Ok(())
    }

    /// Damping `delta` in force at Jacobian `j`: the constant `delta` plus the
    /// schedule's share.
    pub fn delta_at(&self, j: &Matrix2xX<f64>) -> f64 {
        self.scene.delta + self.scene.damping.map_or(0.0, |d| d.delta(j))
    }

    /// Null-space vector `v` at `theta` in the current mode (zero in mode `none`).
    pub fn null_space(&self, theta: &DVector<f64>) -> Result<DVector<f64>> {
        let arm = &self.scene.arm;
        match self.mode {
            Mode::None => Ok(DVector::zeros(arm.dof())),
            Mode::Numerical | Mode::Case1 => Ok(obstacle::null_space_vector(
                arm,
                theta,
                &self.scene.obstacles,
                self.scene.lambda,
            )),
            Mode::Case2 | Mode::Case3 => {
                let nets = self.nets()?;
                let mut g = DVector::zeros(arm.dof());
                for ob in &self.scene.obstacles {
                    g += nets.area_gradient(theta, &ob.point())?;
                }
                Ok(g * (self.scene.lambda / 4.0))
            }
        }
    }

    /// Joint rates `theta_dot(theta)` for task velocity `xdot`: eq. (18) in
    /// modes `none`, `numerical` and Case 2, eq. (21) in Cases 1 and 3.
    pub fn theta_dot(&self, theta: &DVector<f64>, xdot: &Vector2<f64>) -> Result<DVector<f64>> {
        let arm = &self.scene.arm;
        let j = arm.jacobian(theta);
        let delta = self.delta_at(&j);
        let v = self.null_space(theta)?;
        if self.mode.learned_phi() {
            let nets = self.nets()?;
            // The network learnt Phi at delta = 0 (as in the paper). Where the
            // damping schedule is active the pose is near-singular, outside any
            // range a network can fit, so the damped numerical Phi takes over.
            let phi = if delta > 0.0 {
                ik::phi(&j, delta)?
            } else {
                nets.phi(theta)?
            };
            Ok(ik::theta_dot_network(&phi, &j, xdot, &v))
        } else {
            ik::theta_dot_symmetric(&j, xdot, &v, delta)
        }
    }

    fn nets(&self) -> Result<&Arc<dyn Surrogate>> {
        self.networks.as_ref().ok_or_else(|| {
            Error::NetworksUnavailable(format!("mode {} needs trained networks", self.mode))
        })
    }

    /// Commanded task velocity at time `t` and pose `theta`: the line's `Xdot`
    /// plus, when `feedback_gain > 0`, `K (X_ref(t) - X(theta))`.
    fn task_velocity(
        &self,
        line_xdot: &Vector2<f64>,
        t: f64,
        theta: &DVector<f64>,
    ) -> Vector2<f64> {
        let k = self.scene.feedback_gain;
        if k > 0.0 {
            line_xdot + k * (self.line.reference(t) - self.scene.arm.forward(theta))
        } else {
            *line_xdot
        }
    }

    /// One classical RK4 step of size `dt` (section V, step e). On error the
    /// state is left unchanged.
    pub fn step(&mut self) -> Result<Sample> {
        let h = self.scene.dt;
        let t = self.t;
        let xdot = self.line.velocity_at(t + 0.5 * h);
        let th = &self.theta;
        let f = |tt: f64, theta: &DVector<f64>| -> Result<DVector<f64>> {
            let xd = self.task_velocity(&xdot, tt, theta);
            self.theta_dot(theta, &xd)
        };
        let k1 = f(t, th)?;
        let k2 = f(t + 0.5 * h, &(th + 0.5 * h * &k1))?;
        let k3 = f(t + 0.5 * h, &(th + 0.5 * h * &k2))?;
        let k4 = f(t + h, &(th + h * &k3))?;
        let next = th + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        if next.iter().any(|x| !x.is_finite()) {
            return Err(Error::Diverged(format!(
                "non-finite joint angles after the step at t = {t:.3} s; switch damping on"
            )));
        }
        self.theta = next;
        self.step_index += 1;
        self.t = self.step_index as f64 * h;
        let s = self.sample();
        self.stats.record(&s);
        self.stats.steps += 1;
        Ok(s)
    }

    /// A snapshot of the current state.
    pub fn sample(&self) -> Sample {
        let arm = &self.scene.arm;
        let joints = arm.joints(&self.theta);
        let ee = joints[joints.len() - 1];
        let reference = self.line.reference(self.t);
        let mut distance: Option<f64> = None;
        let mut collision = false;
        for ob in &self.scene.obstacles {
            let d = obstacle::clearance(&joints, &ob.point());
            collision |= d < ob.radius;
            distance = Some(distance.map_or(d, |m| m.min(d)));
        }
        let j = arm.jacobian(&self.theta);
        Sample {
            t: self.t,
            theta: self.theta.iter().cloned().collect(),
            joints: joints.iter().map(|p| [p[0], p[1]]).collect(),
            ee: [ee[0], ee[1]],
            reference: [reference[0], reference[1]],
            tracking_error: (ee - reference).norm(),
            distance,
            collision,
            delta: self.delta_at(&j),
            manipulability: ik::manipulability(&j),
            in_range: self.in_range(),
        }
    }

    /// Whether the networks the current mode uses see inputs inside their
    /// trained range (true for numerical modes).
    pub fn in_range(&self) -> bool {
        let Some(nets) = &self.networks else {
            return true;
        };
        let phi_ok = !self.mode.learned_phi() || nets.phi_in_range(&self.theta);
        let v_ok = !self.mode.learned_v()
            || self
                .scene
                .obstacles
                .iter()
                .all(|ob| nets.v_in_range(&self.theta, &ob.point()));
        phi_ok && v_ok
    }

    /// Outcome since the last reset.
    pub fn summary(&self) -> Summary {
        let x = self.scene.arm.forward(&self.theta);
        let target = self.scene.target_vector();
        let final_error = (x - target).norm();
        Summary {
            mode: self.mode,
            steps: self.stats.steps,
            t: self.t,
            min_distance: self.stats.min_distance,
            collided: self.stats.collided,
            final_error,
            max_tracking_error: self.stats.max_tracking_error,
            reached: final_error <= REACH_TOLERANCE,
            target_reachable: self.scene.arm.can_reach(&target),
            out_of_range_steps: self.stats.out_of_range_steps,
            max_delta: self.stats.max_delta,
            auto_damping: self.auto_damping,
        }
    }
}

fn needs_auto_damping(scene: &Scene) -> bool {
    scene.damping.is_none() && !scene.arm.can_reach(&scene.target_vector())
}

fn check_networks(mode: Mode, networks: &Option<Arc<dyn Surrogate>>) -> Result<()> {
    if (mode.learned_phi() || mode.learned_v()) && networks.is_none() {
        return Err(Error::NetworksUnavailable(format!(
            "mode {mode} needs trained networks and none are loaded"
        )));
    }
    Ok(())
}
