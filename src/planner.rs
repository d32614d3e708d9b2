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

use nalgebra::{DVector, Matrix2xX, Vector2};
use serde::{Deserialize, Serialize};

use crate::arm::Arm;
use crate::error::{positive, Error, Result};
use crate::ik::{self, DampingSchedule};
use crate::kinematics::Pose;
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

    /// The name people read in menus and legends: "No avoidance",
    /// "Numerical", "Case 1", "Case 2", "Case 3" (the paper's terms).
    pub fn label(self) -> &'static str {
        match self {
            Mode::None => "No avoidance",
            Mode::Numerical => "Numerical",
            Mode::Case1 => "Case 1",
            Mode::Case2 => "Case 2",
            Mode::Case3 => "Case 3",
        }
    }

    /// What the mode computes, in one line.
    pub fn description(self) -> &'static str {
        match self {
            Mode::None => "v = 0, no obstacle avoidance",
            Mode::Numerical => "Φ and v computed exactly",
            Mode::Case1 => "Φ by a network, v exact",
            Mode::Case2 => "Φ exact, v by a network",
            Mode::Case3 => "Φ and v by networks",
        }
    }

    /// `label: description`, for titles and captions.
    pub fn title(self) -> String {
        format!("{}: {}", self.label(), self.description())
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
            .ok_or_else(|| Error::UnknownName {
                kind: "mode",
                name: s.into(),
                choices: "none, numerical, case1, case2 or case3",
            })
    }
}

/// Learned replacements for `Phi(theta)` (eq. 19) and for the obstacle
/// gradient of eqs. (14)-(15). Implemented by the trained networks.
///
/// Every method reads a [`Pose`] (the planner's one kinematics pass, whose
/// `theta` was validated when it entered the planner) and fills a slice, so
/// the planner's step allocates nothing.
pub trait Surrogate: Send + Sync {
    /// The arm the networks were trained for; the planner refuses them for
    /// any other.
    fn arm(&self) -> &Arm;
    /// Learned `Phi(theta)` at `delta = 0`, row-major `n x 2` into `out`
    /// (`2n` entries).
    fn phi(&self, pose: &Pose, out: &mut [f64]) -> Result<()>;
    /// Learned area gradient `g(theta, O)` into `out` (`n` entries), with
    /// `v = (lambda / 4) g` (see [`obstacle::area_gradient`]).
    fn area_gradient(&self, pose: &Pose, o: [f64; 2], out: &mut [f64]) -> Result<()>;
    /// Whether the pose lies in the range the `Phi` network was trained on.
    fn phi_in_range(&self, pose: &Pose) -> bool;
    /// Whether `(theta, O)` lies in the range the `v` network was trained on.
    fn v_in_range(&self, pose: &Pose, o: [f64; 2]) -> bool;
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
    /// Whether, in the step that led here, the damping schedule switched on
    /// near a singular pose and the exact damped `Phi` (eq. 20) stood in for
    /// the `Phi` network (Cases 1 and 3 only: no network can fit `Phi` where
    /// it is unbounded).
    pub phi_handover: bool,
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
    /// Steps in which the exact damped `Phi` stood in for the `Phi` network
    /// near a singular pose (see [`Sample::phi_handover`]).
    pub handover_steps: usize,
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
    handover_steps: usize,
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
            handover_steps: 0,
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
        if s.phi_handover {
            self.handover_steps += 1;
        }
    }
}

/// Scratch space the planner owns and reuses at every step (as rapier keeps
/// a solver workspace), so that [`Planner::step`] allocates nothing once the
/// planner exists, in every mode and for any arm.
#[derive(Debug, Clone)]
struct Workspace {
    /// The kinematics of the current state; always up to date. A step's first
    /// RK4 stage reads it, and so does the sample.
    pose: Pose,
    /// The kinematics at an RK4 stage (and for [`Planner::theta_dot_into`]).
    stage: Pose,
    /// `theta` at a stage.
    theta_stage: Vec<f64>,
    /// The state after the step, before it is accepted.
    next: Vec<f64>,
    /// The stage rates `k1..k4`.
    k: [Vec<f64>; 4],
    /// What one rate evaluation needs.
    scratch: Scratch,
}

/// Buffers of one rate evaluation: `v`, one obstacle's gradient and `Phi`.
#[derive(Debug, Clone)]
struct Scratch {
    v: Vec<f64>,
    g: Vec<f64>,
    phi: Vec<f64>,
}

impl Scratch {
    fn new(n: usize) -> Self {
        Self {
            v: vec![0.0; n],
            g: vec![0.0; n],
            phi: vec![0.0; 2 * n],
        }
    }
}

