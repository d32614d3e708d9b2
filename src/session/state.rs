//! The snapshot of a session the page reads every frame.

use serde::Serialize;

use super::{Handle, Session};
use crate::arm::Arm;
use crate::clearance::{Pair, Pairs};
use crate::kinematics::velocity_ellipse;
use crate::networks::{self, NetworkSet, TrainedRange};
use crate::obstacle::{self, Obstacle};
use crate::planner::methods::{INFLUENCE, LAMBDA};
use crate::planner::params;
use crate::planner::{Line, Needs};
use crate::scene::JointWeighting;

/// The snapshot the page reads every frame.
#[derive(Debug, Serialize)]
pub struct State<'a> {
    /// Time (s).
    pub t: f64,
    /// The paper's task last loaded (1 or 2).
    pub task: u32,
    /// Method name.
    pub method: &'static str,
    /// The networks the method uses (`{ phi, v }`).
    pub uses: Needs,
    /// Whether the clock runs.
    pub running: bool,
    /// Whether the run has ended (`t = tf`: the clock stopped there and the
    /// arm holds still; play replays it).
    pub ended: bool,
    /// The run's final time, where its line ends (s).
    pub tf: f64,
    /// Its start pose, and whether that is its own (a line dropped from
    /// where the hand was) rather than the task's.
    pub theta0: &'a [f64],
    /// See `theta0`.
    pub own_start: bool,
    /// Simulated seconds per real second.
    pub speed: f64,
    /// Gain of the obstacle vector.
    pub lambda: f64,
    /// Every parameter of the methods by name (`lambda`, `delta`,
    /// `influence`, ...; [`crate::scene::Param`]), and which of them the method reads.
    pub params: ByName<f64>,
    /// The names of the parameters the method reads.
    pub reads: Vec<&'static str>,
    /// For a method with an influence distance (`distance`, `priority`,
    /// `qp`): it, and the link-obstacle pairs within it now.
    pub influence: Option<f64>,
    /// Those pairs: `{ link, obstacle, point, centre, clearance, normal }`.
    pub dampers: Vec<Pair>,
    /// Whether the damping schedule is on.
    pub damping: bool,
    /// How the methods of eq. (5) use the joint limits (`none`, `wln`).
    pub weighting: JointWeighting,
    /// Whether the floor and the post are obstacles for the methods.
    pub floor: bool,
    /// Whether it was switched on for an out-of-reach target.
    pub auto_damping: bool,
    /// What the keys move (`Session::selected`): `target`, `obstacle` or
    /// `joint`.
    pub selected: &'static str,
    /// Which: the obstacle's index, the elbow's `k`; 0 for the target.
    pub selected_index: usize,
    /// Whether a point of the run's path (the target, for the line) lies
    /// outside the arm's reach, with the damping on or off (the page's note
    /// said so only when the damping was switched on for it).
    pub out_of_reach: bool,
    /// Why the method adds nothing to `none` on this arm (it reads joint
    /// limits the arm does not have), if so: `Method::without_limits`.
    pub without_limits: Option<String>,
    /// Closed-loop gain `K`.
    pub feedback: f64,
    /// Joint angles.
    pub theta: &'a [f64],
    /// Joints `P(0)..P(n)`.
    pub joints: &'a [[f64; 2]],
    /// End effector.
    pub ee: [f64; 2],
    /// Reference point on the line.
    pub reference: [f64; 2],
    /// Target.
    pub target: [f64; 2],
    /// The line being tracked.
    pub line: Line,
    /// The path the hand follows as its text (`circle:1.2,0.8`,
    /// `points:...`: [`crate::scene::Path`]'s syntax, the address's
    /// `path=`); none (`null`) for the line.
    pub path: Option<String>,
    /// The arm.
    pub arm: &'a Arm,
    /// Centre of the first obstacle.
    pub obstacle: Option<[f64; 2]>,
    /// Its radius.
    pub radius: Option<f64>,
    /// All obstacles, `{ centre, radius }`.
    pub obstacles: &'a [Obstacle],
    /// Index of the obstacle nearest to a link now (what `distance` measures).
    pub nearest: Option<usize>,
    /// Distance from the nearest obstacle centre to a link now (named so:
    /// the readouts, plots and tables give the clearance).
    pub distance: Option<f64>,
    /// Smallest such distance since the last reset.
    pub min_distance: Option<f64>,
    /// Clearance between the links and the nearest obstacle's edge now
    /// (negative inside it): what the readouts, the plots, the comparison,
    /// the run's CSV and the atlas give.
    pub clearance: Option<f64>,
    /// Smallest clearance since the last reset.
    pub min_clearance: Option<f64>,
    /// Whether a link is inside an obstacle now.
    pub collision: bool,
    /// Whether one was since the last reset.
    pub collided: bool,
    /// Whether a link reaches below the floor (`y < 0`) now.
    pub below_floor: bool,
    /// Steps of this run with a link below the floor.
    pub below_floor_steps: usize,
    /// Distance from the end effector to the reference.
    pub tracking_error: f64,
    /// Distance from the end effector to the target.
    pub final_error: f64,
    /// `sqrt(det(J J^T))`.
    pub manipulability: f64,
    /// The singular values `sigma_1 >= sigma_2` of `J` (their product is
    /// the manipulability; [`crate::kinematics::velocity_ellipse`]).
    pub singular_values: [f64; 2],
    /// The joints (1-based) past their position limits now.
    pub past_limits: &'a [usize],
    /// Steps of this run with a joint past its limits.
    pub limit_steps: usize,
    /// Damping in force.
    pub delta: f64,
    /// Whether the networks in use see inputs inside their trained range.
    pub in_range: bool,
    /// Whether the exact damped `Phi` stood in for the network in the last step.
    pub phi_handover: bool,
    /// Steps in which it did, since the last reset.
    pub handover_steps: usize,
    /// Whether methods that use networks can run with this arm (networks
    /// installed for it, or built-in ones trained for it).
    pub networks: bool,
    /// What they were trained on.
    pub trained_range: Option<&'a TrainedRange>,
    /// The shipped set installed (`paper`, `reach`), or `None` for
    /// networks trained or loaded by the user (or none installed).
    pub network_set: Option<&'static str>,
    /// The networks' arithmetic: `f64` or `f32`.
    pub precision: &'static str,
    /// Whether each shipped set was trained for this arm, by name.
    pub set_fits: ByName<bool>,
    /// The arm as the command line and the address write it
    /// (`0.5:0.6,0.85,0.6`).
    pub arm_text: String,
    /// Whether the arm is the paper's (the page's first preset).
    pub paper_arm: bool,
    /// The revisions of what results depend on: a result made at another
    /// revision is stale ([`super::Revision`]).
    pub revision: super::Revision,
    /// The numerical ghost, in the network cases.
    pub ghost: Option<GhostState>,
    /// Steps since the last reset.
    pub steps: usize,
    /// Steps taken by the last frame that stepped.
    pub frame_steps: usize,
    /// Time in the planner's steps in that frame (ms), by the session's clock.
    pub solver_ms: f64,
    /// The same per step.
    pub solver_ms_per_step: f64,
    /// What the pointer holds: `"target"` or `"obstacle"`.
    pub dragging: Option<&'static str>,
    /// Which obstacle, if one is held.
    pub dragging_obstacle: Option<usize>,
    /// The last step's error, if it failed.
    pub error: Option<&'a str>,
}

