//! The methods beyond the paper in space (`distance`, `priority`, `qp`):
//! the program's rows hold at every step of the presets' tasks, `qp` keeps
//! every capsule out of the sphere and every joint within its limits while
//! the hand reaches its target, and a program no rate satisfies is relaxed
//! and says so.

use redundant_ik::planner::methods::constraints::{self, Rows};
use redundant_ik::planner::methods::Context;
use redundant_ik::planner::methods::{DAMPER_GAIN, INFLUENCE, STOP_DISTANCE};
use redundant_ik::planner::methods::{DISTANCE, PRIORITY, QP};
use redundant_ik::planner::{Planner, Summary};
use redundant_ik::scene::SpaceScene;
use redundant_ik::space::{Chain, SpacePairs, SpacePose, Sphere, PRESETS};

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Every constraint's rows at `pose`, in the program's order, each with
/// the constraint's name.
fn rows_at(scene: &SpaceScene, pose: &SpacePose) -> Vec<(&'static str, Vec<f64>, f64)> {
    let cx = Context::<Chain, 3> {
        scene,
        networks: None,
    };
    let n = pose.dof();
    let mut out = Vec::new();
    for entry in constraints::ALL {
        let mut rows = Rows::default();
        rows.clear(n);
        (entry.space)(n).rows(&cx, pose, &mut rows).unwrap();
        for (g, h) in rows.iter() {
            out.push((entry.info.name, g.to_vec(), h));
        }
    }
    out
}

/// Steps `scene` with `qp` to its end; at every step the rates of its
/// first RK4 stage keep every row, `G theta_dot <= h` (`<= max(h, 0)` in
/// a step whose program was relaxed). Returns the run's summary and how
/// many rows bound (held with equality).
fn rows_hold_at_every_step(name: &str, scene: &SpaceScene) -> (Summary, usize) {
    assert_eq!(scene.feedback_gain, 0.0, "the line's Xdot is the command");
    let mut p = Planner::new(scene.clone(), QP, None).unwrap();
    let start = p.pose().hand();
    let xdot = [0, 1, 2].map(|k| (scene.target[k] - start[k]) / scene.tf);
    let (mut binding, mut relaxed_steps) = (0, 0);
    let mut samples = vec![p.sample().clone()];
    while !p.done() {
        let theta = p.sample().theta.clone();
        let rates = p.theta_dot(&theta, xdot).unwrap();
        let pose = SpacePose::new(&scene.arm, &theta).unwrap();
        let t = p.time();
        let sample = p.step().unwrap().clone();
        relaxed_steps += usize::from(sample.relaxed);
        for (what, g, h) in rows_at(scene, &pose) {
            let bound = if sample.relaxed { h.max(0.0) } else { h };
            let rate = dot(&g, &rates);
            let tol = 1e-9 * (1.0 + bound.abs());
            assert!(
                rate <= bound + tol,
                "{name}, t = {t}: {what} row {g:?}: {rate} > {bound}"
            );
            binding += usize::from(rate > bound - tol);
        }
        samples.push(sample);
    }
    let run = Planner::new(scene.clone(), QP, None)
        .and_then(Planner::run_to_end)
        .unwrap();
    assert_eq!(run.steps, samples, "{name}: the same run twice");
    assert_eq!(run.summary.relaxed_steps, relaxed_steps, "{name}");
    (run.summary, binding)
}

/// The forearm of `scene`'s chain at its start: the moving segment of the
/// most joints' segments that is longest, its ends.
fn forearm(scene: &SpaceScene) -> ([f64; 3], [f64; 3]) {
    let pose = SpacePose::new(&scene.arm, &scene.theta0).unwrap();
    let len = |s: &redundant_ik::space::Segment| {
        let (a, b) = pose.segment(s);
        (0..3).map(|k| (b[k] - a[k]).powi(2)).sum::<f64>().sqrt()
    };
    let s = scene
        .arm
        .segments()
        .iter()
        .filter(|s| s.moved_by >= 3)
        .max_by(|a, b| len(a).total_cmp(&len(b)))
        .unwrap();
    pose.segment(s)
}

