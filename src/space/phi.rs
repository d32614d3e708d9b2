//! A learned pseudoinverse `Phi` (`n x 3`, row-major) for an arm in space,
//! and what the paper's eq. (21) does with it: refine it with the pose's
//! `J`, damp it, weight it by the joint limits, and turn it into joint
//! rates. The planar forms (`n x 2`) are [`crate::ik`]'s; these are the
//! same formulas with `m = 3`. `jac` is the pose's `3 x n` Jacobian,
//! column-major (one column of three per joint).

use crate::error::{Error, Result};

type M3 = [[f64; 3]; 3];

/// `Phi^T Phi` (3 x 3).
fn gram(phi: &[f64]) -> M3 {
    let mut p = [[0.0; 3]; 3];
    for row in phi.chunks_exact(3) {
        for r in 0..3 {
            for c in 0..3 {
                p[r][c] += row[r] * row[c];
            }
        }
    }
    p
}

/// `J Phi` (3 x 3), optionally with `W^-1` between: `J W^-1 Phi`.
fn j_phi(jac: &[f64], phi: &[f64], winv: Option<&[f64]>) -> M3 {
    let mut m = [[0.0; 3]; 3];
    for (i, (col, row)) in jac.chunks_exact(3).zip(phi.chunks_exact(3)).enumerate() {
        let w = winv.map_or(1.0, |w| w[i]);
        for r in 0..3 {
            for c in 0..3 {
                m[r][c] += col[r] * w * row[c];
            }
        }
    }
    m
}

fn mul(a: &M3, b: &M3) -> M3 {
    let mut m = [[0.0; 3]; 3];
    for r in 0..3 {
        for c in 0..3 {
            m[r][c] = (0..3).map(|k| a[r][k] * b[k][c]).sum();
        }
    }
    m
}

/// The inverse of a 3 x 3 matrix by its adjugate, refused where it is
/// (numerically) singular.
fn inverse(a: &M3) -> Result<M3> {
    let cof = |r: usize, c: usize| {
        let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
        let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
        a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]
    };
    let det = a[0][0] * cof(0, 0) + a[0][1] * cof(0, 1) + a[0][2] * cof(0, 2);
    let scale = a.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(det.is_finite() && det.abs() > 1e-14 * scale.powi(3).max(f64::MIN_POSITIVE)) {
        return Err(Error::Singular(
            "a 3 x 3 matrix of the learned Phi is singular".into(),
        ));
    }
    let mut inv = [[0.0; 3]; 3];
    for (r, row) in inv.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = cof(c, r) / det;
        }
    }
    Ok(inv)
}

/// Each row `p` of `phi` becomes `p M`.
fn times(phi: &mut [f64], m: &M3) {
    for row in phi.chunks_exact_mut(3) {
        let p = [row[0], row[1], row[2]];
        for (c, x) in row.iter_mut().enumerate() {
            *x = p[0] * m[0][c] + p[1] * m[1][c] + p[2] * m[2][c];
        }
    }
}

fn check(phi: &[f64], jac: &[f64]) -> Result<()> {
    if phi.len() == jac.len() {
        Ok(())
    } else {
        Err(Error::DimensionMismatch {
            what: "Phi (n x 3)".into(),
            expected: jac.len(),
            found: phi.len(),
        })
    }
}

fn finite(phi: &[f64], what: &str) -> Result<()> {
    if phi.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(Error::NonFinite { what: what.into() })
    }
}

