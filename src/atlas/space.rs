//! The atlas of an arm in space, on a slice: the task's sphere centred on
//! every point of a grid on an axis-aligned plane, in every chosen method,
//! each outcome classified as the planar atlas's ([`Class`]). The default
//! plane is the vertical one through the task's line; the default region a
//! square of 0.8 m about the line's middle, cut at the floor (a map of the
//! whole reach would be mostly cells no link comes near, which every method
//! passes).

use std::fmt;
use std::str::FromStr;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

mod job;

use super::{Cell, Class, Grid};
use crate::error::{Error, Result, Short};
use crate::networks::space::SpaceNetworks;
use crate::planner::Method;
use crate::scene::{PoseScene, SpaceScene};
use crate::space::Vec3;
pub use job::{SliceHead, SliceJob};

/// The side of the default region (m).
pub const DEFAULT_SIDE: f64 = 0.8;

/// The default grid's points per side.
pub const DEFAULT_SLICE_GRID: usize = 21;

/// An axis-aligned plane: the coordinate it fixes and its value (m).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Plane {
    /// `z = value`: the grid's axes are `x` and `y`.
    Xy(f64),
    /// `y = value`: the axes `x` and `z`.
    Xz(f64),
    /// `x = value`: the axes `y` and `z`.
    Yz(f64),
}

impl Plane {
    /// The vertical plane through the scene's line: `x = ` the line's
    /// middle where the line runs more along `y` than along `x`, else `y
    /// = ` its middle.
    pub fn through_line(scene: &SpaceScene) -> Self {
        let (a, b) = (scene.start(), scene.target);
        let mid = [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]));
        if (b[0] - a[0]).abs() <= (b[1] - a[1]).abs() {
            Plane::Yz(mid[0])
        } else {
            Plane::Xz(mid[1])
        }
    }

    /// The point of the plane at grid coordinates `(u, v)`.
    pub fn point(self, u: f64, v: f64) -> Vec3 {
        match self {
            Plane::Xy(z) => [u, v, z],
            Plane::Xz(y) => [u, y, v],
            Plane::Yz(x) => [x, u, v],
        }
    }

    /// Where the ray from `origin` along `direction` meets the plane, ahead
    /// of `origin`; `None` for a ray parallel to it or pointing away (a
    /// pointer on the page's drawing, through [`crate::session::space`]'s
    /// camera, finds the slice atlas's cell under it this way).
    pub fn hit(self, origin: Vec3, direction: Vec3) -> Option<Vec3> {
        let (axis, value) = match self {
            Plane::Xy(z) => (2, z),
            Plane::Xz(y) => (1, y),
            Plane::Yz(x) => (0, x),
        };
        if direction[axis].abs() < 1e-12 {
            return None;
        }
        let s = (value - origin[axis]) / direction[axis];
        (s > 0.0 && s.is_finite()).then(|| [0, 1, 2].map(|k| origin[k] + s * direction[k]))
    }

    /// A point's grid coordinates `(u, v)`.
    pub fn coordinates(self, p: Vec3) -> (f64, f64) {
        match self {
            Plane::Xy(_) => (p[0], p[1]),
            Plane::Xz(_) => (p[0], p[2]),
            Plane::Yz(_) => (p[1], p[2]),
        }
    }

    /// The names of the grid's axes.
    pub fn axes(self) -> [&'static str; 2] {
        match self {
            Plane::Xy(_) => ["x", "y"],
            Plane::Xz(_) => ["x", "z"],
            Plane::Yz(_) => ["y", "z"],
        }
    }
}

/// `xy:Z0`, `xz:Y0` or `yz:X0` (the command line's `--slice`).
impl FromStr for Plane {
    type Err = Error;
    fn from_str(text: &str) -> Result<Self> {
        let syntax = |expected: &str| Error::Syntax {
            what: "slice",
            text: text.to_string(),
            expected: expected.into(),
        };
        let (axes, value) = text.split_once(':').ok_or_else(|| {
            syntax("xy:Z0, xz:Y0 or yz:X0 (the plane and the coordinate it fixes, m)")
        })?;
        let v: f64 = value
            .trim()
            .parse()
            .map_err(|_| syntax("a number after the colon"))?;
        crate::error::coordinate("slice coordinate", v)?;
        match axes.trim() {
            "xy" => Ok(Plane::Xy(v)),
            "xz" => Ok(Plane::Xz(v)),
            "yz" => Ok(Plane::Yz(v)),
            _ => Err(syntax("the plane xy, xz or yz")),
        }
    }
}

