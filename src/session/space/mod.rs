//! The interactive session of an arm in space, the page's 3-D stage
//! without the browser: a preset's scene (its task, spheres, target), the
//! method and its networks, the run, the clock that plays it, the camera
//! ([`Camera`]) and the pointer and keys that orbit it and drag the target
//! and the spheres in the plane facing it (`pointer.rs`), and the snapshot
//! the page reads (`state.rs`).
//!
//! A run here is computed whole whenever its scene changes (a preset's
//! task is 100 RK4 steps: about 0.15 ms in numerical and 1 ms in Case 3
//! natively, `redundant-ik bench --arm panda`), and the clock plays it: so
//! dragging a sphere against the forearm at `t` shows at once what that
//! run does there, the trail and the plots included, and the comparison,
//! the run file and the atlas read the very run on screen (the clock and
//! the comparison are `clock.rs`).

mod camera;
mod clock;
mod pointer;
mod pose_task;
mod self_collision;
mod self_motion;
mod settings;
mod state;

use std::collections::VecDeque;
use std::sync::Arc;

pub use camera::{Camera, Projection, DISTANCE, FIELD_OF_VIEW, NEAR, PITCH};
pub use pointer::{SpaceHandle, KEY_ORBIT};
pub use pose_task::Orientation;
pub use self_collision::SelfNear;
pub use state::{SpaceMethodRun, SpaceState};

use super::history::Point;
use crate::error::{Error, Result};
use crate::networks::space::{SpaceNetworkSet, SpaceNetworks};
use crate::nn::Precision;
use crate::planner::methods::Method;
use crate::planner::{Sample, Summary, Trajectory};
use crate::run::NetworkChoice;
use crate::scene::SpaceScene;
use crate::space::{SpacePose, Vec3};
use pose_task::run;

/// A spatial run played on the page: see the module documentation.
#[derive(Clone)]
pub struct SpaceSession {
    robot: SessionRobot,
    scene: SpaceScene,
    /// The target's orientation where the task is the hand's pose.
    orientation: Option<Orientation>,
    method: Method,
    networks: Option<Arc<SpaceNetworks>>,
    /// What the networks installed are: a shipped set, or the weights
    /// files' text (which the run file carries).
    network_choice: Option<NetworkChoice<SpaceNetworkSet>>,
    /// The arithmetic the networks compute in.
    precision: Precision,
    /// Every sample of the run from `t = 0` (up to a failed step).
    samples: Vec<Sample<3>>,
    /// The pose task's samples (six coordinates), for its run file; empty
    /// for the position task.
    pose_steps: Vec<Sample<6, Vec3>>,
    /// In the network cases, the numerical route's run of the same scene
    /// (the dashed ghost the page draws beside the learned arm, as in the
    /// plane); empty otherwise.
    ghost: Vec<Sample<3>>,
    /// The ghost's pose at the time shown (when there is a ghost).
    ghost_pose: Option<SpacePose>,
    summary: Summary,
    /// Why the run stopped before `tf`, if it did.
    failure: Option<String>,
    /// The sample shown.
    index: usize,
    running: bool,
    speed: f64,
    backlog: f64,
    /// The pose of the sample shown (one kinematics pass per change).
    pose: SpacePose,
    camera: Camera,
    home: Camera,
    selected: SpaceHandle,
    drag: Option<pointer::Drag>,
    /// Counts the runs computed (the page redraws what depends on it).
    runs: u64,
}

/// The robot a session shows: its key and name as the page says them, its
/// own task (what Task loads) and where it came from, as its run files
/// record it.
#[derive(Debug, Clone)]
struct SessionRobot {
    key: String,
    label: String,
    task: SpaceScene,
    source: crate::urdf::RobotSource,
}

impl SpaceSession {
    /// The preset `key`'s task (`panda`, `iiwa14`) in `method`, paused at
    /// `t = 0`; learned methods need [`SpaceSession::install_networks`]
    /// first.
    pub fn new(key: &str, method: Method) -> Result<Self> {
        let preset = crate::space::SpacePreset::named(key)?;
        Self::of_robot(preset.key, preset.label, SpaceScene::preset(preset), method)
    }

