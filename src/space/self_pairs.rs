//! Self-collision: the pairs of a chain's capsules that may touch, and
//! their distance at a pose.
//!
//! **Which pairs are checked.** Two capsules moved by the same joints are
//! one rigid body, and two on consecutive bodies meet at the joint
//! between them: neither pair is checked (MoveIt's setup assistant calls
//! these "adjacent"). Of the rest, a pair is left out when the user's
//! SRDF disables it (`<disable_collisions>`) or when the two capsules
//! overlap at the zero pose or at the start pose (the setup assistant's
//! "default" and "always in collision" pairs, found here at those two
//! poses instead of by sampling: a coarse capsule that overlaps its
//! neighbour's at rest would otherwise stop the arm before it moves).
//! [`Chain::with_self_collision`] finds the list once; it is part of the
//! chain (a run file carries it).
//!
//! **The distance** of two capsules is the distance of their axes'
//! closest points `Q_a`, `Q_b` less both radii (Ericson, *Real-Time
//! Collision Detection*, 2005, sec. 5.1.9), with the unit normal
//! `n = (Q_a - Q_b) / |Q_a - Q_b|`; it changes at
//! `dd/dt = n^T (J_Qa - J_Qb) theta_dot` (NEO's self-collision form,
//! Haviland and Corke 2021).

use super::pose::{add, cross, dot, norm, scale, sub, SpacePose, Vec3};
use super::Chain;
use crate::error::{Error, Result};

/// The closest points of segments `p1 q1` and `p2 q2`: their parameters
/// `(s, t)` in `[0, 1]` along each (Ericson 2005, sec. 5.1.9).
pub fn closest_parameters(p1: Vec3, q1: Vec3, p2: Vec3, q2: Vec3) -> (f64, f64) {
    let d1 = sub(q1, p1);
    let d2 = sub(q2, p2);
    let r = sub(p1, p2);
    let a = dot(d1, d1);
    let e = dot(d2, d2);
    let f = dot(d2, r);
    let tiny = 1e-18;
    if a <= tiny && e <= tiny {
        return (0.0, 0.0);
    }
    if a <= tiny {
        return (0.0, (f / e).clamp(0.0, 1.0));
    }
    let c = dot(d1, r);
    if e <= tiny {
        return ((-c / a).clamp(0.0, 1.0), 0.0);
    }
    let b = dot(d1, d2);
    let denom = a * e - b * b;
    let mut s = if denom > tiny * a * e {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    (s, t)
}

/// Two capsules of a chain at a pose: the signed distance of their
/// surfaces, the closest axis points and the normal from the second
/// toward the first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfContact {
    /// The signed distance (m; negative: they overlap).
    pub distance: f64,
    /// `Q_a`, on the first capsule's axis.
    pub point_a: Vec3,
    /// `Q_b`, on the second's.
    pub point_b: Vec3,
    /// The unit normal from `Q_b` toward `Q_a`.
    pub normal: Vec3,
}

/// Capsules `a` and `b` of `chain` at `pose`.
pub fn self_contact(chain: &Chain, pose: &SpacePose, a: usize, b: usize) -> SelfContact {
    let (sa, sb) = (&chain.segments()[a], &chain.segments()[b]);
    let (p1, q1) = pose.segment(sa);
    let (p2, q2) = pose.segment(sb);
    let (s, t) = closest_parameters(p1, q1, p2, q2);
    let qa = add(p1, scale(sub(q1, p1), s));
    let qb = add(p2, scale(sub(q2, p2), t));
    let gap = sub(qa, qb);
    let length = norm(gap);
    let normal = if length > 1e-12 {
        scale(gap, 1.0 / length)
    } else {
        // The axes cross: any direction normal to both.
        let c = cross(sub(q1, p1), sub(q2, p2));
        let size = norm(c);
        if size > 1e-12 {
            scale(c, 1.0 / size)
        } else {
            [0.0, 0.0, 1.0]
        }
    };
    SelfContact {
        distance: length - sa.radius - sb.radius,
        point_a: qa,
        point_b: qb,
        normal,
    }
}

/// Whether capsules `a` and `b` are one body or adjacent bodies: moved by
/// the same joints, or by joints one apart.
pub fn adjacent(chain: &Chain, a: usize, b: usize) -> bool {
    let (ma, mb) = (chain.segments()[a].moved_by, chain.segments()[b].moved_by);
    ma.abs_diff(mb) <= 1
}

impl Chain {
    /// The chain with self-collision checked: every pair of its capsules
    /// but the adjacent ones ([`adjacent`]), those in `disabled` (an
    /// SRDF's, as capsule indices, either order) and those that overlap
    /// at any of `poses` (the zero pose and the start pose, say). Refused
    /// for a pose of the wrong length or a capsule index the chain lacks.
    pub fn with_self_collision(
        mut self,
        disabled: &[[usize; 2]],
        poses: &[&[f64]],
    ) -> Result<Self> {
        let count = self.segments().len();
        if let Some(bad) = disabled.iter().flatten().find(|&&k| k >= count) {
            return Err(Error::OutOfRange {
                what: "capsule of a disabled pair".into(),
                value: *bad as f64,
                min: 0.0,
                max: count.saturating_sub(1) as f64,
            });
        }
        let mut states = Vec::with_capacity(poses.len());
        for theta in poses {
            states.push(SpacePose::new(&self, theta)?);
        }
        let mut pairs = Vec::new();
        for a in 0..count {
            for b in a + 1..count {
                let off = disabled
                    .iter()
                    .any(|&[x, y]| (x, y) == (a, b) || (y, x) == (a, b));
                if off || adjacent(&self, a, b) {
                    continue;
                }
                if states
                    .iter()
                    .any(|p| self_contact(&self, p, a, b).distance < 0.0)
                {
                    continue;
                }
                pairs.push([a, b]);
            }
        }
        self.set_self_pairs(pairs)?;
        Ok(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_points_of_crossing_parallel_and_degenerate_segments() {
        // Crossing at right angles, one above the other.
        let (s, t) = closest_parameters(
            [-1.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, -1.0, 1.0],
            [0.0, 1.0, 1.0],
        );
        assert!((s - 0.5).abs() < 1e-15 && (t - 0.5).abs() < 1e-15);
        // Parallel, overlapping: some pair of points at the right distance.
        let (p1, q1, p2, q2) = ([0.0; 3], [2.0, 0.0, 0.0], [1.0, 1.0, 0.0], [3.0, 1.0, 0.0]);
        let (s, t) = closest_parameters(p1, q1, p2, q2);
        let gap = sub(
            add(p1, scale(sub(q1, p1), s)),
            add(p2, scale(sub(q2, p2), t)),
        );
        assert!((norm(gap) - 1.0).abs() < 1e-15);
        // Beyond the ends: clamped.
        let (s, t) =
            closest_parameters([0.0; 3], [1.0, 0.0, 0.0], [3.0, 0.0, 0.0], [4.0, 0.0, 0.0]);
        assert_eq!((s, t), (1.0, 0.0));
        // A point and a segment.
        let (s, t) =
            closest_parameters([0.5, 1.0, 0.0], [0.5, 1.0, 0.0], [0.0; 3], [1.0, 0.0, 0.0]);
        assert_eq!((s, t), (0.0, 0.5));
    }
}
