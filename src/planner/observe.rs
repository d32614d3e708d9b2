//! What is observed of a planner's state: the sample after each step (and
//! after each change of setting), whether the networks in use see inputs
//! in their trained range, and the summary of the run so far.

use super::methods::Note;
use super::{Method, Planner, Sample, Summary, Surrogate, REACH_TOLERANCE};
use crate::clearance::Pair;
use crate::kinematics::Pose;
use crate::obstacle::Obstacle;

impl Planner {
    /// The current state: the start, or the result of the last step. Kept up
    /// to date by the planner (no copy, no allocation).
    pub fn sample(&self) -> &Sample {
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
        let ee = pose.end_effector();
        let reference = self.track.reference(self.t);
        s.t = self.t;
        s.theta.copy_from_slice(pose.theta());
        s.joints.copy_from_slice(pose.joints());
        s.ee = ee;
        s.reference = [reference[0], reference[1]];
        s.tracking_error = distance(ee, [reference[0], reference[1]]);
        s.distance = None;
        s.clearance = None;
        s.collision = false;
        for ob in &self.scene.obstacles {
            let d = pose.clearance(ob.centre);
            s.collision |= d < ob.radius;
            s.distance = Some(s.distance.map_or(d, |m| m.min(d)));
            let c = d - ob.radius;
            s.clearance = Some(s.clearance.map_or(c, |m| m.min(c)));
        }
        if let Some(post) = self.scene.ground() {
            // The ground as an obstacle: a link below the floor or across
            // the post collides.
            let n = pose.dof();
            s.collision |= (0..n).any(|k| Pair::floor(pose, k).clearance < 0.0)
                || (1..n).any(|k| Pair::post(pose, k, post).clearance < 0.0);
        }
        s.delta = self.scene.param(&super::methods::DELTA)
            + self
                .scene
                .damping
                .map_or(0.0, |d| d.delta_at_sigma(pose.sigma_min()));
        s.manipulability = pose.manipulability();
        s.in_range = in_range(
            self.method,
            self.networks.as_deref(),
            pose,
            &self.scene.obstacles,
        );
        s.phi_handover = note.handover;
        s.relaxed = note.relaxed;
        s.past_limits.clear();
        if let Some(limits) = self.scene.arm.joint_limits() {
            let past = limits.ranges().iter().zip(pose.theta());
            for (k, (&[lo, hi], &t)) in past.enumerate() {
                if !(lo..=hi).contains(&t) {
                    s.past_limits.push(k + 1);
                }
            }
        }
    }

    /// Whether the networks the current method uses see inputs inside
    /// their trained range (true for methods without networks).
    pub fn in_range(&self) -> bool {
        self.sample.in_range
    }

    /// Outcome since the last reset.
    pub fn summary(&self) -> Summary {
        let x = self.ws.pose.end_effector();
        // The path's end: the target for the line, the start for a circle,
        // the last point of a polyline.
        let final_error = distance(x, self.track.end());
        Summary {
            method: self.method,
            steps: self.stats.steps,
            t: self.t,
            min_distance: self.stats.min_distance,
            min_clearance: self.stats.min_clearance,
            collided: self.stats.collided,
            final_error,
            max_tracking_error: self.stats.max_tracking_error,
            reached: final_error <= REACH_TOLERANCE,
            success: !self.stats.collided
                && self.stats.limit_steps == 0
                && final_error <= REACH_TOLERANCE,
            target_reachable: self.track.reachable(&self.scene.arm),
            out_of_range_steps: self.stats.out_of_range_steps,
            max_delta: self.stats.max_delta,
            auto_damping: self.auto_damping,
            handover_steps: self.stats.handover_steps,
            relaxed_steps: self.stats.relaxed_steps,
            limit_steps: self.stats.limit_steps,
        }
    }
}

/// Euclidean distance between two points.
#[inline]
fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (a[0] - b[0], a[1] - b[1]);
    (dx * dx + dy * dy).sqrt()
}

/// Whether the networks `method` uses see `pose` (and every obstacle)
/// inside their trained range.
fn in_range(
    method: Method,
    networks: Option<&dyn Surrogate>,
    pose: &Pose,
    obstacles: &[Obstacle],
) -> bool {
    let Some(nets) = networks else {
        return true;
    };
    let needs = method.networks();
    let phi_ok = !needs.phi || nets.phi_in_range(pose);
    let v_ok = !needs.v || obstacles.iter().all(|ob| nets.v_in_range(pose, ob.centre));
    phi_ok && v_ok
}
