//! `C = alpha A B + beta C` on strided matrices in slices, for the
//! trainers' large products.
//!
//! Natively the product goes to nalgebra, which hands it to
//! `matrixmultiply` (AVX2 + FMA kernels chosen at run time) when every
//! dimension exceeds 5; below that nalgebra's own loop misreads operands
//! whose rows are strided (it walks a column by the length of the
//! underlying slice), so small products take a plain loop here. In the
//! page's SIMD build (wasm32 with `simd128`) `matrixmultiply` has no kernel
//! of its own and runs a scalar 4 x 4 one (three quarters of a
//! Levenberg-Marquardt epoch in Chromium); there a packed, register-blocked
//! kernel with wasm SIMD intrinsics (`simd`) does the work.

#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
use nalgebra::{Dyn, MatrixView, MatrixViewMut};

/// A read-only `rows x cols` matrix: entry `(i, j)` at `data[i * rs + j * cs]`.
#[derive(Debug, Clone, Copy)]
pub struct Mat<'a> {
    /// The entries (at least up to the last one addressed).
    pub data: &'a [f64],
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// Distance between rows.
    pub rs: usize,
    /// Distance between columns.
    pub cs: usize,
}

/// A writable `rows x cols` matrix laid out as [`Mat`].
#[derive(Debug)]
pub struct MatMut<'a> {
    /// The entries.
    pub data: &'a mut [f64],
    /// Rows.
    pub rows: usize,
    /// Columns.
    pub cols: usize,
    /// Distance between rows.
    pub rs: usize,
    /// Distance between columns.
    pub cs: usize,
}

impl<'a> Mat<'a> {
    /// Column-major `rows x cols` (columns contiguous).
    pub fn col_major(data: &'a [f64], rows: usize, cols: usize) -> Self {
        Self {
            data,
            rows,
            cols,
            rs: 1,
            cs: rows,
        }
    }

    /// Row-major `rows x cols` (rows contiguous).
    pub fn row_major(data: &'a [f64], rows: usize, cols: usize) -> Self {
        Self {
            data,
            rows,
            cols,
            rs: cols,
            cs: 1,
        }
    }

    /// The transpose (no copy).
    pub fn t(self) -> Self {
        Self {
            rows: self.cols,
            cols: self.rows,
            rs: self.cs,
            cs: self.rs,
            ..self
        }
    }

    #[inline]
    fn at(&self, i: usize, j: usize) -> f64 {
        self.data[i * self.rs + j * self.cs]
    }
}

impl<'a> MatMut<'a> {
    /// Column-major `rows x cols`.
    pub fn col_major(data: &'a mut [f64], rows: usize, cols: usize) -> Self {
        Self {
            data,
            rows,
            cols,
            rs: 1,
            cs: rows,
        }
    }

    /// Row-major `rows x cols`.
    pub fn row_major(data: &'a mut [f64], rows: usize, cols: usize) -> Self {
        Self {
            data,
            rows,
            cols,
            rs: cols,
            cs: 1,
        }
    }
}

/// Scratch space of [`gemm`] (the packed blocks of the SIMD build; nothing
/// elsewhere), owned by the caller and reused, so a product allocates only
/// when it is larger than every one before.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    simd: simd::Packed,
}

/// `C = alpha A B + beta C` (`C` is not read when `beta` is 0). The shapes
/// must agree (`A: m x k`, `B: k x n`, `C: m x n`); the callers build them so.
pub fn gemm(alpha: f64, a: Mat, b: Mat, beta: f64, c: &mut MatMut, scratch: &mut Scratch) {
    debug_assert!(a.rows == c.rows && b.cols == c.cols && a.cols == b.rows);
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    {
        simd::gemm(alpha, a, b, beta, c, &mut scratch.simd);
    }
    #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
    {
        let _ = scratch;
        if a.rows > 5 && a.cols > 5 && b.cols > 5 {
            let mut cv = MatrixViewMut::<f64, Dyn, Dyn, Dyn, Dyn>::from_slice_with_strides_generic(
                c.data,
                Dyn(c.rows),
                Dyn(c.cols),
                Dyn(c.rs),
                Dyn(c.cs),
            );
            cv.gemm(alpha, &view(a), &view(b), beta);
        } else {
            naive(alpha, a, b, beta, c);
        }
    }
}

/// `m` as a nalgebra view.
#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
fn view(m: Mat<'_>) -> MatrixView<'_, f64, Dyn, Dyn, Dyn, Dyn> {
    MatrixView::from_slice_with_strides_generic(
        m.data,
        Dyn(m.rows),
        Dyn(m.cols),
        Dyn(m.rs),
        Dyn(m.cs),
    )
}

/// The textbook triple loop.
#[cfg_attr(
    all(target_arch = "wasm32", target_feature = "simd128"),
    allow(dead_code)
)]
fn naive(alpha: f64, a: Mat, b: Mat, beta: f64, c: &mut MatMut) {
    for i in 0..c.rows {
        for j in 0..c.cols {
            let s: f64 = (0..a.cols).map(|p| a.at(i, p) * b.at(p, j)).sum();
            let cij = &mut c.data[i * c.rs + j * c.cs];
            *cij = if beta == 0.0 {
                alpha * s
            } else {
                alpha * s + beta * *cij
            };
        }
    }
}

#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
mod simd;
