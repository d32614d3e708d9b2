//! The single-precision forward pass ([`Precision::F32`](crate::nn::Precision)):
//! the `f64` kernel's folded, padded, blocked layers rounded to `f32`.
//!
//! Every neuron's sum runs over its inputs in order, one rounded multiply
//! and one rounded add per input (never fused), from its bias; `tansig` is
//! [`tansig32`]. That fixes every rounding, so the portable pass here (the
//! command line, the page's baseline build) and the wasm `f32x4` pass
//! (`single/wasm.rs`, the page's SIMD build) give the same bits: a run the
//! page makes in `f32` replays exactly with `--precision f32` (tested on
//! both in `tests/networks/`). One accumulator per neuron costs the
//! portable pass the overlap of the `f64` kernel's two, but LLVM still
//! vectorises it over the neurons of a block (16 per block, 4 per SSE
//! register).

// Its wasm `f32x4` pass, a child of this module (it reads the kernel's
// layers).
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
mod wasm;

use super::Layer;
#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
use super::{blocks, STACK_WIDTH, WIDE_STACK_WIDTH};
#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
use crate::nn::activation::tansig32;

/// A layer in `f32`, in the `f64` layer's block order.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Layer32 {
    pub(super) inputs: usize,
    pub(super) width: usize,
    pub(super) w: Vec<f32>,
    pub(super) b: Vec<f32>,
    pub(super) tansig: bool,
}

impl Layer32 {
    fn new(l: &Layer) -> Self {
        let round = |v: &[f64]| v.iter().map(|&x| x as f32).collect();
        Self {
            inputs: l.inputs,
            width: l.width,
            w: round(&l.w),
            b: round(&l.b),
            tansig: l.tansig,
        }
    }
}

/// A network's `f32` kernel.
#[derive(Debug, Clone)]
pub(super) struct Kernel32 {
    pub(super) n_in: usize,
    pub(super) n_out: usize,
    pub(super) widest: usize,
    pub(super) layers: Vec<Layer32>,
    /// The layers as `f32x4` quads of neurons, for the `simd128` build.
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    pub(super) simd: Vec<wasm::Layer>,
}

/// Equal when the `f32` layers are (the quads are made from them).
impl PartialEq for Kernel32 {
    fn eq(&self, other: &Self) -> bool {
        self.n_in == other.n_in && self.n_out == other.n_out && self.layers == other.layers
    }
}

impl Kernel32 {
    pub(super) fn new(n_in: usize, n_out: usize, widest: usize, layers: &[Layer]) -> Self {
        let layers: Vec<Layer32> = layers.iter().map(Layer32::new).collect();
        Self {
            n_in,
            n_out,
            widest,
            #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
            simd: layers.iter().map(wasm::Layer::new).collect(),
            layers,
        }
    }

    /// The forward pass, on the stack up to `WIDE_STACK_WIDTH` neurons.
    #[inline]
    pub(super) fn forward(&self, x: &[f64], y: &mut [f64]) {
        #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
        wasm::forward(self, x, y);
        #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
        if self.widest <= STACK_WIDTH {
            forward_in(self, x, y, &mut [0.0; STACK_WIDTH], &mut [0.0; STACK_WIDTH]);
        } else if self.widest <= WIDE_STACK_WIDTH {
            forward_in(
                self,
                x,
                y,
                &mut [0.0; WIDE_STACK_WIDTH],
                &mut [0.0; WIDE_STACK_WIDTH],
            );
        } else {
            forward_in(
                self,
                x,
                y,
                &mut vec![0.0; self.widest],
                &mut vec![0.0; self.widest],
            );
        }
    }
}

#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
fn forward_in(k: &Kernel32, x: &[f64], y: &mut [f64], a: &mut [f32], b: &mut [f32]) {
    let n_in = k.n_in.min(x.len());
    for (ai, xi) in a.iter_mut().zip(&x[..n_in]) {
        *ai = *xi as f32;
    }
    let (mut cur, mut next) = (a, b);
    for layer in &k.layers {
        let input = &cur[..layer.inputs];
        let z = &mut next[..layer.width];
        let (mut o0, mut w0) = (0, 0);
        for bs in blocks(layer.width) {
            let w = &layer.w[w0..w0 + bs * layer.inputs];
            let (zb, bias) = (&mut z[o0..o0 + bs], &layer.b[o0..o0 + bs]);
            match bs {
                16 => block::<16>(input, w, bias, zb),
                8 => block::<8>(input, w, bias, zb),
                _ => block::<4>(input, w, bias, zb),
            }
            o0 += bs;
            w0 += bs * layer.inputs;
        }
        if layer.tansig {
            for v in z.iter_mut() {
                *v = tansig32(*v);
            }
        }
        std::mem::swap(&mut cur, &mut next);
    }
    for (yi, ci) in y.iter_mut().zip(&cur[..k.n_out]) {
        *yi = f64::from(*ci);
    }
}

/// `B` neurons: `z[o] = b[o] + x_0 w[0][o] + x_1 w[1][o] + ...`, in that order.
#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
#[inline(always)]
fn block<const B: usize>(input: &[f32], w: &[f32], bias: &[f32], z: &mut [f32]) {
    let mut acc = [0.0f32; B];
    acc.copy_from_slice(&bias[..B]);
    let (rows, _) = w.as_chunks::<B>();
    for (x, r) in input.iter().zip(rows) {
        for l in 0..B {
            acc[l] += x * r[l];
        }
    }
    z[..B].copy_from_slice(&acc);
}
