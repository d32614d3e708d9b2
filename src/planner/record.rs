//! What the planner tracks and reports: the straight line, the sample after
//! each step, the summary of a run and the whole trajectory.

use serde::{Deserialize, Serialize};

use super::Method;

/// The straight line being tracked: from `start` at time `t0` to `end` at
/// `t0 + duration`, at constant speed, then holding still at `end`; for a
/// hand of `M` coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(bound(
    serialize = "[f64; M]: Serialize",
    deserialize = "[f64; M]: Deserialize<'de>"
))]
pub struct Line<const M: usize = 2> {
    /// The hand where the line starts.
    pub start: [f64; M],
    /// End of the line (the target).
    pub end: [f64; M],
    /// Time at which the line starts (s).
    pub t0: f64,
    /// Time the line takes (s); a whole number of RK4 steps.
    pub duration: f64,
}

impl<const M: usize> Line<M> {
    /// The line from `start` at `t0` to `end`, taking `duration` seconds.
    pub fn new(start: [f64; M], end: [f64; M], t0: f64, duration: f64) -> Self {
        Self {
            start,
            end,
            t0,
            duration,
        }
    }
}

/// The state after one integration step (or at the start), of an arm
/// whose hand has `M` coordinates (the planar arm's by default).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(bound(
    serialize = "[f64; M]: Serialize, P: Serialize",
    deserialize = "[f64; M]: Deserialize<'de>, P: Deserialize<'de>"
))]
pub struct Sample<const M: usize = 2, P = [f64; M]> {
    /// Time (s).
    pub t: f64,
    /// Joint angles (rad).
    pub theta: Vec<f64>,
    /// Joint positions `P(0)..P(n)`, `P(0)` first (in space the joints'
    /// origins, then the hand).
    pub joints: Vec<P>,
    /// The hand (end effector) `X = P(n)`.
    pub ee: [f64; M],
    /// The path's reference point at `t`.
    pub reference: [f64; M],
    /// Distance from the end effector to the reference.
    pub tracking_error: f64,
    /// For the pose task, the angle between the hand's orientation and the
    /// reference's (rad); absent for the hand's position.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub orientation_error: Option<f64>,
    /// Smallest distance from an obstacle centre to a moving link (in
    /// space, to a capsule's axis; none without obstacles).
    pub distance: Option<f64>,
    /// Smallest clearance between a moving link and an obstacle: the
    /// distance between their surfaces, negative inside (none without
    /// obstacles; absent from files written before it was kept).
    #[serde(default)]
    pub clearance: Option<f64>,
    /// Whether a link is inside an obstacle now (in the plane, or below
    /// the floor or across the post where the scene has them).
    pub collision: bool,
    /// The smallest distance between two capsules of the chain that it
    /// checks for self-collision (m, negative: they overlap); absent where
    /// it checks none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub self_clearance: Option<f64>,
    /// Damping `delta` in force at this pose.
    pub delta: f64,
    /// Manipulability `sqrt(det(J J^T))`.
    pub manipulability: f64,
    /// Whether the state is inside the trained range of the networks the
    /// method uses (always true for methods without networks).
    pub in_range: bool,
    /// Whether, in the step that led here, the exact damped `Phi` (eq. 20)
    /// stood in for the `Phi` network (Cases 1 and 3 only): the damping
    /// schedule switched on near a singular pose (no network can fit `Phi`
    /// where it is unbounded), or the refinement could not converge from
    /// the network's `Phi` ([`crate::ik::refine_phi`]).
    pub phi_handover: bool,
    /// Whether, in the step that led here, a quadratic program's constraints
    /// had to be relaxed because no rate satisfied them all (`qp` only).
    #[serde(default, skip_serializing_if = "is_false")]
    pub relaxed: bool,
    /// The joints (numbered from 1) past their position limits at this
    /// pose; absent from the JSON when none is (always, for an arm without
    /// limits).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub past_limits: Vec<usize>,
}