    /// A robot of the user's (a chain read from URDF): `key` and `label`
    /// name it, `task` is its own task ([`SpaceScene::own`]), which the
    /// session starts with and Task loads; refused where the task does not
    /// validate.
    pub fn of_robot(key: &str, label: &str, task: SpaceScene, method: Method) -> Result<Self> {
        task.validate()?;
        let scene = task.clone();
        let robot = SessionRobot {
            key: key.into(),
            label: label.into(),
            task,
            source: crate::urdf::RobotSource::shipped(key),
        };
        let pose = SpacePose::new(&scene.arm, &scene.theta0)?;
        let home = Camera::looking_at(home_focus(&scene), 1.8 * scene.arm.reach().max(0.3));
        let mut s = Self {
            robot,
            scene,
            orientation: None,
            method: Method::NUMERICAL,
            networks: None,
            network_choice: None,
            precision: Precision::F64,
            samples: Vec::new(),
            pose_steps: Vec::new(),
            ghost: Vec::new(),
            ghost_pose: None,
            summary: Summary::nothing(method),
            failure: None,
            index: 0,
            running: false,
            speed: 1.0,
            backlog: 0.0,
            pose,
            camera: home,
            home,
            selected: SpaceHandle::Target,
            drag: None,
            runs: 0,
        };
        s.set_method(method)?;
        Ok(s)
    }

    /// The robot's key (a preset's, `panda`; or the name given a robot of
    /// the user's).
    pub fn robot_key(&self) -> &str {
        &self.robot.key
    }

    /// The robot's name as the page says it (`Franka Panda`).
    pub fn robot_label(&self) -> &str {
        &self.robot.label
    }

    /// Where the robot came from, as its run files record it: a shipped
    /// one by its key, or a URDF of the user's ([`Self::set_source`]).
    pub fn source(&self) -> &crate::urdf::RobotSource {
        &self.robot.source
    }

    /// Records where the robot came from (a URDF of the user's: its name,
    /// text, base and tip), for its run files.
    pub fn set_source(&mut self, source: crate::urdf::RobotSource) {
        self.robot.source = source;
    }

    /// The scene.
    pub fn scene(&self) -> &SpaceScene {
        &self.scene
    }

    /// The method.
    pub fn method(&self) -> Method {
        self.method
    }

    /// The shipped set installed, if one is.
    pub fn network_set(&self) -> Option<SpaceNetworkSet> {
        self.network_choice.as_ref().and_then(NetworkChoice::set)
    }

    /// What the networks installed are (a shipped set, or the weights
    /// files' text), if any are.
    pub fn network_choice(&self) -> Option<&NetworkChoice<SpaceNetworkSet>> {
        self.network_choice.as_ref()
    }

    /// Whether networks are installed.
    pub fn has_networks(&self) -> bool {
        self.networks.is_some()
    }

    /// Whether the networks the method uses see the pose on screen (and,
    /// for `v`, every sphere) inside the boxes they were trained on; true
    /// for a method without networks. Outside, their output is an
    /// extrapolation (the page says so).
    pub fn in_range(&self) -> bool {
        let needs = self.method.info().networks;
        match self.networks.as_ref() {
            Some(n) if self.method.uses_networks() => {
                (!needs.phi || n.in_range(&self.pose, None))
                    && (!needs.v
                        || self
                            .scene
                            .obstacles
                            .iter()
                            .all(|s| n.in_range(&self.pose, Some(s.centre))))
            }
            _ => true,
        }
    }

    /// Installs the networks of `phi_json` and `v_json` (the weights files'
    /// text; `set` names the shipped set they are, if they are one);
    /// refused, changing nothing, when they do not read or were trained for
    /// another chain.
    pub fn install_networks(
        &mut self,
        phi_json: &str,
        v_json: &str,
        set: Option<SpaceNetworkSet>,
    ) -> Result<()> {
        let nets = SpaceNetworks::read(phi_json, v_json)?;
        nets.check_chain(&self.scene.arm)?;
        self.networks = Some(Arc::new(nets).in_precision(self.precision));
        self.network_choice = Some(match set {
            Some(set) => NetworkChoice::Set(set),
            None => NetworkChoice::Files {
                phi: phi_json.into(),
                v: v_json.into(),
            },
        });
        if self.method.uses_networks() {
            self.recompute();
        }
        Ok(())
    }

    /// The arithmetic the networks compute in: `f64` (the default) or
    /// `f32` (a run file's `precision`).
    pub fn precision(&self) -> Precision {
        self.precision
    }

    /// Makes the networks compute in `precision` (those installed are
    /// built again in it; a learned method's run is computed again).
    pub fn set_precision(&mut self, precision: Precision) {
        if precision == self.precision {
            return;
        }
        self.precision = precision;
        self.networks = self.networks.take().map(|n| n.in_precision(precision));
        if self.method.uses_networks() {
            self.recompute();
        }
    }

    /// Switches to `method`; refused, changing nothing, when it has no rule
    /// in space or needs networks the session has not.
    pub fn set_method(&mut self, method: Method) -> Result<()> {
        method.space_rule(self.scene.arm.dof())?;
        if self.orientation.is_some() {
            pose_task::check_pose_method(method)?;
        }
        if method.uses_networks() && self.networks.is_none() {
            return Err(Error::NetworksUnavailable(format!(
                "{} needs networks for the {}: they have not loaded",
                method.label(),
                self.robot.label
            )));
        }
        self.take(self.scene.clone(), self.orientation, method)
    }

