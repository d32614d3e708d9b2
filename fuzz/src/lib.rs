//! The bodies of the fuzz targets (`fuzz/fuzz_targets/*.rs` call them;
//! `tests/fuzz.rs` at the top level replays the committed corpora and the
//! regression inputs through them).
//!
//! Each body turns the fuzzer's bytes into calls of the public API, the
//! way the page, the CLI and the workers call it, and asserts what must
//! hold for every input:
//! - nothing panics (a panic is what the fuzzer reports);
//! - no state the core accepts holds a non-finite joint angle, time or
//!   end-effector position;
//! - an operation that is refused leaves the state as it was;
//! - what loads also saves and loads back to the same thing.
//!
//! Numbers are drawn by [`num`]: mostly ordinary values in `[-3, 3]` (the
//! paper's arm reaches 2.05 m), often the special values people and URLs
//! produce (NaN, infinities, 1e308, -0, subnormals), sometimes raw bits.
//! Sizes are kept small so that a million executions take minutes: what is
//! checked is the handling of bad values, not the planner's endurance
//! (the soak and the atlas benchmarks cover that).

use std::sync::{Arc, OnceLock};

use arbitrary::Unstructured;
use redundant_ik::atlas::{Grid, Job, Spec};
use redundant_ik::ik::DampingSchedule;
use redundant_ik::networks::{NetKind, Sampling, Variant, WeightsFile};
use redundant_ik::nn::lm::{self, Dataset, LmOptions};
use redundant_ik::planner::methods;
use redundant_ik::planner::{Method, Planner, Surrogate};
use redundant_ik::session::{Handle, Session};
use redundant_ik::training::{phi_datasets, v_dataset, Visited};
use redundant_ik::training_job::Request;
use redundant_ik::{Arm, Networks, Obstacle, Scene};

/// Values that people, URLs and hostile files produce.
const SPECIAL: [f64; 14] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    1e308,
    -1e308,
    1e-308,
    5e-324,
    f64::MAX,
    f64::MIN,
    f64::EPSILON,
    1.0,
    -1.0,
];

/// A number: 3 in 4 uniform in `[-3, 3]`, 1 in 8 special, 1 in 8 raw bits.
pub fn num(u: &mut Unstructured) -> f64 {
    match u.int_in_range(0u8..=7).unwrap_or(2) {
        0 => f64::from_bits(u.arbitrary().unwrap_or(0)),
        1 => *u.choose(&SPECIAL).unwrap_or(&f64::NAN),
        _ => {
            let k: u16 = u.arbitrary().unwrap_or(0);
            -3.0 + 6.0 * f64::from(k) / f64::from(u16::MAX)
        }
    }
}

/// A number in `[lo, hi]` as a rule, and any [`num`] 1 time in 8.
fn num_in(u: &mut Unstructured, lo: f64, hi: f64) -> f64 {
    if u.ratio(1u8, 8u8).unwrap_or(false) {
        return num(u);
    }
    let k: u16 = u.arbitrary().unwrap_or(0);
    lo + (hi - lo) * f64::from(k) / f64::from(u16::MAX)
}

fn point(u: &mut Unstructured) -> [f64; 2] {
    [num(u), num(u)]
}

fn small(u: &mut Unstructured, max: usize) -> usize {
    u.int_in_range(0..=max).unwrap_or(0)
}

fn mode(u: &mut Unstructured) -> Method {
    *u.choose(&methods::PAPER).unwrap_or(&Method::NUMERICAL)
}

/// The shipped networks, parsed once per process.
fn shipped() -> &'static Networks {
    static NETS: OnceLock<Networks> = OnceLock::new();
    NETS.get_or_init(|| Networks::embedded().expect("the shipped networks load"))
}

fn shipped_surrogate() -> Arc<dyn Surrogate> {
    static NETS: OnceLock<Arc<Networks>> = OnceLock::new();
    NETS.get_or_init(|| Arc::new(shipped().clone())).clone()
}

