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

use crate::arm::number_list;
use crate::error::{coordinate, Error, Result};
use crate::geometry::segment_distance_squared;
use crate::kinematics::sin_cos;

/// Most points a `points:` path may have.
pub const MAX_POINTS: usize = 64;
/// Most laps a `circle:` path may run.
pub const MAX_LAPS: u32 = 1000;
/// What a refusal of the laps says (with [`MAX_LAPS`]; the spatial
/// path's too).
pub(super) const LAPS: &str = "LAPS must be a whole number from 1 to 1000";
/// What a refusal of the points' count says (with [`MAX_POINTS`]).
const COUNT: &str = "expected 1 to 64 points X,Y";
/// Smallest radius of a `circle:` path (m): its centre must lie this far
/// from the hand's start at least.
pub const MIN_RADIUS: f64 = 1e-6;

/// Least distance (m) between the points of a path drawn on the page's
/// stage ([`Path::drawn`]).
pub const DRAWN_SPACING: f64 = 0.05;

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

    /// The `points:` path through a stroke drawn by a pointer (`stroke`,
    /// world points in the order drawn), to the millimetre and thinned to
    /// points at least [`DRAWN_SPACING`] apart (twice that, and so on,
    /// until at most [`MAX_POINTS`] remain): the first point and each one
    /// that far from the last kept, the stroke's end in place of the last
    /// kept. An empty stroke gives no points, which [`Path::validate`]
    /// refuses.
    pub fn drawn(stroke: &[[f64; 2]]) -> Self {
        Path::Points(thinned(stroke, distance))
    }

    /// Checks the numbers (finite, within [`crate::error::MAX_COORDINATE`]),
    /// the laps and the points' count, and that a circle's centre is not
    /// the hand's `start` (radius 0). A point out of reach is allowed: the
    /// run will miss it.
    pub fn validate(&self, start: [f64; 2]) -> Result<()> {
        let refuse = |expected: &str| {
            Err(Error::Syntax {
                what: "path",
                text: self.to_string(),
                expected: expected.into(),
            })
        };
        let points = match self {
            Path::Line => return Ok(()),
            Path::Circle { centre, laps } => {
                if !(1..=MAX_LAPS).contains(laps) {
                    return refuse(LAPS);
                }
                if distance(*centre, start) < MIN_RADIUS {
                    return refuse(
                        "the centre is the hand's start: the circle would have radius 0",
                    );
                }
                std::slice::from_ref(centre)
            }
            Path::Points(p) if p.is_empty() || p.len() > MAX_POINTS => return refuse(COUNT),
            Path::Points(p) => p,
        };
        check_points(points)
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
        let mut out = vec![start];
        match self {
            Path::Line => out.push(target),
            Path::Points(p) => out.extend_from_slice(p),
            Path::Circle { centre, .. } => {
                let (dx, dy) = (start[0] - centre[0], start[1] - centre[1]);
                let (r, phase, n) = (dx.hypot(dy), dy.atan2(dx), per_lap.max(3));
                for k in 1..n {
                    let (sin, cos) = sin_cos(phase + TAU * k as f64 / n as f64);
                    out.push([centre[0] + r * cos, centre[1] + r * sin]);
                }
                out.push(start);
            }
        }
        out
    }

    /// Exact distance from `p` to the path of a hand starting at `start`
    /// (to the nearest segment; to the circle `||p - c| - r|`).
    pub fn distance_to(&self, p: [f64; 2], start: [f64; 2], target: [f64; 2]) -> f64 {
        let segment = |a: [f64; 2], b: [f64; 2]| segment_distance_squared(p, a, b).sqrt();
        match self {
            Path::Line => segment(start, target),
            Path::Circle { centre, .. } => (distance(p, *centre) - distance(start, *centre)).abs(),
            Path::Points(points) => polyline_distance(start, points, segment),
        }
    }
}

/// The points' coordinates checked as a path's (finite, within
/// [`crate::error::MAX_COORDINATE`]; `path x`, `path y`, `path z`): both
/// kinds of path.
pub(super) fn check_points<const D: usize>(points: &[[f64; D]]) -> Result<()> {
    for p in points {
        for (c, what) in p.iter().zip(["path x", "path y", "path z"]) {
            coordinate(what, *c)?;
        }
    }
    Ok(())
}

/// The distance to the polyline from `start` through `points`, by
/// `segment(a, b)`, the distance to one segment: both kinds of path.
pub(super) fn polyline_distance<const D: usize>(
    start: [f64; D],
    points: &[[f64; D]],
    segment: impl Fn([f64; D], [f64; D]) -> f64,
) -> f64 {
    let mut prev = start;
    let mut best = f64::INFINITY;
    for &q in points {
        best = best.min(segment(prev, q));
        prev = q;
    }
    best
}

/// The points of `points:X,Y;X,Y;...` (`D` numbers each, 1 to
/// [`MAX_POINTS`]), `count` what a refusal of their number says: both kinds
/// of path.
pub(super) fn parse_points<const D: usize>(
    rest: &str,
    refuse: impl Fn(&str) -> Error,
    count: &str,
) -> Result<Vec<[f64; D]>> {
    let mut points = Vec::new();
    for part in rest.split(';').filter(|p| !p.trim().is_empty()) {
        let numbers = number_list(part).map_err(|e| refuse(&e))?;
        let point: [f64; D] = numbers.try_into().map_err(|_| {
            refuse(if D == 2 {
                "expected X,Y for each point"
            } else {
                "expected X,Y,Z for each point"
            })
        })?;
        if points.len() == MAX_POINTS {
            return Err(refuse(count));
        }
        points.push(point);
    }
    if points.is_empty() {
        return Err(refuse(count));
    }
    Ok(points)
}

