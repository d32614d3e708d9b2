//! Networks meant to hold over the whole workspace (`docs/learning.md`):
//! the refinement of a learned `Phi` toward the pseudoinverse by the
//! pose's `J`, angle features,
//! the smoothed sign of the area criterion, and the `reach` recipe's
//! sampling.

#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use std::f64::consts::PI;

use redundant_ik::nalgebra::{DVector, Vector2};
use redundant_ik::networks::{Encoding, NetKind, Variant, WeightsFile};
use redundant_ik::nn::rng::Rng;
use redundant_ik::planner::methods::REFINE;
use redundant_ik::training::{self, Recipe, TrainSpec, REACH_SIGN_SMOOTHING};
use redundant_ik::{ik, obstacle, Arm, Error, Pose, Scene};

/// `J Phi - I` as a row-major 2x2 array (`phi` row-major n x 2, `jac`
/// column-major 2 x n).
fn residual(jac: &[f64], phi: &[f64]) -> [[f64; 2]; 2] {
    let mut e = [[0.0; 2]; 2];
    for (j, p) in jac.chunks_exact(2).zip(phi.chunks_exact(2)) {
        for a in 0..2 {
            for b in 0..2 {
                e[a][b] += j[a] * p[b];
            }
        }
    }
    e[0][0] -= 1.0;
    e[1][1] -= 1.0;
    e
}

fn norm(e: &[[f64; 2]; 2]) -> f64 {
    e.iter().flatten().map(|x| x * x).sum::<f64>().sqrt()
}

fn square(e: &[[f64; 2]; 2]) -> [[f64; 2]; 2] {
    let mut s = [[0.0; 2]; 2];
    for a in 0..2 {
        for b in 0..2 {
            s[a][b] = e[a][0] * e[0][b] + e[a][1] * e[1][b];
        }
    }
    s
}

/// A pose of the paper's arm, its `J` (column-major) and its exact `Phi`
/// (row-major).
fn pose(theta: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let arm = Arm::paper();
    let p = Pose::new(&arm, theta).unwrap();
    let jac = p.jacobian().to_vec();
    let phi = training::sampling::phi_target(&arm, theta).unwrap();
    (jac, phi)
}

/// One plain Newton-Schulz step `Phi <- Phi (2I - J Phi)`, written here
/// on its own: the iteration `ik::refine_phi` was before it projected.
fn newton_schulz(phi: &mut [f64], jac: &[f64], steps: u32) {
    for _ in 0..steps {
        let e = residual(jac, phi);
        let m = [[1.0 - e[0][0], -e[0][1]], [-e[1][0], 1.0 - e[1][1]]];
        for row in phi.chunks_exact_mut(2) {
            let (x, y) = (row[0], row[1]);
            row[0] = x * m[0][0] + y * m[1][0];
            row[1] = x * m[0][1] + y * m[1][1];
        }
    }
}

/// `a b` for row-major 2x2 arrays.
fn mul(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2]) -> [[f64; 2]; 2] {
    let mut s = [[0.0; 2]; 2];
    for r in 0..2 {
        for c in 0..2 {
            s[r][c] = a[r][0] * b[0][c] + a[r][1] * b[1][c];
        }
    }
    s
}

fn transpose(a: &[[f64; 2]; 2]) -> [[f64; 2]; 2] {
    [[a[0][0], a[1][0]], [a[0][1], a[1][1]]]
}

/// `X^T Y` (2x2) of two row-major n x 2 matrices.
fn gram(x: &[f64], y: &[f64]) -> [[f64; 2]; 2] {
    let mut g = [[0.0; 2]; 2];
    for (a, b) in x.chunks_exact(2).zip(y.chunks_exact(2)) {
        for r in 0..2 {
            for c in 0..2 {
                g[r][c] += a[r] * b[c];
            }
        }
    }
    g
}

/// `J J^T` and its inverse, row-major.
fn a_and_inverse(jac: &[f64]) -> ([[f64; 2]; 2], [[f64; 2]; 2]) {
    let (mut p, mut q, mut r) = (0.0, 0.0, 0.0);
    for c in jac.chunks_exact(2) {
        p += c[0] * c[0];
        q += c[0] * c[1];
        r += c[1] * c[1];
    }
    let det = p * r - q * q;
    ([[p, q], [q, r]], [[r / det, -q / det], [-q / det, p / det]])
}