impl Workspace {
    fn new(n: usize) -> Self {
        Self {
            pose: Pose::zeros(n),
            stage: Pose::zeros(n),
            theta_stage: vec![0.0; n],
            next: vec![0.0; n],
            k: [vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]],
            scratch: Scratch::new(n),
        }
    }
}

/// What a rate evaluation reads: the scene, the mode and the networks.
#[derive(Clone, Copy)]
struct Rates<'a> {
    scene: &'a Scene,
    mode: Mode,
    networks: Option<&'a dyn Surrogate>,
}

impl Rates<'_> {
    fn nets(&self) -> Result<&dyn Surrogate> {
        self.networks.ok_or_else(|| {
            Error::NetworksUnavailable(format!("mode {} needs trained networks", self.mode))
        })
    }

    /// Null-space vector `v` at `pose` into `s.v` (zero in mode `none`),
    /// eqs. (14)-(15) summed over the obstacles, numerically or by the network.
    fn null_space(&self, pose: &Pose, s: &mut Scratch) -> Result<()> {
        let scene = self.scene;
        match self.mode {
            Mode::None => s.v.iter_mut().for_each(|x| *x = 0.0),
            Mode::Numerical | Mode::Case1 => obstacle::null_space_vector_into(
                &scene.arm,
                pose,
                &scene.obstacles,
                scene.lambda,
                &mut s.g,
                &mut s.v,
            ),
            Mode::Case2 | Mode::Case3 => {
                let nets = self.nets()?;
                s.v.iter_mut().for_each(|x| *x = 0.0);
                for ob in &scene.obstacles {
                    nets.area_gradient(pose, ob.centre, &mut s.g)?;
                    for (vi, gi) in s.v.iter_mut().zip(&s.g) {
                        *vi += gi;
                    }
                }
                let scale = scene.lambda / 4.0;
                s.v.iter_mut().for_each(|x| *x *= scale);
            }
        }
        Ok(())
    }

    /// The damping schedule's share of `delta` at `pose` (zero when off).
    #[inline]
    fn scheduled_delta(&self, pose: &Pose) -> f64 {
        self.scene
            .damping
            .map_or(0.0, |d| d.delta_at_sigma(pose.sigma_min()))
    }

    /// Joint rates at `pose` for the commanded task velocity `xdot` into
    /// `out`: eq. (18) in modes `none`, `numerical` and Case 2, eq. (21) in
    /// Cases 1 and 3. Returns whether the exact damped `Phi` stood in for the
    /// network (the damping schedule is active: the pose is near-singular,
    /// where `Phi` is unbounded and no network fits it).
    ///
    /// A constant `delta` is applied in every mode; in Cases 1 and 3 to the
    /// network's `Phi` by [`ik::damp_phi`].
    fn theta_dot(
        &self,
        pose: &Pose,
        xdot: [f64; 2],
        s: &mut Scratch,
        out: &mut [f64],
    ) -> Result<bool> {
        self.null_space(pose, s)?;
        let scheduled = self.scheduled_delta(pose);
        let delta = self.scene.delta + scheduled;
        let jac = pose.jacobian();
        if !self.mode.learned_phi() {
            ik::theta_dot_symmetric_into(jac, xdot, &s.v, delta, out)?;
            return Ok(false);
        }
        let handover = scheduled > 0.0;
        if handover {
            ik::phi_into(jac, delta, &mut s.phi)?;
        } else {
            self.nets()?.phi(pose, &mut s.phi)?;
            ik::damp_phi(&mut s.phi, self.scene.delta)?;
        }
        ik::theta_dot_network_into(&s.phi, jac, xdot, &s.v, out)?;
        Ok(handover)
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
    /// The state as the page and the CLI see it, refreshed in place.
    sample: Sample,
    ws: Workspace,
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
        check_networks(mode, &networks, &scene.arm)?;
        let auto_damping = needs_auto_damping(&scene);
        if auto_damping {
            scene.damping = Some(DampingSchedule::default());
        }
        let n = scene.arm.dof();
        let theta = scene.theta0_vector();
        let mut ws = Workspace::new(n);
        ws.pose.update(&scene.arm, theta.as_slice())?;
        let start = ws.pose.end_effector();
        let line = Line {
            start,
            end: scene.target,
            t0: 0.0,
            duration: scene.tf,
        };
        let sample = Sample {
            t: 0.0,
            theta: vec![0.0; n],
            joints: vec![[0.0; 2]; n + 1],
            ee: start,
            reference: start,
            tracking_error: 0.0,
            distance: None,
            collision: false,
            delta: 0.0,
            manipulability: 0.0,
            in_range: true,
            phi_handover: false,
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
            sample,
            ws,
        };
        p.refresh_sample(false);
        p.stats.record(&p.sample);
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
        steps.push(p.sample.clone());
        for _ in 0..n {
            steps.push(p.step()?.clone());
        }
        Ok(Trajectory {
            mode,
            steps,
            summary: p.summary(),
        })
    }

    /// Integrates the scene from `t = 0` to `tf` keeping only the summary:
    /// no sample is stored, so nothing is allocated after the planner is
    /// built (what an atlas of thousands of runs needs).
    pub fn run_summary(
        scene: Scene,
        mode: Mode,
        networks: Option<Arc<dyn Surrogate>>,
    ) -> Result<Summary> {
        let mut p = Self::new(scene, mode, networks)?;
        for _ in 0..p.scene.steps() {
            p.step()?;
        }
        Ok(p.summary())
    }

    /// Back to the scene's start pose at `t = 0`, with a fresh summary.
    /// Allocation-free.
    pub fn reset(&mut self) {
        self.theta.copy_from_slice(&self.scene.theta0);
        // theta0 was validated (length and finiteness) when the scene entered.
        let _ = self.ws.pose.update(&self.scene.arm, self.theta.as_slice());
        self.step_index = 0;
        self.t = 0.0;
        self.line = Line {
            start: self.ws.pose.end_effector(),
            end: self.scene.target,
            t0: 0.0,
            duration: self.scene.tf,
        };
        self.stats = Stats::new();
        self.refresh_sample(false);
        self.stats.record(&self.sample);
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

    /// The kinematics of the current state (joints, Jacobian, ...).
    pub fn pose(&self) -> &Pose {
        &self.ws.pose
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
        check_networks(mode, &self.networks, &self.scene.arm)?;
        self.mode = mode;
        self.resample();
        Ok(())
    }

    /// Installs (or removes) the trained networks. Networks trained for
    /// another arm are refused ([`Error::NetworksForAnotherArm`]).
    pub fn set_networks(&mut self, networks: Option<Arc<dyn Surrogate>>) -> Result<()> {
        check_networks(self.mode, &networks, &self.scene.arm)?;
        self.networks = networks;
        self.resample();
        Ok(())
    }

    /// Re-plans: a new straight line from the current end effector to `target`,
    /// starting now and lasting `duration` seconds (rounded up to whole steps).
    pub fn set_target(&mut self, target: [f64; 2], duration: f64) -> Result<()> {
        crate::error::coordinate("target x", target[0])?;
        crate::error::coordinate("target y", target[1])?;
        positive("line duration", duration)?;
        let steps = (duration / self.scene.dt - 1e-9).ceil().max(1.0);
        self.scene.target = target;
        if needs_auto_damping(&self.scene) {
            self.scene.damping = Some(DampingSchedule::default());
            self.auto_damping = true;
        }
        self.line = Line {
            start: self.ws.pose.end_effector(),
            end: target,
            t0: self.t,
            duration: steps * self.scene.dt,
        };
        self.resample();
        Ok(())
    }

    /// Replaces the obstacles; takes effect at the next step.
    pub fn set_obstacles(&mut self, obstacles: Vec<Obstacle>) -> Result<()> {
        for ob in &obstacles {
            ob.validate(&self.scene.arm)?;
        }
        self.scene.obstacles = obstacles;
        self.resample();
        Ok(())
    }

    /// Sets `lambda`, the gain of the obstacle vector.
    pub fn set_lambda(&mut self, lambda: f64) -> Result<()> {
        scene::validate_lambda(lambda)?;
        self.scene.lambda = lambda;
        Ok(())
    }

    /// Sets the constant damping `delta` (eqs. 6, 17, 20). In Cases 1 and 3
    /// it damps the network's `Phi` through [`ik::damp_phi`].
    pub fn set_delta(&mut self, delta: f64) -> Result<()> {
        scene::validate_delta(delta)?;
        self.scene.delta = delta;
        self.resample();
        Ok(())
    }

    /// Switches the damping schedule on (`Some`) or off (`None`).
    pub fn set_damping(&mut self, damping: Option<DampingSchedule>) -> Result<()> {
        if let Some(d) = &damping {
            d.validate()?;
        }
        self.scene.damping = damping;
        self.resample();
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

    fn rates(&self) -> Rates<'_> {
        Rates {
            scene: &self.scene,
            mode: self.mode,
            networks: self.networks.as_deref(),
        }
    }

    /// Null-space vector `v` at `theta` in the current mode (zero in mode
    /// `none`). A convenience that allocates; the step uses a workspace.
    pub fn null_space(&self, theta: &DVector<f64>) -> Result<DVector<f64>> {
        let n = self.scene.arm.dof();
        let pose = Pose::new(&self.scene.arm, theta.as_slice())?;
        let mut s = Scratch::new(n);
        self.rates().null_space(&pose, &mut s)?;
        Ok(DVector::from_vec(s.v))
    }

    /// Joint rates `theta_dot(theta)` for task velocity `xdot`: eq. (18) in
    /// modes `none`, `numerical` and Case 2, eq. (21) in Cases 1 and 3. A
    /// convenience that allocates; see [`Planner::theta_dot_into`].
    pub fn theta_dot(&self, theta: &DVector<f64>, xdot: &Vector2<f64>) -> Result<DVector<f64>> {
        let n = self.scene.arm.dof();
        let pose = Pose::new(&self.scene.arm, theta.as_slice())?;
        let mut s = Scratch::new(n);
        let mut out = DVector::zeros(n);
        self.rates()
            .theta_dot(&pose, [xdot[0], xdot[1]], &mut s, out.as_mut_slice())?;
        Ok(out)
    }

    /// [`Planner::theta_dot`] into `out` (`n` entries) through the planner's
    /// workspace: one kinematics pass and no allocation. `theta` must have
    /// `n` entries; it is not checked for finiteness (NaN gives NaN rates).
    pub fn theta_dot_into(&mut self, theta: &[f64], xdot: [f64; 2], out: &mut [f64]) -> Result<()> {
        let Self {
            scene,
            mode,
            networks,
            ws,
            ..
        } = self;
        ws.stage.update(&scene.arm, theta)?;
        let rates = Rates {
            scene,
            mode: *mode,
            networks: networks.as_deref(),
        };
        rates.theta_dot(&ws.stage, xdot, &mut ws.scratch, out)?;
        Ok(())
    }

    /// One classical RK4 step of size `dt` (section V, step e), then the new
    /// sample, which the planner keeps (see [`Planner::sample`]). On error
    /// the state is left unchanged. Allocation-free.
    pub fn step(&mut self) -> Result<&Sample> {
        let h = self.scene.dt;
        let t = self.t;
        let line_xdot = self.line.velocity_at(t + 0.5 * h);
        let Self {
            scene,
            mode,
            networks,
            theta,
            line,
            ws,
            ..
        } = self;
        let rates = Rates {
            scene,
            mode: *mode,
            networks: networks.as_deref(),
        };
        let theta = theta.as_slice();
        let gain = scene.feedback_gain;
        // The commanded task velocity at a stage: the line's Xdot plus, when
        // K > 0, K (X_ref(t) - X(theta)).
        let xdot = |tt: f64, pose: &Pose| -> [f64; 2] {
            if gain > 0.0 {
                let r = line.reference(tt);
                let x = pose.end_effector();
                [
                    line_xdot[0] + gain * (r[0] - x[0]),
                    line_xdot[1] + gain * (r[1] - x[1]),
                ]
            } else {
                [line_xdot[0], line_xdot[1]]
            }
        };
        let [k1, k2, k3, k4] = &mut ws.k;
        // Stage 1 reads the kinematics of the current state, computed when
        // the previous step ended.
        let mut handover = rates.theta_dot(&ws.pose, xdot(t, &ws.pose), &mut ws.scratch, k1)?;
        for (stage, (c, tt)) in [(0.5 * h, t + 0.5 * h), (0.5 * h, t + 0.5 * h), (h, t + h)]
            .into_iter()
            .enumerate()
        {
            let (prev, out): (&[f64], &mut [f64]) = match stage {
                0 => (&k1[..], &mut k2[..]),
                1 => (&k2[..], &mut k3[..]),
                _ => (&k3[..], &mut k4[..]),
            };
            for ((s, th), k) in ws.theta_stage.iter_mut().zip(theta).zip(prev) {
                *s = th + c * k;
            }
            ws.stage.update(&scene.arm, &ws.theta_stage)?;
            handover |= rates.theta_dot(&ws.stage, xdot(tt, &ws.stage), &mut ws.scratch, out)?;
        }
        let w = h / 6.0;
        let mut finite = true;
        for (i, next) in ws.next.iter_mut().enumerate() {
            *next = theta[i] + w * (((k1[i] + 2.0 * k2[i]) + 2.0 * k3[i]) + k4[i]);
            finite &= next.is_finite();
        }
        if !finite {
            return Err(Error::Diverged { t });
        }
        self.theta.copy_from_slice(&self.ws.next);
        self.ws.pose.update(&self.scene.arm, &self.ws.next)?;
        self.step_index += 1;
        self.t = self.step_index as f64 * h;
        self.refresh_sample(handover);
        self.stats.record(&self.sample);
        self.stats.steps += 1;
        Ok(&self.sample)
    }

    /// The current state: the start, or the result of the last step. Kept up
    /// to date by the planner (no copy, no allocation).
    pub fn sample(&self) -> &Sample {
        &self.sample
    }

    /// Refreshes the sample after a change of setting (same state, same step).
    fn resample(&mut self) {
        self.refresh_sample(self.sample.phi_handover);
    }

    /// Rewrites the sample in place from the current pose.
    fn refresh_sample(&mut self, phi_handover: bool) {
        let pose = &self.ws.pose;
        let s = &mut self.sample;
        let ee = pose.end_effector();
        let reference = self.line.reference(self.t);
        s.t = self.t;
        s.theta.copy_from_slice(pose.theta());
        s.joints.copy_from_slice(pose.joints());
        s.ee = ee;
        s.reference = [reference[0], reference[1]];
        s.tracking_error = distance(ee, [reference[0], reference[1]]);
        s.distance = None;
        s.collision = false;
        for ob in &self.scene.obstacles {
            let d = pose.clearance(ob.centre);
            s.collision |= d < ob.radius;
            s.distance = Some(s.distance.map_or(d, |m| m.min(d)));
        }
        s.delta = self.scene.delta
            + self
                .scene
                .damping
                .map_or(0.0, |d| d.delta_at_sigma(pose.sigma_min()));
        s.manipulability = pose.manipulability();
        s.in_range = in_range(
            self.mode,
            self.networks.as_deref(),
            pose,
            &self.scene.obstacles,
        );
        s.phi_handover = phi_handover;
    }

    /// Whether the networks the current mode uses see inputs inside their
    /// trained range (true for numerical modes).
    pub fn in_range(&self) -> bool {
        self.sample.in_range
    }

    /// Outcome since the last reset.
    pub fn summary(&self) -> Summary {
        let x = self.ws.pose.end_effector();
        let target = self.scene.target;
        let final_error = distance(x, target);
        Summary {
            mode: self.mode,
            steps: self.stats.steps,
            t: self.t,
            min_distance: self.stats.min_distance,
            collided: self.stats.collided,
            final_error,
            max_tracking_error: self.stats.max_tracking_error,
            reached: final_error <= REACH_TOLERANCE,
            target_reachable: self.scene.arm.can_reach(&self.scene.target_vector()),
            out_of_range_steps: self.stats.out_of_range_steps,
            max_delta: self.stats.max_delta,
            auto_damping: self.auto_damping,
            handover_steps: self.stats.handover_steps,
        }
    }
}

