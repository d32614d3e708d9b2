//! The networks as a specification: the forward pass, the trainer, the
//! weights file, and what the shipped networks achieve (the figures stated
//! in docs/networks.md).
//!
//! One file serves both targets, like tests/core.rs: `cargo test` runs it
//! natively and `wasm-pack test --headless --chrome` runs the same tests in
//! a browser (the trainer has no threads, clock or OS entropy).

#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
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

fn tiny() -> Mlp {
    Mlp {
        sizes: vec![2, 2, 1],
        layers: vec![
            Layer {
                weights: vec![0.5, -1.0, 2.0, 0.25],
                biases: vec![0.1, -0.2],
            },
            Layer {
                weights: vec![1.5, -0.5],
                biases: vec![0.3],
            },
        ],
        input_map: MapMinMax {
            min: vec![0.0, -2.0],
            max: vec![2.0, 2.0],
        },
        output_map: MapMinMax {
            min: vec![10.0],
            max: vec![14.0],
        },
    }
}

#[test]
fn forward_pass_matches_a_hand_computed_network() {
    let net = tiny();
    // x = (1.5, 1.0) -> mapminmax -> (0.5, 0.5)
    let (x1, x2) = (0.5, 0.5);
    let h1 = (0.5 * x1 - 1.0 * x2 + 0.1f64).tanh();
    let h2 = (2.0 * x1 + 0.25 * x2 - 0.2f64).tanh();
    let y = 1.5 * h1 - 0.5 * h2 + 0.3;
    // reverse mapminmax onto [10, 14]
    let expected = (y + 1.0) * 2.0 + 10.0;
    let got = net.forward(&[1.5, 1.0]);
    assert!(
        (got[0] - expected).abs() < 1e-14,
        "{} vs {expected}",
        got[0]
    );
}

#[test]
fn weight_jacobian_matches_finite_differences() {
    let mut rng = Rng::new(3);
    let map = |n| MapMinMax {
        min: vec![-1.0; n],
        max: vec![1.0; n],
    };
    let mut net = Mlp::nguyen_widrow(&[3, 5, 4, 2], map(3), map(2), &mut rng).unwrap();
    let x = [0.3, -0.7, 0.2];
    let p = net.params();
    let mut acts = Activations::new(&net.sizes);
    net.forward_scaled(&x, &mut acts);
    let mut jac = vec![0.0; 2 * p.len()];
    net.output_jacobian(&mut acts, &mut jac);
    let h = 1e-6;
    for k in 0..p.len() {
        let mut q = p.clone();
        q[k] += h;
        net.set_params(&q);
        net.forward_scaled(&x, &mut acts);
        let up = acts.output().to_vec();
        q[k] -= 2.0 * h;
        net.set_params(&q);
        net.forward_scaled(&x, &mut acts);
        let down = acts.output().to_vec();
        for o in 0..2 {
            let fd = (up[o] - down[o]) / (2.0 * h);
            assert!(
                (fd - jac[o * p.len() + k]).abs() < 1e-7,
                "output {o}, parameter {k}: {fd} vs {}",
                jac[o * p.len() + k]
            );
        }
    }
}

fn sine_data() -> Dataset {
    let mut d = Dataset::new(1, 1);
    for i in 0..200 {
        let x = -PI + 2.0 * PI * i as f64 / 199.0;
        d.push(&[x], &[x.sin()]);
    }
    d
}

#[test]
fn trainer_fits_a_sine_and_is_deterministic_for_a_seed() {
    let data = sine_data();
    let opts = LmOptions {
        max_epochs: 100,
        ..LmOptions::default()
    };
    let mut epochs_seen = 0;
    let (a, ra) = lm::train(&[1, 8, 1], &data, opts, 42, |_| {
        epochs_seen += 1;
        true
    })
    .unwrap();
    assert_eq!(epochs_seen, ra.epochs);
    assert!(ra.test_mse < 1e-6, "test MSE {}", ra.test_mse);
    let worst = (0..100)
        .map(|i| {
            let x = -3.0 + 6.0 * i as f64 / 99.0;
            (a.forward(&[x])[0] - f64::sin(x)).abs()
        })
        .fold(0.0, f64::max);
    assert!(worst < 5e-3, "largest error {worst}");
    let (b, rb) = lm::train(&[1, 8, 1], &data, opts, 42, |_| true).unwrap();
    assert_eq!(a, b, "same seed, same weights");
    assert_eq!(ra, rb);
    let (c, _) = lm::train(&[1, 8, 1], &data, opts, 43, |_| true).unwrap();
    assert_ne!(a, c, "another seed, other weights");
}