/// An arm from arbitrary numbers: 0 to 8 links (the core takes 2 to 6).
fn arm(u: &mut Unstructured) -> (f64, Vec<f64>) {
    if u.ratio(1u8, 3u8).unwrap_or(false) {
        let a = Arm::paper();
        return (a.post(), a.links().to_vec());
    }
    let post = num_in(u, 0.0, 1.0);
    let n = small(u, 8);
    let links = (0..n).map(|_| num_in(u, 0.05, 1.0)).collect();
    (post, links)
}

fn assert_finite(what: &str, xs: &[f64]) {
    assert!(
        xs.iter().all(|x| x.is_finite()),
        "non-finite {what} accepted: {xs:?}"
    );
}

/// What a planner's state is, for checking that a refusal changed nothing
/// and that nothing non-finite got in.
#[derive(Debug, Clone, PartialEq)]
struct Snapshot {
    scene: Scene,
    mode: Method,
    time: f64,
    theta: Vec<f64>,
    ee: [f64; 2],
}

impl Snapshot {
    fn of(p: &Planner) -> Self {
        Self {
            scene: p.scene().clone(),
            mode: p.method(),
            time: p.time(),
            theta: p.theta().as_slice().to_vec(),
            ee: p.sample().ee,
        }
    }

    fn assert_finite(&self) {
        assert_finite("joint angle", &self.theta);
        assert_finite("time", &[self.time]);
        assert_finite("end effector", &self.ee);
    }
}

/// Up to `steps` RK4 steps: each one that goes through leaves a finite
/// state, and the first that fails leaves the state as it was.
fn step_checked(p: &mut Planner, steps: usize) {
    for _ in 0..steps {
        let before = Snapshot::of(p);
        if p.step().is_err() {
            assert_eq!(Snapshot::of(p), before, "a failed step changed the state");
            return;
        }
        Snapshot::of(p).assert_finite();
    }
}

// ---- weights files ---------------------------------------------------------

/// Weights files from arbitrary bytes, as the page's file picker, its
/// localStorage and the CLI's `--phi`/`--v` read them: parse, validate,
/// pair with the shipped partner, run a planner on the result. A file
/// that loads must save and load back equal, and its networks must never
/// put a non-finite angle into a planner's state.
pub fn weights(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    let Ok(file) = WeightsFile::from_json(&text) else {
        return;
    };
    // What loads validates, and survives a save.
    file.validate().expect("a loaded file validates");
    let json = file.to_json().expect("a loaded file saves");
    let again = WeightsFile::from_json(&json).expect("a saved file loads");
    assert_eq!(again, file, "save and load changed the file");

    let shipped = shipped();
    let pair = match file.net {
        NetKind::Phi => Networks::from_json(&text, &shipped.v_file().to_json().unwrap()),
        NetKind::V => Networks::from_json(&shipped.phi_file().to_json().unwrap(), &text),
    };
    let Ok(nets) = pair else {
        return;
    };
    let nets: Arc<dyn Surrogate> = Arc::new(nets);
    let mut scene = Scene::task1();
    scene.tf = 1.0;
    for mode in [Method::CASE1, Method::CASE2, Method::CASE3] {
        let Ok(mut p) = Planner::new(scene.clone(), mode, Some(nets.clone())) else {
            continue;
        };
        step_checked(&mut p, 10);
    }
}

// ---- arms, obstacles and scenes --------------------------------------------

