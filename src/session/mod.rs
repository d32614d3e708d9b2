//! The interactive session the browser demo runs, without the browser: a
//! [`Twin`] (the planner and its numerical ghost), the clock that turns real
//! time into RK4 steps, the histories the page draws (trail, stroboscopic
//! trace, time series), dragging the target and the obstacles, and the state
//! snapshot the page reads. The page's wasm layer only binds this to
//! JavaScript and draws it; everything here is tested natively.
//!
//! One file per concern: the scene and its settings here; the clock
//! (`clock.rs`), the histories (`history.rs`), the pointer and the keys
//! (`pointer.rs`), runs off screen and the comparison of the methods
//! (`compare.rs`), the gains and switches of the scene (`settings.rs`) and
//! the snapshot (`state.rs`).

mod clock;
mod compare;
mod history;
mod installed;
mod keys;
mod pointer;
mod revision;
mod scenes;
pub mod self_motion;
mod settings;
pub mod space;
mod state;

use crate::arm::{Arm, JointLimits, RateLimits};
use crate::error::{within, Error, Result};
use crate::networks::{self, NetworkSet};
use crate::nn::Precision;
use crate::obstacle::Obstacle;
use crate::planner::methods::LAMBDA;
use crate::planner::{Method, Planner};
use crate::run::Run;
use crate::scene::{Scene, PAPER_RADIUS, PAPER_TARGET};
use crate::twin::Twin;

pub use clock::MAX_STEPS_PER_FRAME;
pub use compare::MethodRun;
pub use history::{below_floor, Point, STROBE_EVERY};
pub use keys::FINE_NUDGE;
pub use pointer::{Handle, DRAG_LINE_SPEED, MIN_LINE_DURATION, NUDGE};
pub use revision::Revision;
pub use scenes::start_pose;
use scenes::{keep_method_settings, paper_scene};
pub use state::{ByName, GhostState, State};

use history::Histories;
use installed::Installed;

/// Most obstacles a session holds.
pub const MAX_OBSTACLES: usize = crate::geometry::MAX_BALLS;
/// Fewest links of a session's arm.
pub const MIN_LINKS: usize = crate::arm::MIN_LINKS;
/// Most links of a session's arm: what the page's designer offers and its
/// training presets are sized for (the core takes up to
/// [`crate::arm::MAX_LINKS`]).
pub const MAX_LINKS: usize = 6;
/// The gain `K` (1/s) of the page's "Correct drift" switch.
pub const DRIFT_GAIN: f64 = 1.0;

/// The method a session starts with: Case 3 (both networks) where the
/// built-in networks load, else the numerical route.
pub fn default_method() -> Method {
    if networks::builtin().is_ok() {
        Method::CASE3
    } else {
        Method::NUMERICAL
    }
}

/// An interactive simulation: see the module documentation.
#[derive(Clone)]
pub struct Session {
    twin: Twin,
    networks: Option<Installed>,
    task: u32,
    running: bool,
    /// Whether the first obstacle is the paper's (placed by a task; the
    /// others are the user's, which the task buttons keep).
    paper_first: bool,
    /// Whether the run starts from a pose of its own (a line dropped from
    /// where the hand was), not from the task's start pose.
    own_start: bool,
    speed: f64,
    backlog: f64,
    prev_theta: Vec<f64>,
    ghost_prev: Vec<f64>,
    histories: Histories,
    drag: Option<Handle>,
    /// What the keys move (`keys.rs`): the target, an obstacle or an elbow.
    selected: Handle,
    drag_point: Option<[f64; 2]>,
    frame_steps: usize,
    solver_ms: f64,
    solver_ms_per_step: f64,
    error: Option<String>,
    clock: fn() -> f64,
    /// Counts installs and removals of networks, and changes of their
    /// precision (for [`Revision`]).
    networks_installed: u64,
    /// The arithmetic the networks compute in (`installed.rs`).
    precision: Precision,
    revisions: revision::Revisions,
}

fn no_clock() -> f64 {
    0.0
}

