//! The AVX2 + FMA build of the forward pass, chosen at run time: the
//! crate's one `unsafe` block (a call of a `target_feature` function after
//! the run-time check of those features).
#![allow(unsafe_code)]

use std::sync::atomic::{AtomicBool, Ordering};

use super::portable::forward_body;
use super::Kernel;

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
pub(super) fn forward_avx2_fma(k: &Kernel, x: &[f64], y: &mut [f64], a: &mut [f64], b: &mut [f64]) {
    debug_assert!(has_avx2_fma());
    // SAFETY: the only requirement of a `target_feature` function is that
    // the CPU supports the features, which the caller checked at run time
    // with `is_x86_feature_detected!`; the body is safe Rust.
    unsafe { forward_avx2(k, x, y, a, b) }
}
