//! A serial chain of revolute joints in space, from modified (Craig)
//! Denavit-Hartenberg rows (Craig, *Introduction to Robotics*, 3rd ed.,
//! 2005, sec. 3.4): joint `i`'s frame follows frame `i - 1` by
//! `T = Rx(alpha_(i-1)) Tx(a_(i-1)) Rz(theta_i + offset_i) Tz(d_i)`, and the
//! hand (the flange) sits at a fixed point of the last frame. The row of
//! joint `i` holds `a_(i-1)`, `alpha_(i-1)`, `d_i` and `offset_i`, as
//! Robotics Toolbox's `RevoluteMDH(a, alpha, d, offset)` and Franka's FCI
//! table write them.
//!
//! The links' volumes are capsules of one radius on the segments between
//! consecutive distinct frame origins (the base's origin, the joint frames'
//! origins, the flange): a segment ends at a frame's origin, so it moves
//! with the joints before that frame. Two origins coincide when `a_(i-1)`
//! and `d_i` are both zero (a structural test, for every pose). The first
//! segment, from the base to the first joint's origin, moves with no joint:
//! the chain's fixed base, as the planar arm's post is.

use serde::{Deserialize, Serialize};

mod file;
mod joints;
mod reach;
mod segments;

pub use file::ChainFile;
pub use joints::{JointFrame, LinkVolume};
use segments::segments;

use crate::arm::{JointLimits, RateLimits};
use crate::error::{coordinate, finite, non_negative, Error, Result};

/// Fewest joints a [`Chain`] may have: three, to position a hand in space.
pub const MIN_JOINTS: usize = 3;

/// Most joints a [`Chain`] may have.
pub const MAX_JOINTS: usize = 16;

/// One modified Denavit-Hartenberg row: joint `i`'s frame from frame `i - 1`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Row {
    /// `a_(i-1)`: along `x_(i-1)` (m).
    pub a: f64,
    /// `alpha_(i-1)`: about `x_(i-1)` (rad).
    pub alpha: f64,
    /// `d_i`: along `z_i` (m).
    pub d: f64,
    /// Added to `theta_i` (rad): the joint's zero in the row's terms.
    pub offset: f64,
}

impl Row {
    /// A row with no offset.
    pub const fn new(a: f64, alpha: f64, d: f64) -> Self {
        Self {
            a,
            alpha,
            d,
            offset: 0.0,
        }
    }
}

/// A segment of the chain's volume, moved by joints `1..=moved_by` (none
/// for the base), between two of the pose's points: for a chain of
/// modified-DH rows, from one distinct frame origin to the next; for a
/// chain of joint frames (a URDF's), a link's capsule (a sphere where its
/// ends meet) fixed in joint `moved_by`'s frame, whose ends the pose
/// places after the hand.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Segment {
    /// The index of its start among the pose's points (see
    /// [`super::SpacePose::segment`]).
    pub from: usize,
    /// The index of its end.
    pub to: usize,
    /// How many joints, from the first, move it (0: the fixed base).
    pub moved_by: usize,
    /// The capsule's radius (m).
    pub radius: f64,
}

/// A 3-vector.
type Vec3 = [f64; 3];

/// A serial chain of revolute joints in space: a base placement, one
/// modified DH row per joint, the flange in the last frame, the capsules'
/// radius and the joints' limits.
///
/// Its JSON (a run file's `scene.arm`) is what `ChainFile` reads: a
/// file carries the whole robot, and reading it checks it as
/// [`Chain::placed`] and [`Chain::with_limits`] do.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "ChainFile")]
pub struct Chain {
    /// The base frame in the world: a rotation (rows) and a translation.
    base: ([[f64; 3]; 3], [f64; 3]),
    /// The modified-DH rows (none for a chain of joint frames).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    rows: Vec<Row>,
    /// The joint frames of a chain read from URDF (none for rows).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    joints: Vec<JointFrame>,
    /// The flange in the last joint's frame (m).
    flange: [f64; 3],
    /// The hand's frame in the last joint's frame, by rows: what turns
    /// the last joint's axes into the hand's (the identity for the
    /// presets; a URDF tip's fixed rotation). Written where it is not the
    /// identity.
    #[serde(skip_serializing_if = "is_identity")]
    flange_rotation: [[f64; 3]; 3],
    /// The capsules' radius (m): of every capsule of a chain of rows, the
    /// largest of a chain of joint frames.
    radius: f64,
    /// The links' capsules of a chain of joint frames (none for rows,
    /// whose capsules lie between the frames' origins).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    volumes: Vec<LinkVolume>,
    #[serde(skip_serializing_if = "Option::is_none")]
    joint_limits: Option<JointLimits>,
    #[serde(skip_serializing_if = "Option::is_none")]
    rate_limits: Option<RateLimits>,
    /// The pairs of capsules checked for self-collision, as indices into
    /// the segments (none: self-collision is not checked;
    /// [`Chain::with_self_collision`]).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    self_pairs: Vec<[usize; 2]>,
    /// The volume's segments, found once from the rows.
    #[serde(skip)]
    segments: Vec<Segment>,
    /// `(sin, cos)` of each row's `alpha`, taken once: a pose's pass then
    /// takes one sine and cosine per joint, of its angle.
    #[serde(skip)]
    twists: Vec<(f64, f64)>,
}