#[test]
fn trainer_stops_when_the_callback_says_so() {
    let (_, r) = lm::train(&[1, 4, 1], &sine_data(), LmOptions::default(), 1, |r| {
        r.epoch < 3
    })
    .unwrap();
    assert_eq!(r.epochs, 3);
    assert_eq!(r.stop, lm::StopReason::Cancelled);
}

#[test]
fn trainer_rejects_data_that_does_not_fit_the_network() {
    let data = sine_data();
    assert!(lm::train(&[2, 4, 1], &data, LmOptions::default(), 1, |_| true).is_err());
    let mut bad = sine_data();
    bad.targets[3] = f64::NAN;
    assert!(lm::train(&[1, 4, 1], &bad, LmOptions::default(), 1, |_| true).is_err());
}

#[test]
fn shipped_weights_round_trip_exactly() {
    for json in [
        networks::PHI_PLAIN_JSON,
        networks::PHI_ROWS_JSON,
        networks::PHI_EQUIVARIANT_JSON,
        networks::V_PLAIN_JSON,
    ] {
        let file = WeightsFile::from_json(json).unwrap();
        let text = file.to_json().unwrap();
        // The shipped text is exactly what the writer produces (`train` adds a newline).
        assert_eq!(text.trim_end(), json.trim_end());
        let again = WeightsFile::from_json(&text).unwrap();
        assert_eq!(file, again);
        // Bit-for-bit, not just approximately.
        for (a, b) in file.nets.iter().zip(&again.nets) {
            for (x, y) in a.mlp.params().iter().zip(b.mlp.params()) {
                assert_eq!(x.to_bits(), y.to_bits());
            }
        }
    }
}

fn embedded_v() -> WeightsFile {
    WeightsFile::from_json(networks::V_PLAIN_JSON).unwrap()
}

fn embedded_phi() -> WeightsFile {
    WeightsFile::from_json(networks::PHI_PLAIN_JSON).unwrap()
}

fn rejected(phi: &WeightsFile, v: &WeightsFile) -> String {
    let p = serde_json::to_string(phi).unwrap();
    let q = serde_json::to_string(v).unwrap();
    match Networks::from_json(&p, &q) {
        Err(Error::Weights(msg)) => msg,
        other => panic!("expected a weights error, got {other:?}"),
    }
}

#[test]
fn bad_weights_files_are_rejected_with_a_clear_error() {
    let v = embedded_v();
    // Wrong shape: a weight missing.
    let mut f = embedded_phi();
    f.nets[0].mlp.layers[1].weights.pop();
    assert!(rejected(&f, &v).contains("weights"), "{}", rejected(&f, &v));
    // Wrong bias count.
    let mut f = embedded_phi();
    f.nets[0].mlp.layers[0].biases.push(0.0);
    assert!(rejected(&f, &v).contains("biases"));
    // Not finite (NaN cannot be written in JSON; it is caught by validation).
    let mut f = embedded_phi();
    f.nets[0].mlp.layers[0].weights[3] = f64::NAN;
    assert!(matches!(Networks::new(f, v.clone()), Err(Error::Weights(m)) if m.contains("finite")));
    // Wrong input count for the variant: a plain Phi net over 2 inputs.
    let eq = WeightsFile::from_json(networks::PHI_EQUIVARIANT_JSON).unwrap();
    let mut f = eq.clone();
    f.variant = Variant::Plain;
    assert!(rejected(&f, &v).contains("inputs"));
    // The files swapped.
    let p = serde_json::to_string(&embedded_phi()).unwrap();
    let q = serde_json::to_string(&v).unwrap();
    assert!(matches!(
        Networks::from_json(&q, &p),
        Err(Error::Weights(_))
    ));
    // Truncated, empty, not JSON, unknown format or variant.
    let half = &networks::PHI_PLAIN_JSON[..networks::PHI_PLAIN_JSON.len() / 2];
    for bad in [half, "", "hello", "{}", "[1, 2]"] {
        assert!(matches!(
            Networks::from_json(bad, &q),
            Err(Error::Weights(_))
        ));
    }
    let other_format = networks::V_PLAIN_JSON.replacen("redundant-ik-weights/1", "x/9", 1);
    assert!(
        matches!(Networks::from_json(&p, &other_format), Err(Error::Weights(m)) if m.contains("format"))
    );
    let other_variant = networks::V_PLAIN_JSON.replacen("\"plain\"", "\"sideways\"", 1);
    assert!(matches!(
        Networks::from_json(&p, &other_variant),
        Err(Error::Weights(_))
    ));
    // Out-of-range numbers in the JSON text.
    let huge = networks::V_PLAIN_JSON.replacen("\"post\": 0.5", "\"post\": 1e999", 1);
    assert!(matches!(
        Networks::from_json(&p, &huge),
        Err(Error::Weights(_))
    ));
}