/// Arms, obstacles and scenes from arbitrary numbers (or, 1 time in 4, a
/// scene as JSON, as the workers receive it), then a planner in every mode
/// for up to 12 steps. A scene the planner accepts validates; no step
/// accepts a non-finite angle; a failed step changes nothing.
pub fn scene(data: &[u8]) {
    let mut u = Unstructured::new(data);
    let scene = if u.ratio(1u8, 4u8).unwrap_or(false) {
        let text = String::from_utf8_lossy(u.take_rest());
        match serde_json::from_str::<Scene>(&text) {
            Ok(s) => s,
            Err(_) => return,
        }
    } else {
        let (post, links) = arm(&mut u);
        let Ok(arm) = Arm::new(post, links) else {
            return;
        };
        // The arm's own questions must answer for any point.
        let p = point(&mut u);
        let _ = arm.can_reach(&redundant_ik::nalgebra::Vector2::new(p[0], p[1]));
        let theta0 = (0..arm.dof().min(8))
            .map(|_| num(&mut u))
            .collect::<Vec<_>>();
        let _ = arm.check_angles(&theta0);
        let obstacles = (0..small(&mut u, 3))
            .map(|_| Obstacle::new(num(&mut u), num(&mut u), num_in(&mut u, 0.0, 0.3)))
            .collect::<Vec<_>>();
        for o in &obstacles {
            let _ = o.validate(&arm);
        }
        let dt = num_in(&mut u, 0.01, 0.2);
        Scene {
            arm,
            theta0,
            target: point(&mut u),
            obstacles,
            lambda: num_in(&mut u, 0.0, 10.0),
            delta: num_in(&mut u, 0.0, 0.1),
            damping: u
                .ratio(1u8, 2u8)
                .unwrap_or(false)
                .then(DampingSchedule::default),
            dt,
            tf: dt * small(&mut u, 30) as f64,
            feedback_gain: num_in(&mut u, 0.0, 5.0),
        }
    };
    let networks = (scene.arm == Arm::paper()).then(shipped_surrogate);
    for mode in methods::PAPER {
        let Ok(mut p) = Planner::new(scene.clone(), mode, networks.clone()) else {
            continue;
        };
        scene.validate().expect("an accepted scene validates");
        Snapshot::of(&p).assert_finite();
        step_checked(&mut p, scene.steps().min(12));
    }
}

// ---- the session: what the page drives ---------------------------------------

/// A session (the page's simulation) driven by up to 32 operations: steps,
/// ticks, targets, obstacles (add, move, remove, replace), modes, `lambda`,
/// damping, feedback, speed, arms, networks, tasks, drags and nudges, with
/// arbitrary numbers. After every operation no angle, time or position is
/// non-finite; an operation refused (other than a step, whose refusal
/// keeps the last good step) leaves the planner as it was; the state the
/// page reads serialises.
pub fn session(data: &[u8]) {
    let mut u = Unstructured::new(data);
    let task = if u.ratio(1u8, 2u8).unwrap_or(true) {
        1
    } else {
        2
    };
    let Ok(mut s) = Session::new(task) else {
        panic!("the paper's task {task} makes a session");
    };
    if u.ratio(3u8, 4u8).unwrap_or(false) {
        s.set_networks(Arc::new(shipped().clone()))
            .expect("the shipped networks fit the paper's arm");
    }
    for _ in 0..32 {
        if u.is_empty() {
            break;
        }
        let before = Snapshot::of(s.planner());
        let op = u.int_in_range(0u8..=24).unwrap_or(0);
        // Operations that step may fail part-way and keep the last good step.
        let steps = matches!(op, 0..=2 | 19 | 20);
        let result = match op {
            0 => s.step(),
            1 => {
                // Bounded, so that one input cannot ask for 100 000 steps.
                let t = num(&mut u);
                let t = if t.is_finite() {
                    s.planner().time() + t.abs().min(0.5)
                } else {
                    t
                };
                s.run_until(t)
            }
            2 => {
                s.set_running(true);
                s.tick(num(&mut u) * 100.0)
            }
            3 => {
                s.set_running(u.arbitrary().unwrap_or(false));
                Ok(())
            }
            4 => {
                let d = u.ratio(1u8, 2u8).unwrap_or(false).then(|| num(&mut u));
                s.set_target(point(&mut u), d)
            }
            5 => s.set_obstacle(point(&mut u)),
            6 => s.move_obstacle(small(&mut u, 9), point(&mut u)),
            7 => s
                .add_obstacle(Obstacle::new(num(&mut u), num(&mut u), num(&mut u)))
                .map(|_| ()),
            8 => s.remove_obstacle(small(&mut u, 9)),
            9 => {
                let obstacles = (0..small(&mut u, 10))
                    .map(|_| Obstacle::new(num(&mut u), num(&mut u), num_in(&mut u, 0.0, 0.3)))
                    .collect();
                s.set_obstacles(obstacles)
            }
            10 => s.set_method(mode(&mut u)),
            11 => s.set_lambda(num(&mut u)),
            12 => s.set_damping(u.arbitrary().unwrap_or(false)),
            13 => s.set_feedback(num(&mut u)),
            14 => s.set_speed(num(&mut u)),
            15 => {
                let (post, links) = arm(&mut u);
                match Arm::new(post, links) {
                    Ok(a) => s.set_arm(a),
                    Err(e) => Err(e),
                }
            }
            16 => s.clear_networks(),
            17 => s.set_networks(Arc::new(shipped().clone())),
            18 => s.load_task(u.int_in_range(0u32..=3).unwrap_or(1)),
            19 => {
                s.run_task();
                // A whole task is 100 steps: take a few of them.
                s.tick(100.0)
            }
            20 => {
                s.reset();
                Ok(())
            }
            21 => {
                let handle = match small(&mut u, 3) {
                    0 => None,
                    1 => Some(Handle::Target),
                    _ => Some(Handle::Obstacle(small(&mut u, 9))),
                };
                s.drag_start(handle);
                s.drag_to(point(&mut u))
            }
            22 => s.drag_end(point(&mut u)),
            23 => {
                s.drag_cancel();
                Ok(())
            }
            _ => {
                let handle = if u.arbitrary().unwrap_or(false) {
                    Handle::Target
                } else {
                    Handle::Obstacle(small(&mut u, 9))
                };
                s.nudge(handle, num(&mut u), num(&mut u))
            }
        };
        let after = Snapshot::of(s.planner());
        after.assert_finite();
        if let Some(g) = s.ghost() {
            Snapshot::of(g).assert_finite();
        }
        if result.is_err() && !steps {
            assert_eq!(after, before, "refused operation {op} changed the planner");
        }
        serde_json::to_string(&s.state()).expect("the state serialises");
    }
}

