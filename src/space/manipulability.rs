//! Yoshikawa's manipulability (1985) of a chain's hand in space,
//! `w = sqrt(det(J J^T))` with the `3 x n` positional Jacobian (the product
//! `sigma_1 sigma_2 sigma_3` of its singular values, the volume of the
//! velocity ellipsoid), and its gradient in closed form.
//!
//! **The gradient.** With `A = J J^T = sum_i J_i J_i^T`,
//! `dA/dtheta_j = sum_i (dJ_ij J_i^T + J_i dJ_ij^T)` and, for revolute
//! joints, `dJ_ij = dJ_i/dtheta_j = z_j x J_i` for `j <= i` (joint `j` turns
//! the axis `z_i`, its origin and the hand alike) and `z_i x J_j` for
//! `j > i` (only the hand moves, by `J_j`). Jacobi's formula
//! `d det(A) = tr(adj(A) dA)` (Magnus and Neudecker 2019, ch. 8, eq. 9)
//! with the symmetric `B = adj(A)` gives
//! `d det(A)/dtheta_j = 2 sum_i (B J_i) . dJ_ij`
//! `= 2 z_j . sum_{i >= j} J_i x (B J_i) + 2 J_j . sum_{i < j} (B J_i) x z_i`
//! (a suffix and a prefix sum: `O(n)`), and `dw = d det(A) / (2 w)`.
//!
//! **A chain whose axes are all parallel** (the planar arm set in a plane
//! of space) moves its hand in a plane at every pose: `J` has rank 2,
//! `det(J J^T) = 0` everywhere and carries no information. Yoshikawa's
//! measure of a rank-2 Jacobian is the product of its two nonzero singular
//! values, `w = sqrt(e_2(A))` with `e_2(A) = ((tr A)^2 - tr(A^2)) / 2` (the
//! sum of the principal `2 x 2` minors: the planar `det(J J^T)` of the
//! plane's two rows), whose differential is `tr((tr(A) I - A) dA)`: the
//! same sum with `B = tr(A) I - A`. So such a chain has the planar arm's
//! `w` and gradient. Whether the axes are parallel does not depend on the
//! pose (modified DH: `z_i` is `z_(i-1)` turned by `alpha_i` alone).
//!
//! As in the plane ([`crate::kinematics::Pose::manipulability_gradient_into`]),
//! `w` is floored in the gradient's denominator, where a singular pose
//! leaves it undefined.

use super::linalg::eigenvalues_sym3;
use super::pose::{add, cross, dot, norm, SpacePose, Vec3};

/// Whether every joint axis of `pose` is parallel to the first (the chain
/// moves its hand in a plane; true of a chain of one joint, or none).
pub fn axes_parallel(pose: &SpacePose) -> bool {
    let n = pose.dof();
    n == 0 || (1..n).all(|i| norm(cross(pose.axis(0), pose.axis(i))) <= 1e-12)
}

/// `det(A)` of `A = J J^T`, or `e_2(A)` for a chain whose axes are
/// parallel, with the matrix `B` of its differential `tr(B dA)`.
fn measure(pose: &SpacePose) -> (f64, [[f64; 3]; 3]) {
    let a = pose.jjt();
    if axes_parallel(pose) {
        let tr = a[0][0] + a[1][1] + a[2][2];
        let mut b = a.map(|row| row.map(|x| -x));
        let mut sq = 0.0;
        for (r, row) in a.iter().enumerate() {
            b[r][r] += tr;
            sq += row.iter().map(|x| x * x).sum::<f64>();
        }
        (0.5 * (tr * tr - sq), b)
    } else {
        let c = |r: usize, s: usize, t: usize, u: usize| a[r][s] * a[t][u] - a[r][u] * a[t][s];
        // adj(A) of a symmetric A: its cofactors.
        let b = [
            [c(1, 1, 2, 2), -c(0, 1, 2, 2), c(0, 1, 1, 2)],
            [-c(0, 1, 2, 2), c(0, 0, 2, 2), -c(0, 0, 1, 2)],
            [c(0, 1, 1, 2), -c(0, 0, 1, 2), c(0, 0, 1, 1)],
        ];
        let det = a[0][0] * b[0][0] + a[0][1] * b[1][0] + a[0][2] * b[2][0];
        (det, b)
    }
}