/// Refines a learned `Phi` toward the pseudoinverse `J+` in place, by
/// `steps` Newton-Schulz steps `Phi <- Phi (2 I - J Phi)` with one turn
/// into `J^T`'s range, `Phi <- J^T (Phi^T Phi)`, after the first;
/// `steps = 0` leaves `Phi` as the network gave it (the paper's). Returns
/// `false`, `Phi` then unusable, where the steps are not sure to converge:
/// the residual `E = I - J Phi` has `|E|_F >= 1` at the network's output
/// or after the turn (the caller takes the exact route there).
///
/// A Newton-Schulz step squares `E` (`J Phi' = I - E^2`), so it converges
/// wherever `|E| < 1`, and diverges (to 1e40 in a few steps) where not: on
/// the Panda, 10% of the poses of the `Phi` network's distribution with its
/// median relative error of 0.15 (`docs/space.md`). Its iterates keep the
/// network's range, so alone it converges to *a* right inverse of `J`, not
/// to `J+`, and the null-space projector `I - Phi J` stays oblique by the
/// network's error. The turn puts `Phi` in `J^T`'s range, where the only
/// right inverse is `J+ = J^T (J J^T)^-1`; at `Phi = J+`, `Phi^T Phi = (J
/// J^T)^-1` and the turn gives `J+` back, so the pseudoinverse is a fixed
/// point of every step. It comes after one step rather than first: with
/// `Phi = J+ + N` (`J N` small), `Phi^T Phi = (J J^T)^-1 + N^T N + ...`,
/// and the residual after the turn, `J J^T` times that error, grows with
/// `J`'s condition number squared, so a step first makes the error it
/// multiplies smaller (on the Panda after two steps: median 4.5e-3 turned
/// after one step, 2.1e-2 turned first).
pub fn refine_phi(phi: &mut [f64], jac: &[f64], steps: u32) -> Result<bool> {
    check(phi, jac)?;
    for k in 0..steps {
        if !newton_schulz_step(phi, jac) {
            return Ok(false);
        }
        if k == 0 {
            let p = gram(phi);
            for (row, col) in phi.chunks_exact_mut(3).zip(jac.chunks_exact(3)) {
                for (c, x) in row.iter_mut().enumerate() {
                    *x = col[0] * p[0][c] + col[1] * p[1][c] + col[2] * p[2][c];
                }
            }
            if residual(jac, phi) >= 1.0 {
                return Ok(false);
            }
        }
    }
    finite(phi, "refined Phi")?;
    Ok(true)
}

/// `|I - J Phi|_F`.
fn residual(jac: &[f64], phi: &[f64]) -> f64 {
    let m = j_phi(jac, phi, None);
    let mut sum = 0.0;
    for (r, row) in m.iter().enumerate() {
        for (c, x) in row.iter().enumerate() {
            sum += (if r == c { 1.0 } else { 0.0 } - x).powi(2);
        }
    }
    if sum.is_finite() {
        sum.sqrt()
    } else {
        f64::INFINITY
    }
}

/// `Phi <- Phi (2 I - J Phi)`, refused (`false`, `Phi` unchanged) where
/// `|I - J Phi|_F >= 1`.
fn newton_schulz_step(phi: &mut [f64], jac: &[f64]) -> bool {
    let mut m = j_phi(jac, phi, None);
    let mut sum = 0.0;
    for (r, row) in m.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            let e = if r == c { 1.0 } else { 0.0 } - *x;
            sum += e * e;
            *x = if r == c { 1.0 } else { 0.0 } + e;
        }
    }
    if sum.is_nan() || sum >= 1.0 {
        return false;
    }
    times(phi, &m);
    true
}

/// Damps an undamped `Phi_0` by a constant `delta` in place,
/// `Phi_delta = Phi_0 (I + delta Phi_0^T Phi_0)^-1`: eq. (20)'s
/// `J^T (J J^T + delta I)^-1` exactly when `Phi_0 = J+`
/// ([`crate::ik::damp_phi`] in the plane).
pub fn damp_phi(phi: &mut [f64], delta: f64) -> Result<()> {
    if delta == 0.0 {
        return Ok(());
    }
    let mut d = gram(phi);
    for (r, row) in d.iter_mut().enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = delta * *x + if r == c { 1.0 } else { 0.0 };
        }
    }
    times(phi, &inverse(&d)?);
    finite(phi, "damped Phi")
}

/// Weights an undamped `Phi_0` by a diagonal `W` (given as `winv`) and
/// damps it by `delta`, in place: `Phi_W = W^-1 Phi_0 M_W^-1 M_I (I +
/// delta P)^-1`, `P = Phi_0^T Phi_0`, `M_W = J W^-1 Phi_0 + delta P`
/// (`M_I` the same with `W = I`): `W^-1 J^T (J W^-1 J^T + delta I)^-1`
/// exactly when `Phi_0 = J+` ([`crate::ik::weight_phi`] in the plane,
/// where the derivation is).
pub fn weight_phi(phi: &mut [f64], jac: &[f64], winv: &[f64], delta: f64) -> Result<()> {
    check(phi, jac)?;
    let p = gram(phi);
    let (mut mw, mut mi) = (j_phi(jac, phi, Some(winv)), j_phi(jac, phi, None));
    let mut d = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for r in 0..3 {
        for c in 0..3 {
            mw[r][c] += delta * p[r][c];
            mi[r][c] += delta * p[r][c];
            d[r][c] += delta * p[r][c];
        }
    }
    let t = mul(&mul(&inverse(&mw)?, &mi), &inverse(&d)?);
    for (row, w) in phi.chunks_exact_mut(3).zip(winv) {
        row.iter_mut().for_each(|x| *x *= w);
    }
    times(phi, &t);
    finite(phi, "weighted Phi")
}