impl Session {
    /// The paper's task `task` (1 or 2) with the numerical route, damping
    /// on, paused at `t = 0`.
    pub fn new(task: u32) -> Result<Self> {
        let planner = Planner::new(paper_scene(task, true, 0.0)?, Method::NUMERICAL, None)?;
        let mut s = Self {
            twin: Twin::new(planner),
            networks: None,
            task,
            running: false,
            paper_first: true,
            own_start: false,
            speed: 2.0,
            backlog: 0.0,
            prev_theta: Vec::new(),
            ghost_prev: Vec::new(),
            histories: Histories::default(),
            drag: None,
            selected: Handle::Target,
            drag_point: None,
            frame_steps: 0,
            solver_ms: 0.0,
            solver_ms_per_step: 0.0,
            error: None,
            clock: no_clock,
            networks_installed: 0,
            precision: Precision::F64,
            revisions: revision::Revisions::default(),
        };
        s.restart();
        Ok(s)
    }

    /// The clock (ms) that times the planner's steps for the state's
    /// `solver_ms`; none by default (the core knows no clock).
    pub fn set_clock(&mut self, clock: fn() -> f64) {
        self.clock = clock;
    }

    /// The planner.
    pub fn planner(&self) -> &Planner {
        self.twin.main()
    }

    /// The scene in use (the planner's).
    pub fn scene(&self) -> &Scene {
        self.twin.main().scene()
    }

    /// The numerical ghost, while the method uses networks.
    pub fn ghost(&self) -> Option<&Planner> {
        self.twin.ghost()
    }

    /// Loads the paper's scene `task` (start pose, target, `lambda = 4` and
    /// the paper's obstacle in place of the first), keeping the obstacles
    /// the user added, the method, the damping switch and the feedback
    /// gain, and runs it from `t = 0` to `tf`. With an arm other than the
    /// paper's, the arm stays and starts from [`start_pose`] (obstacles that
    /// would overlap its post are left out).
    pub fn load_task(&mut self, task: u32) -> Result<()> {
        let old = self.planner().scene();
        let mut scene = paper_scene(task, old.damping.is_some(), old.feedback_gain)?;
        keep_method_settings(&mut scene, old);
        let paper = scene.obstacles[0];
        let mut obstacles = old.obstacles.clone();
        if self.paper_first && !obstacles.is_empty() {
            obstacles[0] = paper;
        } else {
            obstacles.insert(0, paper);
            obstacles.truncate(MAX_OBSTACLES);
        }
        scene.obstacles = obstacles;
        if !old.arm.same_geometry(&scene.arm) {
            // Another arm: the paper's target and obstacle from its own start pose.
            scene.theta0 = start_pose(&old.arm);
            scene.arm = old.arm.clone();
            scene.obstacles.retain(|o| o.validate(&scene.arm).is_ok());
        } else {
            // The paper's, with its limits (if any).
            scene.arm = old.arm.clone();
        }
        let paper_first = scene.obstacles.first() == Some(&paper);
        let planner = Planner::new(scene, self.planner().method(), self.networks().cloned())?;
        self.twin.replace(planner);
        self.task = task;
        self.paper_first = paper_first;
        self.own_start = false;
        self.restart();
        self.run_to_end();
        Ok(())
    }

    /// After a change to the scene: a run that has ended replays from
    /// `t = 0`, so the change shows; while a run goes on (or waits at
    /// `t = 0`) it takes effect at the next step, and the readouts of the
    /// run take in the distance it makes now.
    fn after_change(&mut self) {
        if self.drag.is_some() {
            return;
        }
        if self.ended() && !self.running {
            self.run_task();
        } else {
            let _ = self.twin.apply(|p| {
                p.observe_now();
                Ok(())
            });
        }
    }

    /// Back to `t = 0` of the current scene, paused, histories cleared.
    pub fn reset(&mut self) {
        self.twin.reset();
        self.restart();
    }

    /// Resets and runs the current scene from `t = 0` to its final time.
    pub fn run_task(&mut self) {
        self.reset();
        self.run_to_end();
    }

