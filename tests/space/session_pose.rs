//! The hand's full pose as the page's task, as a specification: the
//! session's pose task is the planner's pose run (its run file is the
//! command line's and reads back), the target's orientation set by roll,
//! pitch and yaw, by a rotation and by turns about the world's axes, and
//! what the pose task refuses, changing nothing.

use redundant_ik::export::PoseRunFile;
use redundant_ik::planner::methods::{CASE1, CASE3, QP};
use redundant_ik::planner::{Method, Planner};
use redundant_ik::scene::{SpacePath, SpaceScene};
use redundant_ik::session::space::SpaceSession;
use redundant_ik::space::rotation::{exp, matrix_rpy, rpy_matrix};

fn panda(method: Method) -> SpaceSession {
    SpaceSession::new("panda", method).expect("the Panda's task runs")
}

/// The session's pose run as the page writes its file.
fn pose_file(s: &SpaceSession) -> PoseRunFile {
    PoseRunFile::of(
        None,
        s.pose_scene().expect("the pose task"),
        s.pose_trajectory().expect("the pose task's run"),
        None,
        s.precision(),
    )
}

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

#[test]
fn the_pose_task_starts_with_the_hands_own_orientation_and_holds_it() {
    let mut s = panda(QP);
    assert_eq!(s.state().task, "position");
    assert!(s.orientation().is_none() && s.state().target_rpy.is_none());
    s.set_pose_task(true).unwrap();
    let st = s.state();
    assert_eq!(st.task, "pose");
    let (target, hand) = (st.target_rpy.unwrap(), st.hand_rpy);
    assert!(close(&target, &hand, 1e-9), "{target:?} {hand:?}");
    assert_eq!(st.orientation_weight, Some(1.0));
    s.run_until(1e9).unwrap();
    let sum = s.summary();
    assert!(sum.final_error < 5e-3, "{sum:?}");
    assert!(sum.final_orientation_error.unwrap() < 5e-3, "{sum:?}");
    // Back to the position task: no orientation, no pose samples.
    s.set_pose_task(false).unwrap();
    assert!(s.pose_trajectory().is_none() && s.summary().final_orientation_error.is_none());
}

#[test]
fn a_turned_target_is_reached_in_position_and_orientation_and_its_file_replays() {
    let mut s = panda(QP);
    s.set_pose_task(true).unwrap();
    s.turn_target(2, 0.4).unwrap();
    s.turn_target(0, -0.2).unwrap();
    s.run_until(1e9).unwrap();
    let sum = s.summary().clone();
    assert!(sum.final_error < 5e-3, "{sum:?}");
    assert!(sum.final_orientation_error.unwrap() < 5e-3, "{sum:?}");
    // The run on screen is the planner's run of the pose scene, to the bit.
    let scene = s.pose_scene().unwrap();
    let own = Planner::run(scene, QP, None).unwrap();
    let file = pose_file(&s);
    assert_eq!(file.steps, own.steps);
    // Its file reads back as the same run.
    let back = PoseRunFile::from_json(&file.to_json()).unwrap();
    assert_eq!(back.steps, own.steps);
    assert_eq!(back.scene.target, s.pose_scene().unwrap().target);
    // The view's positions are the pose samples' positions.
    for (a, b) in s.samples().iter().zip(&own.steps) {
        assert_eq!(a.ee, [b.ee[0], b.ee[1], b.ee[2]]);
        assert_eq!(a.orientation_error, b.orientation_error);
    }
}

#[test]
fn roll_pitch_yaw_and_a_rotation_set_the_same_orientation() {
    let mut s = panda(QP);
    s.set_pose_task(true).unwrap();
    let rpy = [3.0, 0.2, -0.5];
    s.set_target_rpy(rpy).unwrap();
    let got = s.state().target_rpy.unwrap();
    assert!(close(&got, &rpy, 1e-12), "{got:?}");
    let first = s.pose_scene().unwrap().target;
    s.set_target_rpy([0.0; 3]).unwrap();
    s.set_target_rotation(&rpy_matrix(rpy)).unwrap();
    let again = s.pose_scene().unwrap().target;
    assert!(close(&first, &again, 1e-12), "{first:?} {again:?}");
    // A turn about z adds to the yaw where roll and pitch are zero.
    s.set_target_rpy([0.0, 0.0, 0.3]).unwrap();
    s.turn_target(2, 0.2).unwrap();
    let r = exp(s.orientation().unwrap().rotation);
    assert!(close(&matrix_rpy(&r), &[0.0, 0.0, 0.5], 1e-12));
    // The weight of Z.
    s.set_orientation_weight(4.0).unwrap();
    assert_eq!(s.pose_scene().unwrap().arm.orientation_weight(), 4.0);
}

