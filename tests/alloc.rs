//! A step allocates nothing: with a global allocator that counts, once a
//! planner exists its RK4 steps (and resets) make no heap allocation, in
//! every method, for arms of 2 to 6 links, with several obstacles, damping and
//! closed-loop feedback. Runs natively and in the browser.

#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::Arc;

use redundant_ik::networks::{NetworkSet, Networks};
use redundant_ik::planner::methods;
use redundant_ik::{Arm, DampingSchedule, Obstacle, Planner, Scene, Surrogate};

thread_local! {
    /// Allocations made by this thread (tests run on several threads).
    static ALLOCATIONS: Cell<u64> = const { Cell::new(0) };
}

fn count() {
    // `try_with`: the slot may be gone while a thread shuts down.
    let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
}

fn allocations() -> u64 {
    ALLOCATIONS.with(Cell::get)
}

struct Counting;

// SAFETY: every call is forwarded unchanged to the system allocator.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count();
        System.alloc_zeroed(layout)
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        System.realloc(ptr, layout, new_size)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by `f` on this thread.
fn allocations_in(f: impl FnOnce()) -> u64 {
    let before = allocations();
    f();
    allocations() - before
}

/// Task 1's scene with two obstacles, the damping schedule and feedback.
fn busy_scene() -> Scene {
    let mut s = Scene::task1();
    s.obstacles.push(Obstacle::new(1.1, 1.2, 0.05));
    s.damping = Some(DampingSchedule::default());
    s.feedback_gain = 1.0;
    s
}

/// Task 2 with an obstacle the arm starts within 2 cm of and one beside
/// the line: `qp`'s dampers bind (and need relaxing) from the first step,
/// so its solver runs.
fn damper_scene() -> Scene {
    let mut s = Scene::task2();
    s.obstacles = vec![
        Obstacle::new(0.615, 0.8925, 0.05),
        Obstacle::new(0.82, 0.51, 0.05),
    ];
    s
}

#[test]
fn a_step_allocates_nothing_in_any_method() {
    // Both shipped sets: the reach set's 96-96 Phi is wider than the
    // paper's networks, and its route refines Phi.
    for set in NetworkSet::ALL {
        let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded_set(set).unwrap());
        let mut refined = busy_scene();
        refined.set_param(&methods::REFINE, 2.0).unwrap();
        // The paths beyond the line: a circle, and a polyline (whose
        // reset keeps its corners).
        let mut circle = Scene::task1();
        circle.path = "circle:1.2,0.8".parse().unwrap();
        circle.feedback_gain = 1.0;
        let mut points = Scene::task1();
        points.path = "points:1.2,0.3;0.6,0.3".parse().unwrap();
        for scene in [
            Scene::task1(),
            Scene::task2(),
            busy_scene(),
            damper_scene(),
            refined,
            circle,
            points,
        ] {
            for &method in methods::ALL {
                let mut p = Planner::new(scene.clone(), method, Some(nets.clone())).unwrap();
                let n = allocations_in(|| {
                    for _ in 0..20 {
                        p.step().unwrap();
                    }
                });
                assert_eq!(n, 0, "{set:?} {method}: {n} allocations in 20 steps");
                let n = allocations_in(|| p.reset());
                assert_eq!(n, 0, "{set:?} {method}: reset allocated {n} times");
            }
        }
    }
}

#[test]
fn a_step_allocates_nothing_for_arms_of_two_to_six_links() {
    for links in 2..=6 {
        let arm = Arm::new(0.5, vec![2.0 / links as f64; links]).unwrap();
        let mut s = Scene::task1();
        s.theta0 = (0..links).map(|i| 0.3 + 0.2 * i as f64).collect();
        s.arm = arm;
        s.target = [0.8, 0.9];
        s.obstacles = vec![Obstacle::new(1.2, 0.2, 0.05), Obstacle::new(-0.8, 1.0, 0.1)];
        s.damping = Some(DampingSchedule::default());
        // Methods with networks need networks trained for the arm.
        for method in methods::ALL.iter().copied().filter(|m| !m.uses_networks()) {
            let mut p = Planner::new(s.clone(), method, None).unwrap();
            let n = allocations_in(|| {
                for _ in 0..20 {
                    p.step().unwrap();
                }
            });
            assert_eq!(n, 0, "{links} links, {method}: {n} allocations");
        }
    }
}

