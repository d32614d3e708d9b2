//! The hand's full pose as the task (`m = 6`, the paper's section IV): a
//! chain whose task coordinates are the hand's position and the rotation
//! vector of its orientation, `X = (p, r)` with `R = exp(r)`, and whose
//! Jacobian is the geometric one, `6 x n`: column `i` is
//! `(z_i x (p - o_i), z_i)` (Siciliano et al. 2009, eq. 3.30), the hand's
//! linear and angular velocity per unit rate of joint `i`. Rates of the
//! orientation are angular velocities in the world's axes (not rates of
//! `r`): the task's error is the rotation vector of `R_ref R^T` and its
//! shortest path turns about one axis at a constant rate
//! (`crate::model::Model::geodesic`), both in the same axes.
//!
//! **The paper's `Z`** (eqs. 6-7) weights the orientation rows against
//! the position rows: `Z = diag(1, 1, 1, z, z, z)` with `z` the
//! [`PoseChain::orientation_weight`] (m^2/rad^2: a radian of orientation
//! error costs what `sqrt(z)` metres of position error cost). It enters
//! eq. (6) as `(J W^-1 J^T + delta Z^-1)^-1`, so it only matters where
//! the solve is damped (`delta > 0`, the damping schedule, an unreachable
//! target): undamped, a full-rank `J` tracks both parts exactly whatever
//! `Z`.

use serde::{Deserialize, Serialize};

use super::pose::{dot, SpacePose, Vec3};
use super::rotation::{self, Mat3};
use super::Chain;
use crate::error::{Error, Result};

/// The default [`PoseChain::orientation_weight`]: `Z = I`, the paper's.
pub const ORIENTATION_WEIGHT: f64 = 1.0;

/// A chain whose task is its hand's full pose, under the metric `Z`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, try_from = "PoseChainFile")]
pub struct PoseChain {
    /// The robot.
    pub chain: Chain,
    /// `z` of `Z = diag(1, 1, 1, z, z, z)` (m^2/rad^2).
    orientation_weight: f64,
}

/// The JSON form of a [`PoseChain`].
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PoseChainFile {
    chain: Chain,
    #[serde(default = "default_weight")]
    orientation_weight: f64,
}

fn default_weight() -> f64 {
    ORIENTATION_WEIGHT
}

impl TryFrom<PoseChainFile> for PoseChain {
    type Error = Error;
    fn try_from(f: PoseChainFile) -> Result<Self> {
        PoseChain::new(f.chain, f.orientation_weight)
    }
}

impl PoseChain {
    /// `chain` with the hand's pose as its task and `Z`'s orientation
    /// entry `orientation_weight` (positive and finite).
    pub fn new(chain: Chain, orientation_weight: f64) -> Result<Self> {
        if !(orientation_weight.is_finite() && orientation_weight > 0.0) {
            return Err(Error::OutOfRange {
                what: "orientation weight z of Z (m^2/rad^2)".into(),
                value: orientation_weight,
                min: f64::MIN_POSITIVE,
                max: f64::MAX,
            });
        }
        Ok(Self {
            chain,
            orientation_weight,
        })
    }

    /// `z` of `Z = diag(1, 1, 1, z, z, z)` (m^2/rad^2).
    pub fn orientation_weight(&self) -> f64 {
        self.orientation_weight
    }

    /// The hand's pose `(p, r)` at `theta`; refused for a wrong length.
    pub fn start(&self, theta: &[f64]) -> Result<[f64; 6]> {
        self.chain.check_angles(theta)?;
        let mut pose = self.pose();
        pose.update(self, theta)?;
        Ok(pose.hand())
    }

    /// Buffers for a pose of this chain, all zero.
    pub fn pose(&self) -> HandPose {
        let n = self.chain.dof();
        HandPose {
            space: SpacePose::of(&self.chain),
            jac: vec![0.0; 6 * n],
            jjt: [[0.0; 6]; 6],
            rotation: rotation::IDENTITY,
            hand: [0.0; 6],
            zinv: 1.0 / self.orientation_weight,
        }
    }
}

/// The kinematics of one configuration for the pose task: the chain's
/// pass ([`SpacePose`]), the hand's rotation and rotation vector, the
/// `6 x n` geometric Jacobian and `J J^T`, computed once per pose.
#[derive(Debug, Clone, PartialEq)]
pub struct HandPose {
    space: SpacePose,
    /// `J`, column-major `6 x n`: column `i` is entries `6i..6i + 6`.
    jac: Vec<f64>,
    /// `J J^T`, by rows.
    jjt: [[f64; 6]; 6],
    /// The hand's rotation, by rows: the last joint's axes turned by the
    /// flange's rotation.
    rotation: Mat3,
    /// `(p, r)`: the hand's position and rotation vector.
    hand: [f64; 6],
    /// `1 / z`: the orientation rows' share of the damping, `delta Z^-1`.
    zinv: f64,
}