/// Two spheres of radius 5 cm on opposite sides of the forearm, at
/// fraction `at` of its length, each 1 cm from its capsule (within the
/// stop distance `d_s = 2 cm`): one damper asks the forearm to move one
/// way, the other the opposite way, so no rate keeps both.
fn squeezed(scene: &SpaceScene, at: f64) -> SpaceScene {
    let (a, b) = forearm(scene);
    let q = [0, 1, 2].map(|k| a[k] + at * (b[k] - a[k]));
    let u = [0, 1, 2].map(|k| b[k] - a[k]);
    // A unit normal to the forearm, horizontal: u x z, normalised.
    let c = [u[1], -u[0], 0.0];
    let l = (c[0] * c[0] + c[1] * c[1]).sqrt();
    let off = scene.arm.radius() + 0.05 + 0.01;
    let mut s = scene.clone();
    s.obstacles = [1.0, -1.0]
        .map(|side| Sphere::new([0, 1, 2].map(|k| q[k] + side * off * c[k] / l), 0.05))
        .to_vec();
    s
}

#[test]
fn on_both_presets_tasks_qp_keeps_every_row_every_capsule_out_of_the_sphere_and_every_joint_within_its_limits(
) {
    // Measured at lambda = 0: the Panda starts 0.101 m from its sphere,
    // the iiwa 0.135 m; both come within the stop distance, 0.0200 m, and
    // end 16 µm and 2 µm from their targets.
    for (p, reach) in PRESETS.iter().zip([1e-3, 1e-5]) {
        // With the paper's area vector off (lambda = 0, NEO's setting) the
        // dampers alone keep the sphere away: they must bind.
        let mut scene = SpaceScene::preset(p);
        scene
            .params
            .set(&redundant_ik::planner::methods::LAMBDA, 0.0)
            .unwrap();
        let (summary, binding) = rows_hold_at_every_step(p.key, &scene);
        assert!(
            binding > 0,
            "{}: no damper bound, the test says little",
            p.key
        );
        assert_eq!(summary.collision_steps, 0, "{}: {summary:?}", p.key);
        assert_eq!(summary.limit_steps, 0, "{}: {summary:?}", p.key);
        assert_eq!(summary.relaxed_steps, 0, "{}: {summary:?}", p.key);
        let start = SpacePose::new(&scene.arm, &scene.theta0).unwrap();
        let c0 = redundant_ik::space::clearance(&scene.arm, &start, &scene.obstacles);
        // Clear at the start; the dampers keep the stop distance (to the
        // step's discretisation, 0.1 mm).
        assert!(c0 > scene.param(&STOP_DISTANCE), "{}: {c0}", p.key);
        assert!(
            summary.min_clearance.unwrap() >= scene.param(&STOP_DISTANCE) - 1e-4,
            "{}: {summary:?} from {c0}",
            p.key
        );
        assert!(summary.final_error < reach, "{}: {summary:?}", p.key);
    }
}

#[test]
fn distance_and_priority_keep_every_capsule_out_of_the_sphere_on_both_presets_tasks() {
    for p in PRESETS {
        let scene = SpaceScene::preset(&p);
        for m in [DISTANCE, PRIORITY] {
            let run = Planner::new(scene.clone(), m, None)
                .and_then(Planner::run_to_end)
                .unwrap();
            assert_eq!(
                run.summary.collision_steps, 0,
                "{} {m}: {:?}",
                p.key, run.summary
            );
            assert!(
                run.summary.final_error < 1e-2,
                "{} {m}: {:?}",
                p.key,
                run.summary
            );
        }
    }
}