impl fmt::Display for Plane {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Plane::Xy(z) => write!(f, "xy:{}", Short(*z)),
            Plane::Xz(y) => write!(f, "xz:{}", Short(*y)),
            Plane::Yz(x) => write!(f, "yz:{}", Short(*x)),
        }
    }
}

/// A finished slice atlas; it reads back from its JSON (`atlas/read.rs`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SliceAtlas {
    /// The arm's preset key, if it is one.
    pub arm: Option<&'static str>,
    /// The plane.
    pub plane: Plane,
    /// The grid on the plane (`region` in the plane's coordinates).
    pub grid: Grid,
    /// The sphere's radius (m).
    pub radius: f64,
    /// The methods, in order.
    pub methods: Vec<Method>,
    /// The cells, row by row (`v` outer, `u` inner).
    pub cells: Vec<Cell<3>>,
}

/// A cell of a slice: `{ centre, outcomes, avoidance_needed }`, the
/// outcomes in the atlas's order.
impl Serialize for Cell<3> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let mut st = s.serialize_struct("Cell", 3)?;
        st.serialize_field("centre", &self.centre)?;
        st.serialize_field("outcomes", &self.outcomes)?;
        st.serialize_field("avoidance_needed", &self.avoidance_needed)?;
        st.end()
    }
}

/// The default region on `plane` for `scene`: a square of
/// [`DEFAULT_SIDE`] about the line's middle, above the floor.
pub fn default_region(scene: &SpaceScene, plane: Plane) -> [f64; 4] {
    let (a, b) = (scene.start(), scene.target);
    let (u, v) = plane.coordinates([0, 1, 2].map(|k| 0.5 * (a[k] + b[k])));
    let h = 0.5 * DEFAULT_SIDE;
    let r = scene.obstacles.first().map_or(0.05, |s| s.radius);
    let bottom = if matches!(plane, Plane::Xy(_)) {
        v - h
    } else {
        (v - h).max(r)
    };
    [u - h, u + h, bottom, bottom + DEFAULT_SIDE]
}

/// Runs the atlas: the scene's first sphere (its radius kept) on every
/// cell of `grid` on `plane`, in each of `methods` (a [`SliceJob`] run to
/// the end, across the machine's cores with the feature `parallel`).
/// Refused when a method does not run in space, or when no cell of the
/// grid lies within the arm's reach of its first joint (a plane that
/// misses the arm).
pub fn slice(
    scene: &SpaceScene,
    plane: Plane,
    grid: Grid,
    methods: &[Method],
    networks: Option<&Arc<SpaceNetworks>>,
) -> Result<SliceAtlas> {
    SliceJob::new(scene, plane, grid, methods, networks)?.to_end()
}

/// [`slice()`] for the hand's pose task (Case 2 with the networks' `v`;
/// Cases 1 and 3 refused).
pub fn pose_slice(
    scene: &PoseScene,
    plane: Plane,
    grid: Grid,
    methods: &[Method],
    networks: Option<&Arc<SpaceNetworks>>,
) -> Result<SliceAtlas> {
    SliceJob::pose(scene, plane, grid, methods, networks)?.to_end()
}

impl SliceAtlas {
    /// Method `k`'s count of `class`.
    pub fn count(&self, k: usize, class: Class) -> usize {
        self.cells
            .iter()
            .filter(|c| c.outcomes[k].class == class)
            .count()
    }

    /// Cells where avoidance is possible (neither on the arm at the start
    /// nor on the path).
    pub fn avoidable(&self) -> usize {
        self.cells
            .iter()
            .filter(|c| c.outcomes.first().is_some_and(|o| o.class.avoidable()))
            .count()
    }

    /// Method `k`'s success rate over the avoidable cells.
    pub fn success_rate(&self, k: usize) -> Option<f64> {
        let n = self.avoidable();
        (n > 0).then(|| self.count(k, Class::Success) as f64 / n as f64)
    }
}
