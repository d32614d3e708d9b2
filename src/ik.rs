//! Inverse kinematics in an inexact context (paper section II and IV):
//! the weighted-perturbed pseudoinverse, eqs. (5)-(7), the cheap symmetric
//! solve of eqs. (17)-(18), the matrix `Phi` of eqs. (19)-(20) and the network
//! route of eq. (21); plus a damping schedule that keeps joint rates bounded
//! near singular poses.
//!
//! These formulas are written out by hand rather than through a generic
//! least-squares routine: the 2x2 systems have closed forms that are both the
//! paper's point (eq. 17 is "Gaussian elimination that takes the symmetry into
//! account") and much cheaper than a general SVD.

use nalgebra::{DMatrix, DVector, Matrix2, Matrix2xX, MatrixXx2, Vector2};
use serde::{Deserialize, Serialize};

use crate::error::{finite, positive, Error, Result};

/// Solves the symmetric positive definite 2x2 system `A x = b` by an
/// `L D L^T` elimination (what eq. 17 asks for). Fails when `A` is numerically
/// singular or not positive definite.
pub fn solve_symmetric_2x2(a: &Matrix2<f64>, b: &Vector2<f64>) -> Result<Vector2<f64>> {
    let (a11, a12, a22) = (a[(0, 0)], 0.5 * (a[(0, 1)] + a[(1, 0)]), a[(1, 1)]);
    let scale = a11.abs().max(a22.abs());
    if a11.is_nan() || a11 <= 0.0 || !scale.is_finite() {
        return Err(Error::Singular(
            "J J^T + delta I is not positive definite".into(),
        ));
    }
    let l21 = a12 / a11;
    let d2 = a22 - l21 * a12;
    if d2.is_nan() || d2 <= 1e-13 * scale {
        return Err(Error::Singular(
            "J J^T + delta I is (numerically) singular: the arm is stretched or folded; switch damping on".into(),
        ));
    }
    let y2 = b[1] - l21 * b[0];
    let x2 = y2 / d2;
    let x1 = (b[0] - a12 * x2) / a11;
    Ok(Vector2::new(x1, x2))
}

fn inverse_symmetric_2x2(a: &Matrix2<f64>) -> Result<Matrix2<f64>> {
    let c0 = solve_symmetric_2x2(a, &Vector2::new(1.0, 0.0))?;
    let c1 = solve_symmetric_2x2(a, &Vector2::new(0.0, 1.0))?;
    Ok(Matrix2::from_columns(&[c0, c1]))
}

fn check_delta(delta: f64) -> Result<()> {
    finite("delta", delta)?;
    if delta < 0.0 {
        return Err(Error::InvalidValue(format!(
            "damping factor delta must not be negative (got {delta})"
        )));
    }
    Ok(())
}

fn check_spd(
    what: &str,
    m: &DMatrix<f64>,
    size: usize,
) -> Result<nalgebra::Cholesky<f64, nalgebra::Dyn>> {
    if m.nrows() != size || m.ncols() != size {
        return Err(Error::DimensionMismatch {
            what: format!("{what} (rows x columns)"),
            expected: size * size,
            found: m.nrows() * m.ncols(),
        });
    }
    if m.iter().any(|x| !x.is_finite()) {
        return Err(Error::NonFinite(what.into()));
    }
    if (m - m.transpose()).amax() > 1e-12 * m.amax().max(1.0) {
        return Err(Error::InvalidValue(format!("{what} must be symmetric")));
    }
    m.clone()
        .cholesky()
        .ok_or_else(|| Error::InvalidValue(format!("{what} must be positive definite")))
}

/// Weighted-perturbed pseudoinverse, eq. (6):
/// `J+ = W^-1 J^T (J W^-1 J^T + delta Z^-1)^-1`, an `n x m` matrix.
///
/// `W` (`n x n`) and `Z` (`m x m`) must be symmetric positive definite.
pub fn pseudoinverse_eq6(
    j: &DMatrix<f64>,
    w: &DMatrix<f64>,
    z: &DMatrix<f64>,
    delta: f64,
) -> Result<DMatrix<f64>> {
    check_delta(delta)?;
    let (m, n) = j.shape();
    let w_inv = check_spd("W", w, n)?.inverse();
    let z_inv = check_spd("Z", z, m)?.inverse();
    let inner = j * &w_inv * j.transpose() + delta * z_inv;
    let inner_inv = inner
        .cholesky()
        .ok_or_else(|| Error::Singular("J W^-1 J^T + delta Z^-1 is singular".into()))?
        .inverse();
    Ok(w_inv * j.transpose() * inner_inv)
}