#[test]
fn networks_reject_bad_input_without_panicking() {
    let nets = Networks::embedded().unwrap();
    let (mut phi, mut g) = ([0.0; 6], [0.0; 3]);
    // The slice API checks theta and the obstacle point.
    assert!(nets.phi_into(&[0.1, 0.2], &mut phi).is_err());
    assert!(nets
        .area_gradient_into(&[0.1, 0.2], [0.5, 0.5], &mut g)
        .is_err());
    let nan = [0.1, f64::NAN, 0.2];
    assert!(nets.phi_into(&nan, &mut phi).is_err());
    assert!(!nets.phi_in_range_slice(&nan));
    let ok = [0.3, 2.0, -0.5];
    assert!(nets
        .area_gradient_into(&ok, [f64::INFINITY, 0.5], &mut g)
        .is_err());
    assert!(!nets.v_in_range_slice(&ok, [f64::INFINITY, 0.5]));
    assert!(nets.phi_into(&ok, &mut phi[..4]).is_err());
    // The planner's interface takes a pose: one of another arm, or a wrong
    // output buffer, is an error too.
    let two_links = Arm::new(0.5, vec![1.0, 1.0]).unwrap();
    let alien = Pose::new(&two_links, &[0.1, 0.2]).unwrap();
    assert!(Surrogate::phi(&nets, &alien, &mut phi[..4]).is_err());
    assert!(Surrogate::area_gradient(&nets, &alien, [0.5, 0.5], &mut g[..2]).is_err());
    assert!(!Surrogate::phi_in_range(&nets, &alien));
    let pose = Pose::new(&Arm::paper(), &ok).unwrap();
    assert!(Surrogate::phi(&nets, &pose, &mut phi[..5]).is_err());
    assert!(Surrogate::area_gradient(&nets, &pose, [0.5, 0.5], &mut g).is_ok());
    assert!(!Surrogate::v_in_range(&nets, &pose, [f64::NAN, 0.5]));
}

#[test]
fn phi_is_rotation_equivariant_which_the_equivariant_variant_uses() {
    // J(theta) = R(theta_1) J(0, theta_2, theta_3), so Phi(theta) = Phi(0, ..) R(theta_1)^T.
    let arm = Arm::paper();
    let th = DVector::from_vec(vec![0.7, 1.9, -0.8]);
    let mut th0 = th.clone();
    th0[0] = 0.0;
    let p = ik::phi(&arm.jacobian(&th), 0.0).unwrap();
    let p0 = ik::phi(&arm.jacobian(&th0), 0.0).unwrap();
    let (s, c) = th[0].sin_cos();
    let rt = redundant_ik::nalgebra::Matrix2::new(c, -s, s, c);
    assert!((p - p0 * rt).amax() < 1e-12);
}

