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

use crate::error::{non_negative, positive, Error, Result};
use crate::kinematics::jjt;

mod refine;
mod weighted;
pub use refine::refine_phi;
pub use weighted::{
    phi_weighted_into, theta_dot_network_weighted_into, theta_dot_weighted_into, weight_phi,
};

/// Solves the symmetric positive definite 2x2 system `A x = b` (what eq. 17
/// asks for). Fails when `A` is numerically singular or not positive
/// definite.
pub fn solve_symmetric_2x2(a: &Matrix2<f64>, b: &Vector2<f64>) -> Result<Vector2<f64>> {
    let a = [a[(0, 0)], 0.5 * (a[(0, 1)] + a[(1, 0)]), a[(1, 1)]];
    let [x1, x2] = solve_spd2(a, [b[0], b[1]])?;
    Ok(Vector2::new(x1, x2))
}

/// `det(A)` of `A = (a11, a12, a22)` after the checks of a positive definite
/// and not numerically singular matrix: `a11 > 0` and
/// `det / a11 > 1e-13 max(|a11|, |a22|)` (the second pivot of `L D L^T`).
#[inline]
fn checked_det([a11, a12, a22]: [f64; 3]) -> Result<f64> {
    let scale = a11.abs().max(a22.abs());
    if a11.is_nan() || a11 <= 0.0 || !scale.is_finite() {
        return Err(not_positive_definite());
    }
    let det = a11 * a22 - a12 * a12;
    if det.is_nan() || det <= 1e-13 * scale * a11 {
        return Err(numerically_singular());
    }
    Ok(det)
}

/// [`solve_symmetric_2x2`] on `A = (a11, a12, a22)`: the allocation-free
/// form the planner uses. The symmetric elimination in closed form,
/// `x = (a22 b1 - a12 b2, a11 b2 - a12 b1) / det(A)`: one division, where
/// the `L D L^T` sweep needs three in a row (a fifth of a numerical
/// `theta_dot` was waiting on them).
#[inline]
pub fn solve_spd2(a: [f64; 3], b: [f64; 2]) -> Result<[f64; 2]> {
    let det = checked_det(a)?;
    let [a11, a12, a22] = a;
    let inv = 1.0 / det;
    Ok([
        (a22 * b[0] - a12 * b[1]) * inv,
        (a11 * b[1] - a12 * b[0]) * inv,
    ])
}

#[cold]
fn not_positive_definite() -> Error {
    Error::Singular("J J^T + delta I is not positive definite".into())
}

#[cold]
fn numerically_singular() -> Error {
    Error::Singular(
        "J J^T + delta I is (numerically) singular: the arm is stretched or folded; switch damping on"
            .into(),
    )
}

/// The inverse of `A = (a11, a12, a22)` as its two columns: the adjugate
/// over the determinant.
fn inverse_spd2(a: [f64; 3]) -> Result<[[f64; 2]; 2]> {
    let det = checked_det(a)?;
    let [a11, a12, a22] = a;
    let inv = 1.0 / det;
    Ok([[a22 * inv, -a12 * inv], [-a12 * inv, a11 * inv]])
}

#[cold]
fn size_error(what: &str, expected: usize, found: usize) -> Error {
    Error::DimensionMismatch {
        what: what.into(),
        expected,
        found,
    }
}

/// Checks the slice lengths of the allocation-free routines: `jac` is
/// `2 x n` column-major, and each of `rest` has `n` entries.
#[inline]
fn check_lengths(jac: &[f64], rest: &[(&str, usize)]) -> Result<usize> {
    if !jac.len().is_multiple_of(2) {
        return Err(size_error(
            "J (2 x n, column-major)",
            jac.len() + 1,
            jac.len(),
        ));
    }
    let n = jac.len() / 2;
    for &(what, len) in rest {
        if len != n {
            return Err(size_error(what, n, len));
        }
    }
    Ok(n)
}

fn check_delta(delta: f64) -> Result<()> {
    non_negative("damping factor delta", delta).map(|_| ())
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
        return Err(Error::NonFinite { what: what.into() });
    }
    let not = |property| Error::NotSpd {
        what: what.into(),
        property,
    };
    if (m - m.transpose()).amax() > 1e-12 * m.amax().max(1.0) {
        return Err(not("symmetric"));
    }
    m.clone().cholesky().ok_or_else(|| not("positive definite"))
}

/// The inverse of a symmetric positive definite matrix, or
/// [`Error::Singular`] saying which one is not.
fn spd_inverse(m: DMatrix<f64>, which: &str) -> Result<DMatrix<f64>> {
    m.cholesky()
        .map(|c| c.inverse())
        .ok_or_else(|| Error::Singular(which.into()))
}