/// Weighted-perturbed pseudoinverse, eq. (7):
/// `J+ = (J^T Z J + delta W)^-1 J^T Z`. Equal to eq. (6) whenever `delta > 0`
/// (for `delta = 0` the `n x n` matrix `J^T Z J` is singular when `m < n`).
pub fn pseudoinverse_eq7(
    j: &DMatrix<f64>,
    w: &DMatrix<f64>,
    z: &DMatrix<f64>,
    delta: f64,
) -> Result<DMatrix<f64>> {
    check_delta(delta)?;
    let (m, n) = j.shape();
    check_spd("W", w, n)?;
    check_spd("Z", z, m)?;
    let outer = j.transpose() * z * j + delta * w;
    let outer_inv = outer
        .cholesky()
        .ok_or_else(|| {
            Error::Singular(
                "J^T Z J + delta W is singular (eq. 7 needs delta > 0 for a redundant arm)".into(),
            )
        })?
        .inverse();
    Ok(outer_inv * j.transpose() * z)
}

/// Joint rates of eq. (5): `theta_dot = J+ Xdot + (I - J+ J) v`.
pub fn theta_dot_eq5(
    j: &DMatrix<f64>,
    pinv: &DMatrix<f64>,
    xdot: &DVector<f64>,
    v: &DVector<f64>,
) -> DVector<f64> {
    let n = j.ncols();
    pinv * xdot + (DMatrix::identity(n, n) - pinv * j) * v
}

/// Cheap numerical route, eqs. (17)-(18): solve the symmetric 2x2 system
/// `(J J^T + delta I) varphi = Xdot - J v`, then `theta_dot = J^T varphi + v`.
pub fn theta_dot_symmetric(
    j: &Matrix2xX<f64>,
    xdot: &Vector2<f64>,
    v: &DVector<f64>,
    delta: f64,
) -> Result<DVector<f64>> {
    let a = j * j.transpose() + delta * Matrix2::identity();
    let rhs = xdot - j * v;
    let varphi = solve_symmetric_2x2(&a, &rhs)?;
    Ok(j.transpose() * varphi + v)
}

/// `Phi(theta) = J^T (J J^T + delta I)^-1`, eqs. (19)-(20): the `n x 2` matrix
/// that the paper's first network learns.
pub fn phi(j: &Matrix2xX<f64>, delta: f64) -> Result<MatrixXx2<f64>> {
    let a = j * j.transpose() + delta * Matrix2::identity();
    Ok(j.transpose() * inverse_symmetric_2x2(&a)?)
}

/// Network route, eq. (21): `theta_dot = Phi (Xdot - J v) + v`, with `Phi` from
/// any provider (a trained network, or [`phi`] itself).
pub fn theta_dot_network(
    phi: &MatrixXx2<f64>,
    j: &Matrix2xX<f64>,
    xdot: &Vector2<f64>,
    v: &DVector<f64>,
) -> DVector<f64> {
    phi * (xdot - j * v) + v
}

/// Smallest singular value of a `2 x n` Jacobian, from the eigenvalues of the
/// 2x2 matrix `J J^T` in closed form.
pub fn smallest_singular_value(j: &Matrix2xX<f64>) -> f64 {
    let a = j * j.transpose();
    let (p, q, r) = (a[(0, 0)], a[(0, 1)], a[(1, 1)]);
    let mean = 0.5 * (p + r);
    let radius = (0.25 * (p - r) * (p - r) + q * q).sqrt();
    (mean - radius).max(0.0).sqrt()
}

/// Square root of `det(J J^T)`: Yoshikawa's manipulability measure.
pub fn manipulability(j: &Matrix2xX<f64>) -> f64 {
    (j * j.transpose()).determinant().max(0.0).sqrt()
}

/// A damping schedule in the spirit of Nakamura and Hanafusa: no damping while
/// the smallest singular value `sigma` of `J` stays above `threshold`, then
/// `delta = delta_max (1 - (sigma / threshold)^2)`, growing smoothly to
/// `delta_max` at the singularity.
///
/// With `delta > 0` the gain of `Phi` is at most `1 / (2 sqrt(delta))`, so joint
/// rates stay bounded even for a fully stretched arm or an unreachable target.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DampingSchedule {
    /// `sigma` below which damping starts (metres, like `J`'s entries).
    pub threshold: f64,
    /// Damping at the singularity, `delta_max` (square metres).
    pub delta_max: f64,
}

impl Default for DampingSchedule {
    fn default() -> Self {
        Self {
            threshold: 0.1,
            delta_max: 0.01,
        }
    }
}

impl DampingSchedule {
    /// Checks both parameters are positive and finite.
    pub fn validate(&self) -> Result<()> {
        positive("damping threshold", self.threshold)?;
        positive("damping delta_max", self.delta_max)?;
        Ok(())
    }

    /// The extra damping this schedule adds at Jacobian `j`.
    pub fn delta(&self, j: &Matrix2xX<f64>) -> f64 {
        let sigma = smallest_singular_value(j);
        if sigma >= self.threshold {
            0.0
        } else {
            let ratio = sigma / self.threshold;
            self.delta_max * (1.0 - ratio * ratio)
        }
    }
}
