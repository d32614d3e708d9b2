//! The forward pass written with wasm `simd128` intrinsics (two `f64` per
//! `v128`). The page is built at `opt-level = "s"` to stay small (level 3
//! costs 13 KB gzipped), and at that level LLVM vectorises nothing, so the
//! hot kernel says what it wants. One set of accumulators per block
//! (Chromium: 10% faster than the portable kernel's two, which spill), so
//! sums run in another order than there: results agree to rounding.
use core::arch::wasm32::*;

use super::{Kernel, Layer as Plain, LANES, STACK_WIDTH, WIDE_STACK_WIDTH};
use crate::nn::activation::TANSIG_CLAMP;

const PAIRS: usize = STACK_WIDTH / 2;
const WIDE_PAIRS: usize = WIDE_STACK_WIDTH / 2;

/// A layer's weights and biases as `v128` pairs of neurons, in the
/// portable layer's block order.
#[derive(Debug, Clone)]
pub(super) struct Layer {
    inputs: usize,
    width: usize,
    w: Vec<v128>,
    b: Vec<v128>,
    tansig: bool,
}

/// Equal when every lane is (as `f64`s compare).
impl PartialEq for Layer {
    fn eq(&self, other: &Self) -> bool {
        let lanes = |v: &[v128]| -> Vec<f64> {
            v.iter()
                .flat_map(|x| [f64x2_extract_lane::<0>(*x), f64x2_extract_lane::<1>(*x)])
                .collect()
        };
        self.inputs == other.inputs
            && self.width == other.width
            && self.tansig == other.tansig
            && lanes(&self.w) == lanes(&other.w)
            && lanes(&self.b) == lanes(&other.b)
    }
}

impl Layer {
    pub(super) fn new(p: &Plain) -> Self {
        let pairs =
            |v: &[f64]| -> Vec<v128> { v.chunks_exact(2).map(|c| f64x2(c[0], c[1])).collect() };
        Self {
            inputs: p.inputs,
            width: p.width,
            w: pairs(&p.w),
            b: pairs(&p.b),
            tansig: p.tansig,
        }
    }
}

/// The forward pass: on the stack up to [`WIDE_STACK_WIDTH`] neurons, through
/// a heap buffer per call beyond (so the SIMD build needs no portable
/// kernel: 1 KB of the page's gzipped module).
pub(super) fn forward(k: &Kernel, x: &[f64], y: &mut [f64]) {
    let zero = f64x2_splat(0.0);
    if k.widest <= STACK_WIDTH {
        forward_in(k, x, y, &mut [zero; PAIRS], &mut [zero; PAIRS]);
    } else if k.widest <= WIDE_STACK_WIDTH {
        forward_in(k, x, y, &mut [zero; WIDE_PAIRS], &mut [zero; WIDE_PAIRS]);
    } else {
        let pairs = k.widest.div_ceil(2);
        forward_in(k, x, y, &mut vec![zero; pairs], &mut vec![zero; pairs]);
    }
}

fn forward_in(k: &Kernel, x: &[f64], y: &mut [f64], a: &mut [v128], b: &mut [v128]) {
    // The raw inputs, two per v128 (the rest zero).
    for (i, xi) in x.iter().take(k.n_in).enumerate() {
        a[i / 2] = if i % 2 == 0 {
            f64x2_replace_lane::<0>(a[i / 2], *xi)
        } else {
            f64x2_replace_lane::<1>(a[i / 2], *xi)
        };
    }
    let (mut cur, mut next) = (a, b);
    for layer in &k.simd {
        let z = &mut next[..layer.width / 2];
        let (mut o0, mut w0) = (0, 0);
        for bs in super::blocks(layer.width) {
            let (p0, np) = (o0 / 2, bs / 2);
            let w = &layer.w[w0..w0 + np * layer.inputs];
            let bias = &layer.b[p0..p0 + np];
            let zb = &mut z[p0..p0 + np];
            match bs {
                16 => block8(&cur[..], layer.inputs, w, bias, zb),
                8 => block4(&cur[..], layer.inputs, w, bias, zb),
                _ => block2(&cur[..], layer.inputs, w, bias, zb),
            }
            o0 += bs;
            w0 += np * layer.inputs;
        }
        if layer.tansig {
            for v in z.iter_mut() {
                *v = tansig2(*v);
            }
        }
        std::mem::swap(&mut cur, &mut next);
    }
    for (i, yi) in y.iter_mut().take(k.n_out).enumerate() {
        let v = cur[i / 2];
        *yi = if i % 2 == 0 {
            f64x2_extract_lane::<0>(v)
        } else {
            f64x2_extract_lane::<1>(v)
        };
    }
    debug_assert_eq!(LANES % 2, 0);
}

