//! The path the hand of an arm in space follows at constant speed over
//! `tf`: the planar [`super::Path`]'s three kinds with a third coordinate.
//! One text everywhere (the command line's `--path`, a spatial run file's
//! `path`):
//!
//! - `line`: the straight line from the hand to the target (the default);
//! - `circle:CX,CY,CZ,NX,NY,NZ[,LAPS]`: the circle about `C` through the
//!   hand's start, in the plane through `C` with normal `N`, `LAPS` whole
//!   laps (default 1), counter-clockwise seen from `N`'s tip. `N` is made
//!   perpendicular to `start - C` (its component along it dropped), so
//!   that the plane holds the start whatever `N`'s tilt; refused when it
//!   is zero or parallel to `start - C`, or when the start is `C`;
//! - `points:X,Y,Z;X,Y,Z;...`: the polyline from the hand through the
//!   points (1 to [`MAX_POINTS`]), ending at the last one.
//!
//! The numbers' checks, the laps' and the points' bounds are the planar
//! path's; the timed reference is the one planner's track
//! ([`crate::planner::Track`]).

use std::fmt;
use std::str::FromStr;

use super::path::{
    check_points, parse_path, path_as_text, polyline_distance, thinned, whole_laps, write_points,
    LAPS,
};
use super::{MAX_POINTS, MIN_RADIUS};
use crate::error::{coordinate, Error, Result};
use crate::space::{closest, cross, dot, norm, scale, sub, Vec3};

/// Smallest sine of the angle between a circle's normal `N` and `start -
/// C`: below it `N` is parallel to `start - C` and gives no plane.
pub const MIN_NORMAL_SINE: f64 = 1e-6;

/// What a refusal of the points' count says.
const COUNT: &str = "expected 1 to 64 points X,Y,Z";
/// What a refusal of a circle's numbers says.
const CIRCLE: &str = "expected circle:CX,CY,CZ,NX,NY,NZ or circle:CX,CY,CZ,NX,NY,NZ,LAPS";

/// What the hand of an arm in space follows (see the module's syntax).
#[derive(Debug, Clone, Default, PartialEq)]
pub enum SpacePath {
    /// The straight line to the scene's target.
    #[default]
    Line,
    /// The circle about `centre` through the hand's start, in the plane
    /// through `centre` with normal `normal` (made perpendicular to
    /// `start - centre`), `laps` times counter-clockwise seen from the
    /// normal's tip.
    Circle {
        /// Centre `C` (m).
        centre: Vec3,
        /// The plane's normal `N` as given (any length but zero).
        normal: Vec3,
        /// Whole laps, at least 1.
        laps: u32,
    },
    /// The polyline from the hand's start through these points (1 to
    /// [`MAX_POINTS`]), ending at the last.
    Points(Vec<Vec3>),
}

/// The plane of a circle about `centre` through `start` with normal
/// `normal`: its orthonormal axes `u = (start - C) / r` and `w = n x u`
/// (`n` the unit normal made perpendicular to `u`), and the radius `r`;
/// or what is wrong.
pub(crate) fn circle_plane(
    centre: Vec3,
    normal: Vec3,
    start: Vec3,
) -> std::result::Result<([Vec3; 2], f64), &'static str> {
    let d = sub(start, centre);
    let r = norm(d);
    if r.is_nan() || r < MIN_RADIUS {
        return Err("the centre is the hand's start: the circle would have radius 0");
    }
    let size = norm(normal);
    if size.is_nan() || size <= 0.0 {
        return Err("the normal N is zero: it must give the circle's plane");
    }
    let u = scale(d, 1.0 / r);
    let n = scale(normal, 1.0 / size);
    let across = sub(n, scale(u, dot(n, u)));
    let sine = norm(across);
    if sine.is_nan() || sine < MIN_NORMAL_SINE {
        return Err(
            "the normal N is parallel to the hand's start minus the centre: no plane through C with it holds the start",
        );
    }
    let n = scale(across, 1.0 / sine);
    Ok(([u, cross(n, u)], r))
}

impl SpacePath {
    /// Whether this is the straight line.
    pub fn is_line(&self) -> bool {
        *self == SpacePath::Line
    }

    /// The `points:` path through a stroke drawn by a pointer (`stroke`,
    /// world points in the order drawn: the page puts them on the plane
    /// through the hand's start facing the camera), thinned as the planar
    /// [`super::Path::drawn`] thins its own. An empty stroke gives no
    /// points, which [`SpacePath::validate`] refuses.
    pub fn drawn(stroke: &[Vec3]) -> Self {
        SpacePath::Points(thinned(stroke, |a, b| norm(sub(a, b))))
    }

