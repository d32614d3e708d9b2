//! The snapshot of a spatial session the page reads every frame, and a
//! method's row of the comparison.

use serde::Serialize;

use super::SpaceSession;
use crate::planner::methods::Method;
use crate::planner::params;
use crate::planner::Summary;
use crate::scene::JointWeighting;
use crate::session::ByName;
use crate::space::manipulability::{manipulability, velocity_ellipsoid};
use crate::space::{rotation, Vec3};

/// The snapshot the page reads every frame.
#[derive(Debug, Serialize)]
pub struct SpaceState<'a> {
    /// `"space"`: what tells the page's code this snapshot from the plane's.
    pub kind: &'static str,
    /// The preset's key (`panda`, `iiwa14`) and what a menu says of it.
    pub arm: &'a str,
    /// See `arm`.
    pub arm_label: &'a str,
    /// The number of joints.
    pub dof: usize,
    /// Method name.
    pub method: &'static str,
    /// The shipped network set installed (`panda-reach`), if one is.
    pub network_set: Option<&'static str>,
    /// Whether networks are installed.
    pub has_networks: bool,
    /// Whether the networks in use see the pose on screen inside their
    /// trained range ([`SpaceSession::in_range`]).
    pub in_range: bool,
    /// The networks' arithmetic: `f64` or `f32`.
    pub precision: &'static str,
    /// Time shown (s), the run's final time, and whether the clock runs
    /// and the run has ended.
    pub t: f64,
    /// See `t`.
    pub tf: f64,
    /// See `t`.
    pub running: bool,
    /// See `t`.
    pub ended: bool,
    /// Playback speed.
    pub speed: f64,
    /// Joint angles shown (rad).
    pub theta: &'a [f64],
    /// The run's start pose (rad).
    pub theta0: &'a [f64],
    /// The joints' ranges `[lo, hi]` (rad).
    pub joint_limits: Option<&'a [[f64; 2]]>,
    /// The hand, where the path has it now, and the line's end (m).
    pub hand: Vec3,
    /// See `hand`.
    pub reference: Vec3,
    /// See `hand`.
    pub target: Vec3,
    /// `|hand - reference|` (m).
    pub tracking_error: f64,
    /// `position` or `pose`: what the hand's task is.
    pub task: &'static str,
    /// The target's roll, pitch and yaw (rad; URDF's fixed axes) and `Z`'s
    /// orientation weight, for the pose task.
    pub target_rpy: Option<Vec3>,
    /// See `target_rpy`.
    pub orientation_weight: Option<f64>,
    /// The hand's roll, pitch and yaw at the pose shown (rad).
    pub hand_rpy: Vec3,
    /// For the pose task, the angle between the hand's orientation and the
    /// reference's at the time shown (rad).
    pub orientation_error: Option<f64>,
    /// Yoshikawa's manipulability `sqrt(det(J J^T))` at the pose shown
    /// (m^3), and the singular values `sigma_1 >= sigma_2 >= sigma_3` of
    /// `J` (m), the velocity ellipsoid's half-lengths.
    pub manipulability: f64,
    /// See `manipulability`.
    pub singular_values: [f64; 3],
    /// The spheres, `[x, y, z, r]` each (m).
    pub spheres: Vec<[f64; 4]>,
    /// The smallest clearance between the links and the spheres now and so
    /// far (m; negative: inside), `None` without spheres.
    pub clearance: Option<f64>,
    /// See `clearance`.
    pub min_clearance: Option<f64>,
    /// A link is inside a sphere now; one was earlier in the run.
    pub collision: bool,
    /// See `collision`.
    pub collided: bool,
    /// When the run first has a link inside a sphere (s), if it does.
    pub first_collision: Option<f64>,
    /// Joints past a limit now.
    pub past_limits: usize,
    /// The whole run's outcome (what it does by `tf`).
    pub summary: &'a Summary,
    /// Why the run stopped before `tf`, if it did.
    pub failure: Option<&'a str>,
    /// What the keys move: `target` or `sphere 2`.
    pub selected: String,
    /// What the pointer holds, if anything.
    pub dragging: Option<String>,
    /// The obstacle gain λ (the method's `lambda`).
    pub lambda: f64,
    /// Every parameter of the methods by name, and those the method reads.
    pub params: ByName<f64>,
    /// See `params`.
    pub reads: Vec<&'static str>,
    /// How the methods of eq. (5) use the joint limits.
    pub weighting: JointWeighting,
    /// Whether the floor is an obstacle.
    pub floor: bool,
    /// Whether the chain's capsules are checked against each other, and
    /// the smallest distance between two checked capsules now (m;
    /// negative: they overlap).
    pub self_collision: bool,
    /// See `self_collision`.
    pub self_clearance: Option<f64>,
    /// Whether the damping schedule near singular poses is on.
    pub damping: bool,
    /// The path the hand follows as its text (`points:0.5,0,0.6;...`, the
    /// address's `path=`); none (`null`) for the line.
    pub path: Option<String>,
    /// Closed-loop gain `K`.
    pub feedback: f64,
    /// The camera: yaw and pitch (rad), distance (m).
    pub view: [f64; 3],
    /// Counts the runs computed (changes whenever the run does).
    pub run_revision: u64,
    /// The numerical ghost at the time shown, in the network cases.
    pub ghost: Option<SpaceGhost<'a>>,
}