/// Euclidean distance between two points.
#[inline]
fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (a[0] - b[0], a[1] - b[1]);
    (dx * dx + dy * dy).sqrt()
}

/// Whether the networks `mode` uses see `pose` (and every obstacle) inside
/// their trained range.
fn in_range(
    mode: Mode,
    networks: Option<&dyn Surrogate>,
    pose: &Pose,
    obstacles: &[Obstacle],
) -> bool {
    let Some(nets) = networks else {
        return true;
    };
    let phi_ok = !mode.learned_phi() || nets.phi_in_range(pose);
    let v_ok = !mode.learned_v() || obstacles.iter().all(|ob| nets.v_in_range(pose, ob.centre));
    phi_ok && v_ok
}

fn needs_auto_damping(scene: &Scene) -> bool {
    scene.damping.is_none() && !scene.arm.can_reach(&scene.target_vector())
}

/// Network modes need networks, and networks must be trained for `arm`.
fn check_networks(mode: Mode, networks: &Option<Arc<dyn Surrogate>>, arm: &Arm) -> Result<()> {
    match networks {
        None if mode.learned_phi() || mode.learned_v() => Err(Error::NetworksUnavailable(format!(
            "mode {mode} needs trained networks and none are loaded"
        ))),
        Some(n) if n.arm() != arm => {
            let spec = |a: &Arm| (a.post(), a.links().to_vec());
            Err(Error::NetworksForAnotherArm {
                trained: spec(n.arm()),
                arm: spec(arm),
            })
        }
        _ => Ok(()),
    }
}
