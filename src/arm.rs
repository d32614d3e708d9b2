//! The planar redundant arm: a fixed vertical base post and `n` revolute links.
//!
//! Conventions (SPEC.md, "Arm and coordinates"): the absolute angle of link `i`
//! is `phi_i = theta_1 + ... + theta_i`, measured from the vertical axis towards
//! `+X1`, so joint `k` sits at `P(k) = P(k-1) + L_k (sin phi_k, cos phi_k)` with
//! `P(0) = (0, L0)` the top of the post. The end effector is `X = P(n)`.

use nalgebra::{DVector, Matrix2xX, Vector2};
use serde::{Deserialize, Serialize};

use crate::error::{coordinate, non_negative, positive, Error, Result};
use crate::kinematics::{segment_distance_squared, Pose};

/// Fewest links an [`Arm`] may have: two, to position a planar end effector.
pub const MIN_LINKS: usize = 2;

/// Most links an [`Arm`] may have. The page offers 2 to 6; the limit keeps
/// the networks' fixed-size input buffers sufficient and refuses absurd input.
pub const MAX_LINKS: usize = 32;

/// Largest joint angle accepted (rad), about 160 000 turns: far beyond any
/// run (the numerical route turns a joint by a few radians per task), small
/// enough that sums of angles stay exact to a microradian and finite.
/// Without it, `theta = [1e308, 1e308, ...]` passed as finite and its
/// absolute angles overflowed to NaN positions (found by fuzzing).
pub const MAX_ANGLE: f64 = 1.0e6;

/// A planar arm on a vertical base post of length `post`, with revolute links of
/// lengths `links[0..n]` (the paper's `L0` and `L1..L3`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Arm {
    post: f64,
    links: Vec<f64>,
}

impl Arm {
    /// An arm with the given post height and link lengths (metres).
    ///
    /// The post may be zero (base joint on the ground); every link must be a
    /// positive finite length, and there must be at least two links so that the
    /// end effector can reach a planar neighbourhood. Lengths beyond
    /// [`crate::error::MAX_COORDINATE`] are refused (their joint positions would overflow).
    pub fn new(post: f64, links: Vec<f64>) -> Result<Self> {
        non_negative("post length L0", post)?;
        coordinate("post length L0", post)?;
        if !(MIN_LINKS..=MAX_LINKS).contains(&links.len()) {
            return Err(Error::LinkCount {
                found: links.len(),
                min: MIN_LINKS,
                max: MAX_LINKS,
            });
        }
        for (i, &l) in links.iter().enumerate() {
            let what = format!("link length L{}", i + 1);
            positive(&what, l)?;
            coordinate(&what, l)?;
        }
        Ok(Self { post, links })
    }

    /// The paper's arm (section VI): `L0 = 0.5`, `L1 = 0.6`, `L2 = 0.85`, `L3 = 0.6` m.
    pub fn paper() -> Self {
        Self {
            post: 0.5,
            links: vec![0.6, 0.85, 0.6],
        }
    }

    /// Number of joints `n`.
    pub fn dof(&self) -> usize {
        self.links.len()
    }

    /// Height of the fixed base post, `L0`.
    pub fn post(&self) -> f64 {
        self.post
    }

    /// Link lengths `L1..Ln`.
    pub fn links(&self) -> &[f64] {
        &self.links
    }

    /// Top of the post, `P(0) = (0, L0)`: the first revolute joint.
    pub fn base(&self) -> Vector2<f64> {
        Vector2::new(0.0, self.post)
    }

    /// Largest distance from `P(0)` that the end effector can reach.
    pub fn max_reach(&self) -> f64 {
        self.links.iter().sum()
    }

    /// Smallest distance from `P(0)` that the end effector can reach
    /// (zero unless one link is longer than all others together).
    pub fn min_reach(&self) -> f64 {
        let longest = self.links.iter().cloned().fold(0.0, f64::max);
        (2.0 * longest - self.max_reach()).max(0.0)
    }

    /// Whether the point lies in the reachable annulus around `P(0)`.
    pub fn can_reach(&self, point: &Vector2<f64>) -> bool {
        let r = (point - self.base()).norm();
        r <= self.max_reach() && r >= self.min_reach()
    }

    /// Checks that `theta` has `n` finite entries.
    pub fn check_theta(&self, theta: &DVector<f64>) -> Result<()> {
        self.check_angles(theta.as_slice())
    }

    /// Checks that `theta` has `n` finite entries, none beyond
    /// [`MAX_ANGLE`] (the message is only formatted when there is a problem).
    pub fn check_angles(&self, theta: &[f64]) -> Result<()> {
        if theta.len() != self.dof() {
            return Err(Error::DimensionMismatch {
                what: "theta".into(),
                expected: self.dof(),
                found: theta.len(),
            });
        }
        match theta.iter().position(|t| t.abs() > MAX_ANGLE || t.is_nan()) {
            Some(i) if theta[i].is_finite() => Err(Error::TooLarge {
                what: format!("theta_{}", i + 1),
                value: theta[i],
                max: MAX_ANGLE,
                unit: "rad",
            }),
            Some(i) => Err(Error::NonFinite {
                what: format!("theta_{}", i + 1),
            }),
            None => Ok(()),
        }
    }

    /// Absolute link angles `phi_i = theta_1 + ... + theta_i`.
    pub fn absolute_angles(&self, theta: &DVector<f64>) -> Vec<f64> {
        theta
            .iter()
            .scan(0.0, |acc, &t| {
                *acc += t;
                Some(*acc)
            })
            .collect()
    }

    /// All joint positions `P(0), P(1), ..., P(n)`; the last is the end effector.
    pub fn joints(&self, theta: &DVector<f64>) -> Vec<Vector2<f64>> {
        Pose::lenient(self, theta.as_slice())
            .joints()
            .iter()
            .map(|p| Vector2::new(p[0], p[1]))
            .collect()
    }

    /// Forward kinematics `X = f(theta)`, eq. (1): the end effector `P(n)`.
    ///
    /// # Examples
    /// ```
    /// use redundant_ik::{Arm, nalgebra::DVector};
    /// use std::f64::consts::PI;
    /// let x = Arm::paper().forward(&DVector::from_vec(vec![PI / 12.0, PI / 2.0, -PI / 6.0]));
    /// assert!((x[0] - 1.555884).abs() < 1e-6 && (x[1] - 1.014851).abs() < 1e-6);
    /// ```
    pub fn forward(&self, theta: &DVector<f64>) -> Vector2<f64> {
        let x = Pose::lenient(self, theta.as_slice()).end_effector();
        Vector2::new(x[0], x[1])
    }

    /// Analytic Jacobian `J = dX/dtheta`, eq. (3), a `2 x n` matrix:
    /// `J[0][i] = sum_{k>=i} L_k cos phi_k`, `J[1][i] = -sum_{k>=i} L_k sin phi_k`.
    pub fn jacobian(&self, theta: &DVector<f64>) -> Matrix2xX<f64> {
        Matrix2xX::from_column_slice(Pose::lenient(self, theta.as_slice()).jacobian())
    }
}

/// Euclidean distance from point `p` to the segment `a`-`b`.
pub fn point_segment_distance(p: &Vector2<f64>, a: &Vector2<f64>, b: &Vector2<f64>) -> f64 {
    segment_distance_squared([p[0], p[1]], [a[0], a[1]], [b[0], b[1]]).sqrt()
}
