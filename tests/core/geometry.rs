//! Kinematics, the pseudoinverse identities (eqs. 5-7, 17-21) and the
//! obstacle vector (eqs. 12-16).

use super::*;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

#[test]
fn forward_kinematics_reproduces_the_papers_start_points() {
    let arm = Arm::paper();
    let x1 = arm.forward(&theta(&[PI / 12.0, PI / 2.0, -PI / 6.0]));
    assert!(
        (x1 - Vector2::new(1.555884, 1.014851)).norm() < 1e-6,
        "{x1}"
    );
    let x2 = arm.forward(&Scene::task2().theta0_vector());
    assert!(
        (x2 - Vector2::new(1.495943, 0.559559)).norm() < 1e-6,
        "{x2}"
    );
    // The theta0 printed for Task 2 does not give the printed start
    // (docs/conventions.md).
    let printed = arm.forward(&theta(&[PI / 12.0, PI / 2.0, PI / 6.0]));
    assert!((printed - Vector2::new(1.400592, 0.435295)).norm() < 1e-6);
}

#[test]
fn joints_start_at_the_post_top_and_end_at_the_end_effector() {
    let arm = Arm::paper();
    let th = Scene::task1().theta0_vector();
    let p = arm.joints(&th);
    assert_eq!(p.len(), 4);
    assert_eq!(p[0], Vector2::new(0.0, 0.5));
    assert!((p[3] - arm.forward(&th)).norm() < 1e-15);
    for (k, l) in arm.links().iter().enumerate() {
        assert!(((p[k + 1] - p[k]).norm() - l).abs() < 1e-12);
    }
}

#[test]
fn analytic_jacobian_matches_central_differences() {
    let mut rng = Lcg(1);
    for arm in [
        Arm::paper(),
        Arm::new(0.3, vec![0.4, 0.7, 0.2, 0.5]).unwrap(),
    ] {
        for _ in 0..20 {
            let th = rng.theta(arm.dof());
            let j = arm.jacobian(&th);
            let h = 1e-6;
            for i in 0..arm.dof() {
                let mut tp = th.clone();
                let mut tm = th.clone();
                tp[i] += h;
                tm[i] -= h;
                let fd = (arm.forward(&tp) - arm.forward(&tm)) / (2.0 * h);
                assert!(
                    (fd - j.column(i)).norm() < 1e-8,
                    "column {i}: {fd} vs {}",
                    j.column(i)
                );
            }
        }
    }
}

#[test]
fn eq6_equals_eq7_for_random_spd_weights() {
    let mut rng = Lcg(2);
    let arm = Arm::paper();
    for _ in 0..20 {
        let j = jacobian_dyn(&arm, &rng.theta(3));
        let (w, z) = (rng.spd(3), rng.spd(2));
        let delta = rng.uniform(1e-3, 1.0);
        let a = ik::pseudoinverse_eq6(&j, Weights { w: &w, z: &z }, delta).unwrap();
        let b = ik::pseudoinverse_eq7(&j, Weights { w: &w, z: &z }, delta).unwrap();
        assert!((&a - &b).amax() < 1e-9 * a.amax().max(1.0), "{a} vs {b}");
    }
}

#[test]
fn undamped_pseudoinverse_is_a_right_inverse() {
    let mut rng = Lcg(3);
    let arm = Arm::paper();
    for _ in 0..20 {
        let j = jacobian_dyn(&arm, &rng.theta(3));
        let pinv = ik::pseudoinverse_eq6(
            &j,
            Weights {
                w: &rng.spd(3),
                z: &rng.spd(2),
            },
            0.0,
        )
        .unwrap();
        let jj = &j * &pinv;
        assert!((jj - DMatrix::identity(2, 2)).amax() < 1e-9);
    }
}

#[test]
fn null_space_term_moves_no_end_effector() {
    let mut rng = Lcg(4);
    let arm = Arm::paper();
    for _ in 0..20 {
        let j = jacobian_dyn(&arm, &rng.theta(3));
        let pinv = ik::pseudoinverse_eq6(
            &j,
            Weights {
                w: &rng.spd(3),
                z: &rng.spd(2),
            },
            0.0,
        )
        .unwrap();
        let v = DVector::from_fn(3, |_, _| rng.uniform(-5.0, 5.0));
        let projected = (DMatrix::identity(3, 3) - &pinv * &j) * &v;
        assert!((&j * projected).amax() < 1e-9);
    }
}

#[test]
fn symmetric_route_and_network_route_equal_eq5() {
    // Eqs. (17)-(18) and eq. (21) with the exact Phi are eq. (5) with W = Z = I.
    let mut rng = Lcg(5);
    let arm = Arm::paper();
    let (w, z) = (DMatrix::identity(3, 3), DMatrix::identity(2, 2));
    for delta in [0.0, 0.01, 0.3] {
        for _ in 0..10 {
            let th = rng.theta(3);
            let j = arm.jacobian(&th);
            let xdot = Vector2::new(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0));
            let v = DVector::from_fn(3, |_, _| rng.uniform(-1.0, 1.0));
            let pinv =
                ik::pseudoinverse_eq6(&jacobian_dyn(&arm, &th), Weights { w: &w, z: &z }, delta)
                    .unwrap();
            let xd = DVector::from_column_slice(xdot.as_slice());
            let eq5 = ik::theta_dot_eq5(&jacobian_dyn(&arm, &th), &pinv, &xd, &v);
            let eq18 = ik::theta_dot_symmetric(&j, &xdot, &v, delta).unwrap();
            let eq21 = ik::theta_dot_network(&ik::phi(&j, delta).unwrap(), &j, &xdot, &v);
            assert!((&eq5 - &eq18).amax() < 1e-9, "{eq5} vs {eq18}");
            assert!((&eq5 - &eq21).amax() < 1e-9, "{eq5} vs {eq21}");
        }
    }
}

