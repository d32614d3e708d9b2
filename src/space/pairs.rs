//! The capsule pairs of a pose within a distance: what the methods beyond
//! the paper read in space (`distance`, `priority`, `qp`), as
//! [`crate::clearance::Pairs`] are in the plane, computed once per pose.
//!
//! Each moving segment of the chain ([`super::Chain::segments`] with
//! `moved_by > 0`) pairs with every sphere ([`CapsulePair`]: the signed
//! surface distance `d = |C - Q| - r_c - R`, `Q` the axis point nearest the
//! centre `C`, the unit normal `n = (Q - C) / |Q - C|`) and, where a scene
//! asks for it, with the floor `z = 0` as a plane: the capsule's lowest
//! point is below its lower end, `d = min(z_A, z_B) - r_c`, `n = +z`, `Q`
//! that end. Either way the distance changes at `dd/dt = n . J_Q
//! theta_dot`, `J_Q` the point Jacobian at `Q`
//! ([`SpacePose::point_jacobian_into`]).

use super::pose::{dot, SpacePose, Vec3};
use super::self_pairs::self_contact;
use super::{CapsulePair, Chain, Sphere, MAX_SPHERES};

/// What a capsule keeps clear of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Obstruction {
    /// The scene's sphere of this index.
    Sphere(usize),
    /// The floor, `z = 0`.
    Floor,
    /// Another capsule of the chain, of this index in
    /// [`Chain::segments`] (self-collision).
    Link(usize),
}

/// One moving capsule and what it keeps clear of, at one pose.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct SpacePair {
    /// The segment's index in [`Chain::segments`].
    pub segment: usize,
    /// What it keeps clear of.
    pub against: Obstruction,
    /// The signed distance between the surfaces (m; negative: they overlap).
    pub distance: f64,
    /// The capsule's axis point `Q` nearest the obstruction.
    pub point: Vec3,
    /// The unit normal `n` from the obstruction toward the capsule.
    pub normal: Vec3,
    /// The joints that move the segment.
    pub moved_by: usize,
    /// For another capsule of the chain: its axis point nearest this one
    /// (the origin for a sphere or the floor, which do not move).
    pub other_point: Vec3,
    /// For another capsule: the joints that move it (0 for a sphere or
    /// the floor).
    pub other_moved_by: usize,
}

impl SpacePair {
    /// Whether it keeps two capsules of the chain apart (self-collision).
    #[inline]
    pub fn is_link(&self) -> bool {
        matches!(self.against, Obstruction::Link(_))
    }

    /// The pair of a capsule and a sphere.
    pub fn sphere(p: &CapsulePair) -> Self {
        Self {
            segment: p.segment,
            against: Obstruction::Sphere(p.sphere),
            distance: p.distance,
            point: p.point,
            normal: p.normal,
            moved_by: p.moved_by,
            other_point: [0.0; 3],
            other_moved_by: 0,
        }
    }

    /// The pair of capsules `a` and `b` of `chain` at `pose`
    /// (self-collision): `Q_a` is its point, `Q_b` the other's, the normal
    /// from `b` toward `a`.
    pub fn link(chain: &Chain, pose: &SpacePose, a: usize, b: usize) -> Self {
        let c = self_contact(chain, pose, a, b);
        let segments = chain.segments();
        Self {
            segment: a,
            against: Obstruction::Link(b),
            distance: c.distance,
            point: c.point_a,
            normal: c.normal,
            moved_by: segments[a].moved_by,
            other_point: c.point_b,
            other_moved_by: segments[b].moved_by,
        }
    }

    /// The pair of segment `segment` of `chain` and the floor `z = 0` at
    /// `pose`: its lower end, `d = z - r_c`, `n = +z`.
    pub fn floor(chain: &Chain, pose: &SpacePose, segment: usize) -> Self {
        let s = &chain.segments()[segment];
        let (a, b) = pose.segment(s);
        let q = if b[2] < a[2] { b } else { a };
        Self {
            segment,
            against: Obstruction::Floor,
            distance: q[2] - s.radius,
            point: q,
            normal: [0.0, 0.0, 1.0],
            moved_by: s.moved_by,
            other_point: [0.0; 3],
            other_moved_by: 0,
        }
    }

