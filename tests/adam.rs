//! Adam with minibatches (`nn::adam`): reproducible for a seed, it fits
//! known functions, bad options are errors, and the batched gradient is the
//! derivative of the batch loss. The Phi-over-the-torus workload of
//! `docs/speed.md` is the ignored test at the end.

#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use redundant_ik::nn::adam::{self, AdamOptions, Decay};
use redundant_ik::nn::backprop::Backprop;
use redundant_ik::nn::lm::{self, LmOptions};
use redundant_ik::nn::mlp::{MapMinMax, Mlp};
use redundant_ik::nn::{Dataset, Rng, StopReason};
use redundant_ik::Error;

/// `y = sin(x)` on 200 points of `[-pi, pi]`.
fn sine_data() -> Dataset {
    let mut d = Dataset::new(1, 1);
    for i in 0..200 {
        let x = -std::f64::consts::PI + i as f64 * std::f64::consts::TAU / 199.0;
        d.push(&[x], &[x.sin()]);
    }
    d
}

/// A smooth 2-in/2-out map on 400 random points of `[-1, 1]^2`.
fn smooth_data() -> Dataset {
    let mut rng = Rng::new(7);
    let mut d = Dataset::new(2, 2);
    for _ in 0..400 {
        let (a, b) = (rng.range(-1.0, 1.0), rng.range(-1.0, 1.0));
        d.push(&[a, b], &[(a * b).sin() + 0.5 * a, (a - b).cos() * b]);
    }
    d
}

fn quick() -> AdamOptions {
    AdamOptions {
        max_epochs: 300,
        batch: 16,
        learning_rate: 1e-2,
        patience: 300,
        ..AdamOptions::default()
    }
}

#[test]
fn a_seed_fixes_the_weights() {
    let data = smooth_data();
    let opts = AdamOptions {
        max_epochs: 20,
        ..quick()
    };
    let (a, ra) = adam::train(&[2, 6, 5, 2], &data, opts, 3, |_| true).unwrap();
    let (b, rb) = adam::train(&[2, 6, 5, 2], &data, opts, 3, |_| true).unwrap();
    assert_eq!(a, b);
    assert_eq!(ra, rb);
    let (c, _) = adam::train(&[2, 6, 5, 2], &data, opts, 4, |_| true).unwrap();
    assert_ne!(a, c, "another seed, other weights");
}

#[test]
fn it_fits_the_sine_below_1e_4() {
    let opts = AdamOptions {
        max_epochs: 600,
        patience: 600,
        ..quick()
    };
    let (mlp, report) = adam::train(&[1, 10, 1], &sine_data(), opts, 1, |_| true).unwrap();
    // Mean squared error in mapminmax units ([-1, 1]), as the LM test states it.
    assert!(report.test_mse < 1e-4, "{report:?}");
    assert!(report.train_mse < 1e-4, "{report:?}");
    let y = mlp.forward(&[1.0])[0];
    assert!((y - 1f64.sin()).abs() < 2e-2, "sin(1) = {y}");
}

#[test]
fn it_fits_a_smooth_two_by_two_map_below_1e_3() {
    let data = smooth_data();
    let mut first = None;
    let (_, report) = adam::train(&[2, 12, 8, 2], &data, quick(), 1, |r| {
        first.get_or_insert(r.train_mse);
        true
    })
    .unwrap();
    assert!(report.test_mse < 1e-3, "{report:?}");
    assert!(report.train_mse < first.unwrap() / 50.0, "{report:?}");
    assert!(report.best_epoch > 0);
}

#[test]
fn it_starts_from_the_split_of_levenberg_marquardt() {
    let data = smooth_data();
    let one = AdamOptions {
        max_epochs: 1,
        ..quick()
    };
    let lm_one = LmOptions {
        max_epochs: 1,
        ..LmOptions::default()
    };
    let (_, ra) = adam::train(&[2, 4, 2], &data, one, 9, |_| true).unwrap();
    let (_, rl) = lm::train(&[2, 4, 2], &data, lm_one, 9, |_| true).unwrap();
    assert_eq!(ra.split, rl.split);
    assert_eq!(ra.split, [280, 60, 60]);
}

