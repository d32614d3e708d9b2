//! Arms of any length: the area gradient, poses, sin and cos, the damped
//! learned Phi, the allocation-free routines and reset.

use super::*;
use redundant_ik::nalgebra::DVector;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

/// A random arm of `n` links on a post, with lengths in [0.3, 0.9].
fn random_arm(rng: &mut Lcg, n: usize) -> Arm {
    Arm::new(0.5, (0..n).map(|_| rng.uniform(0.3, 0.9)).collect()).unwrap()
}

#[test]
fn the_area_gradient_is_the_gradient_of_the_summed_triangle_areas_for_any_arm() {
    // g_i = sum_k sign(D_k) dD_k/dtheta_i (eq. 15), computed in O(n) by
    // suffix sums; checked against the n x n matrix of dD_k/dtheta_i and
    // against central differences of V = sum_k |D_k|.
    let mut rng = Lcg(11);
    for n in 2..=6 {
        let arm = random_arm(&mut rng, n);
        for _ in 0..20 {
            let th = rng.theta(n);
            let o = Vector2::new(rng.uniform(-1.5, 1.5), rng.uniform(-0.5, 2.5));
            let g = obstacle::area_gradient(&arm, &th, &o);
            let d = obstacle::triangle_determinants(&arm.joints(&th), &o);
            let dd = obstacle::determinant_gradient(&arm, &th, &o);
            let sign = |x: f64| {
                if x > 0.0 {
                    1.0
                } else if x < 0.0 {
                    -1.0
                } else {
                    0.0
                }
            };
            for i in 0..n {
                let from_matrix: f64 = (0..n).map(|k| sign(d[k]) * dd[(k, i)]).sum();
                assert!((g[i] - from_matrix).abs() < 1e-12, "n = {n}, i = {i}");
            }
            if d.iter().all(|x| x.abs() > 1e-3) {
                let area = |t: &DVector<f64>| -> f64 {
                    obstacle::triangle_determinants(&arm.joints(t), &o)
                        .iter()
                        .map(|x| x.abs())
                        .sum()
                };
                let h = 1e-6;
                for i in 0..n {
                    let (mut tp, mut tm) = (th.clone(), th.clone());
                    tp[i] += h;
                    tm[i] -= h;
                    let fd = (area(&tp) - area(&tm)) / (2.0 * h);
                    assert!((fd - g[i]).abs() < 1e-6, "n = {n}: {fd} vs {}", g[i]);
                }
            }
        }
    }
}

#[test]
fn a_pose_holds_the_kinematics_of_its_angles() {
    let mut rng = Lcg(12);
    for n in 2..=6 {
        let arm = random_arm(&mut rng, n);
        let th = rng.theta(n);
        let pose = Pose::new(&arm, th.as_slice()).unwrap();
        let joints = arm.joints(&th);
        for (p, q) in pose.joints().iter().zip(&joints) {
            assert_eq!(p, &[q[0], q[1]]);
        }
        let j = arm.jacobian(&th);
        assert_eq!(pose.jacobian(), j.as_slice());
        let phi = arm.absolute_angles(&th);
        for (i, a) in phi.iter().enumerate() {
            assert!((pose.sin()[i] - a.sin()).abs() < 3e-16);
            assert!((pose.cos()[i] - a.cos()).abs() < 3e-16);
        }
        assert!((pose.sigma_min() - ik::smallest_singular_value(&j)).abs() < 1e-15);
        assert!((pose.manipulability() - ik::manipulability(&j)).abs() < 1e-15);
        let o = Vector2::new(0.4, 0.7);
        assert_eq!(pose.clearance([0.4, 0.7]), obstacle::clearance(&joints, &o));
    }
}

#[test]
fn a_pose_refuses_angles_that_do_not_fit_and_stays_as_it_was() {
    let arm = Arm::paper();
    let mut pose = Pose::new(&arm, &[0.1, 0.2, 0.3]).unwrap();
    let before = pose.clone();
    assert!(matches!(
        pose.update(&arm, &[0.1, 0.2]),
        Err(Error::DimensionMismatch { .. })
    ));
    let four = Arm::new(0.5, vec![0.5; 4]).unwrap();
    assert!(pose.update(&four, &[0.1, 0.2, 0.3, 0.4]).is_err());
    assert_eq!(pose, before);
    assert!(matches!(
        Pose::new(&arm, &[0.1, f64::NAN, 0.3]),
        Err(Error::NonFinite { .. })
    ));
}

#[test]
fn sin_cos_is_within_two_ulp_of_the_c_library_to_8e5_rad_and_1e_10_rad_beyond() {
    // fdlibm's reduction and kernels up to 2^19 pi/2 (8.2e5 rad); beyond,
    // the argument modulo the rounded 2 pi, within 1e-10 at 1e6 rad.
    let mut worst = 0.0f64;
    for i in 0..=200_000 {
        for scale in [4.0, 100.0, 1e5, 8e5, 1e6] {
            let x = (i as f64 / 100_000.0 - 1.0) * scale;
            let (s, c) = kinematics::sin_cos(x);
            let (s0, c0) = x.sin_cos();
            let err = (s - s0).abs().max((c - c0).abs());
            if x.abs() <= 823_549.0 {
                worst = worst.max(err);
                // Two ulp of a value of magnitude at most 1.
                assert!(err <= 2.3e-16, "x = {x}: {err}");
            } else {
                assert!(err <= 1e-10, "x = {x}: {err}");
            }
        }
    }
    assert!(worst > 0.0, "not the library's own function");
    let (s, c) = kinematics::sin_cos(f64::NAN);
    assert!(s.is_nan() && c.is_nan());
    let (s, c) = kinematics::sin_cos(f64::INFINITY);
    assert!(s.is_nan() && c.is_nan());
    assert_eq!(kinematics::sin_cos(0.0), (0.0, 1.0));
}