#[test]
fn determinant_gradient_matches_finite_differences_and_is_lower_triangular() {
    let mut rng = Lcg(6);
    let arm = Arm::paper();
    for _ in 0..30 {
        let th = rng.theta(3);
        let o = Vector2::new(rng.uniform(-1.0, 2.0), rng.uniform(-0.5, 2.0));
        let g = obstacle::determinant_gradient(&arm, &th, &o);
        let h = 1e-6;
        for i in 0..3 {
            let mut tp = th.clone();
            let mut tm = th.clone();
            tp[i] += h;
            tm[i] -= h;
            let dp = obstacle::triangle_determinants(&arm.joints(&tp), &o);
            let dm = obstacle::triangle_determinants(&arm.joints(&tm), &o);
            for k in 0..3 {
                let fd = (dp[k] - dm[k]) / (2.0 * h);
                assert!(
                    (fd - g[(k, i)]).abs() < 1e-7,
                    "dD_{k}/dtheta_{i}: {fd} vs {}",
                    g[(k, i)]
                );
                if i > k {
                    assert_eq!(g[(k, i)], 0.0, "D_{k} must not depend on theta_{i}");
                }
            }
        }
    }
}

#[test]
fn triangle_determinant_is_twice_the_signed_area() {
    let joints = [Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)];
    // O above the link: det[(0, 1), (1, 0)] = -1, area of the triangle 1/2.
    let d = obstacle::triangle_determinants(&joints, &Vector2::new(0.0, 1.0));
    assert_eq!(d, vec![-1.0]);
}

#[test]
fn obstacle_vector_is_the_area_gradient_scaled_by_lambda_over_four() {
    let arm = Arm::paper();
    let th = Scene::task1().theta0_vector();
    let ob = Obstacle::new(0.5, 0.5, 0.05);
    let g = obstacle::area_gradient(&arm, &th, &ob.point());
    let v4 = obstacle::null_space_vector(&arm, &th, &[ob], 4.0);
    let v2 = obstacle::null_space_vector(&arm, &th, &[ob], 2.0);
    assert!((&v4 - &g).amax() < 1e-15);
    assert!((&v2 * 2.0 - &v4).amax() < 1e-15);
    // Ascent direction: a small step along g increases the total area sum V_k.
    let area = |t: &DVector<f64>| -> f64 {
        obstacle::triangle_determinants(&arm.joints(t), &ob.point())
            .iter()
            .map(|d| d.abs())
            .sum()
    };
    assert!(area(&(&th + 1e-4 * &g)) > area(&th));
    // Two obstacles sum.
    let ob2 = Obstacle::new(1.0, 1.5, 0.05);
    let both = obstacle::null_space_vector(&arm, &th, &[ob, ob2], 4.0);
    let sum = &g + obstacle::area_gradient(&arm, &th, &ob2.point());
    assert!((both - sum).amax() < 1e-14);
}

#[test]
fn clearance_is_the_distance_to_the_nearest_moving_link() {
    let joints = [
        Vector2::new(0.0, 0.5),
        Vector2::new(1.0, 0.5),
        Vector2::new(1.0, 1.5),
    ];
    let d = obstacle::clearance(&joints, &Vector2::new(0.5, 0.8));
    assert!((d - 0.3).abs() < 1e-15);
    let d = obstacle::clearance(&joints, &Vector2::new(2.0, 2.5));
    assert!((d - 2f64.sqrt()).abs() < 1e-15);
}

#[test]
fn a_flat_list_of_numbers_is_discs_in_the_plane_and_spheres_in_space() {
    use redundant_ik::geometry::{Ball, MAX_BALLS};
    let discs = Ball::<2>::from_flat(&[1.0, 2.0, 0.1, -1.0, 0.5, 0.2]).unwrap();
    assert_eq!(
        discs,
        vec![Obstacle::new(1.0, 2.0, 0.1), Obstacle::new(-1.0, 0.5, 0.2)]
    );
    let spheres = Ball::<3>::from_flat(&[0.4, 0.1, 0.7, 0.05]).unwrap();
    assert_eq!(spheres[0].centre, [0.4, 0.1, 0.7]);
    assert_eq!(spheres[0].radius, 0.05);
    assert!(Ball::<2>::from_flat(&[]).unwrap().is_empty());
    // A count that is not a whole number of balls, and too many of them.
    let part = Ball::<2>::from_flat(&[1.0, 2.0]).unwrap_err().to_string();
    assert!(
        part.contains("three numbers per obstacle: x, y, r"),
        "{part}"
    );
    let part = Ball::<3>::from_flat(&[1.0, 2.0, 3.0])
        .unwrap_err()
        .to_string();
    assert!(
        part.contains("four numbers per sphere: x, y, z, r"),
        "{part}"
    );
    let many = Ball::<3>::from_flat(&[0.5; 4 * (MAX_BALLS + 1)])
        .unwrap_err()
        .to_string();
    assert!(many.contains("number of spheres"), "{many}");
}
