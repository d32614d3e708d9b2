//! The path the hand follows at constant speed over `tf` (issue 25, item
//! 4): the paper's straight line to the target (section V, step a), a
//! circle through the hand's start, or a polyline through points. One text
//! everywhere (the command line's `--path`, the page's `path=` and the
//! element's `path` attribute, a scene's JSON `path`):
//!
//! - `line`: the straight line from the hand to the target (the default);
//! - `circle:CX,CY[,LAPS]`: the circle about `(CX, CY)` through the hand's
//!   start (its radius the start's distance from the centre),
//!   counter-clockwise, `LAPS` whole laps (default 1);
//! - `points:X,Y;X,Y;...`: the polyline from the hand through the points,
//!   ending at the last one.
//!
//! The timed reference `X_ref(t)` along a path is the planner's
//! (`crate::planner::Track`); this file is the syntax, its checks and the
//! geometry the atlas and the figures need.

use std::f64::consts::TAU;
use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::arm::{number, number_list};
use crate::error::{coordinate, Error, Result};
use crate::geometry::segment_distance_squared;

/// Most points a `points:` path may have.
pub const MAX_POINTS: usize = 64;
/// Most laps a `circle:` path may run.
pub const MAX_LAPS: u32 = 1000;
/// Smallest radius of a `circle:` path (m): its centre must lie this far
/// from the hand's start at least.
pub const MIN_RADIUS: f64 = 1e-6;

/// What the hand follows (see the module's syntax).
#[derive(Debug, Clone, Default, PartialEq)]
pub enum Path {
    /// The straight line to the scene's target (the paper's task).
    #[default]
    Line,
    /// The circle about `centre` through the hand's start, `laps` times
    /// counter-clockwise.
    Circle {
        /// Centre `(x, y)` (m).
        centre: [f64; 2],
        /// Whole laps, at least 1.
        laps: u32,
    },
    /// The polyline from the hand's start through these points (1 to
    /// [`MAX_POINTS`]), ending at the last.
    Points(Vec<[f64; 2]>),
}

impl Path {
    /// Whether this is the paper's straight line.
    pub fn is_line(&self) -> bool {
        *self == Path::Line
    }

    /// Checks the numbers (finite, within [`crate::error::MAX_COORDINATE`]),
    /// the laps and the points' count, and that a circle's centre is not
    /// the hand's `start` (radius 0). A point out of reach is allowed: the
    /// run will miss it.
    pub fn validate(&self, start: [f64; 2]) -> Result<()> {
        let syntax = |expected: String| Error::Syntax {
            what: "path",
            text: self.to_string(),
            expected,
        };
        match self {
            Path::Line => Ok(()),
            Path::Circle { centre, laps } => {
                coordinate("path circle centre x", centre[0])?;
                coordinate("path circle centre y", centre[1])?;
                if !(1..=MAX_LAPS).contains(laps) {
                    return Err(syntax(format!("LAPS must be 1 to {MAX_LAPS}")));
                }
                if distance(*centre, start) < MIN_RADIUS {
                    return Err(syntax(
                        "the centre is the hand's start: the circle would have radius 0".into(),
                    ));
                }
                Ok(())
            }
            Path::Points(points) => {
                if points.is_empty() || points.len() > MAX_POINTS {
                    return Err(syntax(format!("expected 1 to {MAX_POINTS} points")));
                }
                for p in points {
                    coordinate("path point x", p[0])?;
                    coordinate("path point y", p[1])?;
                }
                Ok(())
            }
        }
    }

    /// Where the path ends for a hand starting at `start`: the `target`
    /// for a line, the start for a circle (whole laps), the last point.
    pub fn end(&self, start: [f64; 2], target: [f64; 2]) -> [f64; 2] {
        match self {
            Path::Line => target,
            Path::Circle { .. } => start,
            Path::Points(p) => p.last().copied().unwrap_or(start),
        }
    }

    /// The path as a polyline from `start`: exact for a line and for
    /// points, a circle through `per_lap` chords (its corners on the
    /// circle, the start first and last).
    pub fn outline(&self, start: [f64; 2], target: [f64; 2], per_lap: usize) -> Vec<[f64; 2]> {
        match self {
            Path::Line => vec![start, target],
            Path::Points(p) => std::iter::once(start).chain(p.iter().copied()).collect(),
            Path::Circle { centre, .. } => {
                let (r, phase) = polar(*centre, start);
                let n = per_lap.max(3);
                let mut out: Vec<[f64; 2]> = (0..n)
                    .map(|k| {
                        let a = phase + TAU * k as f64 / n as f64;
                        [centre[0] + r * a.cos(), centre[1] + r * a.sin()]
                    })
                    .collect();
                out[0] = start;
                out.push(start);
                out
            }
        }
    }

