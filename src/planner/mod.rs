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
//! One planner for every arm: `Planner<A, M>` is generic over the arm
//! model `A` whose hand has `M` coordinates ([`crate::model::Model`] and
//! [`Planned`]): the planar arm (`Planner`, the default, `M = 2`) and a
//! chain in space (`Planner<Chain, 3>`). The task dimension is fixed at
//! compile time, the joint count at run time.
//!
//! One file per concern: the state and its construction here, the
//! settings that change it ([`settings`](self)), the RK4 step and rate
//! evaluations (`integrate.rs`), what is observed of the state (`observe.rs`:
//! the sample and the summary), the records (`record.rs`), the learned
//! replacements' interface (`surrogate.rs`) and the methods (`methods/`).

mod along;
mod integrate;
mod kind;
pub mod methods;
mod observe;
pub mod params;
mod path;
mod record;
mod rk4;
pub mod self_motion;
mod settings;
mod surrogate;

use std::fmt;
use std::sync::Arc;

use nalgebra::DVector;

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::ik::DampingSchedule;
use crate::model::Scene as _;

pub use kind::{Contact, Planned, SceneOf};
pub use methods::{Group, Method, MethodInfo, Needs};
pub use observe::observe_pose;
pub use path::Track;
pub use record::{Line, Sample, Summary, Trajectory};
pub use surrogate::Surrogate;

use methods::Rule;
use record::Stats;
use rk4::Rk4;

/// Final end-effector error below which a run counts as having reached its
/// target (5 mm, the acceptance bound for the network cases).
pub const REACH_TOLERANCE: f64 = 5e-3;

/// Final orientation error below which a run of the pose task counts as
/// having reached its target (rad; about 0.29 degrees, what 5 mm is at a
/// lever of 1 m).
pub const REACH_ANGLE: f64 = 5e-3;

/// The networks a planner of arm `A` may hold.
pub type Networks<A, const M: usize> = Arc<dyn Surrogate<A, M>>;

/// The motion planner of an arm `A` whose hand has `M` coordinates (the
/// planar arm's by default): state plus everything needed to take the next
/// step.
#[derive(Clone)]
pub struct Planner<A: Planned<M> = Arm, const M: usize = 2> {
    scene: A::Scene,
    method: Method,
    networks: Option<Networks<A, M>>,
    theta: DVector<f64>,
    step_index: usize,
    t: f64,
    track: Track<M>,
    stats: Stats,
    auto_damping: bool,
    /// Whether every point of the track lies in the arm's reach (found
    /// where the track is made: the page's state reads it every frame).
    reachable: bool,
    /// The state as the page and the CLI see it, refreshed in place.
    sample: Sample<M, A::Point>,
    ws: Workspace<A, M>,
}

/// Scratch space the planner owns and reuses at every step (as rapier keeps
/// a solver workspace), so that [`Planner::step`] allocates nothing once the
/// planner exists, with every method and for any arm.
#[derive(Clone)]
struct Workspace<A: Planned<M>, const M: usize> {
    /// The kinematics of the current state; always up to date. A step's first
    /// RK4 stage reads it, and so does the sample.
    pose: A::Pose,
    /// The kinematics at an RK4 stage (and for [`Planner::theta_dot_into`]).
    stage: A::Pose,
    /// The RK4 step's scratch space (the stage rates, a stage's angles,
    /// the state after the step).
    rk4: Rk4,
    /// The method's computation, with its own scratch space.
    rule: Box<dyn Rule<A, M>>,
}

impl<A: Planned<M>, const M: usize> Workspace<A, M> {
    fn new(arm: &A, method: Method) -> Result<Self> {
        let n = arm.dof();
        Ok(Self {
            pose: arm.pose(),
            stage: arm.pose(),
            rk4: Rk4::new(n),
            rule: rule_of(method, n)?,
        })
    }
}

/// The rule of `method` for an `n`-joint arm `A`, or why it has none.
fn rule_of<A: Planned<M>, const M: usize>(method: Method, n: usize) -> Result<Box<dyn Rule<A, M>>> {
    A::rule(method.entry())
        .map(|build| build(n))
        .ok_or_else(|| Error::NotInSpace {
            method: method.name(),
            choices: methods::space_names(),
        })
}

impl<A: Planned<M>, const M: usize> fmt::Debug for Planner<A, M> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Planner")
            .field("method", &self.method)
            .field("t", &self.t)
            .field("theta", &self.theta.as_slice())
            .field("networks", &self.networks.is_some())
            .finish()
    }
}