#[test]
fn the_damper_rows_are_minus_n_jq_with_the_damper_bound_for_spheres_and_the_floor() {
    let mut scene = SpaceScene::preset(&PRESETS[0]);
    scene.floor = true;
    // Every pair counts, the floor's too (the arm stands 0.3 m and more
    // above it).
    scene.params.set(&INFLUENCE, 5.0).unwrap();
    scene.params.set(&DAMPER_GAIN, 0.7).unwrap();
    let pose = SpacePose::new(&scene.arm, &scene.theta0).unwrap();
    let (di, ds, xi) = (5.0, scene.param(&STOP_DISTANCE), 0.7);
    let dampers: Vec<_> = rows_at(&scene, &pose)
        .into_iter()
        .filter(|(what, _, _)| *what == "damper")
        .collect();
    let segments = scene.arm.segments();
    let moving: Vec<usize> = (0..segments.len())
        .filter(|&k| segments[k].moved_by > 0)
        .collect();
    assert_eq!(
        dampers.len(),
        2 * moving.len(),
        "one sphere and the floor per moving capsule"
    );
    let n = pose.dof();
    let mut jq = vec![0.0; 3 * n];
    let r = scene.arm.radius();
    for (i, &k) in moving.iter().enumerate() {
        let s = segments[k];
        let (a, b) = pose.segment(&s);
        // The sphere's row: -n . J_Q at the axis point nearest the centre.
        let sp = scene.obstacles[0];
        let (t, d) = redundant_ik::space::closest(sp.centre, a, b);
        let q = [0, 1, 2].map(|j| a[j] + t * (b[j] - a[j]));
        let normal = [0, 1, 2].map(|j| (q[j] - sp.centre[j]) / d);
        pose.point_jacobian_into(q, s.moved_by, &mut jq);
        let (_, g, h) = &dampers[i];
        for (c, gc) in g.iter().enumerate() {
            let want = -dot(&normal, &jq[3 * c..3 * c + 3]);
            assert!((gc - want).abs() < 1e-12, "segment {k}: {g:?}");
        }
        let dist = d - r - sp.radius;
        assert!(
            (h - xi * (dist - ds) / (di - ds)).abs() < 1e-12,
            "segment {k}: {h}"
        );
        // The floor's: its lower end, d = z - r, n = +z.
        let end = if b[2] < a[2] { b } else { a };
        pose.point_jacobian_into(end, s.moved_by, &mut jq);
        let (_, g, h) = &dampers[moving.len() + i];
        for (c, gc) in g.iter().enumerate() {
            assert!(
                (gc + jq[3 * c + 2]).abs() < 1e-12,
                "floor, segment {k}: {g:?}"
            );
        }
        assert!(
            (h - xi * (end[2] - r - ds) / (di - ds)).abs() < 1e-12,
            "floor {k}: {h}"
        );
    }
    // The same pairs as SpacePairs lists them, in the same order.
    let mut pairs = SpacePairs::default();
    pairs.update(&scene.arm, &pose, &scene.obstacles, 5.0);
    pairs.add_floor(&scene.arm, &pose, 5.0);
    assert_eq!(pairs.len(), dampers.len());
    // Without the floor its rows go.
    scene.floor = false;
    let count = rows_at(&scene, &pose)
        .iter()
        .filter(|(w, _, _)| *w == "damper")
        .count();
    assert_eq!(count, moving.len());
}

/// At three quarters of its length the forearm alone is squeezed; at its
/// middle the iiwa's upper arm is close to the spheres too, four nearly
/// opposite active rows on which the solver loses its digits (the program
/// then holds the arm still: `methods/space/qp.rs`). Either way the steps
/// are relaxed and keep the relaxed rows.
#[test]
fn a_forearm_squeezed_between_two_spheres_gives_relaxed_steps_that_keep_the_relaxed_rows() {
    for p in PRESETS {
        for at in [0.75, 0.5] {
            let scene = squeezed(&SpaceScene::preset(&p), at);
            let (summary, _) = rows_hold_at_every_step(p.key, &scene);
            assert!(summary.relaxed_steps > 0, "{} at {at}: {summary:?}", p.key);
            assert_eq!(summary.collision_steps, 0, "{} at {at}: {summary:?}", p.key);
            assert_eq!(summary.limit_steps, 0, "{} at {at}: {summary:?}", p.key);
        }
    }
}