#[test]
fn theta_dot_into_allocates_nothing() {
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    for &method in methods::ALL {
        let mut p = Planner::new(Scene::task1(), method, Some(nets.clone())).unwrap();
        let theta = Scene::task1().theta0;
        let mut out = [0.0; 3];
        let n = allocations_in(|| p.theta_dot_into(&theta, [-0.1, -0.08], &mut out).unwrap());
        assert_eq!(n, 0, "{method}");
        // What the Python package's Controller.step calls: the path's rates
        // at a time of the user's loop, with feedback.
        p.set_feedback_gain(1.0).unwrap();
        let n = allocations_in(|| p.rates_at(&theta, 0.35, &mut out).unwrap());
        assert_eq!(n, 0, "{method}: rates_at");
    }
}

/// In space: every method with a spatial rule on both presets' tasks, with
/// the floor, the damping schedule and feedback, and with the forearm
/// squeezed between two spheres (qp's relaxed program).
#[test]
fn a_spatial_step_allocates_nothing_in_any_method() {
    use redundant_ik::scene::SpaceScene;
    use redundant_ik::space::{SpacePose, Sphere, PRESETS};
    for preset in PRESETS {
        let task = SpaceScene::preset(&preset);
        let mut busy = task.clone();
        busy.floor = true;
        busy.damping = Some(DampingSchedule::default());
        busy.feedback_gain = 1.0;
        busy.params.set(&methods::INFLUENCE, 0.8).unwrap();
        // Two spheres 1 cm from the forearm on opposite sides.
        let pose = SpacePose::new(&task.arm, &task.theta0).unwrap();
        let segments = task.arm.segments();
        let last = segments[segments.len() - 2];
        let (a, b) = pose.segment(&last);
        let q = [0, 1, 2].map(|k| a[k] + 0.75 * (b[k] - a[k]));
        let c = [b[1] - a[1], a[0] - b[0], 0.0];
        let l = c[0].hypot(c[1]);
        let off = task.arm.radius() + 0.06;
        let mut squeezed = task.clone();
        squeezed.obstacles = [1.0, -1.0]
            .map(|s| Sphere::new([0, 1, 2].map(|k| q[k] + s * off * c[k] / l), 0.05))
            .to_vec();
        // As many spheres as a scene may hold, every pair within the
        // influence distance, the floor's too: the most rows there can be.
        let mut crowded = busy.clone();
        crowded.params.set(&methods::INFLUENCE, 50.0).unwrap();
        crowded.obstacles = (0..redundant_ik::space::MAX_SPHERES)
            .map(|i| {
                let a = i as f64 * std::f64::consts::TAU / 8.0;
                Sphere::new([1.2 * a.cos(), 1.2 * a.sin(), 1.0], 0.05)
            })
            .collect();
        for (k, scene) in [task, busy, squeezed, crowded].into_iter().enumerate() {
            for method in methods::ALL.iter().copied().filter(|m| m.in_space()) {
                let Some(mut p) = planner_with_shipped(&scene, preset.key, method) else {
                    continue;
                };
                let mut relaxed = false;
                let n = allocations_in(|| {
                    for _ in 0..20 {
                        relaxed |= p.step().unwrap().relaxed;
                    }
                });
                assert_eq!(n, 0, "{} {method}: {n} allocations in 20 steps", preset.key);
                if k == 2 && method == methods::QP {
                    assert!(relaxed, "{}: the squeeze did not relax qp", preset.key);
                }
            }
        }
    }
}

#[test]
fn the_counter_does_count() {
    // The tests above could not fail if the counter saw nothing.
    let n = allocations_in(|| {
        std::hint::black_box(vec![1.0; 3]);
    });
    assert!(n >= 1);
}

