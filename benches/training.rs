//! Criterion benchmarks of the trainers: one Adam epoch against one
//! Levenberg-Marquardt epoch on the same data (`docs/speed.md`, "Adam").
//! `cargo bench --bench training`.
//!
//! The data are the workload Adam was written for: `Phi` of the paper's arm
//! over the whole joint torus (`theta_1 = 0`, poses with `sigma_min(J) <
//! 0.15` left out), inputs `(sin t2, cos t2, sin t3, cos t3)`, 20,000
//! samples (14,000 in training).

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use redundant_ik::nalgebra::DVector;
use redundant_ik::nn::adam::{AdamOptions, AdamTrainer};
use redundant_ik::nn::data::fresh_network;
use redundant_ik::nn::lm::{LmOptions, LmTrainer};
use redundant_ik::nn::{Dataset, Rng};
use redundant_ik::training::sampling::phi_target;
use redundant_ik::{ik, Arm};

fn phi_torus(count: usize, seed: u64) -> Dataset {
    let arm = Arm::paper();
    let mut rng = Rng::new(seed);
    let mut d = Dataset::new(4, 6);
    let pi = std::f64::consts::PI;
    while d.len() < count {
        let (t2, t3) = (rng.range(-pi, pi), rng.range(-pi, pi));
        let theta = [0.0, t2, t3];
        let j = arm.jacobian(&DVector::from_column_slice(&theta));
        if ik::smallest_singular_value(&j) < 0.15 {
            continue;
        }
        let phi = phi_target(&arm, &theta).unwrap();
        d.push(&[t2.sin(), t2.cos(), t3.sin(), t3.cos()], &phi);
    }
    d
}

fn epochs(c: &mut Criterion) {
    let data = phi_torus(20_000, 1);
    let mut g = c.benchmark_group("epoch_phi_torus_20000_samples");
    g.sample_size(10);
    for sizes in [vec![4, 35, 14, 6], vec![4, 96, 96, 6]] {
        let name = |trainer: &str| {
            let widths: Vec<String> = sizes.iter().map(|s| s.to_string()).collect();
            format!("{trainer}_{}", widths.join("-"))
        };
        let mut rng = Rng::new(1);
        let mlp = fresh_network(&sizes, &data, &mut rng).unwrap();
        let adam =
            AdamTrainer::new(mlp.clone(), &data, AdamOptions::default(), rng.clone()).unwrap();
        g.bench_function(name("adam_batch64"), |b| {
            b.iter_batched(
                || adam.clone(),
                |mut t| black_box(t.epoch()),
                BatchSize::LargeInput,
            )
        });
        // J^T J of 4-96-96-6 is 10,374^2 entries (861 MB, and as much again
        // for the trial copy): Levenberg-Marquardt only for the narrow network.
        if sizes[1] < 50 {
            let lm = LmTrainer::new(mlp, &data, LmOptions::default(), &mut rng).unwrap();
            g.bench_function(name("lm"), |b| {
                b.iter_batched(
                    || lm.clone(),
                    |mut t| black_box(t.epoch()),
                    BatchSize::LargeInput,
                )
            });
        }
    }
    g.finish();
}

criterion_group!(benches, epochs);
criterion_main!(benches);
