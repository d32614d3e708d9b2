//! Criterion benchmarks of the networks: forward passes, `theta_dot` in every
//! method, one Levenberg-Marquardt epoch per shipped network size and a short
//! whole training run. `cargo bench --bench networks`.

use std::hint::black_box;
use std::sync::Arc;

use criterion::{criterion_group, criterion_main, BatchSize, Criterion};
use redundant_ik::nalgebra::Vector2;
use redundant_ik::networks::{Encoding, NetKind, Networks, Sampling, Variant};
use redundant_ik::nn::lm::{LmOptions, LmTrainer};
use redundant_ik::nn::mlp::{MapMinMax, Mlp};
use redundant_ik::nn::{Dataset, Rng};
use redundant_ik::planner::methods;
use redundant_ik::training::{self, TrainSpec};
use redundant_ik::{Arm, Planner, Scene, Surrogate};

fn forward(c: &mut Criterion) {
    let theta = Scene::task1().theta0;
    let mut g = c.benchmark_group("forward");
    for variant in [Variant::Plain, Variant::Rows, Variant::Equivariant] {
        let nets = Networks::embedded_with(variant).unwrap();
        let mut out = [0.0; 6];
        g.bench_function(format!("phi_{}", variant.name()), |b| {
            b.iter(|| nets.phi_into(black_box(&theta), &mut out).unwrap())
        });
    }
    let nets = Networks::embedded().unwrap();
    let mut out = [0.0; 3];
    g.bench_function("v_plain", |b| {
        b.iter(|| {
            nets.area_gradient_into(black_box(&theta), [0.5, 0.5], &mut out)
                .unwrap()
        })
    });
    g.bench_function("numerical_phi", |b| {
        let arm = Arm::paper();
        let th = Scene::task1().theta0_vector();
        b.iter(|| redundant_ik::ik::phi(&arm.jacobian(black_box(&th)), 0.0).unwrap())
    });
    g.bench_function("numerical_area_gradient", |b| {
        let arm = Arm::paper();
        let th = Scene::task1().theta0_vector();
        let o = Vector2::new(0.5, 0.5);
        b.iter(|| redundant_ik::obstacle::area_gradient(&arm, black_box(&th), &o))
    });
    g.finish();
}

fn theta_dot(c: &mut Criterion) {
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    let xdot = Vector2::new(-0.1, -0.08);
    let mut g = c.benchmark_group("theta_dot");
    for &method in methods::ALL {
        let mut p = Planner::new(Scene::task1(), method, Some(nets.clone())).unwrap();
        let th = Scene::task1().theta0;
        let mut out = [0.0; 3];
        g.bench_function(method.name(), |b| {
            b.iter(|| {
                p.theta_dot_into(black_box(&th), [xdot[0], xdot[1]], &mut out)
                    .unwrap()
            })
        });
    }
    g.finish();
    let mut g = c.benchmark_group("task1_run_100_rk4_steps");
    for &method in methods::ALL {
        g.bench_function(method.name(), |b| {
            b.iter(|| Planner::run(Scene::task1(), method, Some(nets.clone())).unwrap())
        });
    }
    g.finish();
}

fn lm_epoch(c: &mut Criterion) {
    let arm = Arm::paper();
    let sampling = Sampling::default();
    let samples = training::draw_samples(&arm, &sampling, 3000, 1).unwrap();
    let phi_plain = training::phi_datasets(&arm, Variant::Plain, Encoding::Raw, &samples).unwrap();
    let phi_rows = training::phi_datasets(&arm, Variant::Rows, Encoding::Raw, &samples).unwrap();
    let phi_eq =
        training::phi_datasets(&arm, Variant::Equivariant, Encoding::Raw, &samples).unwrap();
    let v = training::v_dataset(&arm, Variant::Plain, Encoding::Raw, 0.0, &samples).unwrap();
    let cases: [(&str, &Dataset, Vec<usize>); 4] = [
        ("phi_plain_3-35-14-6", &phi_plain[0], vec![3, 35, 14, 6]),
        ("phi_rows_3-35-14-2", &phi_rows[0], vec![3, 35, 14, 2]),
        ("phi_equivariant_2-35-14-6", &phi_eq[0], vec![2, 35, 14, 6]),
        ("v_plain_5-25-14-3", &v, vec![5, 25, 14, 3]),
    ];
    let mut g = c.benchmark_group("lm_epoch_3000_samples");
    g.sample_size(10);
    for (name, data, sizes) in cases {
        let mut rng = Rng::new(1);
        let mlp = Mlp::nguyen_widrow(
            &sizes,
            MapMinMax::fit(&data.inputs, data.n_in),
            MapMinMax::fit(&data.targets, data.n_out),
            &mut rng,
        )
        .unwrap();
        let trainer = LmTrainer::new(mlp, data, LmOptions::default(), &mut rng).unwrap();
        g.bench_function(name, |b| {
            b.iter_batched(
                || trainer.clone(),
                |mut t| black_box(t.epoch()),
                BatchSize::LargeInput,
            )
        });
    }
    g.finish();
}

fn training_run(c: &mut Criterion) {
    let mut g = c.benchmark_group("training_run");
    g.sample_size(10);
    for (net, variant) in [
        (NetKind::Phi, Variant::Equivariant),
        (NetKind::V, Variant::Plain),
    ] {
        let mut spec = TrainSpec::paper(net, variant, 1);
        spec.samples = 1000;
        spec.options.max_epochs = 20;
        g.bench_function(
            format!("{:?}_{}_1000_samples_20_epochs", net, variant.name()).to_lowercase(),
            |b| b.iter(|| training::train_weights(&spec, |_, _| true).unwrap()),
        );
    }
    g.finish();
}

criterion_group!(benches, forward, theta_dot, lm_epoch, training_run);
criterion_main!(benches);