impl AsRef<Chain> for Chain {
    fn as_ref(&self) -> &Chain {
        self
    }
}

/// Whether `r` is the identity, exactly.
fn is_identity(r: &[[f64; 3]; 3]) -> bool {
    *r == IDENTITY
}

pub use super::rotation::IDENTITY;

impl Chain {
    /// A chain with its base at the world's origin, unrotated.
    pub fn new(rows: Vec<Row>, flange: [f64; 3], radius: f64) -> Result<Self> {
        Self::placed(IDENTITY, [0.0; 3], rows, flange, radius)
    }

    /// A chain whose base frame is rotated by `rotation` (a proper
    /// rotation matrix, by rows) and moved to `origin` in the world.
    pub fn placed(
        rotation: [[f64; 3]; 3],
        origin: [f64; 3],
        rows: Vec<Row>,
        flange: [f64; 3],
        radius: f64,
    ) -> Result<Self> {
        if !(MIN_JOINTS..=MAX_JOINTS).contains(&rows.len()) {
            return Err(Error::LinkCount {
                found: rows.len(),
                min: MIN_JOINTS,
                max: MAX_JOINTS,
            });
        }
        for (i, r) in rows.iter().enumerate() {
            let j = i + 1;
            coordinate(&format!("a of joint {j}"), r.a)?;
            finite(&format!("alpha of joint {j}"), r.alpha)?;
            coordinate(&format!("d of joint {j}"), r.d)?;
            finite(&format!("offset of joint {j}"), r.offset)?;
        }
        for (&f, axis) in flange.iter().zip(["x", "y", "z"]) {
            coordinate(&format!("flange {axis}"), f)?;
        }
        for (&o, axis) in origin.iter().zip(["x", "y", "z"]) {
            coordinate(&format!("base {axis}"), o)?;
        }
        non_negative("capsule radius", radius)?;
        coordinate("capsule radius", radius)?;
        check_rotation(&rotation)?;
        let segments = segments(&rows, flange, radius);
        let twists = rows
            .iter()
            .map(|r| crate::kinematics::sin_cos(r.alpha))
            .collect();
        Ok(Self {
            twists,
            base: (rotation, origin),
            rows,
            joints: Vec::new(),
            flange,
            flange_rotation: IDENTITY,
            radius,
            volumes: Vec::new(),
            joint_limits: None,
            rate_limits: None,
            self_pairs: Vec::new(),
            segments,
        })
    }

    /// The chain with these limits (each `None` for unlimited); refused
    /// when a list does not have one entry per joint.
    pub fn with_limits(
        mut self,
        joint_limits: Option<JointLimits>,
        rate_limits: Option<RateLimits>,
    ) -> Result<Self> {
        let n = self.dof();
        if let Some(l) = &joint_limits {
            if l.ranges().len() != n {
                return Err(Error::DimensionMismatch {
                    what: "joint limits".into(),
                    expected: n,
                    found: l.ranges().len(),
                });
            }
        }
        if let Some(r) = &rate_limits {
            if r.rates().len() != n {
                return Err(Error::DimensionMismatch {
                    what: "rate limits".into(),
                    expected: n,
                    found: r.rates().len(),
                });
            }
        }
        self.joint_limits = joint_limits;
        self.rate_limits = rate_limits;
        Ok(self)
    }