impl<A: Planned<M>, const M: usize> Planner<A, M> {
    /// A planner at the scene's start. Methods that use networks need
    /// `networks`, trained for the scene's arm.
    ///
    /// A target outside the workspace is legal: the damping schedule is then
    /// switched on (and the summary says so), so the arm stretches towards it
    /// with bounded joint rates instead of blowing up.
    pub fn new<S>(mut scene: S, method: Method, networks: Option<Networks<A, M>>) -> Result<Self>
    where
        S: SceneOf<A, M> + crate::model::Scene<A>,
        A: Planned<M, Scene = S>,
    {
        scene.validate()?;
        check_networks(method, &networks, scene.arm())?;
        let n = scene.arm().dof();
        let theta = DVector::from_column_slice(scene.theta0());
        let mut ws = Workspace::new(scene.arm(), method)?;
        scene.arm().update(&mut ws.pose, theta.as_slice())?;
        let start = A::hand(&ws.pose);
        let track = A::track(&scene, start, 0.0, scene.tf())?;
        let reachable = track.all_points(|p| scene.arm().reaches(&ws.pose, p));
        let auto_damping = DampingSchedule::switch_on_out_of_reach(scene.damping_mut(), reachable);
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
    pub fn run<S>(
        scene: S,
        method: Method,
        networks: Option<Networks<A, M>>,
    ) -> Result<Trajectory<M, A::Point>>
    where
        S: SceneOf<A, M> + crate::model::Scene<A>,
        A: Planned<M, Scene = S>,
    {
        Self::new(scene, method, networks)?.run_to_end()
    }

    /// Integrates the scene from `t = 0` to `tf` keeping only the summary:
    /// no sample is stored, so nothing is allocated after the planner is
    /// built (what an atlas of thousands of runs needs).
    pub fn run_summary<S>(
        scene: S,
        method: Method,
        networks: Option<Networks<A, M>>,
    ) -> Result<Summary>
    where
        S: SceneOf<A, M> + crate::model::Scene<A>,
        A: Planned<M, Scene = S>,
    {
        let mut p = Self::new(scene, method, networks)?;
        p.summary_to_end()
    }

    /// Runs to `tf` from the current state, recording every sample (the
    /// current one first).
    pub fn run_to_end(mut self) -> Result<Trajectory<M, A::Point>> {
        let left = self.scene.steps().saturating_sub(self.step_index);
        let mut steps = Vec::with_capacity(left + 1);
        steps.push(self.sample.clone());
        while !self.done() {
            steps.push(self.step()?.clone());
        }
        Ok(Trajectory {
            method: self.method,
            steps,
            summary: self.summary(),
        })
    }

    /// Runs to `tf` from the current state keeping only the summary (the
    /// summary [`Planner::run_to_end`] gives, to the last bit): nothing is
    /// allocated. The planner is left at the end, or where a step failed
    /// (the error is returned).
    pub fn summary_to_end(&mut self) -> Result<Summary> {
        while !self.done() {
            self.step()?;
        }
        Ok(self.summary())
    }

    /// Back to the scene's start pose at `t = 0`, with a fresh summary.
    /// Allocation-free.
    pub fn reset(&mut self) {
        self.theta.copy_from_slice(self.scene.theta0());
        // theta0 was validated (length and finiteness) when the scene entered.
        let _ = self
            .scene
            .arm()
            .update(&mut self.ws.pose, self.theta.as_slice());
        self.step_index = 0;
        self.t = 0.0;
        // The track's path is the scene's (a new target makes both the
        // line): only its timing and start are renewed, allocating nothing.
        let start = A::hand(&self.ws.pose);
        A::renew_track(&self.scene, start, 0.0, self.scene.tf(), &mut self.track);
        self.stats = Stats::new();
        self.refresh_sample(methods::Note::default());
        self.stats.record(&self.sample);
    }

    /// The scene (with any target, obstacle or gain changes applied).
    pub fn scene(&self) -> &A::Scene {
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

    /// Whether the run has reached the scene's `tf`.
    pub fn done(&self) -> bool {
        self.step_index >= self.scene.steps()
    }

    /// Current joint angles.
    pub fn theta(&self) -> &DVector<f64> {
        &self.theta
    }

    /// The kinematics of the current state (joints, Jacobian, ...).
    pub fn pose(&self) -> &A::Pose {
        &self.ws.pose
    }

    /// The straight line being tracked; for a path other than the line,
    /// the straight line from its start to its end (see [`Planner::track`]).
    pub fn line(&self) -> Line<M> {
        self.track.line
    }

    /// The path being tracked, with its timing.
    pub fn track(&self) -> &Track<M> {
        &self.track
    }

    /// The path being tracked as a polyline, for drawing (a circle through
    /// 96 chords).
    pub fn outline(&self) -> Vec<[f64; M]> {
        A::outline(&self.scene, self.track.line.start, self.track.line.end)
    }

    /// Whether every point of the path (the target, for the line) lies in
    /// the arm's reach.
    pub fn reachable(&self) -> bool {
        self.reachable
    }

    /// Whether the planner switched the damping schedule on because the
    /// path leaves the arm's reach and the scene had none.
    pub fn auto_damping(&self) -> bool {
        self.auto_damping
    }

    /// A sample of this planner's arm with room for its joints, zero
    /// (what [`observe_pose`] fills).
    pub fn blank_sample(arm: &A) -> Sample<M, A::Point> {
        Sample::zeros(arm.dof(), [0.0; M])
    }

    /// The networks in use, if any.
    pub fn networks(&self) -> Option<&Networks<A, M>> {
        self.networks.as_ref()
    }
}

/// Methods that use networks need them, and networks must be trained for
/// `arm`.
fn check_networks<A: Planned<M>, const M: usize>(
    method: Method,
    networks: &Option<Networks<A, M>>,
    arm: &A,
) -> Result<()> {
    match networks {
        None if method.uses_networks() => Err(Error::NetworksUnavailable(format!(
            "method {method} needs networks trained for this arm and none are loaded (--networks)"
        ))),
        Some(n) if method.entry().info.networks.phi && !n.has_phi() => {
            Err(Error::NetworksUnavailable(format!(
                "method {method} needs a Phi network, and none is trained for this task (the hand's pose: its pseudoinverse is n x 6, the networks' n x 3); Case 2, whose Phi is exact, runs with the v network"
            )))
        }
        Some(n) => n.check(arm),
        None => Ok(()),
    }
}
