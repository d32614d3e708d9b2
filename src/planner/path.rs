//! The path being tracked in time: the reference `X_ref(t)` of the
//! closed loop `Xdot + K (X_ref - X)` and the task velocity `Xdot` along
//! it, at constant speed from `t0` to `t0 + duration`, then holding still
//! at its end. The paper's straight line ([`Line`], section V step a) and
//! the paths beyond it of [`crate::scene::Path`] (issue 25, item 4):
//!
//! - a circle: the angle about the centre grows linearly,
//!   `X_ref = c + r (cos a, sin a)` with `a = a0 + 2 pi laps s` and
//!   `Xdot = r a' (-sin a, cos a)`, `s = (t - t0) / duration`;
//! - a polyline: the arc length grows linearly, `X_ref` the point at arc
//!   length `s L` (`L` the whole length) and `Xdot` the unit direction of
//!   its segment times `L / duration`.
//!
//! A line's `Xdot` is constant, taken at the step's midpoint (so every
//! RK4 stage sees the same value, the published numbers). A circle's
//! `Xdot` turns within a step, so the planner evaluates it at each RK4
//! stage's own time ([`Track::velocity`]); a polyline's too (its corners).

use std::f64::consts::TAU;

use nalgebra::Vector2;

use super::Line;
use crate::arm::Arm;
use crate::scene::Path;

/// A path with its timing (see the module).
#[derive(Debug, Clone, PartialEq)]
pub enum Track {
    /// The paper's straight line.
    Line(Line),
    /// A circle through the start.
    Circle(Circle),
    /// A polyline from the start.
    Points(Polyline),
}

/// A circle about `centre` of radius `radius`, from angle `phase` through
/// `sweep` radians (counter-clockwise, `2 pi` per lap).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    /// Where the hand starts (and ends).
    pub start: [f64; 2],
    /// Centre (m).
    pub centre: [f64; 2],
    /// Radius (m), the start's distance from the centre.
    pub radius: f64,
    /// The start's angle about the centre (rad).
    pub phase: f64,
    /// The angle swept (rad).
    pub sweep: f64,
    /// Time the circle starts (s).
    pub t0: f64,
    /// Time it takes (s).
    pub duration: f64,
}

/// A polyline through `vertices` (the start first), with the arc length
/// at each vertex.
#[derive(Debug, Clone, PartialEq)]
pub struct Polyline {
    /// The corners, the start first.
    pub vertices: Vec<[f64; 2]>,
    /// Arc length from the start to each corner (m), `0` first.
    pub lengths: Vec<f64>,
    /// Time the polyline starts (s).
    pub t0: f64,
    /// Time it takes (s).
    pub duration: f64,
}

impl Track {
    /// `path` for a hand at `start` at time `t0`, taking `duration`
    /// seconds (`target` is the line's end). The path must have been
    /// validated ([`Path::validate`]).
    pub fn new(path: &Path, start: [f64; 2], target: [f64; 2], t0: f64, duration: f64) -> Self {
        match path {
            Path::Line => Track::Line(Line::new(start, target, t0, duration)),
            Path::Circle { centre, laps } => {
                let (dx, dy) = (start[0] - centre[0], start[1] - centre[1]);
                Track::Circle(Circle {
                    start,
                    centre: *centre,
                    radius: dx.hypot(dy),
                    phase: dy.atan2(dx),
                    sweep: TAU * f64::from(*laps),
                    t0,
                    duration,
                })
            }
            Path::Points(points) => {
                let vertices: Vec<[f64; 2]> = std::iter::once(start)
                    .chain(points.iter().copied())
                    .collect();
                let mut lengths = Vec::with_capacity(vertices.len());
                let mut total = 0.0;
                lengths.push(0.0);
                for w in vertices.windows(2) {
                    total += (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
                    lengths.push(total);
                }
                Track::Points(Polyline {
                    vertices,
                    lengths,
                    t0,
                    duration,
                })
            }
        }
    }

    /// Where the hand starts.
    pub fn start(&self) -> [f64; 2] {
        match self {
            Track::Line(l) => l.start,
            Track::Circle(c) => c.start,
            Track::Points(p) => p.vertices[0],
        }
    }

    /// Where the path ends (and the reference holds still after it).
    pub fn end(&self) -> [f64; 2] {
        match self {
            Track::Line(l) => l.end,
            Track::Circle(c) => c.start,
            Track::Points(p) => p.vertices[p.vertices.len() - 1],
        }
    }

    /// Time the path starts and time it takes (s).
    pub fn timing(&self) -> (f64, f64) {
        match self {
            Track::Line(l) => (l.t0, l.duration),
            Track::Circle(c) => (c.t0, c.duration),
            Track::Points(p) => (p.t0, p.duration),
        }
    }

    fn fraction(&self, t: f64) -> f64 {
        let (t0, d) = self.timing();
        ((t - t0) / d).clamp(0.0, 1.0)
    }

    /// Reference point `X_ref(t)`: the start before `t0`, the end after.
    pub fn reference(&self, t: f64) -> Vector2<f64> {
        match self {
            Track::Line(l) => l.reference(t),
            Track::Circle(c) => {
                let s = self.fraction(t);
                if s >= 1.0 {
                    // Whole laps end exactly where they began.
                    return Vector2::new(c.start[0], c.start[1]);
                }
                let a = c.phase + c.sweep * s;
                Vector2::new(
                    c.centre[0] + c.radius * a.cos(),
                    c.centre[1] + c.radius * a.sin(),
                )
            }
            Track::Points(p) => {
                let s = self.fraction(t) * p.total();
                let k = p.segment(s, true);
                let (a, b) = (p.vertices[k], p.vertices[k + 1]);
                let len = p.lengths[k + 1] - p.lengths[k];
                let u = if len > 0.0 {
                    ((s - p.lengths[k]) / len).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                Vector2::new(a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1]))
            }
        }
    }