/// The weights of eqs. (6)-(7): `W` (`n x n`, joint space) and `Z`
/// (`m x m`, task space), both symmetric positive definite.
#[derive(Debug, Clone, Copy)]
pub struct Weights<'a> {
    /// `W`.
    pub w: &'a DMatrix<f64>,
    /// `Z`.
    pub z: &'a DMatrix<f64>,
}

impl Weights<'_> {
    /// Checks `delta` and both weights against `J`'s shape; returns the
    /// Cholesky factors of `W` and `Z`.
    fn check(
        &self,
        j: &DMatrix<f64>,
        delta: f64,
    ) -> Result<[nalgebra::Cholesky<f64, nalgebra::Dyn>; 2]> {
        check_delta(delta)?;
        let (m, n) = j.shape();
        Ok([check_spd("W", self.w, n)?, check_spd("Z", self.z, m)?])
    }
}

/// Weighted-perturbed pseudoinverse, eq. (6):
/// `J+ = W^-1 J^T (J W^-1 J^T + delta Z^-1)^-1`, an `n x m` matrix.
pub fn pseudoinverse_eq6(j: &DMatrix<f64>, weights: Weights, delta: f64) -> Result<DMatrix<f64>> {
    let [w, z] = weights.check(j, delta)?;
    let w_inv = w.inverse();
    let inner = j * &w_inv * j.transpose() + delta * z.inverse();
    let inner_inv = spd_inverse(inner, "J W^-1 J^T + delta Z^-1 is singular")?;
    Ok(w_inv * j.transpose() * inner_inv)
}

/// Weighted-perturbed pseudoinverse, eq. (7):
/// `J+ = (J^T Z J + delta W)^-1 J^T Z`. Equal to eq. (6) whenever `delta > 0`
/// (for `delta = 0` the `n x n` matrix `J^T Z J` is singular when `m < n`).
pub fn pseudoinverse_eq7(j: &DMatrix<f64>, weights: Weights, delta: f64) -> Result<DMatrix<f64>> {
    weights.check(j, delta)?;
    let outer = j.transpose() * weights.z * j + delta * weights.w;
    let why = "J^T Z J + delta W is singular (eq. 7 needs delta > 0 for a redundant arm)";
    Ok(spd_inverse(outer, why)? * j.transpose() * weights.z)
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
    let mut out = DVector::zeros(j.ncols());
    theta_dot_symmetric_into(
        j.as_slice(),
        [xdot[0], xdot[1]],
        v.as_slice(),
        delta,
        out.as_mut_slice(),
    )?;
    Ok(out)
}

/// [`theta_dot_symmetric`] on slices, allocation-free: `jac` is `J`
/// column-major (`[J_00, J_10, J_01, J_11, ...]`, as [`crate::kinematics::Pose`]
/// and nalgebra store it), `v` and `out` have `n` entries.
#[inline]
pub fn theta_dot_symmetric_into(
    jac: &[f64],
    xdot: [f64; 2],
    v: &[f64],
    delta: f64,
    out: &mut [f64],
) -> Result<()> {
    check_lengths(jac, &[("v", v.len()), ("theta_dot", out.len())])?;
    let [a11, a12, a22] = jjt(jac);
    let rhs = task_residual(jac, xdot, v);
    let varphi = solve_spd2([a11 + delta, a12, a22 + delta], rhs)?;
    for ((o, col), vi) in out.iter_mut().zip(jac.chunks_exact(2)).zip(v) {
        *o = (col[0] * varphi[0] + col[1] * varphi[1]) + vi;
    }
    Ok(())
}

/// `Xdot - J v`, the task velocity left for the pseudoinverse (eqs. 17, 21).
#[inline]
fn task_residual(jac: &[f64], xdot: [f64; 2], v: &[f64]) -> [f64; 2] {
    let (mut jv0, mut jv1) = (0.0, 0.0);
    for (col, vi) in jac.chunks_exact(2).zip(v) {
        jv0 += col[0] * vi;
        jv1 += col[1] * vi;
    }
    [xdot[0] - jv0, xdot[1] - jv1]
}

/// `Phi(theta) = J^T (J J^T + delta I)^-1`, eqs. (19)-(20): the `n x 2` matrix
/// that the paper's first network learns.
pub fn phi(j: &Matrix2xX<f64>, delta: f64) -> Result<MatrixXx2<f64>> {
    let mut out = vec![0.0; 2 * j.ncols()];
    phi_into(j.as_slice(), delta, &mut out)?;
    Ok(MatrixXx2::from_row_slice(&out))
}