    /// Whether `other` is this chain, whatever the limits of either: the
    /// same base, rows, flange and radius.
    pub fn same_geometry(&self, other: &Chain) -> bool {
        self.same_kinematics(other)
            && (self.radius, &self.volumes) == (other.radius, &other.volumes)
    }

    /// Whether `other` moves as this chain does: the same base, rows and
    /// flange (what its networks depend on), whatever the capsules and
    /// limits.
    pub fn same_kinematics(&self, other: &Chain) -> bool {
        (
            self.base,
            &self.rows,
            &self.joints,
            self.flange,
            self.flange_rotation,
        ) == (
            other.base,
            &other.rows,
            &other.joints,
            other.flange,
            other.flange_rotation,
        )
    }

    /// Whether `other` has this chain's kinematics to within `tol` in
    /// every number (a URDF read in the browser, whose sines and cosines
    /// are the crate's own, against the same file read natively: they
    /// differ in the last bits).
    pub fn kinematics_within(&self, other: &Chain, tol: f64) -> bool {
        let numbers = |c: &Chain| -> Vec<f64> {
            let mut v: Vec<f64> = c
                .base
                .0
                .iter()
                .flatten()
                .chain(&c.base.1)
                .copied()
                .collect();
            for r in &c.rows {
                v.extend([r.a, r.alpha, r.d, r.offset]);
            }
            for j in &c.joints {
                v.extend(j.rotation.iter().flatten().chain(&j.translation));
            }
            v.extend(c.flange.iter().chain(c.flange_rotation.iter().flatten()));
            v
        };
        let slides = |c: &Chain| c.joints.iter().map(|j| j.prismatic).collect::<Vec<_>>();
        let (a, b) = (numbers(self), numbers(other));
        (self.rows.len(), slides(self)) == (other.rows.len(), slides(other))
            && a.len() == b.len()
            && a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= tol)
    }

    /// Number of joints `n`.
    pub fn dof(&self) -> usize {
        self.rows.len() + self.joints.len()
    }

    /// The modified DH rows, joint 1 first.
    pub fn rows(&self) -> &[Row] {
        &self.rows
    }

    /// `(sin alpha, cos alpha)` of each row.
    #[inline]
    pub fn twists(&self) -> &[(f64, f64)] {
        &self.twists
    }

    /// The base frame: its rotation (rows) and origin in the world.
    pub fn base(&self) -> ([[f64; 3]; 3], [f64; 3]) {
        self.base
    }

    /// The pairs of capsules checked for self-collision (segment indices).
    pub fn self_pairs(&self) -> &[[usize; 2]] {
        &self.self_pairs
    }

    /// Sets the pairs checked for self-collision; refused for an index
    /// the chain's segments lack or a capsule paired with itself.
    pub fn set_self_pairs(&mut self, pairs: Vec<[usize; 2]>) -> Result<()> {
        let count = self.segments.len();
        if let Some(&[a, b]) = pairs
            .iter()
            .find(|&&[a, b]| a >= count || b >= count || a == b)
        {
            return Err(Error::Syntax {
                what: "self-collision pair",
                text: format!("{a}, {b}"),
                expected: format!("two different capsules among the chain's {count}"),
            });
        }
        self.self_pairs = pairs;
        Ok(())
    }

    /// The flange (the hand) in the last joint's frame.
    pub fn flange(&self) -> [f64; 3] {
        self.flange
    }

    /// The hand's rotation in the last joint's frame, by rows.
    pub fn flange_rotation(&self) -> [[f64; 3]; 3] {
        self.flange_rotation
    }

    /// The chain with the hand turned by `rotation` (by rows) in the last
    /// joint's frame; refused for a matrix that is not a rotation.
    pub fn with_flange_rotation(mut self, rotation: [[f64; 3]; 3]) -> Result<Self> {
        check_rotation(&rotation)?;
        self.flange_rotation = rotation;
        Ok(self)
    }

    /// The capsules' radius (m).
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The volume's segments, the fixed base first.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// The links' capsules of a chain of joint frames, in their joints'
    /// frames (none for rows).
    pub fn volumes(&self) -> &[LinkVolume] {
        &self.volumes
    }

    /// How many points a pose of this chain places: the base's origin,
    /// the joints' origins, the hand, then each volume's two ends.
    pub fn point_count(&self) -> usize {
        self.dof() + 2 + 2 * self.volumes.len()
    }

    /// The joints' position limits, if any.
    pub fn joint_limits(&self) -> Option<&JointLimits> {
        self.joint_limits.as_ref()
    }

    /// The joints' rate limits, if any.
    pub fn rate_limits(&self) -> Option<&RateLimits> {
        self.rate_limits.as_ref()
    }

    /// Checks `theta` has one finite angle per joint (within
    /// [`crate::arm::MAX_ANGLE`]: [`crate::arm::check_angles`]).
    pub fn check_angles(&self, theta: &[f64]) -> Result<()> {
        crate::arm::check_angles(theta, self.dof())
    }
}

