//! The spatial path being tracked in time: the reference `X_ref(t)` and
//! the task velocity `Xdot` of the hand of an arm in space, at constant
//! speed from `t = 0` to `tf`, then holding still at the path's end. The
//! timing is the planar track's (`planner/path.rs`), its maths shared
//! (`planner/along.rs`): a line's `Xdot` is constant; a circle's and a
//! polyline's are evaluated at each RK4 stage's own time, at a polyline's
//! corner the segment after it but at a step's last stage.

use crate::error::{Error, Result};
use crate::planner::along::{self, polyline_at, Circle};
use crate::scene::{circle_plane, SpacePath};
use crate::space::{norm, sub, Vec3};

/// The shape a [`SpaceTrack`] runs along, its geometry computed once.
#[derive(Debug, Clone, PartialEq)]
enum Shape {
    Line,
    Circle(Circle<3>),
    Points(Vec<Vec3>),
}

/// A spatial path with its timing.
#[derive(Debug, Clone, PartialEq)]
pub struct SpaceTrack {
    start: Vec3,
    end: Vec3,
    duration: f64,
    shape: Shape,
}

impl SpaceTrack {
    /// `path` for a hand at `start` at `t = 0`, taking `duration` seconds
    /// (`target` is the line's end); refused where the path does not
    /// validate ([`SpacePath::validate`]).
    pub fn new(path: &SpacePath, start: Vec3, target: Vec3, duration: f64) -> Result<Self> {
        path.validate(start)?;
        let shape = match path {
            SpacePath::Line => Shape::Line,
            SpacePath::Points(p) => Shape::Points(p.clone()),
            SpacePath::Circle {
                centre,
                normal,
                laps,
            } => {
                let (axes, radius) =
                    circle_plane(*centre, *normal, start).map_err(|why| Error::Syntax {
                        what: "path",
                        text: path.to_string(),
                        expected: why.into(),
                    })?;
                Shape::Circle(Circle {
                    centre: *centre,
                    axes,
                    radius,
                    phase: 0.0,
                    sweep: std::f64::consts::TAU * f64::from(*laps),
                })
            }
        };
        Ok(Self {
            start,
            end: path.end(start, target),
            duration,
            shape,
        })
    }

    /// Where the path ends (and the reference holds still after it).
    pub fn end(&self) -> Vec3 {
        self.end
    }

    /// Whether no point of the path is certainly out of reach of a hand
    /// at most `reach` from `shoulder` ([`Chain::reach`](crate::space::Chain::reach),
    /// an upper bound: a point inside it may still be out of reach): the
    /// line's end, a circle at 256 points, every corner of a polyline.
    /// Allocation-free.
    pub fn reachable(&self, shoulder: Vec3, reach: f64) -> bool {
        let can = |p: Vec3| norm(sub(p, shoulder)) <= reach;
        match &self.shape {
            Shape::Line => can(self.end),
            Shape::Circle(c) => (0..256).all(|k| can(c.at(f64::from(k) / 256.0).0)),
            Shape::Points(p) => p.iter().all(|&v| can(v)),
        }
    }

    /// Reference point `X_ref(t)`: the start before `t = 0`, the end
    /// exactly from the path's end on (whole laps end where they began).
    pub fn reference(&self, t: f64) -> Vec3 {
        let s = along::fraction(t, 0.0, self.duration);
        let (a, b) = (self.start, self.end);
        match &self.shape {
            Shape::Line => [0, 1, 2].map(|k| a[k] + s * (b[k] - a[k])),
            _ if s >= 1.0 => b,
            Shape::Circle(c) => c.at(s).0,
            Shape::Points(p) => polyline_at(a, p, s, true).0,
        }
    }

    /// The task velocity `Xdot` at an RK4 stage's time `t` of a step whose
    /// midpoint is `t_mid`: zero unless `t_mid` lies inside the path's
    /// time; a line's constant, a circle's and a polyline's exact at `t`
    /// (at a polyline's corner, `after` picks the segment that follows it,
    /// for a step's first stages, or the one before it, for its last).
    pub fn velocity(&self, t_mid: f64, t: f64, after: bool) -> Vec3 {
        let h = self.duration;
        if !along::moving(t_mid, 0.0, h) {
            return [0.0; 3];
        }
        let s = along::fraction(t, 0.0, h);
        let d = match &self.shape {
            Shape::Line => {
                let (a, b) = (self.start, self.end);
                return [0, 1, 2].map(|k| (b[k] - a[k]) / h);
            }
            Shape::Circle(c) => c.at(s).1,
            Shape::Points(p) => polyline_at(self.start, p, s, after).1,
        };
        d.map(|x| x / h)
    }
}