// ---- the atlas ---------------------------------------------------------------

/// Small atlases (2 x 2 or 3 x 3 cells, up to 8 steps per run) of a paper
/// task or an arbitrary scene, over an arbitrary region, in arbitrary
/// modes, with or without networks, advanced in arbitrary chunks. A job
/// that starts finishes with one outcome per cell and mode, and its
/// summaries count every cell once.
pub fn atlas(data: &[u8]) {
    let mut u = Unstructured::new(data);
    let mut scene = if u.arbitrary().unwrap_or(true) {
        Scene::task1()
    } else {
        Scene::task2()
    };
    // Perturb the scene as the page's controls do.
    if u.ratio(1u8, 2u8).unwrap_or(false) {
        scene.lambda = num(&mut u);
        scene.feedback_gain = num_in(&mut u, 0.0, 3.0);
        scene.damping = u
            .arbitrary()
            .unwrap_or(false)
            .then(DampingSchedule::default);
        scene.target = point(&mut u);
        if let Some(o) = scene.obstacles.first_mut() {
            o.radius = num_in(&mut u, 0.0, 0.3);
        }
        if u.ratio(1u8, 4u8).unwrap_or(false) {
            scene.obstacles.clear();
        }
    }
    scene.tf = scene.dt * (1 + small(&mut u, 7)) as f64;
    let n = u.int_in_range(1usize..=3).unwrap_or(2);
    let region = [num(&mut u), num(&mut u), num(&mut u), num(&mut u)];
    let Ok(grid) = Grid::new(region, n) else {
        return;
    };
    let mut modes = Vec::new();
    for _ in 0..small(&mut u, 6) {
        modes.push(mode(&mut u));
    }
    let networks = u
        .arbitrary()
        .unwrap_or(true)
        .then(|| Arc::new(shipped().clone()));
    let spec = Spec {
        scene,
        grid,
        modes,
        task: None,
    };
    let Ok(mut job) = Job::new(spec, networks) else {
        return;
    };
    let total = job.total();
    assert_eq!(total, n * n);
    let mut guard = 0;
    while !job.is_done() {
        let before = job.done();
        let after = job.advance(small(&mut u, 4).max(1));
        assert!(after > before && after <= total, "advance made no progress");
        guard += 1;
        assert!(guard <= total, "advance took more calls than cells");
    }
    let atlas = job.finish().expect("a done job finishes");
    assert_eq!(atlas.cells.len(), total);
    for cell in &atlas.cells {
        assert_eq!(cell.outcomes.len(), atlas.modes.len());
    }
    for s in &atlas.summary {
        assert_eq!(
            s.counts.iter().sum::<usize>(),
            total,
            "a summary lost cells"
        );
    }
}