    /// The task velocity `Xdot` of a circle or a polyline at an RK4
    /// stage's time `t` of a step whose midpoint is `t_mid`: zero unless
    /// `t_mid` lies inside the path's time (as for the line), else exact
    /// at `t` (clamped into the path's time). At a polyline's corner,
    /// `after` picks the segment that follows it (a step's first stages)
    /// or the one before it (its last stage). A line's `Xdot` is
    /// [`Line::velocity_at`] of the midpoint, whatever `t`.
    pub fn velocity(&self, t_mid: f64, t: f64, after: bool) -> Vector2<f64> {
        let (t0, d) = self.timing();
        if !(t_mid > t0 && t_mid < t0 + d) {
            return Vector2::zeros();
        }
        match self {
            Track::Line(l) => l.velocity_at(t_mid),
            Track::Circle(c) => {
                let a = c.phase + c.sweep * self.fraction(t);
                let speed = c.radius * c.sweep / c.duration;
                Vector2::new(-speed * a.sin(), speed * a.cos())
            }
            Track::Points(p) => {
                let total = p.total();
                let k = p.segment(self.fraction(t) * total, after);
                let (a, b) = (p.vertices[k], p.vertices[k + 1]);
                let len = p.lengths[k + 1] - p.lengths[k];
                if len > 0.0 {
                    let speed = total / p.duration;
                    Vector2::new(speed * (b[0] - a[0]) / len, speed * (b[1] - a[1]) / len)
                } else {
                    Vector2::zeros()
                }
            }
        }
    }

    /// Whether every point of the path lies in `arm`'s workspace (a
    /// circle checked at 256 points). Allocation-free.
    pub fn reachable(&self, arm: &Arm) -> bool {
        let can = |p: [f64; 2]| arm.can_reach(&Vector2::new(p[0], p[1]));
        match self {
            Track::Line(l) => can(l.end),
            Track::Circle(_) => {
                let (t0, d) = self.timing();
                (0..=256).all(|k| {
                    let x = self.reference(t0 + d * k as f64 / 256.0);
                    can([x[0], x[1]])
                })
            }
            Track::Points(p) => p.vertices.iter().all(|&v| can(v)),
        }
    }

    /// The straight line from the start to the end, with the path's
    /// timing: the line itself for a line.
    pub fn line(&self) -> Line {
        match self {
            Track::Line(l) => *l,
            _ => {
                let (t0, d) = self.timing();
                Line::new(self.start(), self.end(), t0, d)
            }
        }
    }
}

impl Polyline {
    fn total(&self) -> f64 {
        self.lengths[self.lengths.len() - 1]
    }

    /// The segment holding arc length `s` (the one after a corner when
    /// `after`, else the one before it); segments of zero length are
    /// skipped where another holds `s`.
    fn segment(&self, s: f64, after: bool) -> usize {
        let last = self.lengths.len() - 2;
        let hit = (0..=last).find(|&k| {
            let (lo, hi) = (self.lengths[k], self.lengths[k + 1]);
            hi > lo
                && if after {
                    s >= lo && s < hi
                } else {
                    s > lo && s <= hi
                }
        });
        hit.unwrap_or(if s <= 0.0 { 0 } else { last })
    }
}
