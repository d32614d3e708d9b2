//! The spatial planner: the hand follows its line, the presets' tasks say
//! what they were chosen to show, the planar arm's rates come back from a
//! chain with parallel axes, and what cannot run is refused.

use redundant_ik::planner::methods::{self, DELTA};
use redundant_ik::scene::SpaceScene;
use redundant_ik::space::{SpacePreset, Sphere, PRESETS};
use redundant_ik::{Arm, Error, Method, Planner, Scene};

/// Every method with a rule in space that needs no networks (the learned
/// ones are `networks.rs`'s).
fn space_methods() -> Vec<Method> {
    methods::ALL
        .iter()
        .copied()
        .filter(|m| m.in_space() && !m.uses_networks())
        .collect()
}

#[test]
fn without_spheres_every_method_keeps_the_hand_on_its_line() {
    for p in PRESETS {
        let mut scene = SpaceScene::preset(&p);
        scene.obstacles.clear();
        for m in space_methods() {
            let run = Planner::new(scene.clone(), m, None)
                .and_then(Planner::run_to_end)
                .unwrap();
            // qp's task slack is eq. (5) damped by 1 / w (1e-6 at the
            // default slack weight): the hand drifts by its order.
            let tol = if m.reads(&methods::SLACK_WEIGHT) {
                1e-5
            } else {
                1e-6
            };
            assert!(
                run.summary.max_tracking_error < tol,
                "{} {m}: off the line by {:e}",
                p.key,
                run.summary.max_tracking_error
            );
            assert!(
                run.summary.final_error < tol,
                "{} {m}: {:e} from the target",
                p.key,
                run.summary.final_error
            );
            assert_eq!(run.summary.limit_steps, 0, "{} {m}", p.key);
        }
    }
}

/// The presets' tasks were chosen so that the arm without avoidance hits
/// the sphere with its forearm, which starts 10 cm (Panda) and 13 cm (iiwa)
/// clear of it. The paper's criterion at its gain 4 still hits on the
/// Panda and clears the iiwa; 64 clears both (`docs/space.md` gives the
/// numbers).
#[test]
fn the_presets_tasks_hit_without_avoidance_and_the_hand_stays_on_the_line() {
    let run = |scene: &SpaceScene, m: Method| {
        Planner::new(scene.clone(), m, None)
            .and_then(Planner::run_to_end)
            .unwrap()
    };
    for p in PRESETS {
        let scene = SpaceScene::preset(&p);
        assert!(
            run(&scene, Method::NO_AVOIDANCE).steps[0]
                .clearance
                .unwrap()
                > 0.1,
            "{}",
            p.key
        );
        for m in [Method::NO_AVOIDANCE, Method::NUMERICAL] {
            let r = run(&scene, m);
            assert!(r.summary.max_tracking_error < 1e-6, "{} {m}", p.key);
            let hits = r.summary.collision_steps > 0;
            assert_eq!(
                hits,
                m == Method::NO_AVOIDANCE || p.key == "panda",
                "{} {m}: {:?}",
                p.key,
                r.summary
            );
        }
        let mut strong = scene.clone();
        strong.params.set(&methods::LAMBDA, 64.0).unwrap();
        let r = run(&strong, Method::NUMERICAL);
        assert_eq!(
            r.summary.collision_steps, 0,
            "{}: lambda 64 avoids ({:?})",
            p.key, r.summary
        );
    }
}