/// Where the numerical ghost is (the plane's `ghost`, with the hand in
/// space).
#[derive(Debug, Serialize)]
pub struct SpaceGhost<'a> {
    /// Its joint angles (rad).
    pub theta: &'a [f64],
    /// Its hand (m).
    pub hand: Vec3,
}

/// A method's row of the comparison.
#[derive(Debug, Clone, Serialize)]
pub struct SpaceMethodRun {
    /// The method.
    pub method: Method,
    /// Its run's outcome.
    pub summary: Summary,
    /// Why its run stopped before `tf`, if it did.
    pub failure: Option<String>,
}

impl SpaceSession {
    /// The snapshot.
    pub fn state(&self) -> SpaceState<'_> {
        let sample = self.sample();
        let played = self.played();
        let clearance = sample.and_then(|s| s.clearance);
        let c = &self.camera;
        SpaceState {
            kind: "space",
            arm: &self.robot.key,
            arm_label: &self.robot.label,
            dof: self.scene.arm.dof(),
            method: self.method.name(),
            network_set: self.network_set().map(|s| s.name()),
            has_networks: self.networks.is_some(),
            in_range: self.in_range(),
            precision: self.precision.name(),
            t: sample.map_or(0.0, |s| s.t),
            tf: self.scene.tf,
            running: self.running,
            ended: self.ended(),
            speed: self.speed,
            theta: self.pose.theta(),
            theta0: &self.scene.theta0,
            joint_limits: self.scene.arm.joint_limits().map(|l| l.ranges()),
            hand: self.pose.hand(),
            reference: sample.map_or(self.pose.hand(), |s| s.reference),
            target: self.scene.target,
            tracking_error: sample.map_or(0.0, |s| s.tracking_error),
            task: if self.orientation.is_some() {
                "pose"
            } else {
                "position"
            },
            target_rpy: self.target_rotation().map(|r| rotation::matrix_rpy(&r)),
            orientation_weight: self.orientation.map(|o| o.weight),
            hand_rpy: rotation::matrix_rpy(&self.hand_rotation()),
            orientation_error: sample.and_then(|s| s.orientation_error),
            manipulability: manipulability(&self.pose),
            singular_values: velocity_ellipsoid(self.pose.jjt()).1,
            spheres: self
                .scene
                .obstacles
                .iter()
                .map(|s| [s.centre[0], s.centre[1], s.centre[2], s.radius])
                .collect(),
            clearance,
            min_clearance: played.iter().filter_map(|s| s.clearance).reduce(f64::min),
            collision: clearance.is_some_and(|c| c < 0.0),
            collided: played.iter().any(|s| s.clearance.is_some_and(|c| c < 0.0)),
            first_collision: self
                .samples
                .iter()
                .find(|s| s.clearance.is_some_and(|c| c < 0.0))
                .map(|s| s.t),
            past_limits: sample.map_or(0, |s| s.past_limits.len()),
            summary: &self.summary,
            failure: self.failure.as_deref(),
            selected: self.selected().describe(),
            dragging: self
                .dragging()
                .map(|h| h.describe())
                .or_else(|| self.dragging_elbow().map(|k| format!("elbow {}", k + 1))),
            lambda: self.scene.param(&crate::planner::methods::LAMBDA),
            params: ByName(
                params::all()
                    .iter()
                    .map(|p| (p.name, self.scene.param(p)))
                    .collect(),
            ),
            reads: params::all()
                .iter()
                .filter(|p| self.method.reads(p))
                .map(|p| p.name)
                .collect(),
            weighting: self.scene.weighting,
            floor: self.scene.floor,
            self_collision: self.self_collision(),
            self_clearance: sample.and_then(|s| s.self_clearance),
            damping: self.scene.damping.is_some(),
            path: (!self.scene.path.is_line()).then(|| self.scene.path.to_string()),
            feedback: self.scene.feedback_gain,
            view: [c.yaw, c.pitch, c.distance],
            run_revision: self.runs,
            ghost: self.ghost().map(|g| SpaceGhost {
                theta: g.theta(),
                hand: g.hand(),
            }),
        }
    }
}