/// The pseudoinverse `J+ = J^T (J J^T)^-1` (row-major n x 2).
fn pinv(jac: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; jac.len()];
    ik::phi_into(jac, 0.0, &mut out).unwrap();
    out
}

/// A learned `Phi`: `exact` with a relative error `scale` per entry.
fn perturbed(exact: &[f64], scale: f64, rng: &mut Rng) -> Vec<f64> {
    exact
        .iter()
        .map(|x| x + scale * x.abs().max(0.1) * rng.normal())
        .collect()
}

fn max_abs(x: impl IntoIterator<Item = f64>) -> f64 {
    x.into_iter().fold(0.0, |m, v| m.max(v.abs()))
}

/// The largest entry of `P - P^T` for the null-space projector
/// `P = I - Phi J` (n x n): zero exactly when `P` is the orthogonal one.
fn projector_asymmetry(phi: &[f64], jac: &[f64]) -> f64 {
    let n = jac.len() / 2;
    // (Phi J)_ik = Phi_i . J_k (row i of Phi, column k of J).
    let pj = |i: usize, k: usize| phi[2 * i] * jac[2 * k] + phi[2 * i + 1] * jac[2 * k + 1];
    let mut worst = 0.0f64;
    for i in 0..n {
        for k in 0..i {
            worst = worst.max((pj(i, k) - pj(k, i)).abs());
        }
    }
    worst
}

#[test]
fn one_refinement_step_is_a_newton_schulz_step_then_the_projection_onto_the_range_of_jt() {
    let mut rng = Rng::new(3);
    for _ in 0..200 {
        let theta: Vec<f64> = (0..3).map(|_| rng.range(-PI, PI)).collect();
        let (jac, exact) = pose(&theta);
        if exact.iter().any(|x| x.abs() > 20.0) {
            continue; // near a singular pose
        }
        let scale = rng.range(0.01, 0.2);
        let phi0 = perturbed(&exact, scale, &mut rng);
        let e0 = residual(&jac, &phi0);
        let mut phi = phi0.clone();
        ik::refine_phi(&mut phi, &jac, 1).unwrap();
        // refine 1 = Phi1 = Phi0 (2I - J Phi0), then J^T (Phi1^T Phi1).
        let mut phi1 = phi0.clone();
        newton_schulz(&mut phi1, &jac, 1);
        let g = gram(&phi1, &phi1);
        for (i, col) in jac.chunks_exact(2).enumerate() {
            for c in 0..2 {
                let want = col[0] * g[0][c] + col[1] * g[1][c];
                let tol = 1e-12 * want.abs().max(1.0);
                assert!((phi[2 * i + c] - want).abs() < tol, "{phi:?}");
            }
        }
        // Its error is of second order: with A = J J^T and D1 = Phi1 - J+,
        // J Phi - I = -E0^2 - A (E0^2)^T A^-1 + A D1^T D1 (eq. of
        // ik::refine_phi), where plain Newton-Schulz leaves -E0^2.
        let (a, a_inv) = a_and_inverse(&jac);
        let d1: Vec<f64> = phi1.iter().zip(&exact).map(|(p, x)| p - x).collect();
        let e2 = square(&e0);
        let t1 = mul(&mul(&a, &transpose(&e2)), &a_inv);
        let t2 = mul(&a, &gram(&d1, &d1));
        let e1 = residual(&jac, &phi);
        for r in 0..2 {
            for c in 0..2 {
                let want = -e2[r][c] - t1[r][c] + t2[r][c];
                assert!(
                    (e1[r][c] - want).abs() < 1e-11 * (1.0 + norm(&e0)),
                    "E1 = {e1:?}, want {want} at ({r}, {c})"
                );
            }
        }
        // Every further step is a plain Newton-Schulz step, which squares
        // the error: J Phi_{k+1} - I = -(J Phi_k - I)^2.
        let (mut phi_k, mut e_k) = (phi.clone(), e1);
        for k in 2..=3u32 {
            let mut again = phi0.clone();
            ik::refine_phi(&mut again, &jac, k).unwrap();
            newton_schulz(&mut phi_k, &jac, 1);
            for (x, y) in again.iter().zip(&phi_k) {
                assert!((x - y).abs() <= 1e-12 * y.abs().max(1.0), "step {k}");
            }
            let e_next = residual(&jac, &again);
            let want = square(&e_k);
            for r in 0..2 {
                for c in 0..2 {
                    assert!(
                        (e_next[r][c] + want[r][c]).abs() < 1e-12 * (1.0 + norm(&e_k)).powi(2),
                        "step {k}: {e_next:?} vs -{want:?}"
                    );
                }
            }
            e_k = e_next;
        }
    }
}