/// Values by name in a fixed order, written as one JSON object. (A
/// `BTreeMap` would sort them on every state: its sort and tree code cost
/// the page's module about 5 KB, measured with twiggy.)
#[derive(Debug, Clone, PartialEq)]
pub struct ByName<T>(pub Vec<(&'static str, T)>);

impl<T> ByName<T> {
    /// The value of `name`, if there is one.
    pub fn get(&self, name: &str) -> Option<&T> {
        self.0.iter().find(|(k, _)| *k == name).map(|(_, v)| v)
    }
}

impl<T: Serialize> Serialize for ByName<T> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_map(self.0.iter().map(|(k, v)| (k, v)))
    }
}

/// Where the ghost is.
#[derive(Debug, Serialize)]
pub struct GhostState {
    /// Its joint angles.
    pub theta: Vec<f64>,
    /// Its end effector.
    pub ee: [f64; 2],
}

impl Session {
    /// For a method that reads an influence distance, it and the
    /// link-obstacle pairs within it at the current pose (what the page
    /// draws as the active dampers).
    pub fn near_pairs(&self) -> Option<(f64, Pairs)> {
        let p = self.planner();
        if !p.method().reads(&INFLUENCE) {
            return None;
        }
        let influence = p.scene().param(&INFLUENCE);
        let mut pairs = Pairs::default();
        pairs.update(p.pose(), &p.scene().obstacles, influence);
        if let Some(post) = p.scene().ground() {
            pairs.add_ground(p.pose(), post, influence);
        }
        Some((influence, pairs))
    }

