//! The run-time form of a trained [`Mlp`]: the forward pass the planner calls
//! four times per RK4 step, built once when the weights load.
//!
//! What is done at load time so that the hot loop does only multiply-adds
//! and one vectorisable `tansig` per neuron:
//! - `mapminmax` is folded into the first layer (input scaling) and the last
//!   layer (output scaling), so the kernel maps raw inputs to raw outputs;
//! - every layer is stored input-major in blocks of 16, 8 or 4 neurons
//!   (`w[j][o0..o0 + B]` contiguous for each input `j`), its width padded with
//!   zero neurons to a multiple of [`LANES`]; a block's sums stay in
//!   registers while the inputs stream by, which vectorises over neurons
//!   with no horizontal sums;
//! - the hidden activations live in two stack buffers for layers up to
//!   [`STACK_WIDTH`] (padded) wide, or [`WIDE_STACK_WIDTH`] for the wide
//!   networks of the `reach` recipe: no allocation per call.
//!
//! On x86-64 the same code is also compiled for AVX2 + FMA and chosen at run
//! time when the CPU has them ([`Kernel::forward`], [`set_runtime_dispatch`]);
//! the page's SIMD build (wasm32 with `simd128`) runs a kernel written with
//! wasm SIMD intrinsics; everything else runs the portable build.
//!
//! One file per build: the layout and the dispatch here, the portable
//! forward pass (`portable.rs`, which the AVX2 build compiles again), the
//! AVX2 + FMA entry point (`x86.rs`: the crate's one `unsafe` block, to
//! audit in one place) and the wasm SIMD kernel (`wasm.rs`); the
//! activation is [`crate::nn::activation`].

#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
mod portable;
// The f32 kernels (a run's `precision: "f32"`): in every build.
mod single;
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
mod wasm;
#[cfg(all(target_arch = "x86_64", not(target_feature = "fma")))]
mod x86;

use crate::nn::mlp::{MapMinMax, Mlp};
use crate::nn::Precision;
#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
use portable::forward_portable;

/// Widths are padded to a multiple of this many neurons (four `f64` = one
/// AVX2 register, two SSE2 or wasm `simd128` registers).
pub const LANES: usize = 4;

/// Widest padded layer handled with the small stack buffers (the paper's
/// networks: zeroing them is part of every call's cost).
pub const STACK_WIDTH: usize = 64;

/// Widest padded layer handled with stack buffers at all (the 96-96 `Phi`
/// of the `reach` recipe, `docs/learning.md`); wider networks work through
/// a heap buffer per call. Measured with `redundant-ik bench --networks
/// reach`: the heap path made 8 allocations per RK4 step.
pub const WIDE_STACK_WIDTH: usize = 128;

#[derive(Debug, Clone, PartialEq)]
struct Layer {
    /// Real inputs.
    inputs: usize,
    /// Neurons, padded to a multiple of [`LANES`].
    width: usize,
    /// The weights in blocks of 16, 8 or 4 neurons: block `c` of `B` neurons
    /// starting at neuron `o0` holds `w[j][o0..o0 + B]` for `j = 0..inputs`,
    /// contiguous, zero in the padding.
    w: Vec<f64>,
    /// `width` biases, zero in the padding.
    b: Vec<f64>,
    /// `tansig` (hidden) or `purelin` (output).
    tansig: bool,
}

/// A network ready to evaluate: raw inputs to raw outputs.
#[derive(Debug, Clone, PartialEq)]
pub struct Kernel {
    n_in: usize,
    n_out: usize,
    layers: Vec<Layer>,
    widest: usize,
    /// The layers as wasm `v128` pairs, for the `simd128` build.
    #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
    simd: Vec<wasm::Layer>,
    /// The layers rounded to `f32`, when the kernel computes in `f32`.
    single: Option<single::Kernel32>,
}

fn pad(n: usize) -> usize {
    n.div_ceil(LANES) * LANES
}

/// Block sizes covering a padded width: as many 16s as fit, then 8, then 4.
fn blocks(width: usize) -> impl Iterator<Item = usize> {
    let mut left = width;
    std::iter::from_fn(move || {
        let b = [16, 8, 4].into_iter().find(|&b| b <= left)?;
        left -= b;
        Some(b)
    })
}

/// `mapminmax` as an affine map per entry, `scaled = g x + c`.
fn affine(map: &MapMinMax, i: usize) -> (f64, f64) {
    let (lo, hi) = (map.min[i], map.max[i]);
    if hi > lo {
        let g = 2.0 / (hi - lo);
        (g, -g * lo - 1.0)
    } else {
        (1.0, -lo)
    }
}

impl Kernel {
    /// Builds the kernel of a validated network.
    ///
    /// Folding: with the input map `x_s = g x + c`, the first layer
    /// `W x_s + b` becomes `(W diag g) x + (W c + b)`; with the output map
    /// `y = (z - c') / g'`, the last layer becomes `(W / g') a + (b - c') / g'`.
    /// Outputs move by rounding only (tested against [`Mlp::forward`]).
    pub fn new(mlp: &Mlp) -> Self {
        Self::build(mlp, Precision::F64)
    }

    /// Builds the kernel of a validated network, computing in `precision`
    /// (the layers folded in `f64` as in [`Kernel::new`], then rounded).
    pub fn with_precision(mlp: &Mlp, precision: Precision) -> Self {
        Self::build(mlp, precision)
    }

