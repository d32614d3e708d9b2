//! A blocked Cholesky solve for the Levenberg-Marquardt step
//! `(J^T J + mu I) dx = J^T e`.
//!
//! nalgebra's Cholesky is unblocked (16 ms for the 699 x 699 system of the
//! 2-35-14-6 network, as long as the rest of an epoch); `faer`'s is fast but
//! would more than double the page's `.wasm`. This is the textbook
//! right-looking blocked algorithm: factor a 64-wide diagonal block, solve
//! the panel below it, and update the trailing lower triangle with
//! `matrixmultiply`'s `gemm` (through nalgebra), where nearly all the work
//! is. The panel and substitution loops run down contiguous columns
//! (column-major storage), so they vectorise.

use nalgebra::{DMatrix, DVector};

#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
use crate::nn::gemm::{gemm, Mat, MatMut, Scratch};

/// Width of the diagonal blocks.
const BLOCK: usize = 64;

/// Factors the symmetric positive definite `a` in place into `L L^T`
/// (lower triangle; the strict upper triangle is left as it was, unread).
/// Returns `false`, with `a` partly overwritten, if a pivot is not positive
/// and finite (the matrix is not numerically positive definite).
pub fn factor(a: &mut DMatrix<f64>) -> bool {
    let n = a.nrows();
    if a.ncols() != n {
        return false;
    }
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    let mut scratch = Scratch::default();
    let mut k = 0;
    while k < n {
        let kb = BLOCK.min(n - k);
        // Diagonal block and the panel below it, column by column
        // (left-looking within the block): the columns k..k+kb have already
        // received every update from the columns left of k.
        for c in k..k + kb {
            for q in k..c {
                let l_cq = a[(c, q)];
                if l_cq != 0.0 {
                    let (left, mut right) = a.columns_range_pair_mut(q, c);
                    let src = left.rows(c, n - c);
                    let mut dst = right.rows_mut(c, n - c);
                    dst.axpy(-l_cq, &src, 1.0);
                }
            }
            let pivot = a[(c, c)];
            if !(pivot > 0.0 && pivot.is_finite()) {
                return false;
            }
            let d = pivot.sqrt();
            let mut col = a.view_mut((c, c), (n - c, 1));
            col /= d;
        }
        // Trailing update of the lower triangle, one block column at a time:
        // A[j.., j..j+jb] -= L[j.., k..k+kb] L[j..j+jb, k..k+kb]^T.
        let end = k + kb;
        let mut j = end;
        while j < n {
            let jb = BLOCK.min(n - j);
            #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
            {
                let (panel, mut rest) = a.columns_range_pair_mut(k..end, j..j + jb);
                let lhs = panel.rows(j, n - j);
                let rhs_t = panel.rows(j, jb).transpose();
                let mut target = rest.rows_mut(j, n - j);
                target.gemm(-1.0, &lhs, &rhs_t, 1.0);
            }
            // matrixmultiply's scalar kernel in wasm: the SIMD one instead.
            #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
            {
                let (left, right) = a.as_mut_slice().split_at_mut(j * n);
                let panel = &left[k * n + j..];
                let lhs = Mat {
                    data: panel,
                    rows: n - j,
                    cols: kb,
                    rs: 1,
                    cs: n,
                };
                let rhs_t = Mat {
                    data: panel,
                    rows: kb,
                    cols: jb,
                    rs: n,
                    cs: 1,
                };
                let mut target = MatMut {
                    data: &mut right[j..],
                    rows: n - j,
                    cols: jb,
                    rs: 1,
                    cs: n,
                };
                gemm(-1.0, lhs, rhs_t, 1.0, &mut target, &mut scratch);
            }
            j += jb;
        }
        k = end;
    }
    true
}

/// Solves `L L^T x = b` in place, `L` the lower triangle from [`factor`].
pub fn solve(l: &DMatrix<f64>, b: &mut DVector<f64>) {
    let n = l.nrows();
    // L y = b, column-oriented: y_j = b_j / L_jj, then b[j+1..] -= y_j L[j+1.., j].
    for j in 0..n {
        let y = b[j] / l[(j, j)];
        b[j] = y;
        if y != 0.0 {
            let col = l.column(j);
            let mut rest = b.rows_mut(j + 1, n - j - 1);
            rest.axpy(-y, &col.rows(j + 1, n - j - 1), 1.0);
        }
    }
    // L^T x = y: x_j = (y_j - L[j+1.., j] . x[j+1..]) / L_jj.
    for j in (0..n).rev() {
        let col = l.column(j);
        let dot = col.rows(j + 1, n - j - 1).dot(&b.rows(j + 1, n - j - 1));
        b[j] = (b[j] - dot) / l[(j, j)];
    }
}

/// `x` with `a x = b` for a symmetric positive definite `a` (consumed), or
/// `None` if the factorisation fails or the solution is not finite.
pub fn solve_spd(mut a: DMatrix<f64>, b: &DVector<f64>) -> Option<DVector<f64>> {
    if !factor(&mut a) {
        return None;
    }
    let mut x = b.clone();
    solve(&a, &mut x);
    x.iter().all(|v| v.is_finite()).then_some(x)
}