#[test]
fn refinement_converges_to_the_pseudoinverse_and_plain_newton_schulz_to_another_right_inverse() {
    // Random arms of 3-6 links, J+ with a relative error of 1-10 %.
    let mut rng = Rng::new(11);
    let mut checked = 0;
    while checked < 300 {
        let n = 3 + rng.below(4);
        let links: Vec<f64> = (0..n).map(|_| rng.range(0.2, 0.8)).collect();
        let arm = Arm::new(0.5, links).unwrap();
        let theta: Vec<f64> = (0..n).map(|_| rng.range(-PI, PI)).collect();
        let jac = Pose::new(&arm, &theta).unwrap().jacobian().to_vec();
        let exact = pinv(&jac);
        let size = max_abs(exact.iter().copied());
        if size > 20.0 {
            continue; // near a singular pose
        }
        checked += 1;
        let phi0 = perturbed(&exact, rng.range(0.01, 0.1), &mut rng);
        let mut refined = phi0.clone();
        ik::refine_phi(&mut refined, &jac, 8).unwrap();
        let mut plain = phi0.clone();
        newton_schulz(&mut plain, &jac, 8);
        // Both end as right inverses of J ...
        assert!(norm(&residual(&jac, &refined)) < 1e-12, "n = {n}");
        assert!(norm(&residual(&jac, &plain)) < 1e-12, "n = {n}");
        // ... but only the refinement at J+, with the orthogonal
        // null-space projector I - Phi J.
        let off = |phi: &[f64]| max_abs(phi.iter().zip(&exact).map(|(p, x)| p - x)) / size;
        assert!(
            off(&refined) < 1e-10,
            "n = {n}: |Phi - J+| = {:.1e}",
            off(&refined)
        );
        assert!(
            projector_asymmetry(&refined, &jac) < 1e-10,
            "n = {n}: asymmetry {:.1e}",
            projector_asymmetry(&refined, &jac)
        );
        // Plain Newton-Schulz keeps the network's null-space error.
        assert!(off(&plain) > 1e-5, "n = {n}: {:.1e}", off(&plain));
        assert!(projector_asymmetry(&plain, &jac) > 1e-6, "n = {n}");
    }
}

#[test]
fn a_refined_phi_takes_the_damping_and_the_joint_weights_of_eq_20_exactly() {
    // ik::damp_phi and ik::weight_phi are exact for an exact Phi_0; after
    // refinement a learned one is exact too, after plain Newton-Schulz not.
    let mut rng = Rng::new(5);
    let mut checked = 0;
    while checked < 100 {
        let n = 3 + rng.below(4);
        let links: Vec<f64> = (0..n).map(|_| rng.range(0.2, 0.8)).collect();
        let arm = Arm::new(0.5, links).unwrap();
        let theta: Vec<f64> = (0..n).map(|_| rng.range(-PI, PI)).collect();
        let jac = Pose::new(&arm, &theta).unwrap().jacobian().to_vec();
        let exact = pinv(&jac);
        let size = max_abs(exact.iter().copied());
        if size > 20.0 {
            continue;
        }
        checked += 1;
        let phi0 = perturbed(&exact, 0.05, &mut rng);
        let delta = rng.range(1e-3, 1e-2);
        let winv: Vec<f64> = (0..n).map(|_| rng.range(0.2, 1.0)).collect();
        let mut damped = vec![0.0; jac.len()];
        ik::phi_into(&jac, delta, &mut damped).unwrap();
        let mut weighted = vec![0.0; jac.len()];
        ik::phi_weighted_into(&jac, &winv, delta, &mut weighted).unwrap();
        let gap = |a: &[f64], b: &[f64]| max_abs(a.iter().zip(b).map(|(x, y)| x - y)) / size;
        let mut refined = phi0.clone();
        ik::refine_phi(&mut refined, &jac, 8).unwrap();
        let mut plain = phi0.clone();
        newton_schulz(&mut plain, &jac, 8);
        for (phi, exact_after) in [(&refined, true), (&plain, false)] {
            let mut d = phi.clone();
            ik::damp_phi(&mut d, delta).unwrap();
            let mut w = phi.clone();
            ik::weight_phi(&mut w, &jac, &winv, delta).unwrap();
            if exact_after {
                assert!(gap(&d, &damped) < 1e-10, "damped: {:.1e}", gap(&d, &damped));
                assert!(
                    gap(&w, &weighted) < 1e-10,
                    "weighted: {:.1e}",
                    gap(&w, &weighted)
                );
            } else {
                assert!(gap(&d, &damped) > 1e-5, "damped: {:.1e}", gap(&d, &damped));
                assert!(
                    gap(&w, &weighted) > 1e-5,
                    "weighted: {:.1e}",
                    gap(&w, &weighted)
                );
            }
        }
    }
}

