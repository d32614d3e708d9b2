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
//!   [`STACK_WIDTH`] (padded) wide: no allocation per call.
//!
//! On x86-64 the same code is also compiled for AVX2 + FMA and chosen at run
//! time when the CPU has them ([`Kernel::forward`], [`set_runtime_dispatch`]);
//! the page's SIMD build (wasm32 with `simd128`) runs a kernel written with
//! wasm SIMD intrinsics; everything else runs the portable build.

use crate::nn::mlp::{MapMinMax, Mlp};

/// Widths are padded to a multiple of this many neurons (four `f64` = one
/// AVX2 register, two SSE2 or wasm `simd128` registers).
pub const LANES: usize = 4;

/// Widest padded layer handled with stack buffers; wider networks work
/// through a heap buffer per call.
pub const STACK_WIDTH: usize = 64;

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
    simd: Vec<wasm_simd::Layer>,
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
        Self {
            n_in: mlp.inputs(),
            n_out: mlp.outputs(),
            #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
            simd: layers.iter().map(wasm_simd::Layer::new).collect(),
            layers,
            widest,
        }
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
    /// Allocation-free for layers up to [`STACK_WIDTH`] wide.
    #[inline]
    pub fn forward(&self, x: &[f64], y: &mut [f64]) {
        #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
        if self.widest <= STACK_WIDTH {
            return wasm_simd::forward(self, x, y);
        }
        if self.widest <= STACK_WIDTH {
            let mut a = [0.0; STACK_WIDTH];
            let mut b = [0.0; STACK_WIDTH];
            self.dispatch(x, y, &mut a, &mut b);
        } else {
            let mut a = vec![0.0; self.widest];
            let mut b = vec![0.0; self.widest];
            self.dispatch(x, y, &mut a, &mut b);
        }
    }

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

fn forward_portable(k: &Kernel, x: &[f64], y: &mut [f64], a: &mut [f64], b: &mut [f64]) {
    // Where FMA is part of the compile-time target (e.g. -C target-cpu=native)
    // use it; otherwise a separate multiply and add (a software fma would be slow).
    forward_body::<{ cfg!(target_feature = "fma") }>(k, x, y, a, b)
}

