//! The product of [`super::gemm`] with wasm `simd128` intrinsics (two
//! `f64` per `v128`, no fused multiply-add), blocked as in GotoBLAS:
//! blocks of `B` (`KC x NC`) and of `A` (`MC x KC`) are packed into the
//! caller's scratch, so the 4 x 4 micro-kernel reads both from contiguous
//! memory, and its 16 sums stay in eight registers while `KC` products
//! stream by. Packing costs `O(m k + k n)` against the kernel's `m n k`.
//! The blocks are sized for a 32 KB L1 and a 512 KB L2: an `A` panel
//! (`KC x 4`, 4 KB) and a `B` panel (`KC x 4`, 4 KB) per micro-kernel, the
//! `A` block (128 KB) reused across the `B` block's columns.

use core::arch::wasm32::*;

use super::{Mat, MatMut};

/// Rows of a micro-tile (two `v128`).
const MR: usize = 4;
/// Columns of a micro-tile.
const NR: usize = 4;
/// Depth of a block.
const KC: usize = 128;
/// Rows of an `A` block.
const MC: usize = 128;
/// Columns of a `B` block.
const NC: usize = 512;

/// The packed blocks: `A` as pairs of `v128` (rows 0-1 and 2-3 of a
/// panel) per depth, `B` as `NR` values per depth, each in both lanes.
#[derive(Debug, Clone, Default)]
pub(super) struct Packed {
    a: Vec<[v128; 2]>,
    b: Vec<[v128; NR]>,
}

pub(super) fn gemm(alpha: f64, a: Mat, b: Mat, beta: f64, c: &mut MatMut, packed: &mut Packed) {
    if c.cols > c.rows {
        // Packing B (each value splat) costs more per entry than packing
        // A, so B gets the smaller side: C^T = B^T A^T.
        let mut ct = MatMut {
            data: &mut *c.data,
            rows: c.cols,
            cols: c.rows,
            rs: c.cs,
            cs: c.rs,
        };
        return blocked(alpha, b.t(), a.t(), beta, &mut ct, packed);
    }
    blocked(alpha, a, b, beta, c, packed)
}

fn blocked(alpha: f64, a: Mat, b: Mat, beta: f64, c: &mut MatMut, packed: &mut Packed) {
    let (m, n, k) = (c.rows, c.cols, a.cols);
    if beta != 1.0 {
        for j in 0..n {
            for i in 0..m {
                let cij = &mut c.data[i * c.rs + j * c.cs];
                *cij = if beta == 0.0 { 0.0 } else { beta * *cij };
            }
        }
    }
    if m == 0 || n == 0 || k == 0 || alpha == 0.0 {
        return;
    }
    let z = f64x2_splat(0.0);
    let a_len = MC.div_ceil(MR) * KC;
    let b_len = NC.div_ceil(NR) * KC;
    if packed.a.len() < a_len {
        packed.a.resize(a_len, [z; 2]);
    }
    if packed.b.len() < b_len {
        packed.b.resize(b_len, [z; NR]);
    }
    for jc in (0..n).step_by(NC) {
        let nc = NC.min(n - jc);
        for pc in (0..k).step_by(KC) {
            let kc = KC.min(k - pc);
            pack_b(&b, pc, kc, jc, nc, &mut packed.b);
            for ic in (0..m).step_by(MC) {
                let mc = MC.min(m - ic);
                pack_a(&a, ic, mc, pc, kc, &mut packed.a);
                for jr in (0..nc).step_by(NR) {
                    let bp = &packed.b[(jr / NR) * KC..][..kc];
                    for ir in (0..mc).step_by(MR) {
                        let ap = &packed.a[(ir / MR) * KC..][..kc];
                        let acc = kernel(ap, bp);
                        store(
                            alpha,
                            &acc,
                            c,
                            ic + ir,
                            jc + jr,
                            MR.min(mc - ir),
                            NR.min(nc - jr),
                        );
                    }
                }
            }
        }
    }
}