/// Eq. (21) with `m = 3`: `theta_dot = Phi (Xdot - J W^-1 v) + W^-1 v`
/// into `out`, `winv` the weighting's `W^-1` (all ones: the paper's
/// unweighted form).
pub fn theta_dot(
    phi: &[f64],
    jac: &[f64],
    winv: Option<&[f64]>,
    xdot: [f64; 3],
    v: &[f64],
    out: &mut [f64],
) -> Result<()> {
    check(phi, jac)?;
    let w = |i: usize| winv.map_or(1.0, |w| w[i]);
    let mut e = xdot;
    for (i, (col, vi)) in jac.chunks_exact(3).zip(v).enumerate() {
        for r in 0..3 {
            e[r] -= col[r] * (w(i) * vi);
        }
    }
    for (i, ((o, row), vi)) in out.iter_mut().zip(phi.chunks_exact(3)).zip(v).enumerate() {
        *o = (row[0] * e[0] + row[1] * e[1] + row[2] * e[2]) + w(i) * vi;
    }
    Ok(())
}

/// The pseudoinverse `J+ = J^T (J J^T)^-1` row-major into `out` (`3n`),
/// the target the `Phi` network learns. Refused at a singular pose.
pub fn pseudoinverse(jac: &[f64], out: &mut [f64]) -> Result<()> {
    damped_pseudoinverse(jac, None, 0.0, out)
}