/// `a b + c`, fused when the build has FMA.
#[inline(always)]
fn madd<const FMA: bool>(a: f64, b: f64, c: f64) -> f64 {
    if FMA {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

/// The forward pass proper, inlined into each instruction-set build.
#[inline(always)]
fn forward_body<const FMA: bool>(
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

/// Largest `|z|` that `tansig` evaluates; beyond it `tanh z = ±1` in `f64`
/// (`1 - tanh 19.06 < 2^-53`).
const TANSIG_CLAMP: f64 = 20.0;

/// Matlab's `tansig` (`tanh z`) written so that a loop over neurons
/// vectorises: no branches, no calls, one division.
///
/// `tanh z = sign(z) (1 - t) / (1 + t)` with `t = exp(-2 |z|)`. The
/// exponential is reduced as `-2 |z| = k ln 2 + r`, `|r| <= ln(2) / 2`, and
/// `e^r = (Q + rP) / (Q - rP)` with Cephes' rational `P(r^2)`, `Q(r^2)`
/// (relative error below 1e-17 on that interval); `2^k` is assembled from
/// the exponent bits. With `N = Q + rP`, `D = Q - rP`:
/// `tanh |z| = (D - 2^k N) / (D + 2^k N)`. `|z|` is clamped at 20 (where
/// `tanh` is 1 in `f64`) with a compare-and-select, not `f64::min`, whose NaN
/// rule is slow in wasm SIMD. NaN in gives NaN out.
///
/// Largest error against the C library's `tanh`, measured on 4 million
/// points of `[-25, 25]` and near zero: below `5e-16` absolute (tested in
/// `tests/networks.rs`).
#[inline]
pub fn tansig(z: f64) -> f64 {
    tansig_with::<false>(z)
}

/// [`tansig`], with fused multiply-adds when `FMA`.
#[inline(always)]
#[allow(clippy::excessive_precision)] // Cephes' and fdlibm's published digits
fn tansig_with<const FMA: bool>(z: f64) -> f64 {
    const LOG2E: f64 = std::f64::consts::LOG2_E;
    const LN2_HI: f64 = 6.931_471_803_691_238_164_90e-1;
    const LN2_LO: f64 = 1.908_214_929_270_587_700_02e-10;
    // 1.5 * 2^52: adding it rounds to an integer held in the low mantissa bits.
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    const P: [f64; 3] = [
        1.261_771_930_748_105_908_78e-4,
        3.029_944_077_074_419_613_00e-2,
        9.999_999_999_999_999_999_10e-1,
    ];
    const Q: [f64; 4] = [
        3.001_985_051_386_644_550_42e-6,
        2.524_483_403_496_841_041_92e-3,
        2.272_655_482_081_550_287_66e-1,
        2.000_000_000_000_000_000_09e0,
    ];
    let a = z.abs();
    let a = if a > TANSIG_CLAMP { TANSIG_CLAMP } else { a };
    let x = -2.0 * a;
    let kd = madd::<FMA>(x, LOG2E, SHIFT);
    let bits = kd.to_bits();
    let k = kd - SHIFT;
    let r = madd::<FMA>(-k, LN2_LO, madd::<FMA>(-k, LN2_HI, x));
    let rr = r * r;
    let p = r * madd::<FMA>(madd::<FMA>(P[0], rr, P[1]), rr, P[2]);
    let q = madd::<FMA>(madd::<FMA>(madd::<FMA>(Q[0], rr, Q[1]), rr, Q[2]), rr, Q[3]);
    // 2^k for k in [-58, 0]: the low bits of `bits` hold k (two's complement).
    let scale = f64::from_bits(bits.wrapping_add(1023) << 52);
    let (n, d) = (q + p, q - p);
    let sn = scale * n;
    ((d - sn) / (d + sn)).copysign(z)
}

#[cfg(all(target_arch = "x86_64", not(target_feature = "fma")))]
#[allow(unsafe_code)]
mod x86 {
    //! The AVX2 + FMA build of the forward pass, chosen at run time.
    use std::sync::atomic::{AtomicBool, Ordering};

    use super::{forward_body, Kernel};

    pub(super) static ALLOWED: AtomicBool = AtomicBool::new(true);

    /// Whether this CPU has AVX2 and FMA (the detection is cached by std).
    #[inline]
    pub(super) fn has_avx2_fma() -> bool {
        std::is_x86_feature_detected!("avx2") && std::is_x86_feature_detected!("fma")
    }

    /// Whether to run the AVX2 + FMA build: the CPU has them and
    /// [`super::set_runtime_dispatch`] has not switched it off.
    #[inline]
    pub(super) fn use_avx2_fma() -> bool {
        ALLOWED.load(Ordering::Relaxed) && has_avx2_fma()
    }

    #[target_feature(enable = "avx2,fma")]
    unsafe fn forward_avx2(k: &Kernel, x: &[f64], y: &mut [f64], a: &mut [f64], b: &mut [f64]) {
        forward_body::<true>(k, x, y, a, b)
    }

    /// Runs the AVX2 + FMA build. Call only when [`has_avx2_fma`] is true.
    #[inline]
    pub(super) fn forward_avx2_fma(
        k: &Kernel,
        x: &[f64],
        y: &mut [f64],
        a: &mut [f64],
        b: &mut [f64],
    ) {
        debug_assert!(has_avx2_fma());
        // SAFETY: the only requirement of a `target_feature` function is that
        // the CPU supports the features, which the caller checked at run time
        // with `is_x86_feature_detected!`; the body is safe Rust.
        unsafe { forward_avx2(k, x, y, a, b) }
    }
}

#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
mod wasm_simd {
    //! The forward pass written with wasm `simd128` intrinsics (two `f64` per
    //! `v128`). The page is built at `opt-level = "s"` to stay small (level 3
    //! costs 13 KB gzipped), and at that level LLVM vectorises nothing, so the
    //! hot kernel says what it wants. One set of accumulators per block
    //! (Chromium: 10% faster than the portable kernel's two, which spill), so
    //! sums run in another order than there: results agree to rounding.
    use core::arch::wasm32::*;

    use super::{Kernel, Layer as Plain, LANES, STACK_WIDTH, TANSIG_CLAMP};

    const PAIRS: usize = STACK_WIDTH / 2;

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

    pub(super) fn forward(k: &Kernel, x: &[f64], y: &mut [f64]) {
        let zero = f64x2_splat(0.0);
        let mut a = [zero; PAIRS];
        let mut b = [zero; PAIRS];
        // The raw inputs, two per v128 (the rest zero).
        for (i, xi) in x.iter().take(k.n_in).enumerate() {
            a[i / 2] = if i % 2 == 0 {
                f64x2_replace_lane::<0>(a[i / 2], *xi)
            } else {
                f64x2_replace_lane::<1>(a[i / 2], *xi)
            };
        }
        let (mut cur, mut next) = (&mut a, &mut b);
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

    /// [`super::tansig`] on two lanes.
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
}
