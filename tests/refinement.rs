//! The refinement of a learned `Phi` toward the pseudoinverse by the
//! pose's `J` (`ik::refine_phi`, `docs/learning.md`, "Refinement").

#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use std::f64::consts::PI;

use redundant_ik::nn::rng::Rng;
use redundant_ik::planner::methods::REFINE;
use redundant_ik::{ik, training, Arm, Error, Pose, Scene};

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

/// The spectral radius of a 2 x 2 matrix.
fn spectral_radius(e: &[[f64; 2]; 2]) -> f64 {
    let (tr, det) = (e[0][0] + e[1][1], e[0][0] * e[1][1] - e[0][1] * e[1][0]);
    let disc = tr * tr - 4.0 * det;
    if disc >= 0.0 {
        0.5 * (tr.abs() + disc.sqrt())
    } else {
        det.sqrt()
    }
}

#[test]
fn one_refinement_step_is_a_newton_schulz_step_then_the_projection_onto_the_range_of_jt() {
    let mut rng = Rng::new(3);
    let (mut refined, mut refused) = (0, 0);
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
        if !ik::refine_phi(&mut phi, &jac, 1).unwrap() {
            // Refused: the network's error has a spectral radius of 1 or
            // more, and a step would only make it larger.
            assert!(spectral_radius(&e0) >= 1.0, "gave up at {e0:?}");
            refused += 1;
            continue;
        }
        refined += 1;
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
            if !ik::refine_phi(&mut again, &jac, k).unwrap() {
                // It gave up: the error the step would square has a
                // spectral radius of 1 or more, so the steps diverge.
                assert!(spectral_radius(&e_k) >= 1.0, "gave up at {e_k:?}");
                break;
            }
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
    // Most poses converge; the few refused are the near-singular ones.
    assert!(
        refined > 150 && refused < refined / 10,
        "{refined} refined, {refused} refused"
    );
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
    // A "Phi" far from any inverse (|I - J Phi| >= 1) would diverge: the
    // refinement gives up (false) before a step, and the planner hands the
    // step to the exact route; a non-finite Phi is an error.
    let mut wild: Vec<f64> = exact.iter().map(|x| 1e3 * x + 50.0).collect();
    assert!(!ik::refine_phi(&mut wild, &jac, 8).unwrap());
    let mut nan = exact.clone();
    nan[0] = f64::NAN;
    assert_eq!(ik::refine_phi(&mut nan, &jac, 0).ok(), None);
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