#[test]
fn a_circle_of_the_pose_task_keeps_the_start_orientation() {
    let mut s = panda(QP);
    s.set_pose_task(true).unwrap();
    s.turn_target(2, 0.4).unwrap();
    let start = s.pose_scene().unwrap().start();
    s.set_path("circle:0.45,0,0.45,0,1,0".parse().unwrap())
        .unwrap();
    let t = s.pose_scene().unwrap().target;
    assert!(close(&t[3..], &start[3..], 1e-9), "{t:?} {start:?}");
    // And an orientation of its own is refused there.
    let before = s.pose_scene().unwrap();
    assert!(s.turn_target(2, 0.4).is_err());
    assert_eq!(s.pose_scene().unwrap().target, before.target);
    s.set_path(SpacePath::Line).unwrap();
    s.turn_target(2, 0.4).unwrap();
}

#[test]
fn the_pose_task_refuses_what_it_cannot_run_and_loses_nothing() {
    let mut s = panda(QP);
    // An orientation asks for the pose task.
    assert!(s.set_target_rpy([0.1, 0.0, 0.0]).is_err());
    assert!(s.turn_target(0, 0.1).is_err());
    assert!(s.set_orientation_weight(2.0).is_err());
    s.set_pose_task(true).unwrap();
    let before = s.pose_scene().unwrap();
    let runs = s.runs();
    for bad in [[f64::NAN, 0.0, 0.0], [0.0, f64::INFINITY, 0.0]] {
        assert!(s.set_target_rpy(bad).is_err());
    }
    // Not rotations: NaN, zero, a scaling, a reflection.
    let mirror = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, -1.0]];
    let twice = [[2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 2.0]];
    for bad in [[[f64::NAN; 3]; 3], [[0.0; 3]; 3], twice, mirror] {
        assert!(s.set_target_rotation(&bad).is_err(), "{bad:?}");
    }
    assert!(s.turn_target(3, 0.1).is_err() && s.turn_target(0, f64::NAN).is_err());
    for w in [0.0, -1.0, f64::NAN, 1e9] {
        assert!(s.set_orientation_weight(w).is_err(), "{w}");
    }
    // Cases 1 and 3 have no Phi for the pose: refused, with the reason.
    for m in [CASE1, CASE3] {
        let e = s.set_method(m).unwrap_err().to_string();
        assert!(e.contains("pose"), "{e}");
    }
    assert_eq!(s.pose_scene().unwrap().target, before.target);
    assert_eq!((s.method(), s.runs()), (QP, runs));
    // The comparison leaves them out.
    assert!(s
        .compare()
        .iter()
        .all(|r| r.method != CASE1 && r.method != CASE3));
    // A chain of three joints has no pose task.
    let arm = redundant_ik::Arm::paper();
    let chain = super::planar_as_chain(&arm);
    let scene = SpaceScene::own(chain).unwrap();
    let mut three = SpaceSession::of_robot("robot", "planar", scene, QP).unwrap();
    let e = three.set_pose_task(true).unwrap_err().to_string();
    assert!(e.contains("6 joints"), "{e}");
    assert_eq!(three.state().task, "position");
}

#[test]
fn task_brings_back_the_hands_start_orientation() {
    let mut s = panda(QP);
    s.set_pose_task(true).unwrap();
    let own = s.pose_scene().unwrap().target;
    s.turn_target(1, 0.3).unwrap();
    s.load_task().unwrap();
    assert_eq!(s.state().task, "pose");
    assert!(close(&s.pose_scene().unwrap().target, &own, 1e-12));
}