    /// Checks the numbers (finite, within [`crate::error::MAX_COORDINATE`]),
    /// the laps and the points' count, and a circle's plane for a hand
    /// starting at `start` (`circle_plane`). A point out of reach is
    /// allowed: the run will miss it.
    pub fn validate(&self, start: Vec3) -> Result<()> {
        let refuse = |expected: &str| {
            Err(Error::Syntax {
                what: "path",
                text: self.to_string(),
                expected: expected.into(),
            })
        };
        let points: &[Vec3] = match self {
            SpacePath::Line => return Ok(()),
            SpacePath::Circle {
                centre,
                normal,
                laps,
            } => {
                if !(1..=super::MAX_LAPS).contains(laps) {
                    return refuse(LAPS);
                }
                for (c, axis) in centre.iter().zip(["CX", "CY", "CZ"]) {
                    coordinate(&format!("path centre {axis}"), *c)?;
                }
                for (c, axis) in normal.iter().zip(["NX", "NY", "NZ"]) {
                    coordinate(&format!("path normal {axis}"), *c)?;
                }
                return match circle_plane(*centre, *normal, start) {
                    Ok(_) => Ok(()),
                    Err(why) => refuse(why),
                };
            }
            SpacePath::Points(p) if p.is_empty() || p.len() > MAX_POINTS => return refuse(COUNT),
            SpacePath::Points(p) => p,
        };
        check_points(points)
    }

    /// Where the path ends for a hand starting at `start`: the `target`
    /// for a line, the start for a circle (whole laps), the last point.
    pub fn end(&self, start: Vec3, target: Vec3) -> Vec3 {
        match self {
            SpacePath::Line => target,
            SpacePath::Circle { .. } => start,
            SpacePath::Points(p) => p.last().copied().unwrap_or(start),
        }
    }

    /// The path as a polyline from `start`: exact for a line and for
    /// points, a circle through `per_lap` chords (its corners on the
    /// circle, the start first and last; the start alone where the circle
    /// has no plane).
    pub fn outline(&self, start: Vec3, target: Vec3, per_lap: usize) -> Vec<Vec3> {
        let mut out = vec![start];
        match self {
            SpacePath::Line => out.push(target),
            SpacePath::Points(p) => out.extend_from_slice(p),
            SpacePath::Circle { centre, normal, .. } => {
                if let Ok(([u, w], r)) = circle_plane(*centre, *normal, start) {
                    let n = per_lap.max(3);
                    for k in 1..n {
                        let a = std::f64::consts::TAU * k as f64 / n as f64;
                        let (sin, cos) = crate::kinematics::sin_cos(a);
                        out.push(std::array::from_fn(|i| {
                            centre[i] + r * (cos * u[i] + sin * w[i])
                        }));
                    }
                    out.push(start);
                }
            }
        }
        out
    }

    /// Exact distance from `p` to the path of a hand starting at `start`
    /// (to the nearest segment; to a circle `sqrt(h^2 + (rho - r)^2)`, `h`
    /// the height above its plane and `rho` the distance from `C` within
    /// it).
    pub fn distance_to(&self, p: Vec3, start: Vec3, target: Vec3) -> f64 {
        match self {
            SpacePath::Line => closest(p, start, target).1,
            SpacePath::Circle { centre, normal, .. } => {
                let Ok(([u, w], r)) = circle_plane(*centre, *normal, start) else {
                    return norm(sub(p, start));
                };
                let d = sub(p, *centre);
                let (a, b) = (dot(d, u), dot(d, w));
                let height = norm(sub(sub(d, scale(u, a)), scale(w, b)));
                height.hypot(a.hypot(b) - r)
            }
            SpacePath::Points(points) => {
                polyline_distance(start, points, |a, b| closest(p, a, b).1)
            }
        }
    }
}

/// `line`, `circle:CX,CY,CZ,NX,NY,NZ[,LAPS]` or `points:X,Y,Z;...` (see
/// the module); the numbers by [`crate::arm`]'s parser, so finite ones
/// only. The checks that need the hand's start are
/// [`SpacePath::validate`]'s.
impl FromStr for SpacePath {
    type Err = Error;
    fn from_str(text: &str) -> Result<Self> {
        parse_path(
            text,
            SpacePath::Line,
            |numbers, refuse| {
                let (numbers, laps) = match numbers[..] {
                    [cx, cy, cz, nx, ny, nz] => ([cx, cy, cz, nx, ny, nz], 1.0),
                    [cx, cy, cz, nx, ny, nz, laps] => ([cx, cy, cz, nx, ny, nz], laps),
                    _ => return Err(refuse(CIRCLE)),
                };
                let [cx, cy, cz, nx, ny, nz] = numbers;
                Ok(SpacePath::Circle {
                    centre: [cx, cy, cz],
                    normal: [nx, ny, nz],
                    laps: whole_laps(laps).ok_or_else(|| refuse(LAPS))?,
                })
            },
            SpacePath::Points,
            COUNT,
            "expected line, circle:CX,CY,CZ,NX,NY,NZ[,LAPS] or points:X,Y,Z;X,Y,Z;...",
        )
    }
}

impl fmt::Display for SpacePath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            SpacePath::Line => f.write_str("line"),
            SpacePath::Circle {
                centre: [cx, cy, cz],
                normal: [nx, ny, nz],
                laps,
            } => {
                write!(f, "circle:{cx},{cy},{cz},{nx},{ny},{nz}")?;
                if *laps != 1 {
                    write!(f, ",{laps}")?;
                }
                Ok(())
            }
            SpacePath::Points(points) => write_points(f, points),
        }
    }
}

path_as_text!(SpacePath);
