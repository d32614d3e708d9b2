//! The weighted routes of eqs. (5)-(7) with a diagonal `W` (weighted least
//! norm, `crate::planner::methods::weighting`): the exact solve, the
//! weighted exact `Phi`, a learned `Phi` weighted, and the network route
//! with it.

use super::{
    check_delta, check_lengths, inverse_spd2, numerically_singular, size_error, solve_spd2,
};
use crate::error::Result;

/// `J W^-1 J^T` of a diagonal `W` given as its inverse `winv` (`n`
/// entries), as `(a11, a12, a22)`.
#[inline]
fn jwjt(jac: &[f64], winv: &[f64]) -> [f64; 3] {
    let (mut a11, mut a12, mut a22) = (0.0, 0.0, 0.0);
    for (col, w) in jac.chunks_exact(2).zip(winv) {
        a11 += w * col[0] * col[0];
        a12 += w * col[0] * col[1];
        a22 += w * col[1] * col[1];
    }
    [a11, a12, a22]
}

/// [`crate::ik::theta_dot_symmetric_into`] with a diagonal weight `W` of eqs. (6)-(7)
/// (`Z = I`), given as its inverse `winv` (`n` entries, each in `(0, 1]` for
/// weighted least norm): eq. (5) with `J+ = W^-1 J^T (J W^-1 J^T + delta I)^-1`
/// and the null-space vector taken in the same metric, `W^-1 v` (the
/// gradient of a criterion in the joint space weighted by `W`):
/// `theta_dot = J+ Xdot + (I - J+ J) W^-1 v`, solved as eq. (18) is,
/// `(J W^-1 J^T + delta I) varphi = Xdot - J W^-1 v`,
/// `theta_dot = W^-1 (J^T varphi + v)`. Every term of joint `i`'s rate is
/// divided by `w_i`, so a joint whose weight grows without bound stops,
/// however the secondary task pulls it. With `winv` all ones it is
/// [`crate::ik::theta_dot_symmetric_into`] to the last bit.
#[inline]
pub fn theta_dot_weighted_into(
    jac: &[f64],
    winv: &[f64],
    xdot: [f64; 2],
    v: &[f64],
    delta: f64,
    out: &mut [f64],
) -> Result<()> {
    check_lengths(
        jac,
        &[
            ("W^-1", winv.len()),
            ("v", v.len()),
            ("theta_dot", out.len()),
        ],
    )?;
    let [a11, a12, a22] = jwjt(jac, winv);
    let rhs = weighted_residual(jac, winv, xdot, v);
    let varphi = solve_spd2([a11 + delta, a12, a22 + delta], rhs)?;
    for (((o, col), vi), w) in out.iter_mut().zip(jac.chunks_exact(2)).zip(v).zip(winv) {
        *o = w * ((col[0] * varphi[0] + col[1] * varphi[1]) + vi);
    }
    Ok(())
}

/// `Xdot - J W^-1 v`, the task velocity left for a weighted pseudoinverse.
#[inline]
fn weighted_residual(jac: &[f64], winv: &[f64], xdot: [f64; 2], v: &[f64]) -> [f64; 2] {
    let (mut jv0, mut jv1) = (0.0, 0.0);
    for ((col, vi), w) in jac.chunks_exact(2).zip(v).zip(winv) {
        jv0 += col[0] * (w * vi);
        jv1 += col[1] * (w * vi);
    }
    [xdot[0] - jv0, xdot[1] - jv1]
}

/// The network route, eq. (21), with a weighted `Phi_W` (from
/// [`weight_phi`] or [`phi_weighted_into`]) and the null-space vector in the
/// same metric as in [`theta_dot_weighted_into`]:
/// `theta_dot = Phi_W (Xdot - J W^-1 v) + W^-1 v`.
pub fn theta_dot_network_weighted_into(
    phi: &[f64],
    jac: &[f64],
    winv: &[f64],
    xdot: [f64; 2],
    v: &[f64],
    out: &mut [f64],
) -> Result<()> {
    check_lengths(
        jac,
        &[
            ("Phi (n x 2)", phi.len() / 2),
            ("W^-1", winv.len()),
            ("v", v.len()),
            ("theta_dot", out.len()),
        ],
    )?;
    let e = weighted_residual(jac, winv, xdot, v);
    for (((o, row), vi), w) in out.iter_mut().zip(phi.chunks_exact(2)).zip(v).zip(winv) {
        *o = (row[0] * e[0] + row[1] * e[1]) + w * vi;
    }
    Ok(())
}