impl HandPose {
    /// The pose of `arm` at `theta`; refused as [`SpacePose::update`]
    /// refuses.
    pub fn update(&mut self, arm: &PoseChain, theta: &[f64]) -> Result<()> {
        self.space.update(&arm.chain, theta)?;
        let n = self.space.dof();
        let last: [Vec3; 3] = self.space.frame(n - 1);
        // The last frame's matrix has its axes for columns.
        let frame: Mat3 = std::array::from_fn(|r| std::array::from_fn(|c| last[c][r]));
        self.rotation = rotation::mul(&frame, &arm.chain.flange_rotation());
        let p = self.space.hand();
        let r = rotation::log(&self.rotation);
        self.hand = [p[0], p[1], p[2], r[0], r[1], r[2]];
        let linear = self.space.jacobian();
        for i in 0..n {
            // A joint that slides does not turn the hand.
            let w = if self.space.is_prismatic(i) {
                [0.0; 3]
            } else {
                self.space.axis(i)
            };
            let col = &mut self.jac[6 * i..6 * i + 6];
            col[..3].copy_from_slice(&linear[3 * i..3 * i + 3]);
            col[3..].copy_from_slice(&w);
        }
        let mut a = [[0.0; 6]; 6];
        for col in self.jac.chunks_exact(6) {
            for (row, &cr) in a.iter_mut().zip(col) {
                for (x, &cc) in row.iter_mut().zip(col) {
                    *x += cr * cc;
                }
            }
        }
        self.jjt = a;
        Ok(())
    }

    /// The chain's pass: joint frames, points, the positional Jacobian
    /// (what the volumes, the obstacles and the criterion read).
    #[inline]
    pub fn space(&self) -> &SpacePose {
        &self.space
    }

    /// `(p, r)`: the hand's position (m) and rotation vector (rad).
    #[inline]
    pub fn hand(&self) -> [f64; 6] {
        self.hand
    }

    /// The hand's rotation, by rows.
    #[inline]
    pub fn rotation(&self) -> Mat3 {
        self.rotation
    }

    /// `J`, column-major `6 x n`.
    #[inline]
    pub fn jacobian(&self) -> &[f64] {
        &self.jac
    }

    /// `J J^T`, by rows.
    #[inline]
    pub fn jjt(&self) -> [[f64; 6]; 6] {
        self.jjt
    }

    /// `delta Z^-1`'s diagonal for a damping `delta`.
    #[inline]
    pub fn damping(&self, delta: f64) -> [f64; 6] {
        let o = delta * self.zinv;
        [delta, delta, delta, o, o, o]
    }

    /// `Z`'s diagonal, `(1, 1, 1, z, z, z)`.
    #[inline]
    pub fn weights(&self) -> [f64; 6] {
        let z = 1.0 / self.zinv;
        [1.0, 1.0, 1.0, z, z, z]
    }

    /// The joint angles.
    #[inline]
    pub fn theta(&self) -> &[f64] {
        self.space.theta()
    }
}

/// The pose task's error `a - b`: the positions' difference and the
/// rotation vector of `R_a R_b^T`.
pub fn pose_error(a: [f64; 6], b: [f64; 6]) -> [f64; 6] {
    let d = rotation::difference([a[3], a[4], a[5]], [b[3], b[4], b[5]]);
    [a[0] - b[0], a[1] - b[1], a[2] - b[2], d[0], d[1], d[2]]
}

/// The shortest path from pose `a` to pose `b` at fraction `s`: the
/// positions' line, and `R(s) = exp(s w) R_a` with `w = log(R_b R_a^T)`
/// (one axis, a constant rate); its rate `d/ds` is `(b_p - a_p, w)`.
pub fn pose_geodesic(a: [f64; 6], b: [f64; 6], s: f64) -> ([f64; 6], [f64; 6]) {
    let ra = rotation::exp([a[3], a[4], a[5]]);
    let w = rotation::log(&rotation::mul_transpose(
        &rotation::exp([b[3], b[4], b[5]]),
        &ra,
    ));
    let r = if s == 0.0 {
        [a[3], a[4], a[5]]
    } else {
        rotation::log(&rotation::mul(&rotation::exp(w.map(|x| s * x)), &ra))
    };
    let d: [f64; 3] = std::array::from_fn(|k| b[k] - a[k]);
    (
        [
            a[0] + s * d[0],
            a[1] + s * d[1],
            a[2] + s * d[2],
            r[0],
            r[1],
            r[2],
        ],
        [d[0], d[1], d[2], w[0], w[1], w[2]],
    )
}

/// The hand's position error (m) and orientation error (rad) between
/// poses `a` and `b`.
pub fn pose_distance(a: [f64; 6], b: [f64; 6]) -> (f64, f64) {
    let e = pose_error(a, b);
    (
        dot([e[0], e[1], e[2]], [e[0], e[1], e[2]]).sqrt(),
        dot([e[3], e[4], e[5]], [e[3], e[4], e[5]]).sqrt(),
    )
}

impl AsRef<Chain> for PoseChain {
    fn as_ref(&self) -> &Chain {
        &self.chain
    }
}

impl AsRef<SpacePose> for HandPose {
    fn as_ref(&self) -> &SpacePose {
        &self.space
    }
}
