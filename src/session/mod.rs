//! The interactive session the browser demo runs, without the browser: a
//! [`Twin`] (the planner and its numerical ghost), the clock that turns real
//! time into RK4 steps, the histories the page draws (trail, stroboscopic
//! trace, time series), dragging the target and the obstacle, and the state
//! snapshot the page reads. The page's wasm layer only binds this to
//! JavaScript and draws it; everything here is tested natively.

use std::sync::Arc;

use serde::Serialize;

use crate::arm::Arm;
use crate::error::{finite, within, Error, Result};
use crate::ik::DampingSchedule;
use crate::networks::{Networks, TrainedRange};
use crate::obstacle::Obstacle;
use crate::planner::{Mode, Planner, Summary, Surrogate};
use crate::scene::{Scene, PAPER_RADIUS, PAPER_TARGET};
use crate::twin::Twin;

mod state;

pub use state::{GhostState, State};

/// Speed (m/s) of the straight line planned when the user drops the target.
pub const DRAG_LINE_SPEED: f64 = 0.25;
/// Shortest line planned after a drag (s).
pub const MIN_LINE_DURATION: f64 = 1.0;
/// Every how many steps a pose joins the stroboscopic trace (the paper's figures).
pub const STROBE_EVERY: usize = 5;
/// Most steps one animation frame may take (keeps a slow device responsive).
pub const MAX_STEPS_PER_FRAME: usize = 40;
/// How far one arrow key moves the target or the obstacle (m).
pub const NUDGE: f64 = 0.05;
/// Caps on the stored histories.
const MAX_TRAIL: usize = 4000;
const MAX_STROBE: usize = 200;
const MAX_HISTORY: usize = 600;

/// Most obstacles a session holds.
pub const MAX_OBSTACLES: usize = 8;

/// What the pointer holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Handle {
    /// The target of the straight line.
    Target,
    /// Obstacle `i`.
    Obstacle(usize),
}

impl Handle {
    /// `"target"` or `"obstacle"`.
    pub fn name(self) -> &'static str {
        match self {
            Handle::Target => "target",
            Handle::Obstacle(_) => "obstacle",
        }
    }
}

/// One point of the time-series plots.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Time (s).
    pub t: f64,
    /// Distance from the nearest obstacle centre to a link.
    pub distance: Option<f64>,
    /// Tracking error (m).
    pub error: f64,
    /// Joint angles.
    pub theta: Vec<f64>,
}

/// One mode's run of the current scene, for the comparison table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModeRun {
    /// Mode name.
    pub mode: &'static str,
    /// Mode label (`Mode::label`).
    pub label: &'static str,
    /// The outcome, if the run went through.
    pub summary: Option<Summary>,
    /// Why it did not.
    pub error: Option<String>,
}

/// Networks installed in a session, with what they were trained on.
#[derive(Clone)]
struct Installed {
    surrogate: Arc<dyn Surrogate>,
    range: TrainedRange,
    networks: Arc<Networks>,
}

/// An interactive simulation: see the module documentation.
#[derive(Clone)]
pub struct Session {
    twin: Twin,
    networks: Option<Installed>,
    task: u32,
    running: bool,
    stop_at: Option<f64>,
    speed: f64,
    backlog: f64,
    prev_theta: Vec<f64>,
    ghost_prev: Vec<f64>,
    trail: Vec<[f64; 2]>,
    strobe: Vec<Vec<[f64; 2]>>,
    strobe_count: usize,
    history: Vec<Point>,
    drag: Option<Handle>,
    drag_point: Option<[f64; 2]>,
    frame_steps: usize,
    solver_ms: f64,
    solver_ms_per_step: f64,
    error: Option<String>,
    clock: fn() -> f64,
}

fn no_clock() -> f64 {
    0.0
}

/// A start pose for `arm`: the paper's Task 1 pose for its first three
/// joints (`pi/12, pi/2, -pi/6`), then each further joint bent `-pi/6`,
/// which keeps a 2- to 6-link arm off the ground, bent (not singular) and
/// inside its reach.
pub fn start_pose(arm: &Arm) -> Vec<f64> {
    use std::f64::consts::PI;
    let paper = [PI / 12.0, PI / 2.0, -PI / 6.0];
    (0..arm.dof())
        .map(|i| paper.get(i).copied().unwrap_or(-PI / 6.0))
        .collect()
}