/// `B[pc.., jc..]` (`kc x nc`) into panels of `NR` columns, each `kc` rows
/// of `NR` values (each splat into a `v128`), zero beyond the matrix.
fn pack_b(b: &Mat, pc: usize, kc: usize, jc: usize, nc: usize, out: &mut [[v128; NR]]) {
    for (panel, jr) in (0..nc).step_by(NR).enumerate() {
        let dst = &mut out[panel * KC..][..kc];
        for (p, row) in dst.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = f64x2_splat(if jr + j < nc {
                    b.at(pc + p, jc + jr + j)
                } else {
                    0.0
                });
            }
        }
    }
}

/// `A[ic.., pc..]` (`mc x kc`) into panels of `MR` rows, each `kc` pairs of
/// `v128` (rows 0-1 and 2-3 of the panel), zero beyond the matrix.
fn pack_a(a: &Mat, ic: usize, mc: usize, pc: usize, kc: usize, out: &mut [[v128; 2]]) {
    for (panel, ir) in (0..mc).step_by(MR).enumerate() {
        let dst = &mut out[panel * KC..][..kc];
        let row = |i: usize, p: usize| {
            if ir + i < mc {
                a.at(ic + ir + i, pc + p)
            } else {
                0.0
            }
        };
        for (p, pair) in dst.iter_mut().enumerate() {
            *pair = [f64x2(row(0, p), row(1, p)), f64x2(row(2, p), row(3, p))];
        }
    }
}

/// The 4 x 4 tile `sum_p A[.., p] B[p, ..]`: `acc[2 j]` holds rows 0-1 of
/// column `j`, `acc[2 j + 1]` rows 2-3. The panels are slices of arrays,
/// so the loop needs no bounds check.
#[inline(always)]
fn kernel(a: &[[v128; 2]], b: &[[v128; NR]]) -> [v128; 8] {
    let z = f64x2_splat(0.0);
    let (mut c0, mut c1, mut c2, mut c3) = (z, z, z, z);
    let (mut c4, mut c5, mut c6, mut c7) = (z, z, z, z);
    for (&[a0, a1], &[b0, b1, b2, b3]) in a.iter().zip(b) {
        c0 = f64x2_add(c0, f64x2_mul(a0, b0));
        c1 = f64x2_add(c1, f64x2_mul(a1, b0));
        c2 = f64x2_add(c2, f64x2_mul(a0, b1));
        c3 = f64x2_add(c3, f64x2_mul(a1, b1));
        c4 = f64x2_add(c4, f64x2_mul(a0, b2));
        c5 = f64x2_add(c5, f64x2_mul(a1, b2));
        c6 = f64x2_add(c6, f64x2_mul(a0, b3));
        c7 = f64x2_add(c7, f64x2_mul(a1, b3));
    }
    [c0, c1, c2, c3, c4, c5, c6, c7]
}

/// `C[i0.., j0..] += alpha acc` for the `rows x cols` entries inside `C`.
#[inline(always)]
fn store(
    alpha: f64,
    acc: &[v128; 8],
    c: &mut MatMut,
    i0: usize,
    j0: usize,
    rows: usize,
    cols: usize,
) {
    let mut j = 0;
    while j < cols {
        let lanes = [
            f64x2_extract_lane::<0>(acc[2 * j]),
            f64x2_extract_lane::<1>(acc[2 * j]),
            f64x2_extract_lane::<0>(acc[2 * j + 1]),
            f64x2_extract_lane::<1>(acc[2 * j + 1]),
        ];
        let base = i0 * c.rs + (j0 + j) * c.cs;
        if c.rs == 1 && rows == MR {
            let col = &mut c.data[base..base + MR];
            col[0] += alpha * lanes[0];
            col[1] += alpha * lanes[1];
            col[2] += alpha * lanes[2];
            col[3] += alpha * lanes[3];
        } else if c.cs == 1 && rows == MR {
            // A transposed product: the tile's columns run along C's rows.
            let rs = c.rs;
            let col = &mut c.data[base..base + 3 * rs + 1];
            col[0] += alpha * lanes[0];
            col[rs] += alpha * lanes[1];
            col[2 * rs] += alpha * lanes[2];
            col[3 * rs] += alpha * lanes[3];
        } else {
            let mut i = 0;
            while i < rows {
                c.data[base + i * c.rs] += alpha * lanes[i];
                i += 1;
            }
        }
        j += 1;
    }
}
