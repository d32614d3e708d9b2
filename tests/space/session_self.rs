//! Self-collision on the page's session, as a specification: the switch
//! puts the command line's pairs into the scene (its run the planner's),
//! the pairs near each other are what the view draws, and Task keeps the
//! switch. The scene is docs/pose.md's: the Panda's pose task to a point
//! beside its own column, where the numerical route folds the arm into
//! itself and qp does not.

use redundant_ik::planner::methods::{QP, SELF_INFLUENCE};
use redundant_ik::planner::{Method, Planner};
use redundant_ik::scene::{PoseScene, SpaceScene};
use redundant_ik::session::space::SpaceSession;

fn folding(method: Method) -> SpaceSession {
    let mut s = SpaceSession::new("panda", method).unwrap();
    s.set_spheres(&[]).unwrap();
    s.set_target([0.0, 0.25, 0.2]).unwrap();
    s.set_pose_task(true).unwrap();
    s
}

#[test]
fn the_switch_checks_the_command_lines_pairs_and_the_run_is_the_planners() {
    let mut s = folding(Method::NUMERICAL);
    assert!(!s.self_collision() && s.summary().min_self_clearance.is_none());
    s.set_self_collision(true).unwrap();
    assert!(s.state().self_collision);
    // The pairs are the command line's (--self-collision).
    let mut space = SpaceScene::by_key("panda").unwrap();
    let zero = [0.0; 7];
    space.arm = space
        .arm
        .clone()
        .with_self_collision(&[], &[&zero, &space.theta0])
        .unwrap();
    assert_eq!(s.scene().arm.self_pairs(), space.arm.self_pairs());
    // The numerical route folds the arm into itself; qp does not.
    let numerical = s.summary().clone();
    assert!(numerical.self_collision_steps > 0, "{numerical:?}");
    s.set_method(QP).unwrap();
    let qp = s.summary().clone();
    assert_eq!(qp.self_collision_steps, 0, "{qp:?}");
    // The run on screen is the planner's pose run of the same scene.
    let own = Planner::run(s.pose_scene().unwrap(), QP, None).unwrap();
    assert_eq!(s.pose_trajectory().unwrap().steps, own.steps);
    // Off again: no pairs, no self-clearance.
    s.set_self_collision(false).unwrap();
    assert!(s.scene().arm.self_pairs().is_empty() && s.summary().min_self_clearance.is_none());
}

#[test]
fn the_view_draws_the_pairs_within_their_influence_distance() {
    let mut s = folding(Method::NUMERICAL);
    assert!(s.self_near().is_empty(), "nothing without the switch");
    s.set_self_collision(true).unwrap();
    // Where the numerical run folds the arm into itself two links
    // overlap: drawn, with a negative distance.
    let worst = s
        .samples()
        .iter()
        .min_by(|a, b| {
            a.self_clearance
                .unwrap()
                .total_cmp(&b.self_clearance.unwrap())
        })
        .unwrap()
        .t;
    s.run_until(worst).unwrap();
    let near = s.self_near();
    let reach = s.scene().param(&SELF_INFLUENCE);
    assert!(!near.is_empty());
    assert!(near.iter().all(|n| n.distance < reach));
    assert!(near.iter().any(|n| n.distance < 0.0), "{near:?}");
    let least = near
        .iter()
        .map(|n| n.distance)
        .fold(f64::INFINITY, f64::min);
    assert!((least - s.state().self_clearance.unwrap()).abs() < 1e-12);
    // The segment joins points on the two capsules' axes: its length is the
    // distance plus both radii.
    let r = s.scene().arm.radius();
    for n in &near {
        let [a, b] = n.points;
        let len = (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt();
        assert!(
            (len.max(0.0) - (n.distance + 2.0 * r)).abs() < 1e-9 || n.distance + 2.0 * r < 0.0,
            "{n:?}"
        );
    }
}

#[test]
fn task_keeps_the_switch_and_a_run_file_carries_the_pairs() {
    let mut s = folding(QP);
    s.set_self_collision(true).unwrap();
    s.load_task().unwrap();
    assert!(s.self_collision(), "Task keeps the switch");
    let pairs = s.scene().arm.self_pairs().to_vec();
    assert!(!pairs.is_empty());
    let scene: PoseScene = s.pose_scene().unwrap();
    assert_eq!(scene.arm.chain.self_pairs(), &pairs[..]);
}
