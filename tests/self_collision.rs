//! Self-collision: which capsule pairs a chain checks, an SRDF's disabled
//! pairs, the pairs' rows against finite differences, and the Panda's
//! pose task where the numerical route brings two links into contact and
//! `qp`'s dampers hold them apart at every step.

use redundant_ik::model::Model;
use redundant_ik::planner::methods::STOP_DISTANCE;
use redundant_ik::planner::{Method, Planner};
use redundant_ik::scene::{PoseScene, SpaceScene};
use redundant_ik::space::self_pairs::{adjacent, self_contact};
use redundant_ik::space::{Chain, SpacePair, SpacePairs, SpacePose};
use redundant_ik::urdf::srdf::{disabled_links, disabled_pairs};
use redundant_ik::urdf::volume::{Source, Volume};

fn panda() -> Chain {
    SpaceScene::by_key("panda").unwrap().arm
}

/// The Panda's pose task to a point beside its own column, the hand's
/// start orientation kept: the scene of docs/self-collision.md.
fn folding() -> PoseScene {
    let mut space = SpaceScene::by_key("panda").unwrap();
    space.target = [0.0, 0.25, 0.2];
    space.obstacles.clear();
    space.arm = space
        .arm
        .clone()
        .with_self_collision(&[], &[&[0.0; 7], &space.theta0])
        .unwrap();
    PoseScene::from_space(space, None, 1.0).unwrap()
}

#[test]
fn a_chain_checks_every_pair_but_adjacent_disabled_and_touching_ones() {
    let chain = panda();
    assert!(chain.self_pairs().is_empty(), "off unless asked for");
    let zero = [0.0; 7];
    let on = chain.clone().with_self_collision(&[], &[&zero]).unwrap();
    let pose = SpacePose::new(&on, &zero).unwrap();
    let n = on.segments().len();
    let mut expected = Vec::new();
    for a in 0..n {
        for b in a + 1..n {
            if !adjacent(&on, a, b) && self_contact(&on, &pose, a, b).distance >= 0.0 {
                expected.push([a, b]);
            }
        }
    }
    assert_eq!(on.self_pairs(), expected.as_slice());
    assert!(!expected.is_empty());
    // A disabled pair is left out, in either order.
    let [a, b] = expected[0];
    let fewer = chain
        .clone()
        .with_self_collision(&[[b, a]], &[&zero])
        .unwrap();
    assert_eq!(fewer.self_pairs(), &expected[1..]);
    // Bad input is refused.
    assert!(chain
        .clone()
        .with_self_collision(&[[0, 99]], &[&zero])
        .is_err());
    assert!(chain
        .clone()
        .with_self_collision(&[], &[&[0.0; 3]])
        .is_err());
    let mut broken = chain;
    assert!(broken.set_self_pairs(vec![[2, 2]]).is_err());
}

#[test]
fn a_self_pairs_row_is_the_rate_of_its_distance() {
    let scene = folding();
    let chain = &scene.arm.chain;
    let theta = [0.3, -0.5, 0.4, -2.4, 0.2, 1.6, 0.5];
    let pose = SpacePose::new(chain, &theta).unwrap();
    let mut pairs = SpacePairs::with_capacity(64);
    pairs.add_self(chain, &pose, f64::INFINITY);
    assert_eq!(pairs.len(), chain.self_pairs().len());
    let h = 1e-7;
    let mut row = vec![0.0; 7];
    for (p, &[a, b]) in pairs.as_slice().iter().zip(chain.self_pairs()) {
        p.gradient_into(&pose, &mut row);
        for i in 0..7 {
            let mut t = theta;
            t[i] += h;
            let moved = SpacePose::new(chain, &t).unwrap();
            let fd = (self_contact(chain, &moved, a, b).distance - p.distance) / h;
            assert!(
                (fd - row[i]).abs() < 1e-5,
                "pair {a}-{b} joint {i}: {fd} vs {}",
                row[i]
            );
        }
        let again = SpacePair::link(chain, &pose, a, b);
        assert_eq!(again.distance, p.distance);
    }
}