/// A step of every method in space allocates nothing either: on each
/// preset with its sphere, the damping schedule, feedback and weighted
/// least norm from a start near a limit (the weights' solves run), along
/// the line, a circle and a polyline.
#[test]
fn a_spatial_step_allocates_nothing_in_any_method_in_space() {
    use redundant_ik::scene::{JointWeighting, SpacePath, SpaceScene};
    use redundant_ik::space::PRESETS;
    for p in PRESETS {
        let mut scene = SpaceScene::preset(&p);
        let [lo, hi] = scene.arm.joint_limits().unwrap().ranges()[0];
        scene.theta0[0] = lo + 0.1 * (hi - lo);
        scene.damping = Some(DampingSchedule::default());
        scene.feedback_gain = 1.0;
        scene.weighting = JointWeighting::Wln;
        let x = scene.start();
        let paths = [
            SpacePath::Line,
            SpacePath::Circle {
                centre: [x[0], x[1], x[2] - 0.1],
                normal: [1.0, 0.0, 0.0],
                laps: 1,
            },
            SpacePath::Points(vec![
                [x[0], x[1] + 0.1, x[2]],
                [x[0] - 0.1, x[1] + 0.1, x[2] + 0.1],
            ]),
        ];
        for path in paths {
            scene.path = path;
            for m in methods::ALL.iter().filter(|m| m.in_space()) {
                let Some(mut planner) = planner_with_shipped(&scene, p.key, *m) else {
                    continue;
                };
                planner.step().unwrap();
                let n = allocations_in(|| {
                    for _ in 0..20 {
                        planner.step().unwrap();
                    }
                });
                assert_eq!(
                    n, 0,
                    "{} {m} {}: {n} allocations in 20 steps",
                    p.key, scene.path
                );
                // The Python package's Controller.step along the path.
                let theta = planner.theta().as_slice().to_vec();
                let mut out = vec![0.0; theta.len()];
                let n = allocations_in(|| planner.rates_at(&theta, 1.3, &mut out).unwrap());
                assert_eq!(n, 0, "{} {m} {}: rates_at", p.key, scene.path);
            }
        }
    }
}

/// What the slice atlas does for each cell allocates nothing: moving a
/// spatial planner's sphere, resetting it to `t = 0` and running it to
/// `tf` keeping only the summary, in every method on both presets.
#[test]
fn a_spatial_planner_moved_and_reset_runs_without_allocating() {
    use redundant_ik::scene::SpaceScene;
    use redundant_ik::space::{Sphere, PRESETS};
    for p in PRESETS {
        let mut scene = SpaceScene::preset(&p);
        scene.tf = 0.2;
        let s = scene.obstacles[0];
        for m in methods::ALL.iter().filter(|m| m.in_space()) {
            let Some(mut planner) = planner_with_shipped(&scene, p.key, *m) else {
                continue;
            };
            planner.summary_to_end().unwrap();
            let n = allocations_in(|| {
                for dz in [0.05, -0.05] {
                    let c = [s.centre[0], s.centre[1], s.centre[2] + dz];
                    planner.set_sphere(0, Sphere::new(c, s.radius)).unwrap();
                    planner.reset();
                    planner.summary_to_end().unwrap();
                }
            });
            assert_eq!(n, 0, "{} {m}: {n} allocations", p.key);
        }
    }
}

/// A spatial planner of `method` with the networks shipped for the preset
/// `key` where it learns; `None` for a learned method on a preset with
/// none (only the Panda has a set).
fn planner_with_shipped(
    scene: &redundant_ik::scene::SpaceScene,
    key: &str,
    method: redundant_ik::Method,
) -> Option<redundant_ik::Planner<redundant_ik::space::Chain, 3>> {
    use redundant_ik::networks::space::SpaceNetworkSet;
    let nets = if method.uses_networks() {
        Some(SpaceNetworkSet::for_arm(key)?.load().unwrap() as redundant_ik::planner::Networks<_, 3>)
    } else {
        None
    };
    Some(redundant_ik::Planner::new(scene.clone(), method, nets).unwrap())
}