/// The velocity ellipsoid `{J theta_dot : |theta_dot| <= 1}` of `J J^T =
/// jjt` (by rows): its principal axes (orthonormal, the eigenvectors of
/// `J J^T`, the longest first, a right-handed frame) and half-lengths (the
/// singular values `sigma_i = sqrt(lambda_i)` of `J`). The planar
/// [`crate::kinematics::velocity_ellipse`] in three dimensions. Each
/// eigenvector is the longest cross product of two rows of `J J^T -
/// lambda I` (whose rows span the plane normal to it); where two
/// eigenvalues coincide any axes of their plane do, and the third axis is
/// taken as the cross product of the first two.
pub fn velocity_ellipsoid(jjt: [[f64; 3]; 3]) -> ([Vec3; 3], [f64; 3]) {
    let lambda = eigenvalues_sym3(jjt);
    let half = lambda.map(|l| l.max(0.0).sqrt());
    let axis = |l: f64, fallback: Vec3| -> Vec3 {
        let m: [Vec3; 3] = std::array::from_fn(|r| {
            std::array::from_fn(|c| jjt[r][c] - if r == c { l } else { 0.0 })
        });
        let best = [cross(m[0], m[1]), cross(m[0], m[2]), cross(m[1], m[2])]
            .into_iter()
            .max_by(|a, b| norm(*a).total_cmp(&norm(*b)))
            .unwrap_or(fallback);
        let size = norm(best);
        if size > 1e-12 * (1.0 + l.abs()).powi(2) {
            best.map(|x| x / size)
        } else {
            fallback
        }
    };
    let first = axis(lambda[0], [1.0, 0.0, 0.0]);
    // The second, made normal to the first (a repeated eigenvalue leaves
    // it free in their plane).
    let mut second = axis(lambda[1], [0.0, 1.0, 0.0]);
    let along = dot(second, first);
    second = add(second, first.map(|x| -along * x));
    if norm(second) < 1e-9 {
        second = if first[0].abs() < 0.9 {
            cross(first, [1.0, 0.0, 0.0])
        } else {
            cross(first, [0.0, 1.0, 0.0])
        };
    }
    let size = norm(second);
    let second = second.map(|x| x / size);
    ([first, second, cross(first, second)], half)
}

/// The manipulability `w = sqrt(det(J J^T))` of `pose` (for a chain whose
/// axes are parallel, `sqrt(e_2(J J^T))`: see the module documentation).
pub fn manipulability(pose: &SpacePose) -> f64 {
    measure(pose).0.max(0.0).sqrt()
}

/// The gradient of [`manipulability`] into `out` (`n` entries), with `w`
/// floored at `floor` in its denominator. No allocation.
pub fn manipulability_gradient_into(pose: &SpacePose, floor: f64, out: &mut [f64]) {
    let (f, b) = measure(pose);
    let w = f.max(0.0).sqrt().max(floor);
    let jac = pose.jacobian();
    let bj = |col: &[f64]| -> Vec3 { [0, 1, 2].map(|r| dot(b[r], [col[0], col[1], col[2]])) };
    let n = pose.dof().min(out.len());
    // Suffix sums first: out_j = z_j . sum_{i >= j} J_i x (B J_i).
    // A joint that slides turns nothing: its z_j x J_i and z_i x J_j
    // terms are zero.
    let turns = |j: usize| !pose.is_prismatic(j);
    let mut suffix = [0.0; 3];
    for j in (0..n).rev() {
        let col = &jac[3 * j..3 * j + 3];
        suffix = add(suffix, cross([col[0], col[1], col[2]], bj(col)));
        out[j] = if turns(j) {
            dot(pose.axis(j), suffix)
        } else {
            0.0
        };
    }
    // Then the prefix: out_j += J_j . sum_{i < j} (B J_i) x z_i.
    let mut prefix = [0.0; 3];
    for (j, o) in out.iter_mut().enumerate().take(n) {
        let col = &jac[3 * j..3 * j + 3];
        let jj = [col[0], col[1], col[2]];
        *o = (*o + dot(jj, prefix)) / w;
        if turns(j) {
            prefix = add(prefix, cross(bj(col), pose.axis(j)));
        }
    }
}
