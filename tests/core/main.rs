//! The core, as a specification: kinematics, the pseudoinverse identities,
//! the obstacle vector, the integrator and the paper's reference runs.
//!
//! One test serves both targets: `cargo test` runs it natively and
//! `wasm-pack test --headless --chrome` runs the same tests in a browser.

#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use std::f64::consts::PI;

use redundant_ik::ik::{self, DampingSchedule, Weights};
use redundant_ik::kinematics;
use redundant_ik::nalgebra::{DMatrix, DVector, Vector2};
use redundant_ik::obstacle::{self, Obstacle};
use redundant_ik::planner::methods::{self, DELTA, LAMBDA};
use redundant_ik::scene::Param;
use redundant_ik::{Arm, Error, Method, Planner, Pose, Scene};

/// Small deterministic generator so that the same "random" poses are checked
/// on every target (no OS entropy in the browser).
struct Lcg(u64);
impl Lcg {
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        lo + (hi - lo) * ((self.0 >> 11) as f64 / (1u64 << 53) as f64)
    }
    fn theta(&mut self, n: usize) -> DVector<f64> {
        DVector::from_fn(n, |_, _| self.uniform(-PI, PI))
    }
    fn spd(&mut self, n: usize) -> DMatrix<f64> {
        let a = DMatrix::from_fn(n, n, |_, _| self.uniform(-1.0, 1.0));
        &a * a.transpose() + DMatrix::identity(n, n) * 0.5
    }
}

fn theta(v: &[f64]) -> DVector<f64> {
    DVector::from_column_slice(v)
}

fn jacobian_dyn(arm: &Arm, th: &DVector<f64>) -> DMatrix<f64> {
    let j = arm.jacobian(th);
    DMatrix::from_fn(2, arm.dof(), |r, c| j[(r, c)])
}

mod any_arm;
mod geometry;
mod runs;