/// The planar arm as a chain in space (every axis the world's `+y`, the
/// planar `(x, y)` the world's `(x, z)`). Its hand cannot move along `y`,
/// so `J J^T` is singular there: with a damping `delta > 0` both routes
/// solve, and the rates are the planar ones.
#[test]
fn a_chain_whose_axes_are_parallel_gives_the_planar_rates() {
    let arm = Arm::paper();
    let chain = super::planar_as_chain(&arm);
    let mut planar = Scene::task1();
    planar.params.set(&DELTA, 0.02).unwrap();
    let o = planar.obstacles[0].centre;
    let mut space = SpaceScene::preset(&PRESETS[0]);
    space.arm = chain;
    space.theta0 = planar.theta0.clone();
    space.target = [planar.target[0], 0.0, planar.target[1]];
    space.obstacles = vec![Sphere::new([o[0], 0.0, o[1]], 0.05)];
    space.params = planar.params.clone();
    for m in space_methods() {
        let plane = Planner::new(planar.clone(), m, None).unwrap();
        let spatial = Planner::new(space.clone(), m, None).unwrap();
        for theta in [
            vec![0.3, 1.2, -0.4],
            vec![-0.2, 0.9, 0.7],
            planar.theta0.clone(),
        ] {
            let want = plane.theta_dot(&theta, [0.1, -0.2]).unwrap();
            let got = spatial.theta_dot(&theta, [0.1, 0.0, -0.2]).unwrap();
            for (g, w) in got.iter().zip(want.iter()) {
                assert!((g - w).abs() < 1e-12, "{m}: {got:?} against {want:?}");
            }
        }
    }
}

#[test]
fn what_cannot_run_in_space_is_refused_with_a_reason() {
    let scene = SpaceScene::preset(&PRESETS[0]);
    // Every method runs in space; a learned one needs the networks.
    assert!(methods::ALL.iter().all(|m| m.in_space()));
    for m in methods::ALL.iter().filter(|m| m.uses_networks()) {
        let e = Planner::new(scene.clone(), *m, None).err().unwrap();
        assert!(matches!(e, Error::NetworksUnavailable(_)), "{m}: {e}");
        assert!(e.to_string().contains("--networks"), "{e}");
    }
    let mut outside = scene.clone();
    outside.theta0[3] = 0.5; // the Panda's joint 4 stays below -0.0698
    assert!(Planner::new(outside, Method::NUMERICAL, None).is_err());
    let mut on_base = scene.clone();
    on_base.obstacles = vec![Sphere::new([0.02, 0.0, 0.1], 0.05)];
    let e = Planner::new(on_base, Method::NUMERICAL, None)
        .err()
        .unwrap();
    assert!(matches!(e, Error::SphereOnBase { .. }), "{e}");
    let mut nan = scene;
    nan.target[1] = f64::NAN;
    assert!(Planner::new(nan, Method::NUMERICAL, None).is_err());
    assert!(SpaceScene::by_key("ur5").is_err());
    assert!(SpacePreset::by_key("panda").is_some());
}

/// A target past the chain's reach switches the damping schedule on, as a
/// planar arm's does: every method then ends with its joints inside their
/// limits and no angle wound round (before, the Panda's joint 6 reached
/// 23.7 rad for the target (2, 0, 0.5) with the numerical route). A scene
/// with its own schedule keeps it, and a reachable target leaves it off.
#[test]
fn a_target_out_of_reach_is_detected_and_damped() {
    for p in PRESETS {
        let mut scene = SpaceScene::preset(&p);
        scene.target = [2.0, 0.0, 0.5];
        for m in space_methods() {
            let planner = Planner::new(scene.clone(), m, None).unwrap();
            assert!(!planner.reachable(), "{} {m}", p.key);
            assert!(planner.auto_damping(), "{} {m}", p.key);
            assert!(planner.scene().damping.is_some());
            let run = planner.run_to_end().unwrap();
            assert_eq!(
                run.summary.limit_steps, 0,
                "{} {m}: {:?}",
                p.key, run.summary
            );
            let last = &run.steps.last().unwrap().theta;
            assert!(
                last.iter().all(|t| t.abs() < std::f64::consts::TAU),
                "{} {m}: {last:?}",
                p.key
            );
            assert!(
                run.summary.final_error > 0.5,
                "{} {m}: the target is not reached",
                p.key
            );
        }
        let own = SpaceScene {
            damping: Some(redundant_ik::ik::DampingSchedule {
                threshold: 0.2,
                delta_max: 0.02,
            }),
            ..scene.clone()
        };
        let planner = Planner::new(own.clone(), Method::NUMERICAL, None).unwrap();
        assert!(!planner.reachable() && !planner.auto_damping());
        assert_eq!(planner.scene().damping, own.damping);
        let home = Planner::new(SpaceScene::preset(&p), Method::NUMERICAL, None).unwrap();
        assert!(home.reachable() && !home.auto_damping());
        assert!(home.scene().damping.is_none());
    }
}
