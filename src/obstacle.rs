//! The null-space vector for obstacle avoidance, paper section III:
//! triangle areas between each moving link and the obstacle point, eqs.
//! (12)-(16), and their gradient, eqs. (14)-(15).

use nalgebra::{DMatrix, DVector, Vector2};
use serde::{Deserialize, Serialize};

use crate::arm::{point_segment_distance, Arm};
use crate::error::{coordinate, positive, Error, Result};

/// A disc obstacle. Its centre is the point `O` of eq. (16); the radius only
/// decides what counts as a collision.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Obstacle {
    /// Centre `O = (O1, O2)` in metres.
    pub centre: [f64; 2],
    /// Radius in metres.
    pub radius: f64,
}

impl Obstacle {
    /// A disc at `(x, y)` with radius `radius`.
    pub fn new(x: f64, y: f64, radius: f64) -> Self {
        Self {
            centre: [x, y],
            radius,
        }
    }

    /// The centre as a vector.
    pub fn point(&self) -> Vector2<f64> {
        Vector2::new(self.centre[0], self.centre[1])
    }

    /// Checks the obstacle is finite, has a positive radius and stays clear of
    /// the base post (the segment from `(0, 0)` to `P(0)`), which cannot move
    /// out of its way.
    pub fn validate(&self, arm: &Arm) -> Result<()> {
        coordinate("obstacle x", self.centre[0])?;
        coordinate("obstacle y", self.centre[1])?;
        positive("obstacle radius", self.radius)?;
        coordinate("obstacle radius", self.radius)?;
        let d = point_segment_distance(&self.point(), &Vector2::zeros(), &arm.base());
        if d <= self.radius {
            return Err(Error::ObstacleOnPost {
                x: self.centre[0],
                y: self.centre[1],
                radius: self.radius,
            });
        }
        Ok(())
    }
}

/// `D_k = det[O - P(k-1), P(k) - P(k-1)]` for every moving link `k = 1..n`,
/// eq. (16); `V_k = |D_k|` (eq. 12) is twice the area of the triangle between
/// link `k` and `O`.
pub fn triangle_determinants(joints: &[Vector2<f64>], o: &Vector2<f64>) -> Vec<f64> {
    joints
        .windows(2)
        .map(|w| {
            let a = o - w[0];
            let b = w[1] - w[0];
            a[0] * b[1] - a[1] * b[0]
        })
        .collect()
}

/// Analytic `dD_k / dtheta_i` as an `n x n` matrix (row `k`, column `i`).
///
/// With `a = O - P(k-1)` and `b = P(k) - P(k-1) = L_k (sin phi_k, cos phi_k)`,
/// `D_k = det[a, b]` and `dD_k/dtheta_i = det[da, b] + det[a, db]`, where
/// `db/dtheta_i = L_k (cos phi_k, -sin phi_k)` for `i <= k` and
/// `da/dtheta_i = -dP(k-1)/dtheta_i = -sum_{i<=m<k} L_m (cos phi_m, -sin phi_m)`.
/// `D_k` depends only on `theta_1..theta_k`, so the matrix is lower triangular.
pub fn determinant_gradient(arm: &Arm, theta: &DVector<f64>, o: &Vector2<f64>) -> DMatrix<f64> {
    let n = arm.dof();
    let phi = arm.absolute_angles(theta);
    let joints = arm.joints(theta);
    // t[m] = d(link vector m)/d(phi_m)
    let t: Vec<Vector2<f64>> = (0..n)
        .map(|m| arm.links()[m] * Vector2::new(phi[m].cos(), -phi[m].sin()))
        .collect();
    let det = |a: &Vector2<f64>, b: &Vector2<f64>| a[0] * b[1] - a[1] * b[0];
    let mut g = DMatrix::zeros(n, n);
    for k in 0..n {
        let a = o - joints[k];
        let b = joints[k + 1] - joints[k];
        // dP(k-1)/dtheta_i for i = k down to 0: suffix sums of t[i..k].
        let mut dp_prev = Vector2::zeros();
        for i in (0..=k).rev() {
            if i < k {
                dp_prev += t[i];
            }
            g[(k, i)] = det(&(-dp_prev), &b) + det(&a, &t[k]);
        }
    }
    g
}

/// The obstacle-avoidance gradient for one obstacle point with `lambda = 4`:
/// `g_i = sum_k sign(D_k) dD_k/dtheta_i` (eq. 15, zero where `D_k = 0`), so
/// that `v = (lambda / 4) g`. This is the quantity the paper's second network
/// learns; it does not depend on `lambda`.
pub fn area_gradient(arm: &Arm, theta: &DVector<f64>, o: &Vector2<f64>) -> DVector<f64> {
    let d = triangle_determinants(&arm.joints(theta), o);
    let g = determinant_gradient(arm, theta, o);
    let n = arm.dof();
    let mut out = DVector::zeros(n);
    for (k, dk) in d.iter().enumerate() {
        let s = if *dk > 0.0 {
            1.0
        } else if *dk < 0.0 {
            -1.0
        } else {
            0.0
        };
        if s != 0.0 {
            for i in 0..n {
                out[i] += s * g[(k, i)];
            }
        }
    }
    out
}

/// Null-space vector for obstacle avoidance, eqs. (14)-(15), summed over all
/// obstacle points: `v_i = (lambda / 4) sum_O sum_k dV_k/dtheta_i`.
pub fn null_space_vector(
    arm: &Arm,
    theta: &DVector<f64>,
    obstacles: &[Obstacle],
    lambda: f64,
) -> DVector<f64> {
    let mut v = DVector::zeros(arm.dof());
    for ob in obstacles {
        v += area_gradient(arm, theta, &ob.point());
    }
    v * (lambda / 4.0)
}

/// Clearance: the smallest distance from `o` to the moving link segments
/// `P(k-1)-P(k)`, `k = 1..n` (the post is not counted).
pub fn clearance(joints: &[Vector2<f64>], o: &Vector2<f64>) -> f64 {
    joints
        .windows(2)
        .map(|w| point_segment_distance(o, &w[0], &w[1]))
        .fold(f64::INFINITY, f64::min)
}
