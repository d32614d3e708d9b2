//! The forward pass, the weight Jacobian and the Levenberg-Marquardt trainer.

use super::*;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

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
