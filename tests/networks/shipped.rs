//! What the shipped networks achieve: accuracy and the task outcomes of
//! Cases 1-3.

use super::*;
use redundant_ik::nalgebra::DVector;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

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
        for method in methods::ALL.iter().copied().filter(|m| m.uses_networks()) {
            let o = evaluation::run_task(&nets, task, method, None, 0.0).unwrap();
            assert!(
                o.success(),
                "task {task} {method}: min distance {:.4}, collided {}, final error {:.2e}, {:?}",
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
            for method in methods::ALL.iter().copied().filter(|m| m.networks().phi) {
                let o = evaluation::run_task(&nets, task, method, None, 0.0).unwrap();
                assert!(o.success(), "{variant:?} task {task} {method}: {o:?}");
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
fn planner_runs_every_method_with_the_networks_as_surrogate() {
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    let p = Planner::new(Scene::task2(), Method::CASE3, Some(nets.clone())).unwrap();
    let xdot = Vector2::new(-0.1, -0.03);
    let td = p
        .theta_dot(p.theta().as_slice(), [xdot[0], xdot[1]])
        .map(DVector::from_vec)
        .unwrap();
    let arm = Arm::paper();
    // The commanded end-effector velocity is met to the Phi network's accuracy:
    // J theta_dot - Xdot = J (Phi_net - Phi) (Xdot - J v).
    let j = arm.jacobian(p.theta());
    let v = p
        .null_space(p.theta().as_slice())
        .map(DVector::from_vec)
        .unwrap();
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