/// `P` pairs of neurons accumulated over every input. Written out per
/// block size (a macro, not a loop over the pairs): at `opt-level = "s"`
/// LLVM neither unrolls the loop nor keeps an accumulator array in
/// registers.
macro_rules! block {
    ($name:ident, $p:literal, $($l:literal)+) => {
        #[inline(always)]
        fn $name(input: &[v128], inputs: usize, w: &[v128], bias: &[v128], z: &mut [v128]) {
            let mut acc = [f64x2_splat(0.0); $p];
            acc.copy_from_slice(&bias[..$p]);
            let (rows, _) = w.as_chunks::<$p>();
            let (pairs, _) = rows.as_chunks::<2>();
            for (xv, [r0, r1]) in input.iter().zip(pairs).take(inputs / 2) {
                let x0 = i64x2_shuffle::<0, 0>(*xv, *xv);
                let x1 = i64x2_shuffle::<1, 1>(*xv, *xv);
                $( acc[$l] = f64x2_add(f64x2_mul(x0, r0[$l]), acc[$l]); )+
                $( acc[$l] = f64x2_add(f64x2_mul(x1, r1[$l]), acc[$l]); )+
            }
            if inputs % 2 == 1 {
                if let (Some(xv), Some(r)) = (input.get(inputs / 2), rows.get(inputs - 1)) {
                    let x0 = i64x2_shuffle::<0, 0>(*xv, *xv);
                    $( acc[$l] = f64x2_add(f64x2_mul(x0, r[$l]), acc[$l]); )+
                }
            }
            z[..$p].copy_from_slice(&acc);
        }
    };
}
block!(block8, 8, 0 1 2 3 4 5 6 7);
block!(block4, 4, 0 1 2 3);
block!(block2, 2, 0 1);

/// [`crate::nn::activation::tansig`] on two lanes.
#[inline(always)]
#[allow(clippy::excessive_precision)] // Cephes' published digits
fn tansig2(z: v128) -> v128 {
    let c = f64x2_splat;
    let a = f64x2_abs(z);
    // Compare-and-select: pmin(a, m) is `m < a ? m : a`, so NaN stays NaN.
    let a = f64x2_pmin(a, c(TANSIG_CLAMP));
    let x = f64x2_mul(c(-2.0), a);
    let kd = f64x2_add(
        f64x2_mul(x, c(std::f64::consts::LOG2_E)),
        c(6_755_399_441_055_744.0),
    );
    let k = f64x2_sub(kd, c(6_755_399_441_055_744.0));
    let r = f64x2_sub(x, f64x2_mul(k, c(6.931_471_803_691_238_164_90e-1)));
    let r = f64x2_sub(r, f64x2_mul(k, c(1.908_214_929_270_587_700_02e-10)));
    let rr = f64x2_mul(r, r);
    let p = f64x2_add(
        f64x2_mul(c(1.261_771_930_748_105_908_78e-4), rr),
        c(3.029_944_077_074_419_613_00e-2),
    );
    let p = f64x2_add(f64x2_mul(p, rr), c(9.999_999_999_999_999_999_10e-1));
    let p = f64x2_mul(r, p);
    let q = f64x2_add(
        f64x2_mul(c(3.001_985_051_386_644_550_42e-6), rr),
        c(2.524_483_403_496_841_041_92e-3),
    );
    let q = f64x2_add(f64x2_mul(q, rr), c(2.272_655_482_081_550_287_66e-1));
    let q = f64x2_add(f64x2_mul(q, rr), c(2.000_000_000_000_000_000_09e0));
    let scale = i64x2_shl(i64x2_add(kd, i64x2_splat(1023)), 52);
    let (n, d) = (f64x2_add(q, p), f64x2_sub(q, p));
    let sn = f64x2_mul(scale, n);
    let t = f64x2_div(f64x2_sub(d, sn), f64x2_add(d, sn));
    // copysign(t, z)
    v128_bitselect(z, t, u64x2_splat(1 << 63))
}