    /// Back to the robot's own task (its target, sphere and settings), the
    /// method, the networks and the self-collision switch kept; for the
    /// pose task, the target's orientation the hand's at the start.
    pub fn load_task(&mut self) -> Result<()> {
        let orientation = match self.orientation {
            Some(o) => {
                let start =
                    crate::scene::PoseScene::from_space(self.robot.task.clone(), None, o.weight)?
                        .start();
                Some(Orientation {
                    rotation: [start[3], start[4], start[5]],
                    ..o
                })
            }
            None => None,
        };
        let task = self.with_self_collision(self.robot.task.clone(), self.self_collision())?;
        self.take(task, orientation, self.method)?;
        self.selected = SpaceHandle::Target;
        self.index = 0;
        self.show(0);
        Ok(())
    }

    /// Takes `scene` when it validates (and the method still runs on it,
    /// in the task in use), then recomputes the run, the time shown kept.
    fn apply(&mut self, scene: SpaceScene) -> Result<()> {
        self.take(scene, self.orientation, self.method)
    }

    /// Runs the scene from `t = 0` to `tf` (or to the first failed step)
    /// and shows the sample at the time shown before.
    fn recompute(&mut self) {
        let played = run(
            &self.scene,
            self.orientation,
            self.method,
            self.networks.clone(),
        );
        // The ghost: the exact route on the same scene, about 0.15 ms of
        // the Panda's task natively (a learned run is 1 ms).
        self.ghost = if self.method.uses_networks() {
            run(&self.scene, self.orientation, Method::NUMERICAL, None).samples
        } else {
            Vec::new()
        };
        self.summary = played.summary;
        self.samples = played.samples;
        self.pose_steps = played.pose_steps;
        self.failure = played.failure;
        self.runs += 1;
        let last = self.samples.len().saturating_sub(1);
        self.show(self.index.min(last));
    }

    fn show(&mut self, index: usize) {
        self.index = index;
        if let Some(s) = self.samples.get(index) {
            // The chain and the angles were checked when the run made them.
            let _ = self.pose.update(&self.scene.arm, &s.theta);
        }
        // The ghost at the same time (at its last sample where it stopped
        // sooner).
        let chain = &self.scene.arm;
        self.ghost_pose = match self.ghost.get(index).or(self.ghost.last()) {
            Some(g) => match self.ghost_pose.take() {
                Some(mut pose) => pose.update(chain, &g.theta).is_ok().then_some(pose),
                None => SpacePose::new(chain, &g.theta).ok(),
            },
            None => None,
        };
    }

    /// The numerical ghost's pose at the time shown, in the network cases
    /// (the exact route on the same scene, drawn dashed beside the
    /// learned arm).
    pub fn ghost(&self) -> Option<&SpacePose> {
        self.ghost_pose.as_ref()
    }

    /// Every sample of the ghost's run (empty without a ghost).
    pub fn ghost_samples(&self) -> &[Sample<3>] {
        &self.ghost
    }

    /// The whole run.
    pub fn trajectory(&self) -> Trajectory<3> {
        Trajectory {
            method: self.method,
            steps: self.samples.clone(),
            summary: self.summary.clone(),
        }
    }

    /// The sample shown.
    pub fn sample(&self) -> Option<&Sample<3>> {
        self.samples.get(self.index)
    }

    /// Every sample of the run.
    pub fn samples(&self) -> &[Sample<3>] {
        &self.samples
    }

    /// The samples up to the one shown (what the trail and plots draw).
    pub fn played(&self) -> &[Sample<3>] {
        &self.samples[..(self.index + 1).min(self.samples.len())]
    }

    /// The plots' points of [`SpaceSession::played`].
    pub fn points(&self) -> VecDeque<Point> {
        self.played()
            .iter()
            .map(|s| Point {
                t: s.t,
                clearance: s.clearance,
                error: s.tracking_error,
                theta: s.theta.clone(),
            })
            .collect()
    }

    /// The pose shown.
    pub fn pose(&self) -> &SpacePose {
        &self.pose
    }

    /// The whole run's outcome (what it does by `tf`).
    pub fn summary(&self) -> &Summary {
        &self.summary
    }

    /// How many runs the session has computed.
    pub fn runs(&self) -> u64 {
        self.runs
    }
}

/// The camera's focus for a scene: between the base, the hand's start and
/// the path's end, at their mean height.
fn home_focus(scene: &SpaceScene) -> Vec3 {
    let (a, b) = (scene.start(), scene.path_end());
    let base = scene.arm.base().1;
    [0, 1, 2].map(|i| (a[i] + b[i] + base[i]) / 3.0)
}
