//! The path being tracked in time: the reference `X_ref(t)` of the
//! closed loop `Xdot + K (X_ref - X)` and the task velocity `Xdot` along
//! it, at constant speed from `t0` to `t0 + duration`, then holding still
//! at its end. The paper's straight line ([`Line`], section V step a) and
//! the paths beyond it of [`crate::scene::Path`] (issue 25, item 4), with
//! `s = (t - t0) / duration` in `[0, 1]`:
//!
//! - a circle: the angle about the centre grows linearly,
//!   `X_ref = c + r (cos a, sin a)` with `a = a0 + 2 pi laps s` and
//!   `Xdot = r a' (-sin a, cos a)`;
//! - a polyline: the arc length grows linearly, `X_ref` the point at arc
//!   length `s L` (`L` the whole length) and `Xdot` the unit direction of
//!   its segment times `L / duration`.
//!
//! A line's `Xdot` is constant, taken at the step's midpoint (so every
//! RK4 stage sees the same value, the published numbers). A circle's
//! `Xdot` turns within a step, so the planner evaluates it at each RK4
//! stage's own time ([`Track::velocity`]); a polyline's too (its corners).
//! The maths of the timing is `along.rs`, shared with the arms in space;
//! sines and cosines by `crate::kinematics::sin_cos`, the page's module's
//! one.

use nalgebra::Vector2;

use super::along::{self, polyline_at, Circle};
use super::Line;
use crate::arm::Arm;
use crate::scene::Path;

/// A path with its timing: `line` runs from the start to the path's end
/// (the target, for the line itself) over the path's time.
#[derive(Debug, Clone, PartialEq)]
pub struct Track {
    /// From the start to the end, with the path's timing; the path itself
    /// for [`Path::Line`].
    pub line: Line,
    /// The path.
    pub path: Path,
}

impl Track {
    /// `path` for a hand at `start` at time `t0`, taking `duration`
    /// seconds (`target` is the line's end). The path must have been
    /// validated ([`Path::validate`]).
    pub fn new(path: Path, start: [f64; 2], target: [f64; 2], t0: f64, duration: f64) -> Self {
        let end = path.end(start, target);
        Self {
            line: Line::new(start, end, t0, duration),
            path,
        }
    }

    /// Where the path ends (and the reference holds still after it).
    pub fn end(&self) -> [f64; 2] {
        self.line.end
    }

    /// The point at fraction `s` of a circle or a polyline and its
    /// derivative `d/ds`; at a polyline's corner the segment after it when
    /// `after`, else the one before.
    fn at(&self, s: f64, after: bool) -> ([f64; 2], [f64; 2]) {
        let start = self.line.start;
        match &self.path {
            Path::Circle { centre, laps } => Circle::planar(*centre, start, *laps).at(s),
            Path::Points(points) => polyline_at(start, points, s, after),
            Path::Line => {
                let [a, b] = [start, self.line.end];
                let d = [b[0] - a[0], b[1] - a[1]];
                ([a[0] + s * d[0], a[1] + s * d[1]], d)
            }
        }
    }

    fn fraction(&self, t: f64) -> f64 {
        along::fraction(t, self.line.t0, self.line.duration)
    }

    /// Reference point `X_ref(t)`: the start before `t0`, the end after.
    pub fn reference(&self, t: f64) -> Vector2<f64> {
        let s = self.fraction(t);
        if self.path.is_line() {
            return self.line.reference(t);
        }
        // The end exactly: whole laps end where they began.
        let x = if s >= 1.0 {
            self.line.end
        } else {
            self.at(s, true).0
        };
        Vector2::new(x[0], x[1])
    }

    /// The task velocity `Xdot` at an RK4 stage's time `t` of a step whose
    /// midpoint is `t_mid`: zero unless `t_mid` lies inside the path's time;
    /// a line's [`Line::velocity_at`] the midpoint whatever `t`, a circle's
    /// and a polyline's exact at `t` (clamped into the path's time; at a
    /// polyline's corner, `after` picks the segment that follows it, for a
    /// step's first stages, or the one before it, for its last).
    pub fn velocity(&self, t_mid: f64, t: f64, after: bool) -> Vector2<f64> {
        let l = &self.line;
        if self.path.is_line() || !along::moving(t_mid, l.t0, l.duration) {
            return l.velocity_at(t_mid);
        }
        let d = self.at(self.fraction(t), after).1;
        Vector2::new(d[0] / l.duration, d[1] / l.duration)
    }

    /// Whether every point of the path lies in `arm`'s workspace (a
    /// circle checked at 256 points). Allocation-free.
    pub fn reachable(&self, arm: &Arm) -> bool {
        let can = |p: [f64; 2]| arm.can_reach(&Vector2::new(p[0], p[1]));
        match &self.path {
            Path::Circle { .. } => (0..256).all(|k| can(self.at(k as f64 / 256.0, true).0)),
            Path::Points(p) => p.iter().all(|&v| can(v)),
            Path::Line => can(self.line.end),
        }
    }

    /// The path as a polyline, for drawing ([`Path::outline`]; a circle
    /// through 96 chords).
    pub fn outline(&self) -> Vec<[f64; 2]> {
        self.path.outline(self.line.start, self.line.end, 96)
    }
}