#[test]
fn the_numerical_route_folds_the_panda_into_itself_and_qp_does_not() {
    let scene = folding();
    let numerical = Planner::run(scene.clone(), Method::NUMERICAL, None).unwrap();
    let s = &numerical.summary;
    assert!(s.self_collision_steps > 0, "{s:?}");
    assert!(s.min_self_clearance.unwrap() < 0.0);
    assert!(!s.success);
    // The paper's criterion knows obstacles only; distance, priority and
    // qp count the chain's own pairs.
    let stop = STOP_DISTANCE.default;
    for m in [redundant_ik::planner::methods::QP] {
        let run = Planner::run(scene.clone(), m, None).unwrap();
        assert_eq!(run.summary.self_collision_steps, 0, "{m}");
        for sample in &run.steps {
            let c = sample.self_clearance.unwrap();
            assert!(c >= stop - 1e-3, "{m} at t = {}: {c}", sample.t);
        }
    }
    for m in ["distance", "priority"] {
        let run = Planner::run(scene.clone(), m.parse().unwrap(), None).unwrap();
        assert_eq!(run.summary.self_collision_steps, 0, "{m}");
    }
}

#[test]
fn qp_holds_the_links_apart_at_their_own_stop_distance() {
    use redundant_ik::model::Scene as _;
    use redundant_ik::planner::methods::{QP, SELF_INFLUENCE, SELF_STOP_DISTANCE};
    // The links' own stop distance, 9 cm, where the obstacles' stays 2 cm:
    // the folding run keeps 9 cm between the links, where with the
    // defaults (the obstacles' numbers) it comes within 6.4 cm.
    let mut scene = folding();
    scene.params_mut().set(&SELF_INFLUENCE, 0.25).unwrap();
    scene.params_mut().set(&SELF_STOP_DISTANCE, 0.09).unwrap();
    let run = Planner::run(scene.clone(), QP, None).unwrap();
    let closest = run
        .steps
        .iter()
        .map(|s| s.self_clearance.unwrap())
        .fold(f64::INFINITY, f64::min);
    assert!(closest >= 0.09 - 1e-3, "{closest}");
    let default = Planner::run(folding(), QP, None).unwrap();
    let closest_default = default.summary.min_self_clearance.unwrap();
    assert!(closest_default < 0.08, "{closest_default}");
    // The obstacles' stop distance does not move the links' pairs.
    let mut scene = folding();
    scene.params_mut().set(&STOP_DISTANCE, 0.1).unwrap();
    let same = Planner::run(scene, QP, None).unwrap();
    assert_eq!(
        same.summary.min_self_clearance,
        default.summary.min_self_clearance
    );
}

#[test]
fn the_pose_model_counts_the_self_pairs_with_the_spheres() {
    let scene = folding();
    let arm = &scene.arm;
    let mut pose = arm.pose();
    arm.update(&mut pose, &[0.3, -0.5, 0.4, -2.4, 0.2, 1.6, 0.5])
        .unwrap();
    let mut pairs = <redundant_ik::space::PoseChain as Model<6>>::pairs(7);
    <redundant_ik::space::PoseChain as Model<6>>::update_pairs(
        &scene,
        &pose,
        f64::INFINITY,
        &mut pairs,
    );
    assert_eq!(pairs.len(), arm.chain.self_pairs().len());
}

fn volume(link: &str) -> Volume {
    Volume {
        link: link.into(),
        moved_by: 1,
        a: [0.0; 3],
        b: [0.0, 0.0, 0.1],
        radius: 0.05,
        source: Source::Segment,
    }
}

#[test]
fn an_srdf_disables_pairs_by_link_name() {
    let srdf = r#"<?xml version="1.0"?>
<robot name="arm">
  <group name="arm"><chain base_link="base" tip_link="hand"/></group>
  <disable_collisions link1="upper" link2="hand" reason="Never"/>
  <disable_collisions link1="base" link2="finger" reason="Adjacent"/>
</robot>"#;
    let links = disabled_links(srdf).unwrap();
    assert_eq!(links.len(), 2);
    let volumes = [
        volume("base"),
        volume("upper"),
        volume("fore"),
        volume("hand"),
        volume("hand"),
    ];
    let (pairs, unknown) = disabled_pairs(&volumes, &links);
    assert_eq!(pairs, vec![[1, 3], [1, 4]]);
    assert_eq!(unknown, vec!["finger".to_string()]);
    // Hostile or broken files are refused with a reason.
    let dtd = r#"<!DOCTYPE robot [<!ENTITY a "aaaa">]><robot>&a;</robot>"#;
    assert!(disabled_links(dtd)
        .unwrap_err()
        .to_string()
        .contains("document type"));
    assert!(
        disabled_links("<robot><disable_collisions link1=\"a\"/></robot>")
            .unwrap_err()
            .to_string()
            .contains("link2")
    );
    assert!(disabled_links("<robot>")
        .unwrap_err()
        .to_string()
        .contains("well-formed"));
    assert!(disabled_links("<srdf/>")
        .unwrap_err()
        .to_string()
        .contains("<robot>"));
}