    /// The snapshot the page reads.
    pub fn state(&self) -> State<'_> {
        let p = self.planner();
        let s = p.sample();
        let summary = p.summary();
        let scene = p.scene();
        let obstacle = scene.obstacles.first();
        let near = self.near_pairs();
        State {
            t: s.t,
            task: self.task,
            method: p.method().name(),
            uses: p.method().networks(),
            running: self.running,
            ended: self.ended(),
            tf: scene.tf,
            theta0: &scene.theta0,
            own_start: self.own_start,
            speed: self.speed,
            lambda: scene.param(&LAMBDA),
            params: ByName(
                params::all()
                    .iter()
                    .map(|q| (q.name, scene.param(q)))
                    .collect(),
            ),
            reads: p.method().params().iter().map(|q| q.name).collect(),
            influence: near.as_ref().map(|(d, _)| *d),
            dampers: near.map_or_else(Vec::new, |(_, pairs)| pairs.as_slice().to_vec()),
            damping: scene.damping.is_some(),
            weighting: scene.weighting,
            floor: scene.floor,
            auto_damping: summary.auto_damping,
            selected: self.selected().name(),
            selected_index: match self.selected() {
                super::Handle::Target => 0,
                super::Handle::Obstacle(i) | super::Handle::Joint(i) => i,
            },
            out_of_reach: !p.reachable(),
            without_limits: p
                .method()
                .without_limits(scene.arm.joint_limits().is_some()),
            feedback: scene.feedback_gain,
            theta: &s.theta,
            joints: &s.joints,
            ee: s.ee,
            reference: s.reference,
            target: scene.target,
            line: p.line(),
            path: (!scene.path.is_line()).then(|| scene.path.to_string()),
            arm: &scene.arm,
            obstacle: obstacle.map(|o| o.centre),
            radius: obstacle.map(|o| o.radius),
            obstacles: &scene.obstacles,
            nearest: nearest(&s.joints, &scene.obstacles),
            distance: s.distance,
            min_distance: summary.min_distance,
            clearance: s.clearance,
            min_clearance: summary.min_clearance,
            collision: s.collision,
            collided: summary.collided,
            below_floor: super::history::below_floor(&s.joints),
            below_floor_steps: self.histories.below_floor,
            tracking_error: s.tracking_error,
            final_error: summary.final_error,
            manipulability: s.manipulability,
            singular_values: velocity_ellipse(p.pose().jjt()).1,
            past_limits: &s.past_limits,
            limit_steps: summary.limit_steps,
            delta: s.delta,
            in_range: s.in_range,
            phi_handover: s.phi_handover,
            handover_steps: summary.handover_steps,
            networks: self.networks_fit(),
            trained_range: self.trained_range(),
            network_set: self.network_set().map(|n| n.name()),
            precision: self.precision().name(),
            set_fits: ByName(
                NetworkSet::ALL
                    .iter()
                    .map(|s| (s.name(), networks::builtin_fits(&scene.arm)))
                    .collect(),
            ),
            arm_text: scene.arm.to_string(),
            paper_arm: scene.arm.same_geometry(&Arm::paper()),
            revision: self.revision(),
            ghost: self.ghost().map(|g| GhostState {
                theta: g.theta().iter().copied().collect(),
                ee: g.sample().ee,
            }),
            steps: summary.steps,
            frame_steps: self.frame_steps,
            solver_ms: self.solver_ms,
            solver_ms_per_step: self.solver_ms_per_step,
            dragging: self.drag.map(Handle::name),
            dragging_obstacle: match self.drag {
                Some(Handle::Obstacle(i)) => Some(i),
                _ => None,
            },
            error: self.error.as_deref(),
        }
    }
}

/// The obstacle whose centre is nearest to a link of the arm with joints
/// `joints`.
fn nearest(joints: &[[f64; 2]], obstacles: &[Obstacle]) -> Option<usize> {
    let joints: Vec<_> = joints
        .iter()
        .map(|p| nalgebra::Vector2::new(p[0], p[1]))
        .collect();
    obstacles
        .iter()
        .map(|o| obstacle::clearance(&joints, &o.point()))
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(i, _)| i)
}