    fn restart(&mut self) {
        self.running = false;
        self.backlog = 0.0;
        self.error = None;
        self.drag = None;
        self.drag_point = None;
        self.histories.clear();
        self.remember_poses();
        self.record();
    }

    /// Sets the method. Methods that use networks take the installed ones,
    /// else the built-in ones where they fit the arm; refused (the method
    /// stays) when there are none for this arm.
    pub fn set_method(&mut self, method: Method) -> Result<()> {
        if method.uses_networks() && self.networks.is_none() {
            let nets = networks::available(self.arm(), None)?;
            self.install(nets, crate::run::NetworkChoice::Set(NetworkSet::Paper))?;
        }
        self.twin.set_method(method)?;
        self.remember_poses();
        self.after_change();
        Ok(())
    }

    /// What runs: the task, the scene, the method and the networks
    /// installed (absent: none installed, so the paper's set where a method
    /// needs them). What the page's workers and its run file take.
    pub fn run(&self) -> Run {
        let p = self.planner();
        Run {
            task: self.task,
            method: p.method(),
            scene: p.scene().clone(),
            networks: self.network_choice().cloned(),
            precision: self.precision,
        }
    }

    /// The revisions of what results depend on ([`Revision`]).
    pub fn revision(&self) -> Revision {
        let p = self.planner();
        self.revisions
            .observe(self.task, p.method(), p.scene(), self.networks_installed)
    }

    /// Simulated seconds per real second (0.05 to 50).
    pub fn set_speed(&mut self, speed: f64) -> Result<()> {
        self.speed = within("speed", speed, 0.05, 50.0)?;
        Ok(())
    }

    /// Moves the first obstacle's centre to `centre` (takes effect at the
    /// next step), or places one there with the paper's radius if there is
    /// none; refused, leaving it where it was, on the base post.
    pub fn set_obstacle(&mut self, centre: [f64; 2]) -> Result<()> {
        if self.obstacles().is_empty() {
            self.add_obstacle(Obstacle::new(centre[0], centre[1], PAPER_RADIUS))?;
            self.paper_first = true;
            return Ok(());
        }
        self.move_obstacle(0, centre)
    }

    /// The obstacles.
    pub fn obstacles(&self) -> &[Obstacle] {
        &self.planner().scene().obstacles
    }

    /// Moves obstacle `index` to `centre`, keeping its radius; refused,
    /// leaving it where it was, on the base post. A run that has ended
    /// replays with it there.
    pub fn move_obstacle(&mut self, index: usize, centre: [f64; 2]) -> Result<()> {
        self.place_obstacle(index, centre)?;
        self.after_change();
        Ok(())
    }

    /// Moves obstacle `index` without replaying (while it is dragged).
    fn place_obstacle(&mut self, index: usize, centre: [f64; 2]) -> Result<()> {
        self.twin.apply(|p| p.move_obstacle(index, centre))
    }

    /// Replaces the obstacles (at most [`MAX_OBSTACLES`]); refused as a
    /// whole if one is invalid.
    pub fn set_obstacles(&mut self, obstacles: Vec<Obstacle>) -> Result<()> {
        if obstacles.len() > MAX_OBSTACLES {
            return Err(Error::OutOfRange {
                what: "number of obstacles".into(),
                value: obstacles.len() as f64,
                min: 0.0,
                max: MAX_OBSTACLES as f64,
            });
        }
        self.twin.apply(|p| p.set_obstacles(obstacles.clone()))?;
        self.paper_first &= !self.obstacles().is_empty();
        self.after_change();
        Ok(())
    }

    /// Adds an obstacle; returns its index. Refused beyond
    /// [`MAX_OBSTACLES`], on the post, or with a bad radius.
    pub fn add_obstacle(&mut self, obstacle: Obstacle) -> Result<usize> {
        let mut all = self.obstacles().to_vec();
        all.push(obstacle);
        let index = all.len() - 1;
        self.set_obstacles(all)?;
        Ok(index)
    }