    fn build(mlp: &Mlp, precision: Precision) -> Self {
        let sizes = &mlp.sizes;
        let last = mlp.layers.len() - 1;
        let mut layers = Vec::with_capacity(mlp.layers.len());
        for (l, layer) in mlp.layers.iter().enumerate() {
            let (r, s) = (sizes[l], sizes[l + 1]);
            // Folded weights and biases, output-major as in the file.
            let mut w = layer.weights.clone();
            let mut b = layer.biases.clone();
            if l == 0 {
                for o in 0..s {
                    for j in 0..r {
                        let (g, c) = affine(&mlp.input_map, j);
                        b[o] += w[o * r + j] * c;
                        w[o * r + j] *= g;
                    }
                }
            }
            if l == last {
                for o in 0..s {
                    let (g, c) = affine(&mlp.output_map, o);
                    for j in 0..r {
                        w[o * r + j] /= g;
                    }
                    b[o] = (b[o] - c) / g;
                }
            }
            let width = pad(s);
            let mut blocked = Vec::with_capacity(r * width);
            let mut o0 = 0;
            for bs in blocks(width) {
                for j in 0..r {
                    for o in o0..o0 + bs {
                        blocked.push(if o < s { w[o * r + j] } else { 0.0 });
                    }
                }
                o0 += bs;
            }
            b.resize(width, 0.0);
            layers.push(Layer {
                inputs: r,
                width,
                w: blocked,
                b,
                tansig: l < last,
            });
        }
        let widest = layers
            .iter()
            .map(|l| l.width)
            .chain([pad(mlp.inputs())])
            .max()
            .unwrap_or(0);
        let (n_in, n_out) = (mlp.inputs(), mlp.outputs());
        Self {
            n_in,
            n_out,
            #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
            simd: layers.iter().map(wasm::Layer::new).collect(),
            single: (precision == Precision::F32)
                .then(|| single::Kernel32::new(n_in, n_out, widest, &layers)),
            layers,
            widest,
        }
    }

    /// The arithmetic of [`Kernel::forward`].
    pub fn precision(&self) -> Precision {
        if self.single.is_some() {
            return Precision::F32;
        }
        Precision::F64
    }

    /// Number of inputs.
    pub fn inputs(&self) -> usize {
        self.n_in
    }

    /// Number of outputs.
    pub fn outputs(&self) -> usize {
        self.n_out
    }

    /// Forward pass on raw values. Reads `min(x.len(), inputs)` inputs (the
    /// rest count as zero) and writes `min(y.len(), outputs)` outputs.
    /// Allocation-free for layers up to [`WIDE_STACK_WIDTH`] wide.
    #[inline]
    pub fn forward(&self, x: &[f64], y: &mut [f64]) {
        if let Some(single) = &self.single {
            return single.forward(x, y);
        }
        #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
        wasm::forward(self, x, y);
        #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
        self.forward_buffered(x, y);
    }

    /// The portable (and AVX2) forward pass, on the stack up to
    /// [`WIDE_STACK_WIDTH`] neurons, through a heap buffer per call beyond.
    #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
    #[inline]
    fn forward_buffered(&self, x: &[f64], y: &mut [f64]) {
        if self.widest <= STACK_WIDTH {
            let mut a = [0.0; STACK_WIDTH];
            let mut b = [0.0; STACK_WIDTH];
            self.dispatch(x, y, &mut a, &mut b);
        } else if self.widest <= WIDE_STACK_WIDTH {
            let mut a = [0.0; WIDE_STACK_WIDTH];
            let mut b = [0.0; WIDE_STACK_WIDTH];
            self.dispatch(x, y, &mut a, &mut b);
        } else {
            let mut a = vec![0.0; self.widest];
            let mut b = vec![0.0; self.widest];
            self.dispatch(x, y, &mut a, &mut b);
        }
    }

    #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
    #[inline]
    fn dispatch(&self, x: &[f64], y: &mut [f64], a: &mut [f64], b: &mut [f64]) {
        #[cfg(all(target_arch = "x86_64", not(target_feature = "fma")))]
        if x86::use_avx2_fma() {
            return x86::forward_avx2_fma(self, x, y, a, b);
        }
        forward_portable(self, x, y, a, b);
    }
}

/// Switches the run-time choice of the AVX2 + FMA kernels on x86-64 on (the
/// default) or off, so that the portable x86-64 baseline kernels can be
/// measured in the same binary (`redundant-ik bench --baseline-kernels`).
/// Returns whether the CPU has AVX2 and FMA at all. Elsewhere a no-op that
/// returns `false`.
pub fn set_runtime_dispatch(enabled: bool) -> bool {
    #[cfg(all(target_arch = "x86_64", not(target_feature = "fma")))]
    {
        x86::ALLOWED.store(enabled, std::sync::atomic::Ordering::Relaxed);
        x86::has_avx2_fma()
    }
    #[cfg(not(all(target_arch = "x86_64", not(target_feature = "fma"))))]
    {
        let _ = enabled;
        false
    }
}

/// Which kernels [`Kernel::forward`] runs here: `"avx2+fma"`, `"simd128"`,
/// `"fma"` (FMA in the compile-time target) or `"portable"`.
pub fn kernel_isa() -> &'static str {
    #[cfg(all(target_arch = "x86_64", not(target_feature = "fma")))]
    if x86::use_avx2_fma() {
        return "avx2+fma";
    }
    if cfg!(all(target_arch = "wasm32", target_feature = "simd128")) {
        "simd128"
    } else if cfg!(target_feature = "fma") {
        "fma"
    } else {
        "portable"
    }
}
