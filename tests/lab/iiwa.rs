//! The KUKA iiwa14 in its plane (`iiwa-planar`): the numbers read from
//! Drake's `planar_iiwa14_spheres_dense_elbow_collision.urdf`, and its own
//! task: the arm without avoidance hits the disc, the avoiding methods
//! keep clear within the robot's limits.

use redundant_ik::arm::{Preset, PRESETS};
use redundant_ik::planner::methods::{DISTANCE, QP};
use redundant_ik::{Method, Planner, Pose, Scene};

fn iiwa() -> &'static Preset {
    PRESETS.iter().find(|p| p.key == "iiwa-planar").unwrap()
}

#[test]
fn the_preset_is_the_urdfs_joints_2_4_and_6_with_their_limits() {
    let p = iiwa();
    assert_eq!(p.post, 0.1575 + 0.2025);
    assert_eq!(p.links, [0.2045 + 0.2155, 0.1845 + 0.2155, 0.081 + 0.045]);
    let arm = p.arm();
    let limits = arm.joint_limits().unwrap();
    assert!(limits
        .ranges()
        .iter()
        .all(|r| *r == [-2.09439510239, 2.09439510239]));
    assert_eq!(
        arm.rate_limits().unwrap().rates(),
        [1.4835298641951802, 1.3089969389957472, 2.356194490192345]
    );
    // Stretched up, the hand is at the URDF's iiwa_link_ee height,
    // 0.36 + 0.42 + 0.40 + 0.126 = 1.306 m.
    let up = Pose::new(&arm, &[0.0, 0.0, 0.0]).unwrap();
    assert!((up.end_effector()[1] - 1.306).abs() < 1e-12);
    assert_eq!(Preset::of(&arm).map(|p| p.key), Some("iiwa-planar"));
}

#[test]
fn its_task_starts_within_its_limits_and_the_arm_without_avoidance_hits_the_disc() {
    let mut scene = Scene::task1();
    scene.arm = iiwa().arm();
    assert!(scene.use_preset_task());
    scene.validate().unwrap();
    assert_eq!(scene.theta0, [0.1, 1.2, 1.6]);
    let hand = Pose::new(&scene.arm, &scene.theta0).unwrap().end_effector();
    assert!(
        (hand[0] - 0.4575).abs() < 1e-3 && (hand[1] - 0.7626).abs() < 1e-3,
        "{hand:?}"
    );
    let none = Planner::run(scene.clone(), Method::NO_AVOIDANCE, None).unwrap();
    assert!(none.summary.collided);
    for m in [Method::NUMERICAL, DISTANCE, QP] {
        let run = Planner::run(scene.clone(), m, None).unwrap();
        assert!(run.summary.success, "{m}: {:?}", run.summary);
        assert_eq!(run.summary.limit_steps, 0, "{m}");
    }
}
