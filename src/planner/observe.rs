//! What is observed of a planner's state: the sample after each step (and
//! after each change of setting), whether the networks in use see inputs
//! in their trained range, and the summary of the run so far.

use super::methods::Note;
use super::{Method, Planned, Planner, Sample, Summary, Surrogate, REACH_ANGLE, REACH_TOLERANCE};
use crate::model::Scene as _;

impl<A: Planned<M>, const M: usize> Planner<A, M> {
    /// The current state: the start, or the result of the last step. Kept up
    /// to date by the planner (no copy, no allocation).
    pub fn sample(&self) -> &Sample<M, A::Point> {
        &self.sample
    }

    /// Refreshes the sample after a change of setting (same state, same
    /// step). Before the first step the run is its start alone, so the
    /// summary starts afresh from the new sample; later the next step
    /// records it (or [`Planner::observe_now`]).
    pub(super) fn resample(&mut self) {
        self.refresh_sample(Note {
            handover: self.sample.phi_handover,
            relaxed: self.sample.relaxed,
        });
        if self.step_index == 0 {
            self.stats = super::record::Stats::new();
            self.stats.record(&self.sample);
        }
    }

    /// Folds the current sample's distance and collision into the run's
    /// summary without a step: after a change between steps (an obstacle
    /// dropped next to the arm while the clock is paused is the closest the
    /// run came to it).
    pub fn observe_now(&mut self) {
        self.stats.observe(&self.sample);
    }

    /// Rewrites the sample in place from the current pose; `note` is what
    /// the rate evaluations of the step that led here said.
    pub(super) fn refresh_sample(&mut self, note: Note) {
        let pose = &self.ws.pose;
        let s = &mut self.sample;
        observe_pose::<A, M>(&self.scene, pose, s);
        let reference = self.track.reference(self.t);
        s.t = self.t;
        s.reference = reference;
        let (position, orientation) = A::errors(s.ee, reference);
        s.tracking_error = position;
        s.orientation_error = orientation;
        s.in_range = in_range::<A, M>(self.method, self.networks.as_deref(), pose, &self.scene);
        s.phi_handover = note.handover;
        s.relaxed = note.relaxed;
    }

    /// Whether the networks the current method uses see inputs inside
    /// their trained range (true for methods without networks).
    pub fn in_range(&self) -> bool {
        self.sample.in_range
    }

    /// Outcome since the last reset.
    pub fn summary(&self) -> Summary {
        let x = A::hand(&self.ws.pose);
        // The path's end: the target for the line, the start for a circle,
        // the last point of a polyline.
        let (final_error, final_orientation_error) = A::errors(x, self.track.end());
        let reached = final_error <= REACH_TOLERANCE
            && final_orientation_error.is_none_or(|e| e <= REACH_ANGLE);
        Summary {
            method: self.method,
            steps: self.stats.steps,
            t: self.t,
            min_distance: self.stats.min_distance,
            min_clearance: self.stats.min_clearance,
            collided: self.stats.collided,
            collision_steps: self.stats.collision_steps,
            min_self_clearance: self.stats.min_self_clearance,
            self_collision_steps: self.stats.self_collision_steps,
            final_error,
            max_tracking_error: self.stats.max_tracking_error,
            final_orientation_error,
            max_orientation_error: self.stats.max_orientation_error,
            reached,
            success: !self.stats.collided
                && self.stats.self_collision_steps == 0
                && self.stats.limit_steps == 0
                && reached,
            target_reachable: self.reachable,
            out_of_range_steps: self.stats.out_of_range_steps,
            max_delta: self.stats.max_delta,
            auto_damping: self.auto_damping,
            handover_steps: self.stats.handover_steps,
            relaxed_steps: self.stats.relaxed_steps,
            limit_steps: self.stats.limit_steps,
        }
    }
}

/// Writes into `s` what a sample records of `pose` in `scene` alone: the
/// angles, the joints and the hand, the obstacles' distance, clearance and
/// collision, the damping in force, the manipulability and the joints past
/// their limits (`s` has room for the arm; nothing is allocated). What
/// depends on the run (the time, the reference, the networks' range, the
/// step's notes) is the planner's to fill; a run file read back fills it
/// from the file.
pub fn observe_pose<A: Planned<M>, const M: usize>(
    scene: &A::Scene,
    pose: &A::Pose,
    s: &mut Sample<M, A::Point>,
) {
    s.theta.copy_from_slice(A::theta(pose));
    for (k, p) in s.joints.iter_mut().enumerate() {
        *p = A::joint_point(pose, k);
    }
    s.ee = A::hand(pose);
    let contact = A::contact(scene, pose);
    s.distance = contact.distance;
    s.clearance = contact.clearance;
    s.collision = contact.collision;
    s.self_clearance = contact.self_clearance;
    s.delta = scene.value(&super::methods::DELTA)
        + scene
            .damping()
            .map_or(0.0, |d| d.delta_at_sigma(A::sigma_min(pose)));
    s.manipulability = A::manipulability(pose);
    s.past_limits.clear();
    if let Some(limits) = scene.arm().joint_limits() {
        let past = limits.ranges().iter().zip(A::theta(pose));
        for (k, (&[lo, hi], &t)) in past.enumerate() {
            if !(lo..=hi).contains(&t) {
                s.past_limits.push(k + 1);
            }
        }
    }
}

/// Whether the networks `method` uses see `pose` (and every obstacle)
/// inside their trained range.
fn in_range<A: Planned<M>, const M: usize>(
    method: Method,
    networks: Option<&dyn Surrogate<A, M>>,
    pose: &A::Pose,
    scene: &A::Scene,
) -> bool {
    let Some(nets) = networks else {
        return true;
    };
    let needs = method.networks();
    let phi_ok = !needs.phi || nets.phi_in_range(pose);
    let v_ok = !needs.v || A::obstacle_centres(scene).all(|o| nets.v_in_range(pose, o));
    phi_ok && v_ok
}
