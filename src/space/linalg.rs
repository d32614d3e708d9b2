//! The `3 x 3` algebra of a hand's position task: the symmetric positive
//! definite solve of eq. (17) with `m = 3`, and the smallest singular value
//! of a `3 x n` Jacobian for the damping schedule, both in closed form (no
//! allocation, no iteration).

use crate::error::{Error, Result};

/// Solves `A x = b` for a symmetric positive definite `A` (by rows) by
/// Cholesky's factorisation; refused where `A` is not (numerically)
/// positive definite: a singular pose with no damping.
#[inline]
pub fn solve_spd3(a: [[f64; 3]; 3], b: [f64; 3]) -> Result<[f64; 3]> {
    let singular = || Error::Singular("J J^T + delta I (3 x 3) is not positive definite".into());
    let scale = a[0][0].abs().max(a[1][1].abs()).max(a[2][2].abs());
    let tiny = 1e-14 * scale.max(f64::MIN_POSITIVE);
    // Each pivot must exceed `tiny`; NaN does not.
    let positive = |d: f64| d.partial_cmp(&tiny) == Some(std::cmp::Ordering::Greater);
    let l00 = a[0][0];
    if !positive(l00) {
        return Err(singular());
    }
    let l00 = l00.sqrt();
    let l10 = a[1][0] / l00;
    let l20 = a[2][0] / l00;
    let d1 = a[1][1] - l10 * l10;
    if !positive(d1) {
        return Err(singular());
    }
    let l11 = d1.sqrt();
    let l21 = (a[2][1] - l20 * l10) / l11;
    let d2 = a[2][2] - l20 * l20 - l21 * l21;
    if !positive(d2) {
        return Err(singular());
    }
    let l22 = d2.sqrt();
    // L y = b, then L^T x = y.
    let y0 = b[0] / l00;
    let y1 = (b[1] - l10 * y0) / l11;
    let y2 = (b[2] - l20 * y0 - l21 * y1) / l22;
    let x2 = y2 / l22;
    let x1 = (y1 - l21 * x2) / l11;
    let x0 = (y0 - l10 * x1 - l20 * x2) / l00;
    Ok([x0, x1, x2])
}

/// The eigenvalues of a symmetric `3 x 3` matrix (by rows), largest first,
/// by the trigonometric solution of its characteristic cubic (Smith 1961,
/// "Eigenvalues of a symmetric 3 x 3 matrix", Comm. ACM 4(4)).
pub fn eigenvalues_sym3(a: [[f64; 3]; 3]) -> [f64; 3] {
    let p1 = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    if p1 == 0.0 {
        let mut d = [a[0][0], a[1][1], a[2][2]];
        d.sort_by(|x, y| y.total_cmp(x));
        return d;
    }
    let q = (a[0][0] + a[1][1] + a[2][2]) / 3.0;
    let p2 = (a[0][0] - q).powi(2) + (a[1][1] - q).powi(2) + (a[2][2] - q).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    let b = |i: usize, j: usize| (a[i][j] - if i == j { q } else { 0.0 }) / p;
    let det = b(0, 0) * (b(1, 1) * b(2, 2) - b(1, 2) * b(2, 1))
        - b(0, 1) * (b(1, 0) * b(2, 2) - b(1, 2) * b(2, 0))
        + b(0, 2) * (b(1, 0) * b(2, 1) - b(1, 1) * b(2, 0));
    let r = (det / 2.0).clamp(-1.0, 1.0);
    let phi = r.acos() / 3.0;
    // The kinematics' cosine (libm's would add its argument reduction to the page's module).
    let e1 = q + 2.0 * p * crate::kinematics::sin_cos(phi).1;
    let e3 = q + 2.0 * p * crate::kinematics::sin_cos(phi + 2.0 * std::f64::consts::PI / 3.0).1;
    [e1, 3.0 * q - e1 - e3, e3]
}

/// The smallest singular value of a `3 x n` Jacobian from `J J^T`.
#[inline]
pub fn smallest_singular_value3(jjt: [[f64; 3]; 3]) -> f64 {
    eigenvalues_sym3(jjt)[2].max(0.0).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cholesky_solve_solves_and_refuses_a_singular_matrix() {
        let a = [[4.0, 1.0, 0.5], [1.0, 3.0, 0.2], [0.5, 0.2, 2.0]];
        let b = [1.0, -2.0, 0.5];
        let x = solve_spd3(a, b).unwrap();
        for r in 0..3 {
            let ax: f64 = (0..3).map(|c| a[r][c] * x[c]).sum();
            assert!((ax - b[r]).abs() < 1e-14);
        }
        let rank2 = [[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!(matches!(solve_spd3(rank2, b), Err(Error::Singular(_))));
        assert!(solve_spd3([[f64::NAN, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]], b).is_err());
    }

    #[test]
    fn the_eigenvalues_of_a_symmetric_matrix() {
        // diag(3, 2, 1) rotated: the same eigenvalues.
        let (c, s) = (0.6f64, 0.8f64);
        let r = [[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]];
        let d = [3.0, 1.0, 2.0];
        let mut a = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                a[i][j] = (0..3).map(|k| r[i][k] * d[k] * r[j][k]).sum();
            }
        }
        let e = eigenvalues_sym3(a);
        for (got, want) in e.iter().zip([3.0, 2.0, 1.0]) {
            assert!((got - want).abs() < 1e-12, "{e:?}");
        }
        assert_eq!(
            eigenvalues_sym3([[2.0, 0.0, 0.0], [0.0, 5.0, 0.0], [0.0, 0.0, 1.0]]),
            [5.0, 2.0, 1.0]
        );
    }
}