#[test]
fn trained_range_is_reported_and_leaving_it_is_flagged() {
    let nets = Networks::embedded().unwrap();
    let r = nets.trained_range();
    let json = serde_json::to_string(&r).unwrap();
    assert!(json.contains("obstacle_min"));
    assert_eq!(r.obstacle_min, [0.3, 0.3]);
    // The tasks' start poses are inside; a stretched arm (singular) is not.
    let start = Scene::task1().theta0;
    assert!(nets.phi_in_range_slice(&start));
    assert!(nets.v_in_range_slice(&start, [0.5, 0.5]));
    assert!(!nets.phi_in_range_slice(&[0.3, 0.0, 0.0]));
    assert!(!nets.v_in_range_slice(&start, [1.5, -0.4]));
}

/// Accuracy stated in docs/networks.md (fresh samples, seed 7; bounds with
/// some slack over the measured figures).
#[test]
fn shipped_networks_meet_the_documented_accuracy() {
    let nets = Networks::embedded().unwrap();
    let test = evaluation::fresh_samples(&nets, NetKind::Phi, 400, 7).unwrap();
    let bounds = [
        (Variant::Equivariant, 2.0e-4, 2.0e-3),
        (Variant::Plain, 1.0e-3, 1.0e-2),
        (Variant::Rows, 1.0e-3, 1.0e-2),
    ];
    for (variant, median, p99) in bounds {
        let n = Networks::embedded_with(variant).unwrap();
        let s = ErrorStats::of(evaluation::phi_relative_errors(&n, &test).unwrap());
        assert!(
            s.median < median && s.p99 < p99,
            "Phi {variant:?}: median {:.2e}, p99 {:.2e}",
            s.median,
            s.p99
        );
    }
    let v = ErrorStats::of(evaluation::v_relative_errors(&nets, &test).unwrap());
    assert!(v.median < 0.06, "v median relative error {:.3}", v.median);
}

#[test]
fn cases_1_to_3_avoid_the_obstacle_and_reach_the_target_on_both_tasks() {
    let nets = Networks::embedded().unwrap();
    for task in [1, 2] {
        for mode in methods::ALL.iter().copied().filter(|m| m.uses_networks()) {
            let o = evaluation::run_task(&nets, task, mode, None, 0.0).unwrap();
            assert!(
                o.success(),
                "task {task} {mode}: min distance {:.4}, collided {}, final error {:.2e}, {:?}",
                o.min_distance,
                o.collided,
                o.final_error,
                o.error
            );
            assert!(o.min_distance > 0.05);
        }
    }
}

#[test]
fn paper_form_networks_also_succeed_on_both_tasks() {
    // One 3-35-14-6 net, and three 3-35-14-2 nets (one per row of Phi); open
    // loop, as in the paper.
    for variant in [Variant::Plain, Variant::Rows] {
        let nets = Networks::embedded_with(variant).unwrap();
        for task in [1, 2] {
            for mode in methods::ALL.iter().copied().filter(|m| m.networks().phi) {
                let o = evaluation::run_task(&nets, task, mode, None, 0.0).unwrap();
                assert!(o.success(), "{variant:?} task {task} {mode}: {o:?}");
            }
        }
    }
}

#[test]
fn closed_loop_feedback_shrinks_the_network_cases_final_error() {
    let nets = Networks::embedded_with(Variant::Plain).unwrap();
    for task in [1, 2] {
        let open = evaluation::run_task(&nets, task, Method::CASE3, None, 0.0).unwrap();
        let closed = evaluation::run_task(&nets, task, Method::CASE3, None, 1.0).unwrap();
        assert!(closed.success());
        assert!(
            closed.final_error < 0.5 * open.final_error,
            "{open:?} {closed:?}"
        );
    }
}

