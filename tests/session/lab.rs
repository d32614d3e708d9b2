//! The page for the lab: the joint weighting and the floor switch reach the
//! planner and the ghost, move the revisions, and the state carries them
//! with the singular values of `J` and the joints past their limits.

use super::*;
use redundant_ik::arm::JointLimits;
use redundant_ik::kinematics::velocity_ellipse;
use redundant_ik::scene::JointWeighting;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

#[test]
fn the_weighting_and_the_floor_reach_both_planners_and_move_the_revisions() {
    let mut s = with_networks(1);
    s.set_method(Method::CASE3).unwrap();
    let before = s.state().revision;
    s.set_weighting(JointWeighting::Wln);
    let mid = s.state().revision;
    assert!(mid.scene > before.scene && mid.atlas > before.atlas && mid.run > before.run);
    s.set_floor(true);
    let after = s.state().revision;
    assert!(after.scene > mid.scene && after.atlas > mid.atlas);
    let st = s.state();
    assert_eq!(st.weighting, JointWeighting::Wln);
    assert!(st.floor);
    assert_eq!(s.planner().scene().weighting, JointWeighting::Wln);
    let ghost = s.ghost().expect("Case 3 has its ghost");
    assert_eq!(ghost.scene().weighting, JointWeighting::Wln);
    assert!(ghost.scene().floor);
    // They stay with another arm, as the other settings of the methods do.
    s.set_arm(four_links()).unwrap();
    assert_eq!(s.state().weighting, JointWeighting::Wln);
    assert!(s.state().floor);
}

#[test]
fn the_state_has_the_singular_values_and_the_joints_past_their_limits() {
    let mut s = Session::new(1).unwrap();
    s.set_method(Method::NUMERICAL).unwrap();
    let theta0 = s.state().theta0.to_vec();
    let tight = JointLimits::new(theta0.iter().map(|t| [t - 0.05, t + 0.05]).collect()).unwrap();
    s.set_arm_limits(Some(tight), None).unwrap();
    let st = s.state();
    assert!(st.past_limits.is_empty() && st.limit_steps == 0);
    let [a, b] = st.singular_values;
    assert!(a >= b && (a * b - st.manipulability).abs() < 1e-12);
    let pose = s.planner().pose();
    assert_eq!(st.singular_values, velocity_ellipse(pose.jjt()).1);
    s.run_task();
    s.run_until(10.0).unwrap();
    let st = s.state();
    assert!(st.limit_steps > 0, "the run leaves the tight limits");
    assert!(
        st.past_limits.iter().all(|&j| (1..=3).contains(&j)),
        "1-based joints"
    );
}

/// Joint range on an arm without joint limits has nothing to keep to: the
/// state says so (the page shows it beside the drawing), and says nothing
/// once the arm has limits or for a method that does not read them.
#[test]
fn the_state_says_when_joint_range_has_no_limits_to_keep_to() {
    let mut s = Session::new(1).unwrap();
    s.set_method(Method::NUMERICAL).unwrap();
    assert_eq!(s.state().without_limits, None);
    s.set_method(methods::JOINT_RANGE).unwrap();
    let why = s.state().without_limits.expect("a reason");
    assert!(
        why.contains("no joint limits") && why.contains("No avoidance"),
        "{why}"
    );
    let limits = JointLimits::new(vec![[-2.0, 2.0], [-0.5, 2.5], [-2.0, 2.0]]).unwrap();
    s.set_arm_limits(Some(limits), None).unwrap();
    assert_eq!(s.state().without_limits, None);
}
