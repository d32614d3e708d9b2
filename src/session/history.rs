//! What the page draws of the past: the end-effector trail, the
//! stroboscopic trace (every [`STROBE_EVERY`]th pose, as in the paper's
//! figures) and the time series of the plots. Each is capped; the oldest
//! entries go first, in O(1) (ring buffers).

use std::collections::VecDeque;

use crate::planner::Sample;

/// Every how many steps a pose joins the stroboscopic trace (the paper's figures).
pub const STROBE_EVERY: usize = 5;
/// Most trail points kept.
const MAX_TRAIL: usize = 4000;
/// Most poses of the stroboscopic trace kept.
const MAX_STROBE: usize = 200;
/// Most points of the time series kept.
const MAX_HISTORY: usize = 600;

/// One point of the time-series plots.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// Time (s).
    pub t: f64,
    /// Clearance between the links and the nearest obstacle's edge
    /// (negative inside it; [`crate::planner::Sample::clearance`]).
    pub clearance: Option<f64>,
    /// Tracking error (m).
    pub error: f64,
    /// Joint angles.
    pub theta: Vec<f64>,
}

/// The trail, the stroboscopic trace and the time series of one run.
#[derive(Debug, Clone, Default)]
pub(super) struct Histories {
    pub(super) trail: VecDeque<[f64; 2]>,
    pub(super) strobe: VecDeque<Vec<[f64; 2]>>,
    /// Samples recorded since the trace was last cleared (every
    /// [`STROBE_EVERY`]th joins it).
    strobe_count: usize,
    pub(super) points: VecDeque<Point>,
    /// Samples recorded with a link below the floor.
    pub(super) below_floor: usize,
}

/// Whether a link of the arm with joints `P(0)..P(n)` reaches below the
/// floor (`y < 0`): a real arm would hit the ground there. `P(0)`, the top
/// of the post, never does.
pub fn below_floor(joints: &[[f64; 2]]) -> bool {
    joints.iter().skip(1).any(|p| p[1] < 0.0)
}

/// Appends `value`, dropping the oldest entry when `deque` holds `cap`.
fn push_capped<T>(deque: &mut VecDeque<T>, cap: usize, value: T) {
    if deque.len() >= cap {
        deque.pop_front();
    }
    deque.push_back(value);
}

impl Histories {
    /// Everything cleared (a new run).
    pub(super) fn clear(&mut self) {
        self.trail.clear();
        self.clear_strobe();
        self.points.clear();
        self.below_floor = 0;
    }

    /// The stroboscopic trace cleared (a new line).
    pub(super) fn clear_strobe(&mut self) {
        self.strobe.clear();
        self.strobe_count = 0;
    }

    /// Records a sample.
    pub(super) fn record(&mut self, s: &Sample) {
        push_capped(&mut self.trail, MAX_TRAIL, s.ee);
        self.below_floor += usize::from(below_floor(&s.joints));
        if self.strobe_count.is_multiple_of(STROBE_EVERY) {
            push_capped(&mut self.strobe, MAX_STROBE, s.joints.clone());
        }
        self.strobe_count += 1;
        push_capped(
            &mut self.points,
            MAX_HISTORY,
            Point {
                t: s.t,
                clearance: s.clearance,
                error: s.tracking_error,
                theta: s.theta.clone(),
            },
        );
    }
}