#[test]
fn refinement_leaves_an_exact_pseudoinverse_as_it_is() {
    for theta in [
        [0.3, 1.2, -0.7],
        [PI / 12.0, PI / 2.0, -PI / 6.0],
        [2.0, -1.0, 2.5],
    ] {
        let (jac, exact) = pose(&theta);
        let mut phi = exact.clone();
        ik::refine_phi(&mut phi, &jac, 4).unwrap();
        for (a, b) in phi.iter().zip(&exact) {
            assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "{a} vs {b}");
        }
    }
}

#[test]
fn refinement_refuses_mismatched_sizes_and_reports_a_blow_up() {
    let (jac, exact) = pose(&[0.3, 1.2, -0.7]);
    let mut short = exact[..4].to_vec();
    assert!(matches!(
        ik::refine_phi(&mut short, &jac, 1),
        Err(Error::DimensionMismatch { .. })
    ));
    // A "Phi" far from any inverse (|E| > 1) diverges: refused, not NaN.
    let mut wild: Vec<f64> = exact.iter().map(|x| 1e3 * x + 50.0).collect();
    assert!(ik::refine_phi(&mut wild, &jac, 8).is_err());
}

#[test]
fn refine_is_a_whole_number_of_steps_and_scenes_without_it_stay_as_they_were() {
    let mut scene = Scene::task1();
    for bad in [-1.0, 1.5, 9.0, f64::NAN] {
        assert!(scene.set_param(&REFINE, bad).is_err(), "{bad}");
        assert_eq!(scene.param(&REFINE), 0.0);
    }
    scene.set_param(&REFINE, 2.0).unwrap();
    assert_eq!(scene.params.count(&REFINE), 2);
    // A scene written before the parameter existed reads as the paper's.
    let mut json = serde_json::to_value(Scene::task1()).unwrap();
    assert_eq!(json["params"]["refine"], 0.0);
    json.as_object_mut().unwrap().remove("params");
    let back: Scene = serde_json::from_value(json).unwrap();
    assert_eq!(back, Scene::task1());
}

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
    assert_eq!(WeightsFile::from_json(&json).unwrap(), file);
    // The paper's files carry no encoding and read as raw angles.
    let mut raw = Recipe::Paper.spec(&arm, NetKind::V, 1);
    raw.samples = 60;
    raw.hidden = vec![4];
    raw.set_max_epochs(2);
    let old = training::train_weights(&raw, |_, _| true).unwrap();
    let json = old.to_json().unwrap();
    assert!(!json.contains("encoding"));
    assert_eq!(
        WeightsFile::from_json(&json).unwrap().encoding,
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
    assert_eq!(WeightsFile::from_json(&json).unwrap(), file);
    // The same seed gives the same weights through the whole recipe.
    let again = training::train_weights(&small, |_, _| true).unwrap();
    assert_eq!(again.nets[0].mlp, file.nets[0].mlp);
}
