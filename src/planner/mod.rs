//! The motion planner of section V, steps (a)-(g): a straight-line task at
//! constant speed (or a circle or a polyline, `path.rs`), joint rates from the chosen method ([`methods`]: the
//! paper's eq. (18) or eq. (21), or a method beyond the paper), integrated
//! by the classical fourth-order Runge-Kutta method.
//!
//! A [`Planner`] holds the state and can be stepped one RK4 step at a time;
//! target, obstacles, method and gains may change between steps (the
//! browser demo re-plans a new straight line from the current end effector
//! when the user drags the target). [`Planner::run`] integrates a whole
//! scene.
//!
//! One file per concern: the state and its construction here, the
//! settings that change it ([`settings`](self)), the RK4 step and rate
//! evaluations (`integrate.rs`), what is observed of the state (`observe.rs`:
//! the sample and the summary), the records (`record.rs`), the learned
//! replacements' interface (`surrogate.rs`) and the methods (`methods/`).

mod along;
mod integrate;
pub mod methods;
mod observe;
pub mod params;
mod path;
mod record;
mod rk4;
pub mod self_motion;
mod settings;
pub mod space;
mod surrogate;

use std::fmt;
use std::sync::Arc;

use nalgebra::DVector;

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::ik::DampingSchedule;
use crate::kinematics::Pose;
use crate::scene::Scene;

pub use methods::{Group, Method, MethodInfo, Needs};
pub use path::Track;
pub use record::{Line, Sample, Summary, Trajectory};
pub use surrogate::Surrogate;

use methods::Rule;
use record::Stats;
use rk4::Rk4;

/// Final end-effector error below which a run counts as having reached its
/// target (5 mm, the acceptance bound for the network cases).
pub const REACH_TOLERANCE: f64 = 5e-3;

/// The motion planner: state plus everything needed to take the next step.
#[derive(Clone)]
pub struct Planner {
    scene: Scene,
    method: Method,
    networks: Option<Arc<dyn Surrogate>>,
    theta: DVector<f64>,
    step_index: usize,
    t: f64,
    track: Track,
    stats: Stats,
    auto_damping: bool,
    /// Whether every point of the track lies in the arm's reach (found
    /// where the track is made: the page's state reads it every frame).
    reachable: bool,
    /// The state as the page and the CLI see it, refreshed in place.
    sample: Sample,
    ws: Workspace,
}

/// Scratch space the planner owns and reuses at every step (as rapier keeps
/// a solver workspace), so that [`Planner::step`] allocates nothing once the
/// planner exists, with every method and for any arm.
#[derive(Clone)]
struct Workspace {
    /// The kinematics of the current state; always up to date. A step's first
    /// RK4 stage reads it, and so does the sample.
    pose: Pose,
    /// The kinematics at an RK4 stage (and for [`Planner::theta_dot_into`]).
    stage: Pose,
    /// The RK4 step's scratch space (the stage rates, a stage's angles,
    /// the state after the step).
    rk4: Rk4,
    /// The method's computation, with its own scratch space.
    rule: Box<dyn Rule>,
}

impl Workspace {
    fn new(n: usize, method: Method) -> Self {
        Self {
            pose: Pose::zeros(n),
            stage: Pose::zeros(n),
            rk4: Rk4::new(n),
            rule: method.rule(n),
        }
    }
}

impl fmt::Debug for Planner {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Planner")
            .field("method", &self.method)
            .field("t", &self.t)
            .field("theta", &self.theta.as_slice())
            .field("networks", &self.networks.is_some())
            .finish()
    }
}

impl Planner {
    /// A planner at the scene's start. Methods that use networks need
    /// `networks`, trained for the scene's arm.
    ///
    /// A target outside the workspace is legal: the damping schedule is then
    /// switched on (and the summary says so), so the arm stretches towards it
    /// with bounded joint rates instead of blowing up.
    pub fn new(
        mut scene: Scene,
        method: Method,
        networks: Option<Arc<dyn Surrogate>>,
    ) -> Result<Self> {
        scene.validate()?;
        check_networks(method, &networks, &scene.arm)?;
        let n = scene.arm.dof();
        let theta = scene.theta0_vector();
        let mut ws = Workspace::new(n, method);
        ws.pose.update(&scene.arm, theta.as_slice())?;
        let start = ws.pose.end_effector();
        let track = Track::new(scene.path.clone(), start, scene.target, 0.0, scene.tf);
        let reachable = track.reachable(&scene.arm);
        let auto_damping = DampingSchedule::switch_on_out_of_reach(&mut scene.damping, reachable);
        let mut p = Self {
            sample: Sample::zeros(n, start),
            scene,
            method,
            networks,
            theta,
            step_index: 0,
            t: 0.0,
            track,
            stats: Stats::new(),
            auto_damping,
            reachable,
            ws,
        };
        p.refresh_sample(methods::Note::default());
        p.stats.record(&p.sample);
        Ok(p)
    }

    /// Integrates a whole scene from `t = 0` to `tf` (the paper's runs).
    pub fn run(
        scene: Scene,
        method: Method,
        networks: Option<Arc<dyn Surrogate>>,
    ) -> Result<Trajectory> {
        let mut p = Self::new(scene, method, networks)?;
        let n = p.scene.steps();
        let mut steps = Vec::with_capacity(n + 1);
        steps.push(p.sample.clone());
        for _ in 0..n {
            steps.push(p.step()?.clone());
        }
        Ok(Trajectory {
            method,
            steps,
            summary: p.summary(),
        })
    }

    /// Integrates the scene from `t = 0` to `tf` keeping only the summary:
    /// no sample is stored, so nothing is allocated after the planner is
    /// built (what an atlas of thousands of runs needs).
    pub fn run_summary(
        scene: Scene,
        method: Method,
        networks: Option<Arc<dyn Surrogate>>,
    ) -> Result<Summary> {
        let mut p = Self::new(scene, method, networks)?;
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
        // The track's path is the scene's (a new target makes both the
        // line): only its timing and start are renewed, allocating nothing.
        let start = self.ws.pose.end_effector();
        let end = self.scene.path.end(start, self.scene.target);
        self.track.line = Line::new(start, end, 0.0, self.scene.tf);
        self.stats = Stats::new();
        self.refresh_sample(methods::Note::default());
        self.stats.record(&self.sample);
    }

    /// The scene (with any target, obstacle or gain changes applied).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The current method.
    pub fn method(&self) -> Method {
        self.method
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

    /// The straight line being tracked; for a path other than the line,
    /// the straight line from its start to its end (see [`Planner::track`]).
    pub fn line(&self) -> Line {
        self.track.line
    }

    /// The path being tracked, with its timing.
    pub fn track(&self) -> &Track {
        &self.track
    }

    /// Whether every point of the path (the target, for the line) lies in
    /// the arm's reach.
    pub fn reachable(&self) -> bool {
        self.reachable
    }

    /// The networks in use, if any.
    pub fn networks(&self) -> Option<&Arc<dyn Surrogate>> {
        self.networks.as_ref()
    }
}

/// Methods that use networks need them, and networks must be trained for
/// `arm`.
fn check_networks(method: Method, networks: &Option<Arc<dyn Surrogate>>, arm: &Arm) -> Result<()> {
    match networks {
        None if method.uses_networks() => Err(Error::NetworksUnavailable(format!(
            "method {method} needs trained networks and none are loaded"
        ))),
        Some(n) => n.check(arm),
        None => Ok(()),
    }
}