#[test]
fn case_3_avoids_wherever_the_numerical_route_does_in_9_of_10_scenes() {
    let nets = Networks::embedded().unwrap();
    let mut avoided = 0;
    for (task, o) in GENERALISATION_SCENES {
        let numerical = evaluation::run_task(&nets, task, Method::NUMERICAL, Some(o), 0.0).unwrap();
        let none = evaluation::run_task(&nets, task, Method::NO_AVOIDANCE, Some(o), 0.0).unwrap();
        // A scene counts when the obstacle is in the way and the numerical route avoids it.
        assert!(
            none.collided,
            "scene {o:?} on task {task} is not in the way"
        );
        assert!(!numerical.collided, "numerical collides at {o:?}");
        let case3 = evaluation::run_task(&nets, task, Method::CASE3, Some(o), 0.0).unwrap();
        if case3.error.is_none() && !case3.collided {
            avoided += 1;
        }
    }
    assert!(avoided >= 9, "Case 3 avoided in {avoided} of 10 scenes");
}

#[test]
fn planner_runs_every_mode_with_the_networks_as_surrogate() {
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    let p = Planner::new(Scene::task2(), Method::CASE3, Some(nets.clone())).unwrap();
    let xdot = Vector2::new(-0.1, -0.03);
    let td = p.theta_dot(p.theta(), &xdot).unwrap();
    let arm = Arm::paper();
    // The commanded end-effector velocity is met to the Phi network's accuracy:
    // J theta_dot - Xdot = J (Phi_net - Phi) (Xdot - J v).
    let j = arm.jacobian(p.theta());
    let v = p.null_space(p.theta()).unwrap();
    let err = (&j * &td - xdot).norm();
    assert!(err < 2e-3 * (xdot - &j * v).norm(), "{err}");
    assert!(p.in_range());
}

#[test]
fn a_kind_mismatch_is_named() {
    let v = embedded_v();
    assert_eq!(v.net, NetKind::V);
    let m = rejected(&v, &v);
    assert!(m.contains("Phi"), "{m}");
}

/// Matlab's forward pass written out with the C library's `tanh`: the
/// reference the run-time kernel must reproduce.
fn reference_forward(mlp: &Mlp, x: &[f64]) -> Vec<f64> {
    let scale = |m: &MapMinMax, i: usize, v: f64| {
        if m.max[i] > m.min[i] {
            2.0 * (v - m.min[i]) / (m.max[i] - m.min[i]) - 1.0
        } else {
            v - m.min[i]
        }
    };
    let mut a: Vec<f64> = (0..mlp.inputs())
        .map(|i| scale(&mlp.input_map, i, x[i]))
        .collect();
    let last = mlp.layers.len() - 1;
    for (l, layer) in mlp.layers.iter().enumerate() {
        a = layer
            .weights
            .chunks(mlp.sizes[l])
            .zip(&layer.biases)
            .map(|(row, b)| {
                let z = b + row.iter().zip(&a).map(|(w, v)| w * v).sum::<f64>();
                if l < last {
                    z.tanh()
                } else {
                    z
                }
            })
            .collect();
    }
    a.iter()
        .enumerate()
        .map(|(i, y)| {
            let m = &mlp.output_map;
            if m.max[i] > m.min[i] {
                (y + 1.0) * (m.max[i] - m.min[i]) / 2.0 + m.min[i]
            } else {
                y + m.min[i]
            }
        })
        .collect()
}

#[test]
fn the_run_time_kernels_move_the_shipped_networks_outputs_by_less_than_1e_9() {
    // mapminmax folded into the weights, padded blocks, the vectorised
    // tansig (and FMA where the CPU has it) against Matlab's formulas; on
    // x86-64 both the AVX2 + FMA kernels and the portable ones.
    let mut rng = Rng::new(5);
    let mut worst = 0.0f64;
    for (variant, dispatch) in [
        (Variant::Plain, true),
        (Variant::Rows, true),
        (Variant::Equivariant, true),
        (Variant::Equivariant, false),
    ] {
        redundant_ik::nn::kernel::set_runtime_dispatch(dispatch);
        let nets = Networks::embedded_with(variant).unwrap();
        let files = [nets.phi_file(), nets.v_file()];
        for file in files {
            for entry in &file.nets {
                let kernel = Kernel::new(&entry.mlp);
                let (lo, hi) = (&entry.mlp.input_map.min, &entry.mlp.input_map.max);
                let mut y = vec![0.0; kernel.outputs()];
                for _ in 0..2000 {
                    // Inside the trained box and 20% beyond it.
                    let x: Vec<f64> = lo
                        .iter()
                        .zip(hi)
                        .map(|(a, b)| a + (b - a) * rng.range(-0.2, 1.2))
                        .collect();
                    kernel.forward(&x, &mut y);
                    let r = reference_forward(&entry.mlp, &x);
                    for (a, b) in y.iter().zip(&r) {
                        worst = worst.max((a - b).abs() / (1.0 + b.abs()));
                    }
                }
            }
        }
    }
    redundant_ik::nn::kernel::set_runtime_dispatch(true);
    assert!(worst < 1e-9, "largest change {worst:e}");
    assert!(worst > 0.0, "the kernel must be its own computation");
}