    /// Sets the radius of obstacle `index`, keeping its centre; refused,
    /// changing nothing, with a bad radius or index (or one that reaches
    /// the post).
    pub fn set_obstacle_radius(&mut self, index: usize, radius: f64) -> Result<()> {
        let mut all = self.obstacles().to_vec();
        let count = all.len();
        let Some(ob) = all.get_mut(index) else {
            return Err(Error::OutOfRange {
                what: "obstacle index".into(),
                value: index as f64,
                min: 0.0,
                max: count.saturating_sub(1) as f64,
            });
        };
        ob.radius = radius;
        let paper_first = self.paper_first;
        self.set_obstacles(all)?;
        // The paper's first obstacle stays the task's, whatever its size.
        self.paper_first = paper_first;
        Ok(())
    }

    /// Removes obstacle `index`.
    pub fn remove_obstacle(&mut self, index: usize) -> Result<()> {
        let mut all = self.obstacles().to_vec();
        if index >= all.len() {
            return Err(Error::OutOfRange {
                what: "obstacle index".into(),
                value: index as f64,
                min: 0.0,
                max: all.len().saturating_sub(1) as f64,
            });
        }
        all.remove(index);
        if self.drag == Some(Handle::Obstacle(index)) {
            self.drag = None;
        }
        self.set_obstacles(all)?;
        self.paper_first &= index != 0;
        Ok(())
    }

    /// The arm.
    pub fn arm(&self) -> &Arm {
        &self.planner().scene().arm
    }

    /// Gives the arm other joint limits (`None`: unlimited), for the
    /// planner and the ghost, keeping the scene and the run; refused,
    /// changing nothing, when their count does not match the links or the
    /// start pose lies outside them.
    pub fn set_arm_limits(
        &mut self,
        joint: Option<JointLimits>,
        rate: Option<RateLimits>,
    ) -> Result<()> {
        self.twin
            .apply(|p| p.set_arm_limits(joint.clone(), rate.clone()))?;
        self.after_change();
        Ok(())
    }

    /// Replaces the arm (2 to [`MAX_LINKS`] links). The paper's arm gets
    /// Task 1's start pose; any other a pose of the same shape
    /// ([`start_pose`]). The target stays if the new arm reaches it, else it
    /// moves to the paper's; obstacles that would now overlap the post are
    /// dropped. Networks trained for another arm are set aside (methods
    /// that use networks then need networks for this arm: the method falls
    /// back to `numerical`). Paused at `t = 0`.
    pub fn set_arm(&mut self, arm: Arm) -> Result<()> {
        if !(MIN_LINKS..=MAX_LINKS).contains(&arm.dof()) {
            return Err(Error::LinkCount {
                found: arm.dof(),
                min: MIN_LINKS,
                max: MAX_LINKS,
            });
        }
        let old = self.planner().scene().clone();
        let mut scene = if arm.same_geometry(&Arm::paper()) {
            paper_scene(1, old.damping.is_some(), old.feedback_gain)?
        } else {
            Scene {
                theta0: start_pose(&arm),
                ..old.clone()
            }
        };
        scene.arm = arm.clone();
        let _ = scene.params.set(&LAMBDA, old.param(&LAMBDA));
        keep_method_settings(&mut scene, &old);
        if !scene.use_preset_task() {
            scene.target = old.target;
            if !arm.can_reach(&scene.target_vector()) {
                scene.target = PAPER_TARGET;
            }
            scene.obstacles = old
                .obstacles
                .iter()
                .filter(|o| o.validate(&arm).is_ok())
                .copied()
                .collect();
        }
        let nets = self
            .networks
            .as_ref()
            .filter(|n| n.surrogate.check(&arm).is_ok())
            .cloned();
        let method = match self.planner().method() {
            m if m.uses_networks() && nets.is_none() => Method::NUMERICAL,
            m => m,
        };
        let paper_first = self.paper_first && scene.obstacles.first() == old.obstacles.first();
        let planner = Planner::new(scene, method, nets.as_ref().map(|n| n.surrogate.clone()))?;
        self.paper_first = paper_first;
        self.own_start = false;
        self.networks = nets;
        self.twin.replace(planner);
        self.restart();
        Ok(())
    }
}