/// Refuses a base rotation that is not orthonormal with determinant 1 (to
/// 1e-9).
fn check_rotation(r: &[[f64; 3]; 3]) -> Result<()> {
    for (i, row) in r.iter().enumerate() {
        for (j, v) in row.iter().enumerate() {
            finite(&format!("base rotation ({}, {})", i + 1, j + 1), *v)?;
        }
    }
    let mut worst: f64 = 0.0;
    for i in 0..3 {
        for j in 0..3 {
            let dot: f64 = (0..3).map(|k| r[i][k] * r[j][k]).sum();
            worst = worst.max((dot - if i == j { 1.0 } else { 0.0 }).abs());
        }
    }
    let det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1])
        - r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0])
        + r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
    if worst > 1e-9 || (det - 1.0).abs() > 1e-9 {
        return Err(Error::Syntax {
            what: "base rotation",
            text: format!("{r:?}"),
            expected: "a rotation matrix (orthonormal rows, determinant 1)".into(),
        });
    }
    Ok(())
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn panda_rows() -> Vec<Row> {
        use std::f64::consts::FRAC_PI_2 as H;
        let a = [0.0, 0.0, 0.0, 0.0825, -0.0825, 0.0, 0.088];
        let d = [0.333, 0.0, 0.316, 0.0, 0.384, 0.0, 0.0];
        let alpha = [0.0, -H, H, H, -H, H, H];
        (0..7).map(|i| Row::new(a[i], alpha[i], d[i])).collect()
    }

    #[test]
    fn the_pandas_volume_is_six_segments_between_distinct_origins() {
        let c = Chain::new(panda_rows(), [0.0, 0.0, 0.107], 0.06).unwrap();
        let s: Vec<(usize, usize, usize)> = c
            .segments()
            .iter()
            .map(|s| (s.from, s.to, s.moved_by))
            .collect();
        // Base -> frame 1 (fixed), 1 (= 2) -> 3, 3 -> 4, 4 -> 5, 5 (= 6) -> 7, 7 -> flange.
        assert_eq!(
            s,
            vec![
                (0, 1, 0),
                (1, 3, 2),
                (3, 4, 3),
                (4, 5, 4),
                (5, 7, 6),
                (7, 8, 7)
            ]
        );
    }

    #[test]
    fn a_chain_refuses_too_few_joints_bad_numbers_and_a_bad_base() {
        let rows = panda_rows();
        assert!(matches!(
            Chain::new(rows[..2].to_vec(), [0.0; 3], 0.06),
            Err(Error::LinkCount { .. })
        ));
        let mut bad = rows.clone();
        bad[3].d = f64::NAN;
        assert!(Chain::new(bad, [0.0; 3], 0.06).is_err());
        assert!(Chain::new(rows.clone(), [0.0; 3], -0.1).is_err());
        let skew = [[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!(Chain::placed(skew, [0.0; 3], rows.clone(), [0.0; 3], 0.06).is_err());
        let mirror = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]];
        assert!(Chain::placed(mirror, [0.0; 3], rows, [0.0; 3], 0.06).is_err());
    }

    #[test]
    fn limits_need_one_entry_per_joint() {
        let c = Chain::new(panda_rows(), [0.0, 0.0, 0.107], 0.06).unwrap();
        let short = JointLimits::new(vec![[-1.0, 1.0]; 6]).unwrap();
        assert!(c.clone().with_limits(Some(short), None).is_err());
        let rates = RateLimits::new(vec![1.0; 7]).unwrap();
        assert!(c.with_limits(None, Some(rates)).is_ok());
    }
}