/// The weighted damped pseudoinverse `W^-1 J^T (J W^-1 J^T + delta I)^-1`
/// (eq. 6 with a diagonal `W`, `Z = I`) row-major into `out` (`2n`), `W`
/// given as its inverse `winv`: what stands in for a learned `Phi` where
/// the damping schedule is active and the joints are weighted.
pub fn phi_weighted_into(jac: &[f64], winv: &[f64], delta: f64, out: &mut [f64]) -> Result<()> {
    check_lengths(jac, &[("W^-1", winv.len()), ("Phi (n x 2)", out.len() / 2)])?;
    if out.len() != jac.len() {
        return Err(size_error("Phi (n x 2)", jac.len(), out.len()));
    }
    let [a11, a12, a22] = jwjt(jac, winv);
    let [c0, c1] = inverse_spd2([a11 + delta, a12, a22 + delta])?;
    for ((row, col), w) in out.chunks_exact_mut(2).zip(jac.chunks_exact(2)).zip(winv) {
        row[0] = w * (col[0] * c0[0] + col[1] * c0[1]);
        row[1] = w * (col[0] * c1[0] + col[1] * c1[1]);
    }
    Ok(())
}

/// Weights an undamped `Phi_0` (a learned pseudoinverse, trained with
/// `W = I`) by a diagonal `W` and damps it by `delta`, in place:
/// `Phi_W = W^-1 Phi_0 M_W^-1 M_I (I + delta P)^-1` with `P = Phi_0^T Phi_0`
/// and `M_W = J W^-1 Phi_0 + delta P` (`M_I` the same with `W = I`).
///
/// The network cannot learn every `W`; this asks of it what it learned,
/// as [`crate::ik::damp_phi`] does. With `A = J J^T`, `B = J W^-1 J^T` and an exact
/// `Phi_0 = J^T A^-1`: `P = A^-1`, `M_W = (B + delta I) A^-1`, and
/// `M_I = I + delta P`, so `Phi_W = W^-1 J^T (B + delta I)^-1`, the weighted
/// damped pseudoinverse exactly (and, to the refinement's accuracy, for a
/// `Phi_0` refined by [`super::refine_phi`], which converges to
/// `J^T A^-1`). With `W = I` it is [`crate::ik::damp_phi`]'s
/// `Phi_0 (I + delta P)^-1`: the network's own error is kept as it is, not
/// corrected, so the rates move with the weights continuously from those
/// of the unweighted route. Refused where a 2x2 matrix is singular.
pub fn weight_phi(phi: &mut [f64], jac: &[f64], winv: &[f64], delta: f64) -> Result<()> {
    check_delta(delta)?;
    check_lengths(jac, &[("W^-1", winv.len()), ("Phi (n x 2)", phi.len() / 2)])?;
    // Row-major 2 x 2: M_W, M_I (without delta P yet) and P.
    let (mut mw, mut mi, mut p) = ([0.0; 4], [0.0; 4], [0.0; 4]);
    for ((j, f), w) in jac.chunks_exact(2).zip(phi.chunks_exact(2)).zip(winv) {
        for r in 0..2 {
            for c in 0..2 {
                mi[2 * r + c] += j[r] * f[c];
                mw[2 * r + c] += w * j[r] * f[c];
                p[2 * r + c] += f[r] * f[c];
            }
        }
    }
    let mut d = [1.0, 0.0, 0.0, 1.0];
    for k in 0..4 {
        mw[k] += delta * p[k];
        mi[k] += delta * p[k];
        d[k] += delta * p[k];
    }
    // T = M_W^-1 M_I D^-1.
    let t = mul2(&mul2(&inverse2(mw)?, &mi), &inverse2(d)?);
    for (row, w) in phi.chunks_exact_mut(2).zip(winv) {
        let (x, y) = (w * row[0], w * row[1]);
        row[0] = x * t[0] + y * t[2];
        row[1] = x * t[1] + y * t[3];
    }
    Ok(())
}

/// The inverse of a row-major 2x2 matrix, refused when it is (numerically)
/// singular.
fn inverse2(m: [f64; 4]) -> Result<[f64; 4]> {
    let det = m[0] * m[3] - m[1] * m[2];
    let scale = m.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    if !det.is_finite() || det.abs() <= 1e-13 * scale * scale {
        return Err(numerically_singular());
    }
    Ok([m[3] / det, -m[1] / det, -m[2] / det, m[0] / det])
}

/// The product of two row-major 2x2 matrices.
fn mul2(a: &[f64; 4], b: &[f64; 4]) -> [f64; 4] {
    [
        a[0] * b[0] + a[1] * b[2],
        a[0] * b[1] + a[1] * b[3],
        a[2] * b[0] + a[3] * b[2],
        a[2] * b[1] + a[3] * b[3],
    ]
}