/// `points:X,Y;X,Y;...`: both kinds of path.
pub(super) fn write_points<const D: usize>(
    f: &mut fmt::Formatter<'_>,
    points: &[[f64; D]],
) -> fmt::Result {
    f.write_str("points:")?;
    for (k, p) in points.iter().enumerate() {
        f.write_str(if k == 0 { "" } else { ";" })?;
        for (i, c) in p.iter().enumerate() {
            write!(f, "{}{c}", if i == 0 { "" } else { "," })?;
        }
    }
    Ok(())
}

/// A path's JSON is its text (the address's `path=`): both kinds of path.
macro_rules! path_as_text {
    ($path:ty) => {
        impl serde::Serialize for $path {
            fn serialize<S: serde::Serializer>(
                &self,
                s: S,
            ) -> std::result::Result<S::Ok, S::Error> {
                s.collect_str(self)
            }
        }

        impl<'de> serde::Deserialize<'de> for $path {
            fn deserialize<D: serde::Deserializer<'de>>(
                d: D,
            ) -> std::result::Result<Self, D::Error> {
                let text = String::deserialize(d)?;
                text.parse().map_err(serde::de::Error::custom)
            }
        }
    };
}
pub(super) use path_as_text;

/// The points of a stroke drawn by a pointer (`stroke`, world points in
/// the order drawn; the plane's or space's), to the millimetre and thinned
/// to points at least [`DRAWN_SPACING`] apart by `distance` (twice that,
/// and so on, until at most [`MAX_POINTS`] remain): the first point and
/// each one that far from the last kept, the stroke's end in place of the
/// last kept. An empty stroke gives no points.
pub(super) fn thinned<const D: usize>(
    stroke: &[[f64; D]],
    distance: fn([f64; D], [f64; D]) -> f64,
) -> Vec<[f64; D]> {
    // To the millimetre: a path's text people can read (`+ 0.0` turns
    // the `-0` of a rounded small negative into `0`).
    let mm = |p: [f64; D]| p.map(|v| (v * 1e3).round() / 1e3 + 0.0);
    let mut gap = DRAWN_SPACING;
    loop {
        let mut kept: Vec<[f64; D]> = Vec::new();
        for &p in stroke {
            let p = mm(p);
            if kept.last().is_none_or(|&q| distance(p, q) >= gap) {
                kept.push(p);
            }
        }
        // (A gap grown past every finite distance ends it too: the
        // scene refuses the points then, which are not finite.)
        if kept.len() <= MAX_POINTS || !gap.is_finite() {
            kept.truncate(MAX_POINTS);
            if let (Some(&end), [_, .., last]) = (stroke.last(), &mut kept[..]) {
                *last = mm(end);
            }
            return kept;
        }
        gap *= 2.0;
    }
}

/// `laps` as a whole number of laps from 1 to [`MAX_LAPS`], if it is one
/// (the planar and the spatial circle's rule).
pub(super) fn whole_laps(laps: f64) -> Option<u32> {
    (laps.fract() == 0.0 && (1.0..=f64::from(MAX_LAPS)).contains(&laps)).then_some(laps as u32)
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
        parse_path(
            text,
            Path::Line,
            |numbers, refuse| {
                let (centre, laps) = match numbers[..] {
                    [x, y] => ([x, y], 1.0),
                    [x, y, laps] => ([x, y], laps),
                    _ => return Err(refuse("expected circle:CX,CY or circle:CX,CY,LAPS")),
                };
                Ok(Path::Circle {
                    centre,
                    laps: whole_laps(laps).ok_or_else(|| refuse(LAPS))?,
                })
            },
            Path::Points,
            COUNT,
            "expected line, circle:CX,CY[,LAPS] or points:X,Y;X,Y;...",
        )
    }
}

/// `line`, `circle:NUMBERS` or `points:...` read into `line`, what `circle`
/// makes of the numbers, or `points` of the points of `D` coordinates;
/// `count` and `expected` what a refusal of the points' number and of the
/// kind say: both kinds of path.
pub(super) fn parse_path<T, const D: usize>(
    text: &str,
    line: T,
    circle: impl FnOnce(Vec<f64>, &dyn Fn(&str) -> Error) -> Result<T>,
    points: impl FnOnce(Vec<[f64; D]>) -> T,
    count: &str,
    expected: &str,
) -> Result<T> {
    let refuse = |expected: &str| Error::Syntax {
        what: "path",
        text: text.to_string(),
        expected: expected.into(),
    };
    let t = text.trim();
    if t == "line" {
        return Ok(line);
    }
    let (kind, rest) = t.split_once(':').unwrap_or((t, ""));
    match kind {
        "circle" => circle(number_list(rest).map_err(|e| refuse(&e))?, &refuse),
        "points" => Ok(points(parse_points(rest, refuse, count)?)),
        _ => Err(refuse(expected)),
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
            Path::Points(points) => write_points(f, points),
        }
    }
}

path_as_text!(Path);