/// [`phi`] on slices, allocation-free: `Phi` row-major into `out` (`2n`
/// entries), `jac` column-major as in [`theta_dot_symmetric_into`].
#[inline]
pub fn phi_into(jac: &[f64], delta: f64, out: &mut [f64]) -> Result<()> {
    check_lengths(jac, &[("Phi (n x 2)", out.len() / 2)])?;
    if out.len() != jac.len() {
        return Err(size_error("Phi (n x 2)", jac.len(), out.len()));
    }
    let [a11, a12, a22] = jjt(jac);
    let [c0, c1] = inverse_spd2([a11 + delta, a12, a22 + delta])?;
    for (row, col) in out.chunks_exact_mut(2).zip(jac.chunks_exact(2)) {
        row[0] = col[0] * c0[0] + col[1] * c0[1];
        row[1] = col[0] * c1[0] + col[1] * c1[1];
    }
    Ok(())
}

/// Applies a constant damping `delta` to an undamped `Phi_0` in place:
/// `Phi_delta = Phi_0 (I + delta Phi_0^T Phi_0)^-1`.
///
/// This is how a learned `Phi` (trained at `delta = 0`, as in the paper) takes
/// a constant `delta` in Cases 1 and 3 without the inverse of `J J^T` that the
/// network replaces: with `A = J J^T` and `Phi_0 = J^T A^-1`,
/// `Phi_0^T Phi_0 = A^-1`, so `Phi_0 (I + delta A^-1)^-1 = J^T (A + delta I)^-1`,
/// which is eq. (20) exactly when `Phi_0` is exact; [`refine_phi`] brings a
/// learned `Phi_0` to that pseudoinverse (not only to some right inverse of
/// `J`), so refined, this is eq. (20) to the refinement's accuracy. The 2x2 matrix
/// `I + delta Phi_0^T Phi_0` is at least `I`, so the solve never fails for
/// finite input.
pub fn damp_phi(phi: &mut [f64], delta: f64) -> Result<()> {
    check_delta(delta)?;
    if delta == 0.0 {
        return Ok(());
    }
    let [p, q, r] = jjt(phi);
    let [c0, c1] = inverse_spd2([1.0 + delta * p, delta * q, 1.0 + delta * r])?;
    for row in phi.chunks_exact_mut(2) {
        let (x, y) = (row[0], row[1]);
        row[0] = x * c0[0] + y * c0[1];
        row[1] = x * c1[0] + y * c1[1];
    }
    Ok(())
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

/// [`theta_dot_network`] on slices, allocation-free: `phi` row-major
/// (`2n`), `jac` column-major, `v` and `out` with `n` entries.
#[inline]
pub fn theta_dot_network_into(
    phi: &[f64],
    jac: &[f64],
    xdot: [f64; 2],
    v: &[f64],
    out: &mut [f64],
) -> Result<()> {
    check_lengths(
        jac,
        &[
            ("Phi (n x 2)", phi.len() / 2),
            ("v", v.len()),
            ("theta_dot", out.len()),
        ],
    )?;
    let e = task_residual(jac, xdot, v);
    for ((o, row), vi) in out.iter_mut().zip(phi.chunks_exact(2)).zip(v) {
        *o = (row[0] * e[0] + row[1] * e[1]) + vi;
    }
    Ok(())
}

/// Smallest singular value of a `2 x n` Jacobian, from the eigenvalues of the
/// 2x2 matrix `J J^T` in closed form.
pub fn smallest_singular_value(j: &Matrix2xX<f64>) -> f64 {
    crate::kinematics::smallest_singular_value(jjt(j.as_slice()))
}

/// Square root of `det(J J^T)`: Yoshikawa's manipulability measure.
pub fn manipulability(j: &Matrix2xX<f64>) -> f64 {
    let [a, b, c] = jjt(j.as_slice());
    (a * c - b * b).max(0.0).sqrt()
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

    /// Switches the default schedule on in `damping` where the path leaves
    /// the arm's reach (`reachable` false) and none is set, so the
    /// stretched arm's rates stay bounded: both planners, at the start and
    /// for a new target. Returns whether it did.
    pub fn switch_on_out_of_reach(damping: &mut Option<Self>, reachable: bool) -> bool {
        let on = damping.is_none() && !reachable;
        if on {
            *damping = Some(Self::default());
        }
        on
    }

    /// The extra damping this schedule adds at Jacobian `j`.
    pub fn delta(&self, j: &Matrix2xX<f64>) -> f64 {
        self.delta_at_sigma(smallest_singular_value(j))
    }

    /// The extra damping at a pose whose smallest singular value is `sigma`.
    #[inline]
    pub fn delta_at_sigma(&self, sigma: f64) -> f64 {
        if sigma >= self.threshold {
            0.0
        } else {
            let ratio = sigma / self.threshold;
            self.delta_max * (1.0 - ratio * ratio)
        }
    }
}