#[test]
fn the_callback_can_stop_it_and_patience_ends_it() {
    let mut seen = 0;
    let (_, r) = adam::train(&[1, 4, 1], &sine_data(), quick(), 1, |r| {
        seen = r.epoch;
        r.epoch < 5
    })
    .unwrap();
    assert_eq!((r.stop, r.epochs, seen), (StopReason::Cancelled, 5, 5));
    // A constant rate far too large for the data keeps failing validation.
    let noisy = AdamOptions {
        learning_rate: 0.5,
        decay: Decay::Constant,
        patience: 3,
        ..quick()
    };
    let (_, r) = adam::train(&[1, 4, 1], &sine_data(), noisy, 1, |_| true).unwrap();
    assert!(
        matches!(r.stop, StopReason::ValidationStop | StopReason::Diverged),
        "{r:?}"
    );
    assert!(r.epochs < 300);
}

#[test]
fn a_diverging_rate_stops_with_finite_weights() {
    let wild = AdamOptions {
        learning_rate: 1e300,
        decay: Decay::Constant,
        ..quick()
    };
    let (mlp, r) = adam::train(&[1, 4, 1], &sine_data(), wild, 1, |_| true).unwrap();
    assert!(mlp.validate().is_ok(), "the kept weights are finite");
    assert!(
        matches!(r.stop, StopReason::Diverged | StopReason::ValidationStop),
        "{r:?}"
    );
}

#[test]
fn bad_options_are_errors_not_panics() {
    let data = sine_data();
    let base = quick();
    let bad = [
        AdamOptions {
            max_epochs: 0,
            ..base
        },
        AdamOptions { batch: 0, ..base },
        AdamOptions {
            learning_rate: f64::NAN,
            ..base
        },
        AdamOptions {
            learning_rate: 0.0,
            ..base
        },
        AdamOptions {
            learning_rate: f64::INFINITY,
            ..base
        },
        AdamOptions { beta1: 1.0, ..base },
        AdamOptions {
            beta2: -0.1,
            ..base
        },
        AdamOptions {
            beta2: f64::NAN,
            ..base
        },
        AdamOptions { eps: 0.0, ..base },
        AdamOptions {
            patience: 0,
            ..base
        },
        AdamOptions {
            decay: Decay::Cosine { floor: f64::NAN },
            ..base
        },
        AdamOptions {
            decay: Decay::Cosine { floor: 1.5 },
            ..base
        },
        AdamOptions {
            decay: Decay::Step {
                every: 0,
                factor: 0.5,
            },
            ..base
        },
        AdamOptions {
            decay: Decay::Step {
                every: 10,
                factor: 0.0,
            },
            ..base
        },
        AdamOptions {
            split: [f64::NAN, 0.15],
            ..base
        },
        AdamOptions {
            split: [0.9, 0.2],
            ..base
        },
    ];
    for opts in bad {
        match adam::train(&[1, 4, 1], &data, opts, 1, |_| true) {
            Err(Error::Training(msg)) => assert!(!msg.is_empty()),
            other => panic!("{opts:?} gave {other:?}"),
        }
    }
    // Data that does not fit the network, or holds NaN, or is too small.
    assert!(adam::train(&[2, 4, 1], &data, base, 1, |_| true).is_err());
    let mut nan = sine_data();
    nan.targets[3] = f64::NAN;
    assert!(adam::train(&[1, 4, 1], &nan, base, 1, |_| true).is_err());
    let empty = Dataset::new(1, 1);
    assert!(adam::train(&[1, 4, 1], &empty, base, 1, |_| true).is_err());
    // A batch larger than the training set is fine: one step per epoch.
    let huge = AdamOptions {
        batch: usize::MAX,
        max_epochs: 3,
        ..base
    };
    assert!(adam::train(&[1, 4, 1], &data, huge, 1, |_| true).is_ok());
}

