//! Matlab's `tansig` activation, as the trainer ([`crate::nn::mlp`]) and the
//! run-time kernels ([`crate::nn::kernel`]) both evaluate it, and the
//! multiply-add they share. A leaf of `nn`.

/// `a b + c`, fused when the build has FMA.
#[inline(always)]
pub(crate) fn madd<const FMA: bool>(a: f64, b: f64, c: f64) -> f64 {
    if FMA {
        a.mul_add(b, c)
    } else {
        a * b + c
    }
}

/// Largest `|z|` that `tansig` evaluates; beyond it `tanh z = ±1` in `f64`
/// (`1 - tanh 19.06 < 2^-53`).
pub(crate) const TANSIG_CLAMP: f64 = 20.0;

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
/// `tests/networks/`).
#[inline]
pub fn tansig(z: f64) -> f64 {
    tansig_with::<false>(z)
}

/// [`tansig`], with fused multiply-adds when `FMA`.
#[inline(always)]
#[allow(clippy::excessive_precision)] // Cephes' and fdlibm's published digits
pub(crate) fn tansig_with<const FMA: bool>(z: f64) -> f64 {
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

/// Largest `|z|` that [`tansig32`] evaluates: there the approximation
/// reaches 1 in `f32`.
pub(crate) const TANSIG32_CLAMP: f32 = 7.905_311;

/// The coefficients of [`tansig32`]'s odd numerator, `z^13` first.
#[allow(clippy::excessive_precision)]
pub(crate) const TANSIG32_P: [f32; 7] = [
    -2.760_768_477_423_55e-16,
    2.000_187_904_824_77e-13,
    -8.604_671_522_137_35e-11,
    5.122_297_090_371_14e-08,
    1.485_722_357_179_79e-05,
    6.372_619_288_754_36e-04,
    4.893_524_558_917_86e-03,
];

/// The coefficients of [`tansig32`]'s even denominator, `z^6` first.
#[allow(clippy::excessive_precision)]
pub(crate) const TANSIG32_Q: [f32; 4] = [
    1.198_258_394_667_02e-06,
    1.185_347_056_866_54e-04,
    2.268_434_632_439_00e-03,
    4.893_525_185_543_85e-03,
];

/// `tansig` in `f32`, for the single-precision kernels
/// ([`crate::nn::Precision::F32`]): the rational minimax approximation of
/// degrees 13/6 that Eigen (`generic_fast_tanh_float`), XLA and ONNX
/// Runtime's MLAS use, `tanh z = z P(z^2) / Q(z^2)` on `|z| <= 7.905`, here
/// evaluated on `|z|` and given `z`'s sign, each step one rounded multiply
/// and one rounded add (no fused multiply-add), so that every target, the
/// wasm `f32x4` kernel included, gives the same bits. Largest error against
/// `f64::tanh`: below `1e-6` absolute (tested in `tests/networks/`). NaN
/// in gives NaN out.
#[inline(always)]
pub fn tansig32(z: f32) -> f32 {
    let a = z.abs();
    let a = if a > TANSIG32_CLAMP {
        TANSIG32_CLAMP
    } else {
        a
    };
    let x2 = a * a;
    let mut p = TANSIG32_P[0];
    for c in &TANSIG32_P[1..] {
        p = p * x2 + c;
    }
    let p = p * a;
    let mut q = TANSIG32_Q[0];
    for c in &TANSIG32_Q[1..] {
        q = q * x2 + c;
    }
    (p / q).copysign(z)
}
