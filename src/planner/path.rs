//! The path being tracked in time, for a hand of `M` coordinates: the
//! reference `X_ref(t)` of the closed loop `Xdot + K (X_ref - X)` and the
//! task velocity `Xdot` along it, at constant speed from `t0` to
//! `t0 + duration`, then holding still at its end. The paper's straight
//! line ([`Line`], section V step a) and the paths beyond it (a circle, a
//! polyline: [`crate::scene::Path`] in the plane,
//! [`crate::scene::SpacePath`] in space), with `s = (t - t0) / duration`
//! in `[0, 1]`:
//!
//! - a circle: the angle about the centre grows linearly (`along.rs`);
//! - a polyline: the arc length grows linearly, `X_ref` the point at arc
//!   length `s L` (`L` the whole length) and `Xdot` the unit direction of
//!   its segment times `L / duration`.
//!
//! A line's `Xdot` is constant, taken at the step's midpoint (so every
//! RK4 stage sees the same value, the published numbers). A circle's
//! `Xdot` turns within a step, so the planner evaluates it at each RK4
//! stage's own time ([`Track::velocity`]); a polyline's too (its corners).
//! One track for every arm: what differs is how an arm's scene describes
//! its path, which the arm's [`super::Planned`] turns into a [`Shape`].

use super::along::{self, polyline_at, Circle};
use super::Line;
use crate::model::straight;

/// What a track runs along, its geometry computed once (borrowed from the
/// scene's path where it is a list of points).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Shape<'a, const M: usize> {
    /// The straight line to the path's end.
    Line,
    /// A circle.
    Circle(Circle<M>),
    /// A polyline through the points from the start.
    Points(&'a [[f64; M]]),
}

/// The shape a [`Track`] keeps.
#[derive(Debug, Clone, PartialEq)]
enum Owned<const M: usize> {
    Line,
    Circle(Circle<M>),
    Points(Vec<[f64; M]>),
}

/// The task's shortest path from `a` to `b`: its point at fraction `s`
/// and its rate `d/ds` ([`crate::model::Model::geodesic`]).
pub type Geodesic<const M: usize> = fn(a: [f64; M], b: [f64; M], s: f64) -> ([f64; M], [f64; M]);

/// A path with its timing: `line` runs from the start to the path's end
/// (the target, for the line itself) over the path's time.
#[derive(Debug, Clone)]
pub struct Track<const M: usize = 2> {
    /// From the start to the end, with the path's timing; the path itself
    /// for the straight line.
    pub line: Line<M>,
    shape: Owned<M>,
    /// How the line runs between its ends (the arm's task's shortest path).
    geodesic: Geodesic<M>,
    /// The line's rate `d/ds` along its geodesic (constant: `end - start`
    /// for a straight line), found once when the line is made.
    rate: [f64; M],
}

/// Tracks are equal where their lines and shapes are (the line's
/// geodesic is the task's, the same for every track of one arm).
impl<const M: usize> PartialEq for Track<M> {
    fn eq(&self, other: &Self) -> bool {
        self.line == other.line && self.shape == other.shape
    }
}

impl<const M: usize> Track<M> {
    /// The track of `shape` from `start` at time `t0` to `end`, taking
    /// `duration` seconds.
    pub(crate) fn from_shape(
        shape: Shape<'_, M>,
        geodesic: Geodesic<M>,
        start: [f64; M],
        end: [f64; M],
        t0: f64,
        duration: f64,
    ) -> Self {
        let mut track = Self {
            line: Line::new(start, end, t0, duration),
            shape: Owned::Line,
            geodesic,
            rate: [0.0; M],
        };
        track.renew(shape, start, end, t0, duration);
        track
    }

    /// The straight line from `start` at `t0` to `end`, taking `duration`.
    pub fn straight(start: [f64; M], end: [f64; M], t0: f64, duration: f64) -> Self {
        Self::from_shape(Shape::Line, straight, start, end, t0, duration)
    }

    /// The line from `start` at `t0` to `end` along `geodesic`, taking
    /// `duration`.
    pub fn line_along(
        geodesic: Geodesic<M>,
        start: [f64; M],
        end: [f64; M],
        t0: f64,
        duration: f64,
    ) -> Self {
        Self::from_shape(Shape::Line, geodesic, start, end, t0, duration)
    }

