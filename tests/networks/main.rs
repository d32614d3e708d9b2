//! The networks as a specification: the forward pass, the trainer, the
//! weights file, and what the shipped networks achieve (the figures stated
//! in docs/networks.md).
//!
//! One test serves both targets, like tests/core: `cargo test` runs it
//! natively and `wasm-pack test --headless --chrome` runs the same tests in
//! a browser (the trainer has no threads, clock or OS entropy).

#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use std::f64::consts::PI;
use std::sync::Arc;

use redundant_ik::evaluation::{self, ErrorStats, GENERALISATION_SCENES};
use redundant_ik::nalgebra::{DVector, Vector2};
use redundant_ik::networks::{self, Networks};
use redundant_ik::networks::{NetKind, Variant, WeightsFile};
use redundant_ik::nn::activation::tansig;
use redundant_ik::nn::lm::{self, Dataset, LmOptions};
use redundant_ik::nn::mlp::{Activations, Layer, MapMinMax, Mlp};
use redundant_ik::nn::{Kernel, Rng};
use redundant_ik::planner::methods;
use redundant_ik::{ik, Arm, Error, Method, Planner, Pose, Scene, Surrogate};

fn embedded_v() -> WeightsFile {
    <WeightsFile>::from_json(networks::V_PLAIN_JSON).unwrap()
}

fn embedded_phi() -> WeightsFile {
    <WeightsFile>::from_json(networks::PHI_PLAIN_JSON).unwrap()
}

fn rejected(phi: &WeightsFile, v: &WeightsFile) -> String {
    let p = serde_json::to_string(phi).unwrap();
    let q = serde_json::to_string(v).unwrap();
    match Networks::from_json(&p, &q) {
        Err(Error::Weights(msg)) => msg,
        other => panic!("expected a weights error, got {other:?}"),
    }
}

mod files;
mod kernels;
mod mlp;
mod shipped;
mod single;