// ---- the trainer -----------------------------------------------------------

/// The trainer's entry points with arbitrary small inputs:
/// - the page's training request as JSON (its checks and the specs it
///   makes);
/// - the datasets built from arbitrary visited poses and obstacle points;
/// - Levenberg-Marquardt on an arbitrary small dataset (NaN, infinities,
///   constant columns, one sample) with arbitrary options.
///
/// A trained network validates and has finite weights. (Drawing samples
/// runs whole planner trajectories, which the `scene` target covers.)
pub fn trainer(data: &[u8]) {
    let mut u = Unstructured::new(data);
    match u.int_in_range(0u8..=2).unwrap_or(2) {
        0 => {
            let text = String::from_utf8_lossy(u.take_rest());
            let Ok(request) = serde_json::from_str::<Request>(&text) else {
                return;
            };
            if request.size().is_ok() {
                for net in [NetKind::Phi, NetKind::V] {
                    if let Ok(spec) = request.spec(net) {
                        spec.sampling
                            .validate()
                            .expect("a request's sampling validates");
                    }
                }
            }
        }
        1 => {
            let (post, links) = arm(&mut u);
            let Ok(arm) = Arm::new(post, links) else {
                return;
            };
            let _ = Sampling::for_arm(&arm).validate();
            let samples = (0..small(&mut u, 12))
                .map(|_| Visited {
                    theta: (0..arm.dof().min(8)).map(|_| num(&mut u)).collect(),
                    obstacle: point(&mut u),
                })
                .collect::<Vec<_>>();
            let variant = *u
                .choose(&[Variant::Plain, Variant::Rows, Variant::Equivariant])
                .unwrap_or(&Variant::Plain);
            for set in phi_datasets(&arm, variant, &samples).into_iter().flatten() {
                assert_finite("Phi training input", &set.inputs);
                assert_finite("Phi training target", &set.targets);
            }
            if let Ok(set) = v_dataset(&arm, variant, &samples) {
                assert_finite("v training input", &set.inputs);
                assert_finite("v training target", &set.targets);
            }
        }
        _ => {
            let n_in = u.int_in_range(1usize..=3).unwrap_or(1);
            let n_out = u.int_in_range(1usize..=3).unwrap_or(1);
            let mut set = Dataset::new(n_in, n_out);
            for _ in 0..small(&mut u, 24) {
                let x: Vec<f64> = (0..n_in).map(|_| num(&mut u)).collect();
                let y: Vec<f64> = (0..n_out).map(|_| num(&mut u)).collect();
                set.push(&x, &y);
            }
            let mut sizes = vec![n_in];
            for _ in 0..small(&mut u, 2) {
                sizes.push(u.int_in_range(0usize..=5).unwrap_or(1));
            }
            sizes.push(n_out);
            let opts = LmOptions {
                max_epochs: u.int_in_range(0usize..=4).unwrap_or(1),
                mu: num(&mut u),
                mu_dec: num(&mut u),
                mu_inc: num(&mut u),
                mu_max: num(&mut u),
                min_grad: num(&mut u),
                max_fail: small(&mut u, 6),
                goal: num(&mut u),
                chunk: small(&mut u, 70),
                split: [num(&mut u), num(&mut u)],
            };
            let seed = u.arbitrary().unwrap_or(1);
            if let Ok((mlp, report)) = lm::train(&sizes, &set, opts, seed, |_| true) {
                mlp.validate().expect("a trained network validates");
                assert_finite("trained weight", &mlp.params());
                assert!(report.epochs <= opts.max_epochs);
            }
        }
    }
}