    /// The same track with a new shape and timing, reusing its buffer: no
    /// allocation where a polyline has no more points than before.
    pub(crate) fn renew(
        &mut self,
        shape: Shape<'_, M>,
        start: [f64; M],
        end: [f64; M],
        t0: f64,
        duration: f64,
    ) {
        self.line = Line::new(start, end, t0, duration);
        self.rate = (self.geodesic)(start, end, 0.0).1;
        self.shape = match (shape, std::mem::replace(&mut self.shape, Owned::Line)) {
            (Shape::Line, _) => Owned::Line,
            (Shape::Circle(c), _) => Owned::Circle(c),
            (Shape::Points(p), Owned::Points(mut kept)) => {
                kept.clear();
                kept.extend_from_slice(p);
                Owned::Points(kept)
            }
            (Shape::Points(p), _) => Owned::Points(p.to_vec()),
        };
    }

    /// Whether the track is the straight line.
    pub fn is_line(&self) -> bool {
        self.shape == Owned::Line
    }

    /// Where the path ends (and the reference holds still after it).
    pub fn end(&self) -> [f64; M] {
        self.line.end
    }

    /// The point at fraction `s` of a circle or a polyline and its
    /// derivative `d/ds`; at a polyline's corner the segment after it when
    /// `after`, else the one before.
    fn at(&self, s: f64, after: bool) -> ([f64; M], [f64; M]) {
        let (a, b) = (self.line.start, self.line.end);
        match &self.shape {
            Owned::Circle(c) => c.at(s),
            Owned::Points(points) => polyline_at(a, points, s, after),
            Owned::Line => (self.geodesic)(a, b, s),
        }
    }

    fn fraction(&self, t: f64) -> f64 {
        along::fraction(t, self.line.t0, self.line.duration)
    }

    /// Reference point `X_ref(t)`: the start before `t0`, the end after
    /// (exactly: whole laps end where they began).
    pub fn reference(&self, t: f64) -> [f64; M] {
        if self.is_line() {
            let l = &self.line;
            let s = ((t - l.t0) / l.duration).clamp(0.0, 1.0);
            return (self.geodesic)(l.start, l.end, s).0;
        }
        let s = self.fraction(t);
        if s >= 1.0 {
            self.line.end
        } else {
            self.at(s, true).0
        }
    }

    /// The task velocity `Xdot` at an RK4 stage's time `t` of a step whose
    /// midpoint is `t_mid`: zero unless `t_mid` lies inside the path's time;
    /// a line's `Line::velocity_at` the midpoint whatever `t`, a circle's
    /// and a polyline's exact at `t` (clamped into the path's time; at a
    /// polyline's corner, `after` picks the segment that follows it, for a
    /// step's first stages, or the one before it, for its last).
    pub fn velocity(&self, t_mid: f64, t: f64, after: bool) -> [f64; M] {
        let l = &self.line;
        if self.is_line() || !along::moving(t_mid, l.t0, l.duration) {
            return self.line_velocity(t_mid);
        }
        let d = self.at(self.fraction(t), after).1;
        std::array::from_fn(|k| d[k] / l.duration)
    }

    /// The task velocity at time `t` in a loop of the user's own (the
    /// Python package's `Controller.step`): the path's `Xdot` over the
    /// instant after `t`, so a line's constant rate on `[t0, t0 +
    /// duration)`, a circle's and a polyline's exact at `t` (at a corner,
    /// the segment after it); zero before the path starts and once it has
    /// ended.
    pub fn velocity_after(&self, t: f64) -> [f64; M] {
        let l = &self.line;
        if !(t >= l.t0 && t < l.t0 + l.duration) {
            return [0.0; M];
        }
        if self.is_line() {
            return std::array::from_fn(|k| self.rate[k] / l.duration);
        }
        let d = self.at(self.fraction(t), true).1;
        std::array::from_fn(|k| d[k] / l.duration)
    }

    /// The line's constant task velocity while it runs (its geodesic's
    /// rate over its duration), zero before and after; taken at a step's
    /// midpoint so that every RK4 stage of a step sees the same `Xdot`.
    pub fn line_velocity(&self, t_mid: f64) -> [f64; M] {
        let l = &self.line;
        if t_mid > l.t0 && t_mid < l.t0 + l.duration {
            std::array::from_fn(|k| self.rate[k] / l.duration)
        } else {
            [0.0; M]
        }
    }

    /// Whether `can` holds at every point of the path that bounds it: the
    /// line's end, a circle at 256 points, every corner of a polyline.
    /// Allocation-free.
    pub fn all_points(&self, mut can: impl FnMut([f64; M]) -> bool) -> bool {
        match &self.shape {
            Owned::Line => can(self.line.end),
            Owned::Circle(_) => (0..256).all(|k| can(self.at(f64::from(k) / 256.0, true).0)),
            Owned::Points(p) => p.iter().all(|&v| can(v)),
        }
    }
}