impl Sample<6, [f64; 3]> {
    /// A sample of the hand's pose as one of its position: the hand's and
    /// the reference's points, the orientation's error kept in
    /// `orientation_error` (what the page in space shows of a pose run, and
    /// the figures draw).
    pub fn position(&self) -> Sample<3> {
        let point = |x: [f64; 6]| [x[0], x[1], x[2]];
        Sample {
            t: self.t,
            theta: self.theta.clone(),
            joints: self.joints.clone(),
            ee: point(self.ee),
            reference: point(self.reference),
            tracking_error: self.tracking_error,
            orientation_error: self.orientation_error,
            distance: self.distance,
            clearance: self.clearance,
            collision: self.collision,
            self_clearance: self.self_clearance,
            delta: self.delta,
            manipulability: self.manipulability,
            in_range: self.in_range,
            phi_handover: self.phi_handover,
            relaxed: self.relaxed,
            past_limits: self.past_limits.clone(),
        }
    }
}

fn is_false(b: &bool) -> bool {
    !*b
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl<const M: usize, P: Clone + Default> Sample<M, P> {
    /// A sample of an `n`-joint arm with everything zero but the end
    /// effector and the reference, at `ee` (the planner fills it at once).
    pub(super) fn zeros(n: usize, ee: [f64; M]) -> Self {
        Self {
            t: 0.0,
            theta: vec![0.0; n],
            joints: vec![P::default(); n + 1],
            ee,
            reference: ee,
            tracking_error: 0.0,
            orientation_error: None,
            distance: None,
            clearance: None,
            collision: false,
            self_clearance: None,
            delta: 0.0,
            manipulability: 0.0,
            in_range: true,
            phi_handover: false,
            relaxed: false,
            past_limits: Vec::with_capacity(n),
        }
    }
}

/// What a run achieved, over every step since the last reset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Method of the last step (`method` in JSON, as on the command line;
    /// `mode`, the older name, is read too).
    #[serde(alias = "mode")]
    pub method: Method,
    /// RK4 steps taken.
    pub steps: usize,
    /// Time reached (s).
    pub t: f64,
    /// Smallest obstacle-centre-to-link distance over all steps (none without obstacles).
    pub min_distance: Option<f64>,
    /// Smallest link-to-obstacle clearance over all steps (see
    /// [`Sample::clearance`]).
    #[serde(default)]
    pub min_clearance: Option<f64>,
    /// Whether a link entered an obstacle at any step.
    pub collided: bool,
    /// Samples with a link inside an obstacle (see [`Sample::collision`]);
    /// absent from the JSON when none was.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub collision_steps: usize,
    /// The smallest distance between two capsules the chain checks for
    /// self-collision over all steps (absent where it checks none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_self_clearance: Option<f64>,
    /// Samples with two of those capsules overlapping: a self-collision
    /// (absent from the JSON when none was); a run with any is no
    /// [`Summary::success`].
    #[serde(default, skip_serializing_if = "is_zero")]
    pub self_collision_steps: usize,
    /// Distance from the end effector to the path's end now (the target
    /// for the line, the start for a circle, the last point of a polyline).
    pub final_error: f64,
    /// Largest distance from the end effector to the reference.
    pub max_tracking_error: f64,
    /// For the pose task, the angle between the hand's orientation and the
    /// path's end now (rad); absent for the hand's position.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub final_orientation_error: Option<f64>,
    /// For the pose task, the largest angle between the hand's orientation
    /// and the reference's (rad).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_orientation_error: Option<f64>,
    /// `final_error <= REACH_TOLERANCE` and, for the pose task,
    /// `final_orientation_error <=` [`super::REACH_ANGLE`].
    pub reached: bool,
    /// The run's success, the one test every report uses (the atlas's
    /// `success`, the training check, `eval`): clear of every obstacle and
    /// within the joints' limits throughout, and [`Summary::reached`]. Absent in files written before
    /// it (read as `false`; [`crate::export::RunFile::from_json`] sets it
    /// from the other fields).
    #[serde(default)]
    pub success: bool,
    /// Whether the target (every point of the path) lies in the arm's
    /// workspace at all.
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
    /// (see [`Sample::phi_handover`]).
    pub handover_steps: usize,
    /// Steps in which the quadratic program's constraints were relaxed (see
    /// [`Sample::relaxed`]); absent from the JSON when none was.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub relaxed_steps: usize,
    /// Samples with a joint past its position limits (see
    /// [`Sample::past_limits`]); a run with any is no
    /// [`Summary::success`]. Absent from the JSON when none was.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub limit_steps: usize,
}

