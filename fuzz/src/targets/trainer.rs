//! The `trainer` target.

use arbitrary::Unstructured;
use redundant_ik::networks::{Encoding, NetKind, Sampling, Variant};
use redundant_ik::nn::lm::{self, Dataset, LmOptions};
use redundant_ik::training::{phi_datasets, v_dataset, Visited};
use redundant_ik::training_job::Request;
use redundant_ik::Arm;

use super::checks::assert_finite;
use super::gen::{arm, num, point, small};

/// The trainer's entry points with arbitrary small inputs:
/// - the page's training request as JSON (its checks and the specs it
///   makes);
/// - the datasets built from arbitrary visited poses and obstacle points;
/// - Levenberg-Marquardt on an arbitrary small dataset (NaN, infinities,
///   constant columns, one sample) with arbitrary options.
///
/// A trained network validates and has finite weights. (Drawing samples
/// runs whole planner trajectories, which the `scene` target covers.)
pub fn trainer(data: &[u8]) {
    let mut u = Unstructured::new(data);
    match u.int_in_range(0u8..=2).unwrap_or(2) {
        0 => {
            let text = String::from_utf8_lossy(u.take_rest());
            let Ok(request) = serde_json::from_str::<Request>(&text) else {
                return;
            };
            for net in [NetKind::Phi, NetKind::V] {
                if let Ok(spec) = request.spec(net) {
                    spec.sampling
                        .validate()
                        .expect("a request's sampling validates");
                }
            }
        }
        1 => {
            let (post, links) = arm(&mut u);
            let Ok(arm) = Arm::new(post, links) else {
                return;
            };
            let _ = Sampling::for_arm(&arm).validate();
            let samples = (0..small(&mut u, 12))
                .map(|_| Visited {
                    theta: (0..arm.dof().min(8)).map(|_| num(&mut u)).collect(),
                    obstacle: point(&mut u),
                })
                .collect::<Vec<_>>();
            let variant = *u
                .choose(&[Variant::Plain, Variant::Rows, Variant::Equivariant])
                .unwrap_or(&Variant::Plain);
            // Drawn last, the paper's when the input has ended, so that
            // inputs written before angle features make the same sets.
            let encoding = *u
                .choose(&[Encoding::Raw, Encoding::Angles])
                .unwrap_or(&Encoding::Raw);
            let eps = if u.is_empty() { 0.0 } else { num(&mut u) };
            for set in phi_datasets(&arm, variant, encoding, &samples)
                .into_iter()
                .flatten()
            {
                assert_finite("Phi training input", &set.inputs);
                assert_finite("Phi training target", &set.targets);
            }
            if let Ok(set) = v_dataset(&arm, variant, encoding, eps, &samples) {
                assert_finite("v training input", &set.inputs);
                assert_finite("v training target", &set.targets);
            }
        }
        _ => {
            let n_in = u.int_in_range(1usize..=3).unwrap_or(1);
            let n_out = u.int_in_range(1usize..=3).unwrap_or(1);
            let mut set = Dataset::new(n_in, n_out);
            for _ in 0..small(&mut u, 24) {
                let x: Vec<f64> = (0..n_in).map(|_| num(&mut u)).collect();
                let y: Vec<f64> = (0..n_out).map(|_| num(&mut u)).collect();
                set.push(&x, &y);
            }
            let mut sizes = vec![n_in];
            for _ in 0..small(&mut u, 2) {
                sizes.push(u.int_in_range(0usize..=5).unwrap_or(1));
            }
            sizes.push(n_out);
            let opts = LmOptions {
                max_epochs: u.int_in_range(0usize..=4).unwrap_or(1),
                mu: num(&mut u),
                mu_dec: num(&mut u),
                mu_inc: num(&mut u),
                mu_max: num(&mut u),
                min_grad: num(&mut u),
                max_fail: small(&mut u, 6),
                goal: num(&mut u),
                chunk: small(&mut u, 70),
                split: [num(&mut u), num(&mut u)],
            };
            let seed = u.arbitrary().unwrap_or(1);
            if let Ok((mlp, report)) = lm::train(&sizes, &set, opts, seed, |_| true) {
                mlp.validate().expect("a trained network validates");
                assert_finite("trained weight", &mlp.params());
                assert!(report.epochs <= opts.max_epochs);
            }
        }
    }
}
