//! The floor and the post as obstacles (`--floor`): their pairs have the
//! form of a disc's (clearance, normal, the rate row `n^T J_p` that
//! `distance`, `priority` and the dampers of `qp` read), and with the
//! switch on a link below the floor or across the post collides.

use super::{random_arm, random_theta};
use redundant_ik::clearance::{Against, Pair, Pairs};
use redundant_ik::nn::Rng;
use redundant_ik::planner::methods::{DISTANCE, QP};
use redundant_ik::{Arm, Method, Planner, Pose, Scene};
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

#[test]
fn the_floor_pair_is_the_links_lower_end_and_the_post_pair_the_closest_points() {
    let arm = Arm::paper();
    // Joint 2 at (0.6, 0.5), joint 3 at (0.6, -0.35) (link 2 straight
    // down through the floor), the hand at (0, -0.35).
    let pose = Pose::new(
        &arm,
        &[
            std::f64::consts::FRAC_PI_2,
            std::f64::consts::FRAC_PI_2,
            std::f64::consts::FRAC_PI_2,
        ],
    )
    .unwrap();
    let p = Pair::floor(&pose, 1);
    assert_eq!(p.against, Against::Floor);
    assert!((p.clearance + 0.35).abs() < 1e-12, "{p:?}");
    assert_eq!(p.normal, [0.0, 1.0]);
    // Link 3 runs from (0.6, -0.35) to (0, -0.35): below the post's foot,
    // closest to it at the hand, 0.35 m away.
    let q = Pair::post(&pose, 2, arm.post());
    assert_eq!(q.against, Against::Post);
    assert!((q.clearance - 0.35).abs() < 1e-12, "{q:?}");
    assert!((q.normal[1] + 1.0).abs() < 1e-12, "{q:?}");
    // Link 2 from (0.6, 0.5) to (-0.15, 0.1) (0.75 left, 0.4 down: 0.85 m)
    // crosses the post at y = 0.18: its end 0.15 m past it must go back,
    // to the right.
    let phi2 = (-0.75f64 / 0.85).atan2(-0.4 / 0.85);
    let half = std::f64::consts::FRAC_PI_2;
    let pose = Pose::new(&arm, &[half, phi2 - half, 0.0]).unwrap();
    let end = pose.joints()[2];
    assert!(
        (end[0] + 0.15).abs() < 1e-12 && (end[1] - 0.1).abs() < 1e-12,
        "{end:?}"
    );
    let crossing = Pair::post(&pose, 1, arm.post());
    assert!((crossing.clearance + 0.15).abs() < 1e-12, "{crossing:?}");
    assert_eq!(crossing.normal, [1.0, 0.0]);
    // The first link stands on the post: no pair of it.
    let mut pairs = Pairs::default();
    pairs.add_ground(&pose, arm.post(), f64::INFINITY);
    let posts: Vec<_> = pairs
        .as_slice()
        .iter()
        .filter(|p| p.against == Against::Post)
        .map(|p| p.link)
        .collect();
    assert_eq!(posts, [1, 2]);
}

#[test]
fn the_grounds_rate_rows_match_central_differences_of_the_clearance_on_random_arms() {
    let mut rng = Rng::new(31);
    let (mut compared, mut missed) = (0, 0);
    for _ in 0..400 {
        let arm = random_arm(&mut rng);
        let n = arm.dof();
        let theta = random_theta(&mut rng, n);
        let pose = Pose::new(&arm, &theta).unwrap();
        let mut pairs = Pairs::default();
        pairs.add_ground(&pose, arm.post(), f64::INFINITY);
        for pair in pairs.as_slice() {
            let at = |t: &[f64]| {
                let q = Pose::new(&arm, t).unwrap();
                match pair.against {
                    Against::Floor => Pair::floor(&q, pair.link),
                    _ => Pair::post(&q, pair.link, arm.post()),
                }
            };
            // Away from where the closest feature switches (kinks of c).
            if pair.clearance.abs() < 1e-3 {
                continue;
            }
            let mut row = vec![0.0; n];
            pair.rate_row(&pose, &mut row);
            let h = 1e-7;
            let mut fds = vec![0.0; n];
            for i in 0..n {
                let mut up = theta.clone();
                up[i] += h;
                let mut down = theta.clone();
                down[i] -= h;
                let (u, d) = (at(&up), at(&down));
                fds[i] = (u.clearance - d.clearance) / (2.0 * h);
            }
            let agree = row
                .iter()
                .zip(&fds)
                .all(|(r, f)| (r - f).abs() <= 1e-5 * (1.0 + r.abs()));
            // A kink (the closest end changes) may sit within h: rare.
            if agree {
                compared += 1;
            } else {
                missed += 1;
            }
        }
    }
    assert!(
        compared > 2000 && missed * 100 < compared,
        "{compared} rows agreed, {missed} did not"
    );
}

#[test]
fn with_the_floor_on_distance_keeps_a_four_link_arm_above_it_in_task_2() {
    let mut scene = Scene::task2();
    scene.arm = redundant_ik::arm::PRESETS
        .iter()
        .find(|p| p.key == "four")
        .unwrap()
        .arm();
    scene.theta0 = redundant_ik::session::start_pose(&scene.arm);
    let below = |scene: &Scene, m: Method| {
        let run = Planner::run(scene.clone(), m, None).unwrap();
        let low = run
            .steps
            .iter()
            .flat_map(|s| s.joints[1..].iter().map(|j| j[1]))
            .fold(f64::INFINITY, f64::min);
        (low, run.summary)
    };
    let (low, summary) = below(&scene, DISTANCE);
    assert!(low < -0.1, "without the floor a link goes below it: {low}");
    assert!(!summary.collided, "and nothing counts it");
    scene.floor = true;
    for m in [DISTANCE, QP] {
        let (low, summary) = below(&scene, m);
        assert!(low > 0.0, "{m}: {low}");
        assert!(summary.success, "{m}: {summary:?}");
    }
    // The numerical route ignores the ground; with the switch on, going
    // below it is a collision.
    let mut open = scene.clone();
    open.obstacles.clear();
    let (low, summary) = below(&open, Method::NUMERICAL);
    assert_eq!(summary.collided, low < 0.0, "{low}");
}

#[test]
fn the_switches_travel_in_the_scenes_json_and_old_files_have_neither() {
    let mut scene = Scene::task1();
    let json = serde_json::to_value(&scene).unwrap();
    assert_eq!(json.get("floor"), None);
    assert_eq!(json.get("joint_weighting"), None);
    scene.floor = true;
    scene.weighting = redundant_ik::scene::JointWeighting::Wln;
    let json = serde_json::to_value(&scene).unwrap();
    assert_eq!(json["floor"], true);
    assert_eq!(json["joint_weighting"], "wln");
    let back: Scene = serde_json::from_value(json).unwrap();
    assert_eq!(back, scene);
    let mut bad = serde_json::to_value(&scene).unwrap();
    bad["joint_weighting"] = "heavy".into();
    let e = serde_json::from_value::<Scene>(bad)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("unknown joint weighting 'heavy': use none or wln"),
        "{e}"
    );
}