#[test]
fn networks_wider_than_the_stack_buffers_run_the_same_kernel_through_the_heap() {
    // The whole-reach networks may be wide (Adam trains 96-96): the kernels
    // take them through a heap buffer (the SIMD build too, which carries no
    // portable kernel), with the same results.
    let mut rng = Rng::new(9);
    for sizes in [vec![4, 96, 96, 6], vec![3, 130, 2], vec![70, 8, 3]] {
        let n_in = sizes[0];
        let n_out = *sizes.last().unwrap();
        let input_map = MapMinMax::fit(&[-1.0, 1.0].repeat(n_in), n_in);
        let output_map = MapMinMax::fit(&[-2.0, 3.0].repeat(n_out), n_out);
        let mlp = Mlp::nguyen_widrow(&sizes, input_map, output_map, &mut rng).unwrap();
        let kernel = Kernel::new(&mlp);
        let mut y = vec![0.0; n_out];
        for _ in 0..200 {
            let x: Vec<f64> = (0..n_in).map(|_| rng.range(-1.2, 1.2)).collect();
            kernel.forward(&x, &mut y);
            for (a, b) in y.iter().zip(&reference_forward(&mlp, &x)) {
                assert!(
                    (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
                    "{sizes:?}: {a} vs {b}"
                );
            }
        }
    }
}

#[test]
fn tansig_is_within_5e_16_of_tanh() {
    let mut worst = 0.0f64;
    let n = 400_000;
    for i in 0..=n {
        for x in [
            -25.0 + 50.0 * i as f64 / n as f64,
            (i as f64 / n as f64 - 0.5) * 1e-3,
        ] {
            worst = worst.max((tansig(x) - x.tanh()).abs());
        }
    }
    assert!(worst < 5e-16, "{worst:e}");
    assert_eq!(tansig(0.0), 0.0);
    assert_eq!(tansig(1e300), 1.0);
    assert_eq!(tansig(f64::NEG_INFINITY), -1.0);
    assert!(tansig(f64::NAN).is_nan());
    assert!(tansig(-1e-300) <= 0.0);
}

/// The exact `Phi` dressed as a network: Case 1 with it must be the
/// numerical route.
struct ExactPhi(Networks);

impl Surrogate for ExactPhi {
    fn arm(&self) -> &Arm {
        Surrogate::arm(&self.0)
    }
    fn phi(&self, pose: &Pose, out: &mut [f64]) -> redundant_ik::Result<()> {
        ik::phi_into(pose.jacobian(), 0.0, out)
    }
    fn area_gradient(&self, pose: &Pose, o: [f64; 2], out: &mut [f64]) -> redundant_ik::Result<()> {
        self.0.area_gradient(pose, o, out)
    }
    fn phi_in_range(&self, _: &Pose) -> bool {
        true
    }
    fn v_in_range(&self, _: &Pose, _: [f64; 2]) -> bool {
        true
    }
}

#[test]
fn a_constant_delta_damps_the_network_phi_instead_of_replacing_it() {
    let exact: Arc<dyn Surrogate> = Arc::new(ExactPhi(Networks::embedded().unwrap()));
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    let mut scene = Scene::task1();
    scene.set_param(&methods::DELTA, 0.001).unwrap();
    let numerical = Planner::run(scene.clone(), Method::NUMERICAL, None).unwrap();
    // With an exact Phi, Case 1 with delta is the damped numerical route ...
    let case1_exact = Planner::run(scene.clone(), Method::CASE1, Some(exact)).unwrap();
    for (a, b) in numerical.steps.iter().zip(&case1_exact.steps) {
        for (x, y) in a.theta.iter().zip(&b.theta) {
            assert!((x - y).abs() < 1e-10);
        }
    }
    // ... and with the trained network it is the network's route, damped:
    // not the numerical route's numbers (the old silent swap), and within
    // the network's accuracy of them.
    let case1 = Planner::run(scene.clone(), Method::CASE1, Some(nets.clone())).unwrap();
    let (s, n) = (&case1.summary, &numerical.summary);
    assert_ne!(s.final_error, n.final_error);
    // Damping trades tracking for bounded rates: about 7 mm here on both.
    assert!(
        (s.final_error - n.final_error).abs() < 1e-3,
        "{s:?} vs {n:?}"
    );
    assert!(!s.collided);
    assert_eq!(s.handover_steps, 0, "a constant delta is no hand-over");
    // delta = 0 gives the undamped network route.
    scene.set_param(&methods::DELTA, 0.0).unwrap();
    let undamped = Planner::run(scene, Method::CASE1, Some(nets)).unwrap();
    assert_ne!(undamped.summary.final_error, s.final_error);
}

#[test]
fn near_a_singular_pose_the_damping_schedule_hands_phi_over_and_says_so() {
    // An out-of-reach target stretches the arm; the schedule switches on
    // automatically and, in Cases 1 and 3, the exact damped Phi stands in.
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    let mut scene = Scene::task1();
    scene.target = [2.5, 0.8];
    for &mode in methods::ALL {
        let run = Planner::run(scene.clone(), mode, Some(nets.clone())).unwrap();
        let s = &run.summary;
        assert!(s.auto_damping, "{mode}");
        let flagged = run.steps.iter().filter(|x| x.phi_handover).count();
        assert_eq!(flagged, s.handover_steps, "{mode}");
        if mode == Method::CASE1 {
            // Phi by the network, v exact: the arm stretches and the exact
            // damped Phi takes over.
            assert!(s.handover_steps > 10, "{}", s.handover_steps);
        } else if !mode.networks().phi {
            // No Phi network, nothing to hand over. (Case 3's v network, far
            // outside its trained range here, folds the arm instead: it
            // never comes near the singular pose.)
            assert_eq!(s.handover_steps, 0, "{mode}");
        }
    }
    // In the paper's scenes the networks work alone.
    for mode in methods::ALL.iter().copied().filter(|m| m.networks().phi) {
        let run = Planner::run(Scene::task2(), mode, Some(nets.clone())).unwrap();
        assert_eq!(run.summary.handover_steps, 0);
    }
}

#[test]
fn normal_equations_from_the_layer_structure_equal_those_from_the_jacobian_rows() {
    // J^T J = sum_s D^s (x) (a~ a~'^T) per layer pair (nn::kronecker) must be
    // the sum over J's rows of g g^T, and J^T e the sum of e g.
    let mut rng = Rng::new(9);
    for sizes in [vec![3, 5, 4, 2], vec![2, 7, 3], vec![4, 6, 5, 3, 2]] {
        let (n_in, n_out) = (sizes[0], *sizes.last().unwrap());
        let mlp = Mlp::nguyen_widrow(
            &sizes,
            MapMinMax::fit(&[-1.0, 1.0].repeat(n_in), n_in),
            MapMinMax::fit(&[-1.0, 1.0].repeat(n_out), n_out),
            &mut rng,
        )
        .unwrap();
        let samples = 37;
        let x: Vec<f64> = (0..samples * n_in).map(|_| rng.range(-1.0, 1.0)).collect();
        let t: Vec<f64> = (0..samples * n_out).map(|_| rng.range(-1.0, 1.0)).collect();
        let idx: Vec<usize> = (0..samples).collect();
        let mut acts = Activations::new(&sizes);
        // Blocks of 5 samples, so partial last blocks are exercised.
        let mut normal = redundant_ik::nn::kronecker::Normal::new(&sizes, 5);
        let (jtj, jte) = normal.accumulate(&mlp, &x, &t, &idx, &mut acts);
        let p = mlp.n_params();
        let (mut ref_jtj, mut ref_jte) = (vec![0.0; p * p], vec![0.0; p]);
        let mut jac = vec![0.0; n_out * p];
        for s in 0..samples {
            mlp.forward_scaled(&x[s * n_in..(s + 1) * n_in], &mut acts);
            let y = acts.output().to_vec();
            mlp.output_jacobian(&mut acts, &mut jac);
            for m in 0..n_out {
                let g = &jac[m * p..(m + 1) * p];
                let e = t[s * n_out + m] - y[m];
                for a in 0..p {
                    ref_jte[a] += e * g[a];
                    for b in 0..p {
                        ref_jtj[a * p + b] += g[a] * g[b];
                    }
                }
            }
        }
        let scale = ref_jtj.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for a in 0..p {
            assert!(
                (jte[a] - ref_jte[a]).abs() < 1e-12 * scale,
                "{sizes:?} J^T e [{a}]"
            );
            for b in 0..p {
                let (got, want) = (jtj[(a, b)], ref_jtj[a * p + b]);
                assert!(
                    (got - want).abs() < 1e-12 * scale,
                    "{sizes:?} J^T J [{a}, {b}]: {got} vs {want}"
                );
            }
        }
    }
}

#[test]
fn the_blocked_cholesky_solves_like_nalgebras_and_refuses_what_is_not_positive_definite() {
    use redundant_ik::nalgebra::DMatrix;
    use redundant_ik::nn::cholesky;
    let mut rng = Rng::new(3);
    // Sizes around the block width (64), and the trainer's 699.
    for n in [1, 2, 63, 64, 65, 130, 200, 699] {
        let m = DMatrix::from_fn(n, n / 2 + 1, |_, _| rng.range(-1.0, 1.0));
        let a = &m * m.transpose() + DMatrix::identity(n, n) * 1e-3;
        let b = DVector::from_fn(n, |_, _| rng.range(-1.0, 1.0));
        let x = cholesky::solve_spd(a.clone(), &b).unwrap();
        let reference = a.clone().cholesky().unwrap().solve(&b);
        let rel = (&x - &reference).norm() / reference.norm();
        assert!(rel < 1e-8, "n = {n}: {rel:e}");
        assert!(
            (&a * &x - &b).norm() < 1e-8 * b.norm() * a.norm(),
            "n = {n}"
        );
    }
    let mut indefinite = DMatrix::identity(70, 70);
    indefinite[(66, 66)] = -1.0;
    assert!(cholesky::solve_spd(indefinite, &DVector::zeros(70)).is_none());
    let mut nan = DMatrix::identity(3, 3);
    nan[(2, 2)] = f64::NAN;
    assert!(cholesky::solve_spd(nan, &DVector::zeros(3)).is_none());
}

#[test]
fn the_planner_refuses_networks_trained_for_another_arm() {
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    assert_eq!(nets.arm(), &Arm::paper());
    for arm in [
        Arm::new(0.5, vec![0.6, 0.85, 0.7]).unwrap(),
        Arm::new(0.4, vec![0.6, 0.85, 0.6]).unwrap(),
        Arm::new(0.5, vec![0.6, 0.85, 0.6, 0.4]).unwrap(),
    ] {
        let mut scene = Scene::task1();
        scene.theta0 = vec![0.2; arm.dof()];
        scene.arm = arm.clone();
        // In any mode: networks for another arm are never installed.
        for mode in [Method::NUMERICAL, Method::CASE3] {
            let err = Planner::new(scene.clone(), mode, Some(nets.clone())).unwrap_err();
            assert!(
                matches!(&err, Error::NetworksForAnotherArm { trained, arm: mine }
                    if trained.1 == [0.6, 0.85, 0.6] && mine.1 == arm.links()),
                "{err:?}"
            );
        }
        let mut p = Planner::new(scene, Method::NUMERICAL, None).unwrap();
        assert!(matches!(
            p.set_networks(Some(nets.clone())),
            Err(Error::NetworksForAnotherArm { .. })
        ));
        assert!(p.networks().is_none(), "a refused change changes nothing");
    }
}