    /// `n . J_Q` into `row` (`n` entries): how fast the distance changes
    /// per unit rate of each joint, `dd/dt = row . theta_dot`; column `i`
    /// of `J_Q` is `z_i x (Q - o_i)` for the joints that move the segment.
    /// For two capsules of the chain, `n . (J_Qa - J_Qb)`.
    #[inline]
    pub fn gradient_into(&self, pose: &SpacePose, row: &mut [f64]) {
        for (i, g) in row.iter_mut().enumerate().take(pose.dof()) {
            *g = if i < self.moved_by {
                dot(self.normal, pose.column(i, self.point))
            } else {
                0.0
            };
            if i < self.other_moved_by {
                *g -= dot(self.normal, pose.column(i, self.other_point));
            }
        }
    }
}

/// The capsule pairs of a pose closer than a distance, kept in a buffer
/// that is reused: refreshing them allocates only when there are more
/// pairs than ever before.
#[derive(Debug, Clone, Default)]
pub struct SpacePairs {
    pairs: Vec<SpacePair>,
}

impl SpacePairs {
    /// The most pairs an `n`-joint chain of rows can have: every one of
    /// its at most `n + 1` moving segments with each of [`MAX_SPHERES`]
    /// spheres and the floor, and every pair of its `n + 2` segments (a
    /// chain read from URDF with more volumes grows the buffer once).
    pub const fn most(n: usize) -> usize {
        (MAX_SPHERES + 1) * (n + 1) + (n + 2) * (n + 1) / 2
    }

    /// Room for `capacity` pairs.
    pub fn with_capacity(capacity: usize) -> Self {
        Self {
            pairs: Vec::with_capacity(capacity),
        }
    }

    /// Every pair of a moving capsule and a sphere closer than `within`
    /// (every pair when `within` is infinite), sphere by sphere, each from
    /// the first moving segment.
    pub fn update(&mut self, chain: &Chain, pose: &SpacePose, spheres: &[Sphere], within: f64) {
        self.pairs.clear();
        for (j, sphere) in spheres.iter().enumerate() {
            for (k, s) in chain.segments().iter().enumerate() {
                if s.moved_by == 0 {
                    continue;
                }
                let pair = CapsulePair::at(chain, pose, k, j, sphere);
                if pair.distance < within {
                    self.pairs.push(SpacePair::sphere(&pair));
                }
            }
        }
    }

    /// Appends the pairs of the moving capsules and the floor `z = 0`
    /// closer than `within`.
    pub fn add_floor(&mut self, chain: &Chain, pose: &SpacePose, within: f64) {
        for (k, s) in chain.segments().iter().enumerate() {
            if s.moved_by == 0 {
                continue;
            }
            let pair = SpacePair::floor(chain, pose, k);
            if pair.distance < within {
                self.pairs.push(pair);
            }
        }
    }

    /// Appends the pairs of capsules the chain checks for self-collision
    /// ([`Chain::self_pairs`]) closer than `within`.
    pub fn add_self(&mut self, chain: &Chain, pose: &SpacePose, within: f64) {
        for &[a, b] in chain.self_pairs() {
            let pair = SpacePair::link(chain, pose, a, b);
            if pair.distance < within {
                self.pairs.push(pair);
            }
        }
    }

    /// The pairs: the spheres' (sphere by sphere), then the floor's, then
    /// the chain's own.
    pub fn as_slice(&self) -> &[SpacePair] {
        &self.pairs
    }

    /// The pair with the smallest distance, if any.
    pub fn closest(&self) -> Option<&SpacePair> {
        self.pairs
            .iter()
            .min_by(|a, b| a.distance.total_cmp(&b.distance))
    }

    /// Whether there is no pair.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// How many pairs.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }
}
