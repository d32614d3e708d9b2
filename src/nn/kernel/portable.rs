//! The portable forward pass: plain Rust over blocks of neurons, which the
//! compiler vectorises; compiled once for the target and, on x86-64, once
//! more with AVX2 + FMA (`x86.rs`).

use super::{blocks, Kernel, LANES};
use crate::nn::activation::{madd, tansig_with};

pub(super) fn forward_portable(k: &Kernel, x: &[f64], y: &mut [f64], a: &mut [f64], b: &mut [f64]) {
    // Where FMA is part of the compile-time target (e.g. -C target-cpu=native)
    // use it; otherwise a separate multiply and add (a software fma would be slow).
    forward_body::<{ cfg!(target_feature = "fma") }>(k, x, y, a, b)
}

/// The forward pass proper, inlined into each instruction-set build.
#[inline(always)]
pub(super) fn forward_body<const FMA: bool>(
    k: &Kernel,
    x: &[f64],
    y: &mut [f64],
    a: &mut [f64],
    b: &mut [f64],
) {
    let n_in = k.n_in.min(x.len());
    a[..n_in].copy_from_slice(&x[..n_in]);
    let (mut cur, mut next) = (a, b);
    for layer in &k.layers {
        let input = &cur[..layer.inputs];
        let z = &mut next[..layer.width];
        let (mut o0, mut w0) = (0, 0);
        for bs in blocks(layer.width) {
            let w = &layer.w[w0..w0 + bs * layer.inputs];
            let (zb, bias) = (&mut z[o0..o0 + bs], &layer.b[o0..o0 + bs]);
            match bs {
                16 => block::<16, FMA>(input, w, bias, zb),
                8 => block::<8, FMA>(input, w, bias, zb),
                _ => block::<4, FMA>(input, w, bias, zb),
            }
            o0 += bs;
            w0 += bs * layer.inputs;
        }
        if layer.tansig {
            let (chunks, rest) = z.as_chunks_mut::<LANES>();
            for c in chunks {
                for v in c.iter_mut() {
                    *v = tansig_with::<FMA>(*v);
                }
            }
            for v in rest {
                *v = tansig_with::<FMA>(*v);
            }
        }
        std::mem::swap(&mut cur, &mut next);
    }
    for (yi, ci) in y.iter_mut().zip(&cur[..k.n_out]) {
        *yi = *ci;
    }
}

/// `B` neurons: `z[o] = b[o] + sum_j x_j w[j][o]`, the sums kept in
/// registers while the inputs stream by. Even and odd inputs go to two sets
/// of accumulators, so twice as many independent add chains overlap.
#[inline(always)]
fn block<const B: usize, const FMA: bool>(input: &[f64], w: &[f64], bias: &[f64], z: &mut [f64]) {
    let mut even = [0.0; B];
    let mut odd = [0.0; B];
    even.copy_from_slice(&bias[..B]);
    let (rows, _) = w.as_chunks::<B>();
    let (pairs, _) = rows.as_chunks::<2>();
    let (xs, _) = input.as_chunks::<2>();
    for (x, [r0, r1]) in xs.iter().zip(pairs) {
        for l in 0..B {
            even[l] = madd::<FMA>(x[0], r0[l], even[l]);
            odd[l] = madd::<FMA>(x[1], r1[l], odd[l]);
        }
    }
    if input.len() % 2 == 1 {
        if let (Some(x), Some(r)) = (input.last(), rows.get(input.len() - 1)) {
            for l in 0..B {
                even[l] = madd::<FMA>(*x, r[l], even[l]);
            }
        }
    }
    for (zl, (e, o)) in z[..B].iter_mut().zip(even.iter().zip(&odd)) {
        *zl = e + o;
    }
}
