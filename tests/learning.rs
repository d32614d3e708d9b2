//! Networks meant to hold over the whole workspace (`docs/learning.md`):
//! angle features, the smoothed sign of the area criterion, and the `reach`
//! recipe's sampling (the refinement of a learned `Phi` is
//! `refinement.rs`'s).

#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use std::f64::consts::PI;

use redundant_ik::nalgebra::{DVector, Vector2};
use redundant_ik::networks::{Encoding, NetKind, Variant, WeightsFile};
use redundant_ik::nn::rng::Rng;
use redundant_ik::training::{self, Recipe, TrainSpec, REACH_SIGN_SMOOTHING};
use redundant_ik::{ik, obstacle, Arm, Error};

/// The smoothed criterion `sum_k sqrt(D_k^2 + eps^2)` (in units where
/// `v = (lambda / 4) g` is its gradient with `lambda = 4`), by the
/// triangles' determinants.
fn smoothed_criterion(arm: &Arm, theta: &[f64], o: [f64; 2], eps: f64) -> f64 {
    let joints = arm.joints(&DVector::from_column_slice(theta));
    obstacle::triangle_determinants(&joints, &Vector2::new(o[0], o[1]))
        .iter()
        .map(|d| d.hypot(eps))
        .sum()
}

#[test]
fn the_smoothed_sign_is_the_gradient_of_the_smoothed_criterion() {
    let arm = Arm::paper();
    let mut rng = Rng::new(11);
    for _ in 0..100 {
        let theta: Vec<f64> = (0..3).map(|_| rng.range(-PI, PI)).collect();
        let o = [rng.range(-1.5, 1.5), rng.range(0.0, 2.0)];
        let eps = REACH_SIGN_SMOOTHING;
        let g = obstacle::area_gradient_smoothed(
            &arm,
            &DVector::from_column_slice(&theta),
            &Vector2::new(o[0], o[1]),
            eps,
        );
        for i in 0..3 {
            let h = 1e-6;
            let mut plus = theta.clone();
            let mut minus = theta.clone();
            plus[i] += h;
            minus[i] -= h;
            let fd = (smoothed_criterion(&arm, &plus, o, eps)
                - smoothed_criterion(&arm, &minus, o, eps))
                / (2.0 * h);
            assert!(
                (g[i] - fd).abs() < 1e-6 * (1.0 + fd.abs()),
                "joint {i}: {} vs {fd}",
                g[i]
            );
        }
        // eps = 0 is the paper's sign.
        let paper = obstacle::area_gradient(
            &arm,
            &DVector::from_column_slice(&theta),
            &Vector2::new(o[0], o[1]),
        );
        let zero = obstacle::area_gradient_smoothed(
            &arm,
            &DVector::from_column_slice(&theta),
            &Vector2::new(o[0], o[1]),
            0.0,
        );
        assert_eq!(paper, zero);
    }
    assert_eq!(obstacle::smoothed_sign(-2.0, 0.0), -1.0);
    assert!((obstacle::smoothed_sign(1e-3, 0.1) - 1e-2).abs() < 1e-5);
}

#[test]
fn the_reach_recipe_draws_phi_over_the_whole_torus_above_the_floor() {
    let arm = Arm::paper();
    let spec = TrainSpec::reach(&arm, NetKind::Phi, 4);
    assert!(spec.sampling.whole_torus);
    assert_eq!(
        (spec.variant, spec.encoding),
        (Variant::Equivariant, Encoding::Angles)
    );
    let floor = spec.sampling.sigma_floor;
    assert!((floor - 0.15).abs() < 1e-12, "the paper's arm: 0.15 m");
    let samples = training::draw_samples(&arm, &spec.sampling, 4000, 4).unwrap();
    // Every sample respects the floor; together they cover the torus: of
    // 12 x 12 bins of (theta_2, theta_3), all but those the floor empties
    // (around the stretched and folded poses) hold samples, and theta_1 is
    // uniform over its four quadrants.
    let bins = 12;
    let mut grid = vec![0usize; bins * bins];
    let mut quadrants = [0usize; 4];
    let bin = |a: f64| (((a + PI) / (2.0 * PI) * bins as f64) as usize).min(bins - 1);
    for s in &samples {
        let j = arm.jacobian(&DVector::from_column_slice(&s.theta));
        assert!(ik::smallest_singular_value(&j) >= floor);
        assert!(s.theta.iter().all(|t| (-PI..PI).contains(t)));
        grid[bin(s.theta[1]) * bins + bin(s.theta[2])] += 1;
        quadrants[((s.theta[0] + PI) / (PI / 2.0)) as usize % 4] += 1;
    }
    let filled = grid.iter().filter(|&&c| c > 0).count();
    assert!(filled >= 130, "{filled} of 144 bins hold samples");
    for q in quadrants {
        assert!((800..1200).contains(&q), "theta_1 quadrants {quadrants:?}");
    }
    // Another arm: the floor scales with the reach.
    let four = Arm::new(0.5, vec![0.6, 0.85, 0.6, 0.4]).unwrap();
    let spec4 = TrainSpec::reach(&four, NetKind::Phi, 4);
    let want = 0.15 * four.max_reach() / arm.max_reach();
    assert!((spec4.sampling.sigma_floor - want).abs() < 1e-12);
}

