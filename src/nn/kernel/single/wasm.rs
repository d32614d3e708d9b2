//! The single-precision forward pass written with wasm `simd128`
//! intrinsics: four `f32` neurons per `v128`, the same roundings in the
//! same order as the portable pass of `single.rs` (each neuron's sum over
//! its inputs in order, multiply then add), so both give the same bits.
use core::arch::wasm32::*;

use super::super::{STACK_WIDTH, WIDE_STACK_WIDTH};
use super::{Kernel32, Layer32};
use crate::nn::activation::{TANSIG32_CLAMP, TANSIG32_P, TANSIG32_Q};

const QUADS: usize = STACK_WIDTH / 4;
const WIDE_QUADS: usize = WIDE_STACK_WIDTH / 4;

/// A layer's weights and biases as quads of neurons, in block order.
#[derive(Debug, Clone)]
pub(in crate::nn::kernel) struct Layer {
    inputs: usize,
    width: usize,
    w: Vec<v128>,
    b: Vec<v128>,
    tansig: bool,
}

impl Layer {
    pub(super) fn new(p: &Layer32) -> Self {
        let quads = |v: &[f32]| -> Vec<v128> {
            v.chunks_exact(4)
                .map(|c| f32x4(c[0], c[1], c[2], c[3]))
                .collect()
        };
        Self {
            inputs: p.inputs,
            width: p.width,
            w: quads(&p.w),
            b: quads(&p.b),
            tansig: p.tansig,
        }
    }
}

/// The forward pass: on the stack up to [`WIDE_STACK_WIDTH`] neurons,
/// through a heap buffer per call beyond.
pub(super) fn forward(k: &Kernel32, x: &[f64], y: &mut [f64]) {
    let zero = f32x4_splat(0.0);
    if k.widest <= STACK_WIDTH {
        forward_in(k, x, y, &mut [zero; QUADS], &mut [zero; QUADS]);
    } else if k.widest <= WIDE_STACK_WIDTH {
        forward_in(k, x, y, &mut [zero; WIDE_QUADS], &mut [zero; WIDE_QUADS]);
    } else {
        let quads = k.widest.div_ceil(4);
        forward_in(k, x, y, &mut vec![zero; quads], &mut vec![zero; quads]);
    }
}

fn forward_in(k: &Kernel32, x: &[f64], y: &mut [f64], a: &mut [v128], b: &mut [v128]) {
    // The raw inputs rounded to f32, four per v128 (the rest zero).
    for (i, xi) in x.iter().take(k.n_in).enumerate() {
        let (q, v) = (i / 4, *xi as f32);
        a[q] = match i % 4 {
            0 => f32x4_replace_lane::<0>(a[q], v),
            1 => f32x4_replace_lane::<1>(a[q], v),
            2 => f32x4_replace_lane::<2>(a[q], v),
            _ => f32x4_replace_lane::<3>(a[q], v),
        };
    }
    let (mut cur, mut next) = (a, b);
    for layer in &k.simd {
        let z = &mut next[..layer.width / 4];
        let (mut o0, mut w0) = (0, 0);
        for bs in super::super::blocks(layer.width) {
            let (q0, nq) = (o0 / 4, bs / 4);
            let w = &layer.w[w0..w0 + nq * layer.inputs];
            let bias = &layer.b[q0..q0 + nq];
            let zb = &mut z[q0..q0 + nq];
            match bs {
                16 => block4(&cur[..], layer.inputs, w, bias, zb),
                8 => block2(&cur[..], layer.inputs, w, bias, zb),
                _ => block1(&cur[..], layer.inputs, w, bias, zb),
            }
            o0 += bs;
            w0 += nq * layer.inputs;
        }
        if layer.tansig {
            for v in z.iter_mut() {
                *v = tansig4(*v);
            }
        }
        std::mem::swap(&mut cur, &mut next);
    }
    for (i, yi) in y.iter_mut().take(k.n_out).enumerate() {
        let v = cur[i / 4];
        let lane = match i % 4 {
            0 => f32x4_extract_lane::<0>(v),
            1 => f32x4_extract_lane::<1>(v),
            2 => f32x4_extract_lane::<2>(v),
            _ => f32x4_extract_lane::<3>(v),
        };
        *yi = f64::from(lane);
    }
}

/// `P` quads of neurons accumulated over every input, in input order.
/// Written out per block size (a macro, not a loop over the quads): at
/// `opt-level = "s"` LLVM neither unrolls the loop nor keeps an
/// accumulator array in registers.
macro_rules! block {
    ($name:ident, $p:literal, $($l:literal)+) => {
        #[inline(always)]
        fn $name(input: &[v128], inputs: usize, w: &[v128], bias: &[v128], z: &mut [v128]) {
            let mut acc = [f32x4_splat(0.0); $p];
            acc.copy_from_slice(&bias[..$p]);
            let (rows, _) = w.as_chunks::<$p>();
            let (fours, _) = rows.as_chunks::<4>();
            for (xv, [r0, r1, r2, r3]) in input.iter().zip(fours).take(inputs / 4) {
                let x0 = i32x4_shuffle::<0, 0, 0, 0>(*xv, *xv);
                let x1 = i32x4_shuffle::<1, 1, 1, 1>(*xv, *xv);
                let x2 = i32x4_shuffle::<2, 2, 2, 2>(*xv, *xv);
                let x3 = i32x4_shuffle::<3, 3, 3, 3>(*xv, *xv);
                $( acc[$l] = f32x4_add(f32x4_mul(x0, r0[$l]), acc[$l]); )+
                $( acc[$l] = f32x4_add(f32x4_mul(x1, r1[$l]), acc[$l]); )+
                $( acc[$l] = f32x4_add(f32x4_mul(x2, r2[$l]), acc[$l]); )+
                $( acc[$l] = f32x4_add(f32x4_mul(x3, r3[$l]), acc[$l]); )+
            }
            for j in inputs / 4 * 4..inputs {
                if let (Some(xv), Some(r)) = (input.get(j / 4), rows.get(j)) {
                    let x = match j % 4 {
                        0 => i32x4_shuffle::<0, 0, 0, 0>(*xv, *xv),
                        1 => i32x4_shuffle::<1, 1, 1, 1>(*xv, *xv),
                        _ => i32x4_shuffle::<2, 2, 2, 2>(*xv, *xv),
                    };
                    $( acc[$l] = f32x4_add(f32x4_mul(x, r[$l]), acc[$l]); )+
                }
            }
            z[..$p].copy_from_slice(&acc);
        }
    };
}
block!(block4, 4, 0 1 2 3);
block!(block2, 2, 0 1);
block!(block1, 1, 0);

/// [`crate::nn::activation::tansig32`] on four lanes, the same steps.
#[inline(always)]
fn tansig4(z: v128) -> v128 {
    let c = f32x4_splat;
    // Compare-and-select: pmin(a, m) is `m < a ? m : a`, as the scalar's.
    let a = f32x4_pmin(f32x4_abs(z), c(TANSIG32_CLAMP));
    let x2 = f32x4_mul(a, a);
    let mut p = c(TANSIG32_P[0]);
    for k in &TANSIG32_P[1..] {
        p = f32x4_add(f32x4_mul(p, x2), c(*k));
    }
    let p = f32x4_mul(p, a);
    let mut q = c(TANSIG32_Q[0]);
    for k in &TANSIG32_Q[1..] {
        q = f32x4_add(f32x4_mul(q, x2), c(*k));
    }
    // copysign(p / q, z)
    v128_bitselect(z, f32x4_div(p, q), u32x4_splat(1 << 31))
}