/// The paper's scene `task` with the damping switch and feedback gain given.
fn paper_scene(task: u32, damping: bool, feedback: f64) -> Result<Scene> {
    let mut scene = Scene::task(task)?;
    scene.damping = damping.then(DampingSchedule::default);
    scene.feedback_gain = feedback;
    Ok(scene)
}

impl Session {
    /// The paper's task `task` (1 or 2) in mode `numerical`, damping on,
    /// paused at `t = 0`.
    pub fn new(task: u32) -> Result<Self> {
        let planner = Planner::new(paper_scene(task, true, 0.0)?, Mode::Numerical, None)?;
        let mut s = Self {
            twin: Twin::new(planner),
            networks: None,
            task,
            running: false,
            stop_at: None,
            speed: 2.0,
            backlog: 0.0,
            prev_theta: Vec::new(),
            ghost_prev: Vec::new(),
            trail: Vec::new(),
            strobe: Vec::new(),
            strobe_count: 0,
            history: Vec::new(),
            drag: None,
            drag_point: None,
            frame_steps: 0,
            solver_ms: 0.0,
            solver_ms_per_step: 0.0,
            error: None,
            clock: no_clock,
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

    /// The numerical ghost, in the network cases.
    pub fn ghost(&self) -> Option<&Planner> {
        self.twin.ghost()
    }

    /// What the installed networks were trained on.
    pub fn trained_range(&self) -> Option<&TrainedRange> {
        self.networks.as_ref().map(|n| &n.range)
    }

    /// The networks installed, with their weights files.
    pub fn installed(&self) -> Option<&Networks> {
        self.networks.as_ref().map(|n| n.networks.as_ref())
    }

    /// The networks installed, if any.
    pub fn networks(&self) -> Option<&Arc<dyn Surrogate>> {
        self.networks.as_ref().map(|n| &n.surrogate)
    }

    /// Loads the paper's scene `task` (obstacle, start pose, target and
    /// `lambda = 4`), keeping the mode, the damping switch and the feedback
    /// gain, and runs it from `t = 0` to `tf`. With an arm other than the
    /// paper's, the arm stays and starts from [`start_pose`].
    pub fn load_task(&mut self, task: u32) -> Result<()> {
        let old = self.planner().scene();
        let mut scene = paper_scene(task, old.damping.is_some(), old.feedback_gain)?;
        if old.arm != scene.arm {
            // Another arm: the paper's target and obstacle from its own start pose.
            scene.theta0 = start_pose(&old.arm);
            scene.arm = old.arm.clone();
            scene.obstacles.retain(|o| o.validate(&scene.arm).is_ok());
        }
        let planner = Planner::new(scene, self.planner().mode(), self.networks().cloned())?;
        self.twin.replace(planner);
        self.task = task;
        self.restart();
        self.run_to_end();
        Ok(())
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

    fn run_to_end(&mut self) {
        self.running = true;
        self.stop_at = Some(self.planner().scene().tf);
    }

    fn restart(&mut self) {
        self.running = false;
        self.stop_at = None;
        self.backlog = 0.0;
        self.error = None;
        self.drag = None;
        self.drag_point = None;
        self.trail.clear();
        self.strobe.clear();
        self.history.clear();
        self.strobe_count = 0;
        self.remember_poses();
        self.record();
    }

    /// Sets the mode. The network cases need networks ([`Session::set_networks`]).
    pub fn set_mode(&mut self, mode: Mode) -> Result<()> {
        self.twin.set_mode(mode)?;
        self.remember_poses();
        Ok(())
    }

    /// Installs trained networks (refused if they are for another arm; the
    /// networks in use stay then).
    pub fn set_networks(&mut self, networks: Networks) -> Result<()> {
        let range = networks.trained_range();
        let networks = Arc::new(networks);
        let surrogate: Arc<dyn Surrogate> = networks.clone();
        self.twin.set_networks(Some(surrogate.clone()))?;
        self.networks = Some(Installed {
            surrogate,
            range,
            networks,
        });
        Ok(())
    }

    /// Sets `lambda`, the gain of the obstacle vector (eq. 14).
    pub fn set_lambda(&mut self, lambda: f64) -> Result<()> {
        self.twin.apply(|p| p.set_lambda(lambda))
    }

    /// Switches the damping schedule on or off.
    pub fn set_damping(&mut self, on: bool) -> Result<()> {
        self.twin
            .apply(|p| p.set_damping(on.then(DampingSchedule::default)))
    }

    /// Closed-loop gain `K` (1/s), for the planner and the ghost.
    pub fn set_feedback(&mut self, gain: f64) -> Result<()> {
        self.twin.apply(|p| p.set_feedback_gain(gain))
    }

    /// Simulated seconds per real second (0.05 to 50).
    pub fn set_speed(&mut self, speed: f64) -> Result<()> {
        self.speed = within("speed", speed, 0.05, 50.0)?;
        Ok(())
    }

    /// Plans a new straight line from the current end effector to `target`,
    /// lasting `duration` seconds (default: at [`DRAG_LINE_SPEED`], at least
    /// [`MIN_LINE_DURATION`]).
    pub fn set_target(&mut self, target: [f64; 2], duration: Option<f64>) -> Result<()> {
        let duration = match duration {
            Some(d) => d,
            None => {
                let ee = self.planner().sample().ee;
                let dist = (target[0] - ee[0]).hypot(target[1] - ee[1]);
                (dist / DRAG_LINE_SPEED).max(MIN_LINE_DURATION)
            }
        };
        self.twin.apply(|p| p.set_target(target, duration))?;
        self.strobe.clear();
        self.strobe_count = 0;
        Ok(())
    }

    /// Moves the first obstacle's centre to `centre` (takes effect at the
    /// next step), or places one there with the paper's radius if there is
    /// none; refused, leaving it where it was, on the base post.
    pub fn set_obstacle(&mut self, centre: [f64; 2]) -> Result<()> {
        if self.obstacles().is_empty() {
            return self
                .add_obstacle(Obstacle::new(centre[0], centre[1], PAPER_RADIUS))
                .map(|_| ());
        }
        self.move_obstacle(0, centre)
    }

    /// The obstacles.
    pub fn obstacles(&self) -> &[Obstacle] {
        &self.planner().scene().obstacles
    }

    /// Moves obstacle `index` to `centre`, keeping its radius; refused,
    /// leaving it where it was, on the base post.
    pub fn move_obstacle(&mut self, index: usize, centre: [f64; 2]) -> Result<()> {
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
        self.twin.apply(|p| p.set_obstacles(obstacles.clone()))
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
        self.set_obstacles(all)
    }

    /// The arm.
    pub fn arm(&self) -> &Arm {
        &self.planner().scene().arm
    }

    /// Replaces the arm. The paper's arm gets Task 1's start pose; any
    /// other a pose of the same shape ([`start_pose`]). The target stays if
    /// the new arm reaches it, else it moves to the paper's; obstacles
    /// that would now overlap the post are dropped. Networks trained for
    /// another arm are set aside (the network cases then need networks for
    /// this arm: the mode falls back to `numerical`). Paused at `t = 0`.
    pub fn set_arm(&mut self, arm: Arm) -> Result<()> {
        Arm::new(arm.post(), arm.links().to_vec())?;
        let old = self.planner().scene().clone();
        let mut scene = if arm == Arm::paper() {
            paper_scene(1, old.damping.is_some(), old.feedback_gain)?
        } else {
            Scene {
                theta0: start_pose(&arm),
                ..old.clone()
            }
        };
        scene.arm = arm.clone();
        scene.lambda = old.lambda;
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
        let nets = self
            .networks
            .as_ref()
            .filter(|n| n.surrogate.arm() == &arm)
            .cloned();
        let mode = match self.planner().mode() {
            m if (m.learned_phi() || m.learned_v()) && nets.is_none() => Mode::Numerical,
            m => m,
        };
        let planner = Planner::new(scene, mode, nets.as_ref().map(|n| n.surrogate.clone()))?;
        self.networks = nets;
        self.twin.replace(planner);
        self.restart();
        Ok(())
    }

    /// Sets the networks aside (after an arm change, or to use others).
    pub fn clear_networks(&mut self) -> Result<()> {
        if self.planner().mode().learned_phi() || self.planner().mode().learned_v() {
            self.twin.set_mode(Mode::Numerical)?;
        }
        self.twin.set_networks(None)?;
        self.networks = None;
        Ok(())
    }

    /// Starts or pauses the clock. Starting after a task run continues
    /// without a stop time.
    pub fn set_running(&mut self, running: bool) {
        if running && !self.running {
            self.backlog = 0.0;
            if self
                .stop_at
                .is_some_and(|s| self.planner().time() >= s - 1e-9)
            {
                self.stop_at = None;
            }
        }
        self.running = running;
    }

    /// Whether the clock runs.
    pub fn running(&self) -> bool {
        self.running
    }

    /// One RK4 step; pauses the clock.
    pub fn step(&mut self) -> Result<()> {
        self.running = false;
        self.backlog = 0.0;
        let r = self.advance(1);
        self.remember_poses();
        r
    }

    /// Steps until `t >= time`, honouring a task's stop time; at most 100 000 steps.
    pub fn run_until(&mut self, time: f64) -> Result<()> {
        finite("time", time)?;
        let dt = self.planner().scene().dt;
        let end = self.stop_at.map_or(time, |s| s.min(time));
        let n = ((end - self.planner().time()) / dt - 1e-9)
            .ceil()
            .clamp(0.0, 100_000.0) as usize;
        let r = self.advance(n);
        self.remember_poses();
        self.check_stop();
        r
    }

    /// Advances the clock by `elapsed_ms` of real time, scaled by the speed
    /// (nothing happens while paused; at most [`MAX_STEPS_PER_FRAME`]
    /// steps). If a step fails the clock pauses and the state is the last
    /// good one.
    pub fn tick(&mut self, elapsed_ms: f64) -> Result<()> {
        if !(self.running && elapsed_ms.is_finite() && elapsed_ms > 0.0) {
            return Ok(());
        }
        let dt = self.planner().scene().dt;
        self.backlog += elapsed_ms.min(250.0) / 1000.0 * self.speed / dt;
        let mut n = (self.backlog.floor() as usize).min(MAX_STEPS_PER_FRAME);
        if let Some(stop) = self.stop_at {
            let left = ((stop - self.planner().time()) / dt - 1e-9).ceil().max(0.0) as usize;
            n = n.min(left);
        }
        self.backlog = (self.backlog - n as f64).clamp(0.0, 1.0);
        let r = self.advance(n);
        self.check_stop();
        r
    }

    fn check_stop(&mut self) {
        if self
            .stop_at
            .is_some_and(|stop| self.planner().time() >= stop - 1e-9)
        {
            self.running = false;
            self.backlog = 0.0;
        }
    }

    /// The poses before the next step, for smooth drawing.
    fn remember_poses(&mut self) {
        self.prev_theta.clear();
        self.prev_theta
            .extend_from_slice(self.twin.main().theta().as_slice());
        self.ghost_prev.clear();
        if let Some(g) = self.twin.ghost() {
            self.ghost_prev.extend_from_slice(g.theta().as_slice());
        }
    }

    /// Takes `n` steps, timing the planner's.
    fn advance(&mut self, n: usize) -> Result<()> {
        if n == 0 {
            return Ok(());
        }
        let mut solver = 0.0;
        let mut taken = 0;
        for _ in 0..n {
            self.remember_poses();
            let t0 = (self.clock)();
            let stepped = self.twin.step();
            solver += (self.clock)() - t0;
            if let Err(e) = stepped {
                self.running = false;
                self.backlog = 0.0;
                self.error = Some(e.to_string());
                self.frame_steps = taken;
                return Err(e);
            }
            taken += 1;
            self.record();
        }
        self.error = None;
        self.frame_steps = taken;
        self.solver_ms = solver;
        self.solver_ms_per_step = solver / taken as f64;
        Ok(())
    }

    /// Appends the planner's current sample to the histories.
    fn record(&mut self) {
        let s = self.twin.main().sample();
        if self.trail.len() >= MAX_TRAIL {
            self.trail.drain(..MAX_TRAIL / 4);
        }
        self.trail.push(s.ee);
        if self.strobe_count.is_multiple_of(STROBE_EVERY) {
            if self.strobe.len() >= MAX_STROBE {
                self.strobe.remove(0);
            }
            self.strobe.push(s.joints.clone());
        }
        self.strobe_count += 1;
        if self.history.len() >= MAX_HISTORY {
            self.history.remove(0);
        }
        self.history.push(Point {
            t: s.t,
            distance: s.distance,
            error: s.tracking_error,
            theta: s.theta.clone(),
        });
    }

    /// End-effector trail.
    pub fn trail(&self) -> &[[f64; 2]] {
        &self.trail
    }

    /// Every [`STROBE_EVERY`]th pose's joints since the line was planned.
    pub fn strobe(&self) -> &[Vec<[f64; 2]>] {
        &self.strobe
    }

    /// The time series of the plots.
    pub fn history(&self) -> &[Point] {
        &self.history
    }

    /// The joints to draw for the planner (or the ghost): between the last
    /// two steps while the clock runs, so motion looks smooth at any speed.
    pub fn display_joints(&self, ghost: bool) -> Option<Vec<[f64; 2]>> {
        let (planner, prev) = if ghost {
            (self.twin.ghost()?, &self.ghost_prev)
        } else {
            (self.twin.main(), &self.prev_theta)
        };
        let a = if self.running {
            self.backlog.clamp(0.0, 1.0)
        } else {
            1.0
        };
        let now = planner.theta();
        let theta: Vec<f64> = now
            .iter()
            .zip(prev.iter().chain(std::iter::repeat(&0.0)))
            .map(|(n, p)| p + a * (n - p))
            .collect();
        let arm = &planner.scene().arm;
        Some(
            arm.joints(&nalgebra::DVector::from_vec(theta))
                .iter()
                .map(|p| [p[0], p[1]])
                .collect(),
        )
    }

    // ---- dragging -------------------------------------------------------

    /// What the pointer holds.
    pub fn dragging(&self) -> Option<Handle> {
        self.drag
    }

    /// Where the target marker is: at the pointer while it is dragged.
    pub fn target_marker(&self) -> [f64; 2] {
        match (self.drag, self.drag_point) {
            (Some(Handle::Target), Some(p)) => p,
            _ => self.planner().scene().target,
        }
    }

    /// Grabs a handle (or nothing).
    pub fn drag_start(&mut self, handle: Option<Handle>) {
        self.drag = handle;
        self.drag_point = None;
    }

    /// Moves the held handle to `point`: the obstacle at once (refused on
    /// the post), the target only as a marker until [`Session::drag_end`].
    pub fn drag_to(&mut self, point: [f64; 2]) -> Result<()> {
        match self.drag {
            Some(Handle::Target) => {
                finite("pointer x", point[0])?;
                finite("pointer y", point[1])?;
                self.drag_point = Some(point);
                Ok(())
            }
            Some(Handle::Obstacle(i)) => self.move_obstacle(i, point),
            None => Ok(()),
        }
    }

    /// Ends a drag at `point`. Releasing the target plans a new straight line
    /// from the current end effector and starts the clock.
    pub fn drag_end(&mut self, point: [f64; 2]) -> Result<()> {
        let moved = self.drag_to(point);
        let handle = self.drag.take();
        let point = self.drag_point.take();
        moved?;
        if let (Some(Handle::Target), Some(p)) = (handle, point) {
            self.set_target(p, None)?;
            self.stop_at = None;
            self.set_running(true);
        }
        Ok(())
    }

    /// Abandons a drag: the target stays where it was.
    pub fn drag_cancel(&mut self) {
        self.drag = None;
        self.drag_point = None;
    }

    /// Moves the target (planning a new line and starting the clock) or the
    /// obstacle by `(dx, dy)` steps of [`NUDGE`] metres: the arrow keys.
    pub fn nudge(&mut self, handle: Handle, dx: f64, dy: f64) -> Result<()> {
        let scene = self.planner().scene();
        let at = match handle {
            Handle::Target => scene.target,
            Handle::Obstacle(i) => match scene.obstacles.get(i) {
                Some(o) => o.centre,
                None => return Ok(()),
            },
        };
        let to = [at[0] + dx * NUDGE, at[1] + dy * NUDGE];
        match handle {
            Handle::Target => {
                self.set_target(to, None)?;
                self.set_running(true);
                Ok(())
            }
            Handle::Obstacle(i) => self.move_obstacle(i, to),
        }
    }

    // ---- reading --------------------------------------------------------

    /// Runs the current scene from `t = 0` in each mode, off screen, with
    /// the installed networks or else `fallback`.
    pub fn compare_modes(&self, fallback: Option<Arc<dyn Surrogate>>) -> Vec<ModeRun> {
        let scene = self.planner().scene();
        let networks = self.networks().cloned().or(fallback);
        Mode::ALL
            .iter()
            .map(
                |&mode| match Planner::run_summary(scene.clone(), mode, networks.clone()) {
                    Ok(summary) => ModeRun {
                        mode: mode.name(),
                        label: mode.label(),
                        summary: Some(summary),
                        error: None,
                    },
                    Err(e) => ModeRun {
                        mode: mode.name(),
                        label: mode.label(),
                        summary: None,
                        error: Some(e.to_string()),
                    },
                },
            )
            .collect()
    }
}