#[test]
fn the_reach_recipe_puts_obstacles_all_over_the_reach() {
    for arm in [
        Arm::paper(),
        Arm::new(0.5, vec![0.6, 0.85, 0.6, 0.4]).unwrap(),
    ] {
        let mut spec = TrainSpec::reach(&arm, NetKind::V, 2);
        assert_eq!(spec.sampling.sign_smoothing, REACH_SIGN_SMOOTHING);
        spec.sampling.random_tasks = 12;
        spec.sampling.obstacles_per_task = 10;
        let samples = training::draw_samples(&arm, &spec.sampling, 2000, 2).unwrap();
        let r = arm.max_reach();
        let post = arm.post();
        // The region is the atlas's: the box of the reach above the floor.
        assert_eq!(spec.sampling.obstacle_min, [-r, (post - r).max(0.0)]);
        assert_eq!(spec.sampling.obstacle_max, [r, post + r]);
        // Obstacles left and right of the post, below and above its top,
        // and out to most of the reach.
        let mut sides = [0usize; 4];
        let mut far = 0.0f64;
        for s in &samples {
            let [x, y] = s.obstacle;
            sides[usize::from(x > 0.0) + 2 * usize::from(y > post)] += 1;
            far = far.max(x.hypot(y - post));
        }
        assert!(sides.iter().all(|&c| c > 100), "{sides:?}");
        assert!(far > 0.85 * r, "farthest obstacle {far:.2} of {r:.2} m");
    }
}

#[test]
fn weights_files_record_their_encoding_and_old_files_read_as_raw() {
    let arm = Arm::paper();
    let mut spec = Recipe::Reach.spec(&arm, NetKind::Phi, 1);
    spec.samples = 60;
    spec.hidden = vec![4];
    spec.set_max_epochs(2);
    let file = training::train_weights(&spec, |_, _| true).unwrap();
    assert_eq!(file.encoding, Encoding::Angles);
    assert_eq!(file.range.names[..2], ["sin theta2", "cos theta2"]);
    let json = file.to_json().unwrap();
    assert!(json.contains("\"encoding\": \"angles\""));
    assert_eq!(<WeightsFile>::from_json(&json).unwrap(), file);
    // The paper's files carry no encoding and read as raw angles.
    let mut raw = Recipe::Paper.spec(&arm, NetKind::V, 1);
    raw.samples = 60;
    raw.hidden = vec![4];
    raw.set_max_epochs(2);
    let old = training::train_weights(&raw, |_, _| true).unwrap();
    let json = old.to_json().unwrap();
    assert!(!json.contains("encoding"));
    assert_eq!(
        <WeightsFile>::from_json(&json).unwrap().encoding,
        Encoding::Raw
    );
    // A file whose network does not fit its encoding is refused.
    let mut wrong = file.clone();
    wrong.encoding = Encoding::Raw;
    assert!(matches!(wrong.validate(), Err(Error::Weights(_))));
}

#[test]
fn the_reach_recipe_trains_phi_by_adam_and_the_file_says_so() {
    let arm = Arm::paper();
    // Phi: a network too wide for Levenberg-Marquardt's J^T J, by Adam.
    let phi = Recipe::Reach.spec(&arm, NetKind::Phi, 1);
    assert_eq!(phi.hidden, [96, 96]);
    let adam = phi.adam.expect("the reach recipe trains Phi by Adam");
    assert_eq!(phi.max_epochs(), adam.max_epochs);
    // v keeps the paper's widths and optimiser.
    let v = Recipe::Reach.spec(&arm, NetKind::V, 1);
    assert!(v.adam.is_none());
    assert_eq!(v.max_epochs(), v.options.max_epochs);

    let mut small = phi.clone();
    small.samples = 200;
    small.hidden = vec![8];
    small.set_max_epochs(3);
    let mut epochs = 0;
    let file = training::train_weights(&small, |_, _| {
        epochs += 1;
        true
    })
    .unwrap();
    assert_eq!(epochs, 3, "Adam runs the epochs it is given");
    let recorded = file.training.adam.expect("the file records Adam's options");
    assert_eq!(recorded.max_epochs, 3);
    let json = file.to_json().unwrap();
    assert_eq!(<WeightsFile>::from_json(&json).unwrap(), file);
    // The same seed gives the same weights through the whole recipe.
    let again = training::train_weights(&small, |_, _| true).unwrap();
    assert_eq!(again.nets[0].mlp, file.nets[0].mlp);
}