    /// Exact distance from `p` to the path of a hand starting at `start`
    /// (to the nearest segment; to the circle `||p - c| - r|`).
    pub fn distance_to(&self, p: [f64; 2], start: [f64; 2], target: [f64; 2]) -> f64 {
        let segment = |a: [f64; 2], b: [f64; 2]| segment_distance_squared(p, a, b).sqrt();
        match self {
            Path::Line => segment(start, target),
            Path::Circle { centre, .. } => (distance(p, *centre) - distance(start, *centre)).abs(),
            Path::Points(points) => {
                let mut prev = start;
                let mut best = f64::INFINITY;
                for &q in points {
                    best = best.min(segment(prev, q));
                    prev = q;
                }
                best
            }
        }
    }
}

/// The radius and the angle of `p` about `centre`.
pub(crate) fn polar(centre: [f64; 2], p: [f64; 2]) -> (f64, f64) {
    let (dx, dy) = (p[0] - centre[0], p[1] - centre[1]);
    (dx.hypot(dy), dy.atan2(dx))
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// `line`, `circle:CX,CY[,LAPS]` or `points:X,Y;X,Y;...` (see the module);
/// the numbers by [`crate::arm`]'s parser, so finite ones only. The checks
/// that need the hand's start are [`Path::validate`]'s.
impl FromStr for Path {
    type Err = Error;
    fn from_str(text: &str) -> Result<Self> {
        let syntax = |expected: String| Error::Syntax {
            what: "path",
            text: text.to_string(),
            expected,
        };
        let t = text.trim();
        if t == "line" {
            return Ok(Path::Line);
        }
        if let Some(rest) = t.strip_prefix("circle:") {
            let (x, y, laps) = match rest.split(',').collect::<Vec<_>>()[..] {
                [x, y] => (x, y, None),
                [x, y, laps] => (x, y, Some(laps)),
                _ => return Err(syntax("expected circle:CX,CY or circle:CX,CY,LAPS".into())),
            };
            let centre = [number(x).map_err(&syntax)?, number(y).map_err(&syntax)?];
            let laps = match laps {
                None => 1,
                Some(l) => {
                    let l = number(l).map_err(&syntax)?;
                    if l.fract() != 0.0 || !(1.0..=MAX_LAPS as f64).contains(&l) {
                        return Err(syntax(format!(
                            "LAPS must be a whole number from 1 to {MAX_LAPS}"
                        )));
                    }
                    l as u32
                }
            };
            return Ok(Path::Circle { centre, laps });
        }
        if let Some(rest) = t.strip_prefix("points:") {
            let mut points = Vec::new();
            for part in rest.split(';').filter(|p| !p.trim().is_empty()) {
                if points.len() == MAX_POINTS {
                    return Err(syntax(format!("at most {MAX_POINTS} points")));
                }
                match number_list(part).map_err(&syntax)?[..] {
                    [x, y] => points.push([x, y]),
                    _ => return Err(syntax(format!("expected X,Y, got '{}'", part.trim()))),
                }
            }
            if points.is_empty() {
                return Err(syntax("expected at least one point X,Y".into()));
            }
            return Ok(Path::Points(points));
        }
        Err(syntax(
            "expected line, circle:CX,CY[,LAPS] or points:X,Y;X,Y;...".into(),
        ))
    }
}

impl fmt::Display for Path {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Path::Line => f.write_str("line"),
            Path::Circle { centre, laps } => {
                write!(f, "circle:{},{}", centre[0], centre[1])?;
                if *laps != 1 {
                    write!(f, ",{laps}")?;
                }
                Ok(())
            }
            Path::Points(points) => {
                f.write_str("points:")?;
                for (k, p) in points.iter().enumerate() {
                    let sep = if k == 0 { "" } else { ";" };
                    write!(f, "{sep}{},{}", p[0], p[1])?;
                }
                Ok(())
            }
        }
    }
}

impl Serialize for Path {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<'de> Deserialize<'de> for Path {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let text = String::deserialize(d)?;
        text.parse().map_err(serde::de::Error::custom)
    }
}
