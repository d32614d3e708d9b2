//! Arbitrary values from the fuzzer's bytes: numbers (ordinary, special,
//! raw bits), points, small counts, methods and arms.

use arbitrary::Unstructured;
use redundant_ik::planner::methods;
use redundant_ik::{Arm, Method};

/// Values that people, URLs and hostile files produce.
pub const SPECIAL: [f64; 14] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    1e308,
    -1e308,
    1e-308,
    5e-324,
    f64::MAX,
    f64::MIN,
    f64::EPSILON,
    1.0,
    -1.0,
];

/// A number: 3 in 4 uniform in `[-3, 3]`, 1 in 8 special, 1 in 8 raw bits.
pub fn num(u: &mut Unstructured) -> f64 {
    match u.int_in_range(0u8..=7).unwrap_or(2) {
        0 => f64::from_bits(u.arbitrary().unwrap_or(0)),
        1 => *u.choose(&SPECIAL).unwrap_or(&f64::NAN),
        _ => {
            let k: u16 = u.arbitrary().unwrap_or(0);
            -3.0 + 6.0 * f64::from(k) / f64::from(u16::MAX)
        }
    }
}

/// A number in `[lo, hi]` as a rule, and any [`num`] 1 time in 8.
pub fn num_in(u: &mut Unstructured, lo: f64, hi: f64) -> f64 {
    if u.ratio(1u8, 8u8).unwrap_or(false) {
        return num(u);
    }
    let k: u16 = u.arbitrary().unwrap_or(0);
    lo + (hi - lo) * f64::from(k) / f64::from(u16::MAX)
}

pub fn point(u: &mut Unstructured) -> [f64; 2] {
    [num(u), num(u)]
}

pub fn small(u: &mut Unstructured, max: usize) -> usize {
    u.int_in_range(0..=max).unwrap_or(0)
}

pub fn method(u: &mut Unstructured) -> Method {
    *u.choose(methods::ALL).unwrap_or(&Method::NUMERICAL)
}

/// An arm from arbitrary numbers: 0 to 8 links (the core takes 2 to 6).
pub fn arm(u: &mut Unstructured) -> (f64, Vec<f64>) {
    if u.ratio(1u8, 3u8).unwrap_or(false) {
        let a = Arm::paper();
        return (a.post(), a.links().to_vec());
    }
    let post = num_in(u, 0.0, 1.0);
    let n = small(u, 8);
    let links = (0..n).map(|_| num_in(u, 0.05, 1.0)).collect();
    (post, links)
}