#[test]
fn options_read_from_json_refuse_unknown_fields() {
    let opts: AdamOptions = serde_json::from_str(
        r#"{"batch": 32, "decay": {"kind": "step", "every": 10, "factor": 0.5}}"#,
    )
    .unwrap();
    assert_eq!(opts.batch, 32);
    assert_eq!(opts.max_epochs, AdamOptions::default().max_epochs);
    assert!(serde_json::from_str::<AdamOptions>(r#"{"batch_size": 32}"#).is_err());
    assert!(
        serde_json::from_str::<AdamOptions>(r#"{"decay": {"kind": "cosine", "flor": 0.1}}"#)
            .is_err()
    );
    // A decay's own fields are required and no other's are taken.
    for bad in [
        r#"{"kind": "cosine"}"#,
        r#"{"kind": "step", "every": 10}"#,
        r#"{"kind": "constant", "floor": 0.1}"#,
        r#"{"kind": "cosine", "floor": 0.1, "factor": 0.5}"#,
        r#"{"kind": "linear"}"#,
    ] {
        assert!(serde_json::from_str::<Decay>(bad).is_err(), "{bad}");
    }
    // Every decay writes and reads back as itself.
    for d in [
        Decay::Constant,
        Decay::Cosine { floor: 0.01 },
        Decay::Step {
            every: 250,
            factor: 0.3,
        },
    ] {
        let json = serde_json::to_string(&d).unwrap();
        assert_eq!(serde_json::from_str::<Decay>(&json).unwrap(), d, "{json}");
    }
    assert_eq!(
        serde_json::to_string(&Decay::Cosine { floor: 0.01 }).unwrap(),
        r#"{"kind":"cosine","floor":0.01}"#
    );
}

#[test]
fn the_learning_rate_follows_its_schedule() {
    let cosine = AdamOptions {
        max_epochs: 101,
        learning_rate: 1.0,
        decay: Decay::Cosine { floor: 0.1 },
        ..AdamOptions::default()
    };
    assert_eq!(cosine.rate(1), 1.0);
    assert!((cosine.rate(51) - 0.55).abs() < 1e-12);
    assert!((cosine.rate(101) - 0.1).abs() < 1e-12);
    let step = AdamOptions {
        decay: Decay::Step {
            every: 10,
            factor: 0.5,
        },
        ..cosine
    };
    assert_eq!(
        (step.rate(10), step.rate(11), step.rate(21)),
        (1.0, 0.5, 0.25)
    );
}

#[test]
fn the_batch_gradient_matches_finite_differences() {
    let mut rng = Rng::new(5);
    let sizes = [3, 7, 5, 2];
    let maps = (
        MapMinMax {
            min: vec![-1.0; 3],
            max: vec![1.0; 3],
        },
        MapMinMax {
            min: vec![-1.0; 2],
            max: vec![1.0; 2],
        },
    );
    let mut mlp = Mlp::nguyen_widrow(&sizes, maps.0, maps.1, &mut rng).unwrap();
    let b = 9;
    let x: Vec<f64> = (0..b * 3).map(|_| rng.range(-1.0, 1.0)).collect();
    let t: Vec<f64> = (0..b * 2).map(|_| rng.range(-1.0, 1.0)).collect();
    let mut passes = Backprop::new(&sizes, 16);
    let n = mlp.n_params();
    let mut grad = vec![0.0; n];
    let loss = passes.loss_and_gradient(&mlp, &x, &t, &mut grad).unwrap();
    // The loss is the batch MSE of the reference forward pass.
    let mut acts = redundant_ik::nn::mlp::Activations::new(&sizes);
    let mut sse = 0.0;
    for s in 0..b {
        mlp.forward_scaled(&x[s * 3..(s + 1) * 3], &mut acts);
        sse += acts
            .output()
            .iter()
            .zip(&t[s * 2..(s + 1) * 2])
            .map(|(y, t)| (y - t) * (y - t))
            .sum::<f64>();
    }
    assert!((loss - sse / (2 * b) as f64).abs() < 1e-14, "{loss}");
    let p0 = mlp.params();
    let mut scratch = vec![0.0; n];
    let h = 1e-6;
    let mut worst: f64 = 0.0;
    for k in 0..n {
        let mut p = p0.clone();
        p[k] = p0[k] + h;
        mlp.set_params(&p);
        let up = passes
            .loss_and_gradient(&mlp, &x, &t, &mut scratch)
            .unwrap();
        p[k] = p0[k] - h;
        mlp.set_params(&p);
        let down = passes
            .loss_and_gradient(&mlp, &x, &t, &mut scratch)
            .unwrap();
        let fd = (up - down) / (2.0 * h);
        worst = worst.max((fd - grad[k]).abs() / (grad[k].abs() + 1e-3));
    }
    assert!(worst < 1e-6, "largest relative difference {worst}");
    // Shapes that do not fit are errors.
    assert!(passes
        .loss_and_gradient(&mlp, &x[..4], &t, &mut grad)
        .is_err());
    assert!(passes.loss_and_gradient(&mlp, &[], &[], &mut grad).is_err());
}

/// The workload of `docs/speed.md`, natively only (it takes minutes).
#[cfg(not(target_family = "wasm"))]
mod workload {
    use super::*;

    /// `count` poses of the paper's arm uniform on the joint torus (`theta_1 =
    /// 0`), those with `sigma_min(J) < 0.15` rejected: inputs `(sin t2, cos t2,
    /// sin t3, cos t3)`, targets `Phi(0, t2, t3)` row-major (3 x 2).
    fn phi_torus(count: usize, seed: u64) -> Dataset {
        use redundant_ik::training::sampling::phi_target;
        use redundant_ik::{ik, nalgebra::DVector, Arm};
        let arm = Arm::paper();
        let mut rng = Rng::new(seed);
        let mut d = Dataset::new(4, 6);
        while d.len() < count {
            let pi = std::f64::consts::PI;
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

    /// Median of `|Phi_net - Phi|_F / |Phi|_F` over a set.
    fn median_relative_error(mlp: &Mlp, set: &Dataset) -> f64 {
        let mut errs: Vec<f64> = (0..set.len())
            .map(|i| {
                let y = mlp.forward(&set.inputs[i * 4..(i + 1) * 4]);
                let t = &set.targets[i * 6..(i + 1) * 6];
                let num: f64 = y.iter().zip(t).map(|(a, b)| (a - b) * (a - b)).sum();
                let den: f64 = t.iter().map(|b| b * b).sum();
                (num / den).sqrt()
            })
            .collect();
        errs.sort_by(f64::total_cmp);
        errs[errs.len() / 2]
    }

    fn env<T: std::str::FromStr>(name: &str, default: T) -> T {
        std::env::var(name)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    }

    /// The workload of `docs/speed.md` ("Adam"): Phi of the paper's arm over the
    /// whole torus, 20,000 samples, held-out error on 2,000 fresh ones.
    /// `cargo test --release --test adam -- --ignored --nocapture`; the
    /// recipe is read from `ADAM_HIDDEN` (96,96), `ADAM_EPOCHS`, `ADAM_BATCH`,
    /// `ADAM_LR`, `ADAM_FLOOR` (cosine) or `ADAM_STEP=every,factor`, `ADAM_SEED`,
    /// `ADAM_SAMPLES`; `ADAM_LM=1` trains
    /// by Levenberg-Marquardt instead (for 35,14).
    #[test]
    #[ignore = "a workload of minutes: run with --release -- --ignored --nocapture"]
    fn phi_over_the_torus() {
        let hidden: Vec<usize> = env("ADAM_HIDDEN", "96,96".to_string())
            .split(',')
            .map(|s| s.trim().parse().unwrap())
            .collect();
        let sizes: Vec<usize> = [4].into_iter().chain(hidden).chain([6]).collect();
        let data = phi_torus(env("ADAM_SAMPLES", 20_000), 1);
        let fresh = phi_torus(2_000, 2);
        let seed = env("ADAM_SEED", 1u64);
        #[allow(clippy::disallowed_methods)] // a native timing
        let start = std::time::Instant::now();
        let (mlp, report) = if env("ADAM_LM", 0) == 1 {
            let opts = LmOptions {
                max_epochs: env("ADAM_EPOCHS", 400),
                ..LmOptions::default()
            };
            lm::train(&sizes, &data, opts, seed, |_| true).unwrap()
        } else {
            let defaults = AdamOptions::default();
            let opts = AdamOptions {
                max_epochs: env("ADAM_EPOCHS", defaults.max_epochs),
                batch: env("ADAM_BATCH", defaults.batch),
                learning_rate: env("ADAM_LR", defaults.learning_rate),
                decay: match env("ADAM_STEP", String::new()).split_once(',') {
                    Some((every, factor)) => Decay::Step {
                        every: every.parse().unwrap(),
                        factor: factor.parse().unwrap(),
                    },
                    None => Decay::Cosine {
                        floor: env("ADAM_FLOOR", 0.01),
                    },
                },
                patience: env("ADAM_EPOCHS", defaults.max_epochs),
                ..defaults
            };
            let every = env("ADAM_EVERY", 0usize);
            adam::train(&sizes, &data, opts, seed, |r| {
                if every > 0 && r.epoch % every == 0 {
                    eprintln!(
                        "epoch {} lr {:.2e} train {:.3e} best val {:.3e} |g| {:.2e} {:.1} s",
                        r.epoch,
                        r.mu,
                        r.train_mse,
                        r.val_mse,
                        r.gradient,
                        start.elapsed().as_secs_f64()
                    );
                }
                true
            })
            .unwrap()
        };
        let seconds = start.elapsed().as_secs_f64();
        println!(
            "{sizes:?}: median relative error {:.3e} on 2,000 fresh samples, {seconds:.1} s, {report:?}",
            median_relative_error(&mlp, &fresh)
        );
    }
}
