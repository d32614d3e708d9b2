//! Spheres as obstacles of a spatial chain, and their distances to its
//! capsules in closed form.
//!
//! A capsule of radius `r_c` on the segment `A-B` and a sphere of centre
//! `C` and radius `R` are `|C - Q| - r_c - R` apart, `Q` the point of the
//! segment nearest `C` (`Q = A + t (B - A)`, `t` clamped to `[0, 1]`).
//! The distance's gradient with respect to the joints is `n . J_Q`, `n =
//! (Q - C) / |Q - C|` the unit normal from the sphere to the capsule and
//! `J_Q` the point Jacobian at `Q` ([`SpacePose::point_jacobian_into`]):
//! moving `Q` along the segment changes the distance to second order only,
//! where `t` is inside `(0, 1)`, and not at all where it is clamped.

use std::str::FromStr;

use crate::geometry::{Ball, Placement};

use super::pose::{add, dot, norm, scale, sub, SpacePose, Vec3};
use super::Chain;
use crate::arm::number_list;
use crate::error::{coordinate, positive, Error, Result};

/// Most spheres a scene may hold.
pub const MAX_SPHERES: usize = crate::geometry::MAX_BALLS;

/// A sphere obstacle, a ball in space: its centre `O` (the paper's
/// obstacle point) and radius.
pub type Sphere = Ball<3>;

impl Ball<3> {
    /// A sphere at `centre` of `radius`.
    pub fn new(centre: Vec3, radius: f64) -> Self {
        Self { centre, radius }
    }

    /// Checks the sphere is finite, has a positive radius and stays clear of
    /// the chain's fixed base (the segments no joint moves), which cannot
    /// move out of its way.
    pub fn validate(&self, chain: &Chain) -> Result<()> {
        // The fixed segments do not depend on the angles: any pose shows them.
        self.validate_at(chain, &SpacePose::new(chain, &vec![0.0; chain.dof()])?)
    }

    /// [`Self::validate`] with a pose of `chain` at hand (any angles: it
    /// shows the fixed base), allocating nothing (a planner moving its
    /// sphere for every cell of an atlas).
    pub fn validate_at(&self, chain: &Chain, pose: &SpacePose) -> Result<()> {
        for (&c, what) in self.centre.iter().zip(["sphere x", "sphere y", "sphere z"]) {
            coordinate(what, c)?;
        }
        positive("sphere radius", self.radius)?;
        coordinate("sphere radius", self.radius)?;
        for s in chain.segments().iter().filter(|s| s.moved_by == 0) {
            let (a, b) = pose.segment(s);
            if closest(self.centre, a, b).1 <= self.radius + s.radius {
                return Err(Error::SphereOnBase {
                    centre: self.centre,
                    radius: self.radius,
                });
            }
        }
        Ok(())
    }
}

/// A sphere as people write it, `X,Y,Z` or `X,Y,Z,R` (the radius then
/// comes from the scene's default).
pub type SpherePlacement = Placement<3>;

impl FromStr for SpherePlacement {
    type Err = Error;

    fn from_str(text: &str) -> Result<Self> {
        let syntax = |expected: String| Error::Syntax {
            what: "sphere",
            text: text.to_string(),
            expected,
        };
        match number_list(text).map_err(&syntax)?[..] {
            [x, y, z] => Ok(Self {
                centre: [x, y, z],
                radius: None,
            }),
            [x, y, z, r] => Ok(Self {
                centre: [x, y, z],
                radius: Some(r),
            }),
            ref other => Err(syntax(format!(
                "expected x,y,z or x,y,z,r for an arm in space, got {} numbers (x,y or x,y,r place a disc for a planar arm)",
                other.len()
            ))),
        }
    }
}

/// The point of segment `a-b` nearest `p` and its distance to `p`: `(t,
/// distance)` with the point at `a + t (b - a)`.
#[inline]
pub fn closest(p: Vec3, a: Vec3, b: Vec3) -> (f64, f64) {
    let ab = sub(b, a);
    let len2 = dot(ab, ab);
    let t = if len2 > 0.0 {
        (dot(sub(p, a), ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (t, norm(sub(p, add(a, scale(ab, t)))))
}

/// The nearest pair of one moving capsule and one sphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CapsulePair {
    /// The segment's index in [`Chain::segments`].
    pub segment: usize,
    /// The sphere's index.
    pub sphere: usize,
    /// The signed distance between the surfaces (m; negative: they overlap).
    pub distance: f64,
    /// The capsule's axis point nearest the sphere's centre.
    pub point: Vec3,
    /// The unit normal from the sphere's centre toward `point`.
    pub normal: Vec3,
    /// The joints that move the segment.
    pub moved_by: usize,
}

impl CapsulePair {
    /// The pair of segment `segment` of `chain` and sphere `sphere` (index
    /// `index`) at `pose`. Where the centre lies on the axis the normal is
    /// any unit vector perpendicular to the segment.
    #[inline]
    pub fn at(
        chain: &Chain,
        pose: &SpacePose,
        segment: usize,
        index: usize,
        sphere: &Sphere,
    ) -> Self {
        let s = &chain.segments()[segment];
        let (a, b) = pose.segment(s);
        let (t, d) = closest(sphere.centre, a, b);
        let q = add(a, scale(sub(b, a), t));
        let normal = if d > 0.0 {
            scale(sub(q, sphere.centre), 1.0 / d)
        } else {
            perpendicular(sub(b, a))
        };
        Self {
            segment,
            sphere: index,
            distance: d - s.radius - sphere.radius,
            point: q,
            normal,
            moved_by: s.moved_by,
        }
    }

    /// The distance's gradient with respect to the joints, `n . J_Q`, into
    /// `row` (`n` entries): the rate at which the pair parts per unit rate
    /// of each joint.
    pub fn gradient_into(&self, pose: &SpacePose, row: &mut [f64]) {
        let n = pose.dof();
        for (i, g) in row.iter_mut().enumerate().take(n) {
            *g = if i < self.moved_by {
                dot(self.normal, pose.column(i, self.point))
            } else {
                0.0
            };
        }
    }
}

/// The smallest signed distance between the chain's moving capsules and
/// the spheres at `pose` (infinite without spheres).
pub fn clearance(chain: &Chain, pose: &SpacePose, spheres: &[Sphere]) -> f64 {
    let mut best = f64::INFINITY;
    for (k, s) in chain.segments().iter().enumerate() {
        if s.moved_by == 0 {
            continue;
        }
        for (j, sp) in spheres.iter().enumerate() {
            best = best.min(CapsulePair::at(chain, pose, k, j, sp).distance);
        }
    }
    best
}

/// A unit vector perpendicular to `v` (any, if `v` is zero).
fn perpendicular(v: Vec3) -> Vec3 {
    let other = if v[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let c = super::pose::cross(v, other);
    let l = norm(c);
    if l > 0.0 {
        scale(c, 1.0 / l)
    } else {
        [0.0, 0.0, 1.0]
    }
}