/// Eq. (20) with `m = 3`, weighted by a diagonal `W` given as its inverse
/// `winv` (`None`: `W = I`): `Phi = W^-1 J^T (J W^-1 J^T + delta I)^-1`
/// row-major into `out` (`3n`); what stands in for a learned `Phi` where
/// no network fits. Refused at a singular pose with `delta = 0`.
pub fn damped_pseudoinverse(
    jac: &[f64],
    winv: Option<&[f64]>,
    delta: f64,
    out: &mut [f64],
) -> Result<()> {
    check(out, jac)?;
    let w = |i: usize| winv.map_or(1.0, |w| w[i]);
    let mut a = [[0.0; 3]; 3];
    for (i, col) in jac.chunks_exact(3).enumerate() {
        for r in 0..3 {
            for c in 0..3 {
                a[r][c] += col[r] * (w(i) * col[c]);
            }
        }
    }
    for (i, row) in a.iter_mut().enumerate() {
        row[i] += delta;
    }
    let inv = inverse(&a)?;
    for (i, (row, col)) in out.chunks_exact_mut(3).zip(jac.chunks_exact(3)).enumerate() {
        for (c, x) in row.iter_mut().enumerate() {
            *x = w(i) * (col[0] * inv[0][c] + col[1] * inv[1][c] + col[2] * inv[2][c]);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small generator for the tests (`space` sits below `nn`, whose
    /// `Rng` it may not use): xorshift64*, uniform in `[lo, hi)`.
    struct Rng(u64);

    impl Rng {
        fn new(seed: u64) -> Self {
            Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
        }
        fn range(&mut self, lo: f64, hi: f64) -> f64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            let u = (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64;
            lo + (hi - lo) * u
        }
    }

    fn random_jac(n: usize, rng: &mut Rng) -> Vec<f64> {
        (0..3 * n).map(|_| rng.range(-1.0, 1.0)).collect()
    }

    fn max_diff(a: &[f64], b: &[f64]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max)
    }

    /// Newton-Schulz alone, without the turn into `J^T`'s range.
    fn newton_schulz(phi: &mut [f64], jac: &[f64], steps: u32) {
        for _ in 0..steps {
            assert!(newton_schulz_step(phi, jac));
        }
    }

    #[test]
    fn refinement_converges_to_the_pseudoinverse_itself() {
        let mut rng = Rng::new(7);
        for n in 4..=7 {
            let jac = random_jac(n, &mut rng);
            let mut exact = vec![0.0; 3 * n];
            pseudoinverse(&jac, &mut exact).unwrap();
            let noisy: Vec<f64> = exact
                .iter()
                .map(|x| x + 0.03 * rng.range(-1.0, 1.0))
                .collect();
            let mut ours = noisy.clone();
            assert!(refine_phi(&mut ours, &jac, 6).unwrap());
            assert!(
                max_diff(&ours, &exact) < 1e-10,
                "n = {n}: {}",
                max_diff(&ours, &exact)
            );
            // Newton-Schulz alone finds a right inverse, but not J+.
            let mut old = noisy;
            newton_schulz(&mut old, &jac, 6);
            let jp = j_phi(&jac, &old, None);
            assert!((jp[0][0] - 1.0).abs() < 1e-10 && jp[0][1].abs() < 1e-10);
            assert!(max_diff(&old, &exact) > 1e-4, "n = {n}");
        }
    }

    #[test]
    fn the_exact_pseudoinverse_is_a_fixed_point_and_zero_steps_change_nothing() {
        let mut rng = Rng::new(3);
        let jac = random_jac(7, &mut rng);
        let mut exact = vec![0.0; 21];
        pseudoinverse(&jac, &mut exact).unwrap();
        let mut phi = exact.clone();
        refine_phi(&mut phi, &jac, 1).unwrap();
        assert!(max_diff(&phi, &exact) < 1e-12);
        let noisy: Vec<f64> = exact.iter().map(|x| x + 0.1).collect();
        let mut same = noisy.clone();
        assert!(refine_phi(&mut same, &jac, 0).unwrap());
        assert_eq!(same, noisy);
        // Far from J+ (|I - J Phi| >= 1) the steps are refused, not run.
        let mut far: Vec<f64> = exact.iter().map(|x| -x).collect();
        assert!(!refine_phi(&mut far, &jac, 3).unwrap());
    }

    #[test]
    fn damping_and_weighting_an_exact_phi_give_the_exact_routes() {
        let mut rng = Rng::new(11);
        let n = 7;
        let jac = random_jac(n, &mut rng);
        let winv: Vec<f64> = (0..n).map(|_| rng.range(0.2, 1.0)).collect();
        let delta = 0.05;
        // W^-1 J^T (J W^-1 J^T + delta I)^-1 directly.
        let mut a = [[0.0; 3]; 3];
        for (col, w) in jac.chunks_exact(3).zip(&winv) {
            for r in 0..3 {
                for c in 0..3 {
                    a[r][c] += col[r] * w * col[c];
                }
            }
        }
        for (i, row) in a.iter_mut().enumerate() {
            row[i] += delta;
        }
        let inv = inverse(&a).unwrap();
        let want: Vec<f64> = jac
            .chunks_exact(3)
            .zip(&winv)
            .flat_map(|(col, w)| {
                (0..3).map(move |c| w * (0..3).map(|k| col[k] * inv[k][c]).sum::<f64>())
            })
            .collect();
        let mut exact = vec![0.0; 3 * n];
        pseudoinverse(&jac, &mut exact).unwrap();
        let mut weighted = exact.clone();
        weight_phi(&mut weighted, &jac, &winv, delta).unwrap();
        assert!(
            max_diff(&weighted, &want) < 1e-12,
            "{}",
            max_diff(&weighted, &want)
        );
        // With W = I, weighting is damping.
        let ones = vec![1.0; n];
        let (mut w1, mut d1) = (exact.clone(), exact.clone());
        weight_phi(&mut w1, &jac, &ones, delta).unwrap();
        damp_phi(&mut d1, delta).unwrap();
        assert!(max_diff(&w1, &d1) < 1e-12);
    }

    #[test]
    fn eq21_with_the_exact_phi_is_eq18() {
        let mut rng = Rng::new(5);
        let n = 7;
        let jac = random_jac(n, &mut rng);
        let v: Vec<f64> = (0..n).map(|_| rng.range(-1.0, 1.0)).collect();
        let xdot = [0.1, -0.2, 0.3];
        let mut phi = vec![0.0; 3 * n];
        pseudoinverse(&jac, &mut phi).unwrap();
        let mut out = vec![0.0; n];
        theta_dot(&phi, &jac, None, xdot, &v, &mut out).unwrap();
        // J theta_dot = Xdot and theta_dot - J+ Xdot is v's null-space part.
        for r in 0..3 {
            let jx: f64 = jac.chunks_exact(3).zip(&out).map(|(c, o)| c[r] * o).sum();
            assert!((jx - xdot[r]).abs() < 1e-12);
        }
        assert!(matches!(
            refine_phi(&mut phi[..3], &jac, 1),
            Err(Error::DimensionMismatch { .. })
        ));
    }
}
