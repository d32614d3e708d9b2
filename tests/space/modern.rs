//! The methods beyond the paper in space (`distance`, `priority`, `qp`):
//! the program's rows hold at every step of the presets' tasks, `qp` keeps
//! every capsule out of the sphere and every joint within its limits while
//! the hand reaches its target, and a program no rate satisfies is relaxed
//! and says so.

use redundant_ik::planner::methods::constraints::{self, Rows};
use redundant_ik::planner::methods::space::SpaceContext;
use redundant_ik::planner::methods::{DAMPER_GAIN, INFLUENCE, STOP_DISTANCE};
use redundant_ik::planner::space::{SpacePlanner, SpaceSummary};
use redundant_ik::scene::SpaceScene;
use redundant_ik::space::{SpacePairs, SpacePose, Sphere, PRESETS};
use redundant_ik::planner::methods::{DISTANCE, PRIORITY, QP};
use redundant_ik::Method;

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Every constraint's rows at `pose`, in the program's order, each with
/// the constraint's name.
fn rows_at(scene: &SpaceScene, pose: &SpacePose) -> Vec<(&'static str, Vec<f64>, f64)> {
    let cx = SpaceContext { scene };
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
fn rows_hold_at_every_step(name: &str, scene: &SpaceScene) -> (SpaceSummary, usize) {
    assert_eq!(scene.feedback_gain, 0.0, "the line's Xdot is the command");
    let mut p = SpacePlanner::new(scene.clone(), QP).unwrap();
    let start = p.pose().hand();
    let xdot = [0, 1, 2].map(|k| (scene.target[k] - start[k]) / scene.tf);
    let (mut binding, mut relaxed_steps) = (0, 0);
    let mut samples = vec![p.sample().clone()];
    while !p.done() {
        let theta = p.sample().theta.clone();
        let rates = p.theta_dot(&theta, xdot).unwrap();
        let pose = SpacePose::new(&scene.chain, &theta).unwrap();
        let t = p.t();
        let sample = p.step().unwrap().clone();
        relaxed_steps += usize::from(sample.relaxed);
        for (what, g, h) in rows_at(scene, &pose) {
            let bound = if sample.relaxed { h.max(0.0) } else { h };
            let rate = dot(&g, &rates);
            let tol = 1e-9 * (1.0 + bound.abs());
            assert!(rate <= bound + tol, "{name}, t = {t}: {what} row {g:?}: {rate} > {bound}");
            binding += usize::from(rate > bound - tol);
        }
        samples.push(sample);
    }
    let run = SpacePlanner::new(scene.clone(), QP)
        .and_then(|pl| pl.run())
        .unwrap();
    assert_eq!(run.samples, samples, "{name}: the same run twice");
    assert_eq!(run.summary.relaxed_steps, relaxed_steps, "{name}");
    (run.summary, binding)
}

/// The forearm of `scene`'s chain at its start: the moving segment of the
/// most joints' segments that is longest, its ends.
fn forearm(scene: &SpaceScene) -> ([f64; 3], [f64; 3]) {
    let pose = SpacePose::new(&scene.chain, &scene.theta0).unwrap();
    let len = |s: &redundant_ik::space::Segment| {
        let (a, b) = pose.segment(s);
        (0..3).map(|k| (b[k] - a[k]).powi(2)).sum::<f64>().sqrt()
    };
    let s = scene
        .chain
        .segments()
        .iter()
        .filter(|s| s.moved_by >= 3)
        .max_by(|a, b| len(a).total_cmp(&len(b)))
        .unwrap();
    pose.segment(s)
}

#[test]
fn diag() {
    for p in PRESETS {
        let mut scene = SpaceScene::preset(&p);
        let (a, b) = forearm(&scene);
        let q = [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]));
        let u = [0, 1, 2].map(|k| b[k] - a[k]);
        // A unit normal to the forearm: u x z, normalised.
        let c = [u[1], -u[0], 0.0];
        let l = (c[0] * c[0] + c[1] * c[1]).sqrt();
        let off = scene.chain.radius() + 0.05 + 0.01;
        scene.spheres = [1.0, -1.0]
            .map(|s| Sphere::new([0, 1, 2].map(|k| q[k] + s * off * c[k] / l), 0.05))
            .to_vec();
        let (s, b) = rows_hold_at_every_step(p.key, &scene);
        eprintln!("{} squeezed {s:?} binding {b}", p.key);
    }
}

#[test]
fn diag2() {
    use redundant_ik::planner::methods::{DELTA, LAMBDA, SIGN_SMOOTHING, SLACK_WEIGHT};
    let p = PRESETS[1];
    let mut scene = SpaceScene::preset(&p);
    let (a, b) = forearm(&scene);
    let q = [0, 1, 2].map(|k| 0.5 * (a[k] + b[k]));
    let u = [0, 1, 2].map(|k| b[k] - a[k]);
    let c = [u[1], -u[0], 0.0];
    let l = (c[0] * c[0] + c[1] * c[1]).sqrt();
    let off = scene.chain.radius() + 0.05 + 0.01;
    scene.spheres = [1.0, -1.0]
        .map(|s| Sphere::new([0, 1, 2].map(|k| q[k] + s * off * c[k] / l), 0.05))
        .to_vec();
    let mut pl = SpacePlanner::new(scene.clone(), QP).unwrap();
    let start = pl.pose().hand();
    let xdot = [0, 1, 2].map(|k| (scene.target[k] - start[k]) / scene.tf);
    for _ in 0..5 {
        let r = pl.step().unwrap().relaxed;
        eprintln!("t {} relaxed {r}", pl.t());
    }
    let theta = pl.sample().theta.clone();
    let pose = SpacePose::new(&scene.chain, &theta).unwrap();
    let n = theta.len();
    let rows = rows_at(&scene, &pose);
    let mut v = vec![0.0; n];
    redundant_ik::space::criterion::null_space_vector_into(&scene.chain, &pose, scene.spheres.iter().map(|s| s.centre), scene.param(&LAMBDA), scene.param(&SIGN_SMOOTHING), &mut v);
    let w = 1.0 / (1.0 / scene.param(&SLACK_WEIGHT) + scene.param(&DELTA));
    let jac = pose.jacobian();
    let mut h = vec![0.0; n * n];
    let mut g = vec![0.0; n];
    for r in 0..n {
        for c in 0..n {
            h[r * n + c] = if r == c { 1.0 } else { 0.0 } + w * dot(&jac[3 * r..3 * r + 3], &jac[3 * c..3 * c + 3]);
        }
        g[r] = v[r] + w * dot(&jac[3 * r..3 * r + 3], &xdot);
    }
    let am: Vec<f64> = rows.iter().flat_map(|(_, gg, _)| gg.iter().map(|x| -x)).collect();
    let bm: Vec<f64> = rows.iter().map(|(_, _, hh)| -hh).collect();
    let mut ws = redundant_ik::qp::Workspace::default();
    let mut x = vec![0.0; n];
    let res = redundant_ik::qp::solve(&mut ws, &h, &g, &am, &bm, &mut x);
    eprintln!("res {res:?} x {x:?} active {:?}", ws.active());
    for (i, (what, gg, hh)) in rows.iter().enumerate() {
        eprintln!("{i} {what} {:?} h {hh} rate {}", gg, dot(gg, &x));
    }
    let rates = pl.theta_dot(&theta, xdot).unwrap();
    eprintln!("rates {rates:?}");
}