#[test]
fn a_learned_phi_takes_a_constant_delta_exactly_when_it_is_exact() {
    // Phi_delta = Phi_0 (I + delta Phi_0^T Phi_0)^-1 = J^T (J J^T + delta I)^-1.
    let mut rng = Lcg(13);
    for n in 2..=5 {
        let arm = random_arm(&mut rng, n);
        let j = arm.jacobian(&rng.theta(n));
        if ik::smallest_singular_value(&j) < 0.05 {
            continue;
        }
        for delta in [0.0, 1e-4, 0.01, 0.3] {
            let exact = ik::phi(&j, delta).unwrap();
            let mut damped: Vec<f64> = {
                let p0 = ik::phi(&j, 0.0).unwrap();
                (0..n).flat_map(|i| [p0[(i, 0)], p0[(i, 1)]]).collect()
            };
            ik::damp_phi(&mut damped, delta).unwrap();
            for i in 0..n {
                for c in 0..2 {
                    let e = exact[(i, c)];
                    assert!((damped[2 * i + c] - e).abs() < 1e-12 * (1.0 + e.abs()));
                }
            }
        }
    }
    assert!(ik::damp_phi(&mut [1.0, 2.0], -0.1).is_err());
    assert!(ik::damp_phi(&mut [1.0, 2.0], f64::NAN).is_err());
}

#[test]
fn the_allocation_free_routines_equal_the_matrix_forms_and_refuse_wrong_sizes() {
    let arm = Arm::paper();
    let th = Scene::task1().theta0_vector();
    let j = arm.jacobian(&th);
    let v = DVector::from_vec(vec![0.2, -0.1, 0.3]);
    let xdot = Vector2::new(-0.1, -0.08);
    let m = ik::theta_dot_symmetric(&j, &xdot, &v, 0.01).unwrap();
    let mut out = [0.0; 3];
    ik::theta_dot_symmetric_into(j.as_slice(), [-0.1, -0.08], v.as_slice(), 0.01, &mut out)
        .unwrap();
    assert_eq!(out, [m[0], m[1], m[2]]);
    let mut phi = [0.0; 6];
    ik::phi_into(j.as_slice(), 0.0, &mut phi).unwrap();
    let p = ik::phi(&j, 0.0).unwrap();
    let net = ik::theta_dot_network(&p, &j, &xdot, &v);
    ik::theta_dot_network_into(&phi, j.as_slice(), [-0.1, -0.08], v.as_slice(), &mut out).unwrap();
    assert!((net - DVector::from_row_slice(&out)).amax() < 1e-15);
    // Wrong sizes are errors, not panics.
    assert!(
        ik::theta_dot_symmetric_into(j.as_slice(), [0.0; 2], &[0.0; 2], 0.0, &mut out).is_err()
    );
    assert!(
        ik::theta_dot_symmetric_into(&j.as_slice()[..5], [0.0; 2], &[0.0; 3], 0.0, &mut out)
            .is_err()
    );
    assert!(ik::phi_into(j.as_slice(), 0.0, &mut phi[..5]).is_err());
    assert!(
        ik::theta_dot_network_into(&phi[..4], j.as_slice(), [0.0; 2], &[0.0; 3], &mut out).is_err()
    );
}

#[test]
fn the_planner_rates_through_its_workspace_equal_the_convenience_form() {
    for method in methods::ALL.iter().copied().filter(|m| !m.uses_networks()) {
        let mut p = Planner::new(Scene::task2(), method, None).unwrap();
        let th = DVector::from_vec(vec![0.4, 1.2, 0.3]);
        let a = p
            .theta_dot(
                th.as_slice(),
                [
                    (Vector2::new(-0.05, 0.02))[0],
                    (Vector2::new(-0.05, 0.02))[1],
                ],
            )
            .map(DVector::from_vec)
            .unwrap();
        let mut b = [0.0; 3];
        p.theta_dot_into(th.as_slice(), [-0.05, 0.02], &mut b)
            .unwrap();
        assert_eq!(a.as_slice(), &b);
        assert!(p.theta_dot_into(&[0.1, 0.2], [0.0; 2], &mut b).is_err());
    }
}

#[test]
fn reset_returns_to_the_state_of_a_fresh_planner() {
    let mut s = Scene::task1();
    s.damping = Some(DampingSchedule::default());
    let fresh = Planner::new(s.clone(), Method::NUMERICAL, None).unwrap();
    let mut p = Planner::new(s, Method::NUMERICAL, None).unwrap();
    for _ in 0..37 {
        p.step().unwrap();
    }
    p.reset();
    assert_eq!(p.sample(), fresh.sample());
    assert_eq!(p.summary(), fresh.summary());
    assert_eq!(p.line(), fresh.line());
    for _ in 0..100 {
        p.step().unwrap();
    }
    let run = Planner::run(Scene::task1(), Method::NUMERICAL, None).unwrap();
    assert!((p.summary().final_error - run.summary.final_error).abs() < 1e-12);
}