impl Summary {
    /// The summary of a run that could not start: no step, no clearance,
    /// the final error unknown (NaN; `null` in JSON).
    pub fn nothing(method: Method) -> Self {
        Self {
            method,
            steps: 0,
            t: 0.0,
            min_distance: None,
            min_clearance: None,
            collided: false,
            collision_steps: 0,
            min_self_clearance: None,
            self_collision_steps: 0,
            final_error: f64::NAN,
            max_tracking_error: 0.0,
            final_orientation_error: None,
            max_orientation_error: None,
            reached: false,
            success: false,
            target_reachable: false,
            out_of_range_steps: 0,
            max_delta: 0.0,
            auto_damping: false,
            handover_steps: 0,
            relaxed_steps: 0,
            limit_steps: 0,
        }
    }
}

/// A whole run: every sample from `t = 0` to `tf`, and the summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(bound(
    serialize = "[f64; M]: Serialize, P: Serialize",
    deserialize = "[f64; M]: Deserialize<'de>, P: Deserialize<'de>"
))]
pub struct Trajectory<const M: usize = 2, P = [f64; M]> {
    /// Method used (`method` in JSON; `mode`, the older name, is read too).
    #[serde(alias = "mode")]
    pub method: Method,
    /// One sample per RK4 step, the initial state first.
    pub steps: Vec<Sample<M, P>>,
    /// Outcome.
    pub summary: Summary,
}

#[derive(Debug, Clone, Copy)]
pub(super) struct Stats {
    pub(super) steps: usize,
    pub(super) min_distance: Option<f64>,
    pub(super) min_clearance: Option<f64>,
    pub(super) collided: bool,
    pub(super) collision_steps: usize,
    pub(super) min_self_clearance: Option<f64>,
    pub(super) self_collision_steps: usize,
    pub(super) max_tracking_error: f64,
    pub(super) max_orientation_error: Option<f64>,
    pub(super) out_of_range_steps: usize,
    pub(super) max_delta: f64,
    pub(super) handover_steps: usize,
    pub(super) relaxed_steps: usize,
    pub(super) limit_steps: usize,
}

impl Stats {
    pub(super) fn new() -> Self {
        Self {
            steps: 0,
            min_distance: None,
            min_clearance: None,
            collided: false,
            collision_steps: 0,
            min_self_clearance: None,
            self_collision_steps: 0,
            max_tracking_error: 0.0,
            max_orientation_error: None,
            out_of_range_steps: 0,
            max_delta: 0.0,
            handover_steps: 0,
            relaxed_steps: 0,
            limit_steps: 0,
        }
    }

    pub(super) fn record<const M: usize, P>(&mut self, s: &Sample<M, P>) {
        self.observe(s);
        self.collision_steps += usize::from(s.collision);
        self.self_collision_steps += usize::from(s.self_clearance.is_some_and(|d| d < 0.0));
        self.max_tracking_error = self.max_tracking_error.max(s.tracking_error);
        if let Some(e) = s.orientation_error {
            self.max_orientation_error = Some(self.max_orientation_error.map_or(e, |m| m.max(e)));
        }
        if !s.in_range {
            self.out_of_range_steps += 1;
        }
        self.max_delta = self.max_delta.max(s.delta);
        if s.phi_handover {
            self.handover_steps += 1;
        }
        if s.relaxed {
            self.relaxed_steps += 1;
        }
        if !s.past_limits.is_empty() {
            self.limit_steps += 1;
        }
    }

    /// Folds a sample's distance and collision into the run's (a change of
    /// setting between steps: no step is counted).
    pub(super) fn observe<const M: usize, P>(&mut self, s: &Sample<M, P>) {
        let min = |m: Option<f64>, d: f64| Some(m.map_or(d, |m: f64| m.min(d)));
        if let Some(d) = s.distance {
            self.min_distance = min(self.min_distance, d);
        }
        if let Some(c) = s.clearance {
            self.min_clearance = min(self.min_clearance, c);
        }
        if let Some(c) = s.self_clearance {
            self.min_self_clearance = min(self.min_self_clearance, c);
        }
        self.collided |= s.collision;
    }
}
