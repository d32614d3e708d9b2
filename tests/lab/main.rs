//! The lab (`docs/lab.md`): joint limits in the methods (weighted least
//! norm, the paper's `W` of eq. 7; the outcome of a joint past its
//! limits), the field's other secondary criteria (`manipulability`,
//! `jointrange`) and their gradients.

#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

mod criteria;
mod ground;
mod iiwa;
mod weighting;

use redundant_ik::arm::JointLimits;
use redundant_ik::nn::Rng;
use redundant_ik::Arm;

/// An arm of 2-6 links with random lengths and post.
pub fn random_arm(rng: &mut Rng) -> Arm {
    let n = 2 + rng.below(5);
    Arm::new(
        rng.range(0.0, 0.8),
        (0..n).map(|_| rng.range(0.2, 1.0)).collect(),
    )
    .unwrap()
}

/// `n` angles in `[-2.5, 2.5]`.
pub fn random_theta(rng: &mut Rng, n: usize) -> Vec<f64> {
    (0..n).map(|_| rng.range(-2.5, 2.5)).collect()
}

/// Limits around `theta`: each joint's range holds its angle, `margin` to
/// `margin + 2` rad from either side.
pub fn limits_around(rng: &mut Rng, theta: &[f64], margin: f64) -> JointLimits {
    JointLimits::new(
        theta
            .iter()
            .map(|&t| {
                [
                    t - margin - rng.range(0.0, 2.0),
                    t + margin + rng.range(0.0, 2.0),
                ]
            })
            .collect(),
    )
    .unwrap()
}

/// The paper's joint limits for a 3-link arm, +-120 degrees.
pub const PAPER_LIMITS: &str = "-2.0944:2.0944,-2.0944:2.0944,-2.0944:2.0944";
