//! The robustness atlas, as a specification: the grid, the classes, the
//! equality with single runs, the summaries and the JSON shape. Natively
//! and, with `wasm-pack test`, in the browser.

#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;
#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use std::sync::{Arc, OnceLock};

use redundant_ik::atlas::{Atlas, Class, Grid, Job, Spec, DEFAULT_GRID, MAX_GRID};
use redundant_ik::networks::Networks;
use redundant_ik::planner::methods;
use redundant_ik::{Arm, Error, Method, Planner, Scene};

fn nets() -> Arc<Networks> {
    static NETS: OnceLock<Arc<Networks>> = OnceLock::new();
    NETS.get_or_init(|| Arc::new(Networks::embedded().unwrap()))
        .clone()
}

/// Task `task` on a small grid over `region`, in `methods`.
fn spec(task: u32, region: [f64; 4], n: usize, methods: &[Method]) -> Spec {
    Spec {
        scene: Scene::task(task).unwrap(),
        grid: Grid::new(region, n).unwrap(),
        methods: methods.to_vec(),
        task: Some(task),
    }
}

/// A small atlas of Task 1 around its obstacle, in every method (cached: it is
/// read by several tests).
fn small() -> &'static Atlas {
    static ATLAS: OnceLock<Atlas> = OnceLock::new();
    ATLAS.get_or_init(|| {
        Atlas::run(
            spec(1, [0.1, 1.3, 0.1, 1.3], 7, &methods::PAPER),
            Some(nets()),
        )
        .unwrap()
    })
}

#[test]
fn cell_centres_span_the_region_with_both_ends_included() {
    let g = Grid::new([-1.0, 2.0, 0.5, 1.5], 4).unwrap();
    assert_eq!(g.cells(), 16);
    let xs: Vec<f64> = (0..4).map(|i| g.x(i)).collect();
    let ys: Vec<f64> = (0..4).map(|j| g.y(j)).collect();
    for (got, want) in xs.iter().zip([-1.0, 0.0, 1.0, 2.0]) {
        assert!((got - want).abs() < 1e-15, "{xs:?}");
    }
    for (got, want) in ys.iter().zip([0.5, 0.5 + 1.0 / 3.0, 0.5 + 2.0 / 3.0, 1.5]) {
        assert!((got - want).abs() < 1e-15, "{ys:?}");
    }
    // Cell (i, j) is index j n + i: rows from y0, each from x0.
    assert_eq!(g.point(0), [g.x(0), g.y(0)]);
    assert_eq!(g.point(6), [g.x(2), g.y(1)]);
    for k in 0..g.cells() {
        assert_eq!(g.nearest(g.point(k)), Some(k));
    }
    assert_eq!(g.nearest([5.0, 1.0]), None);
}

#[test]
fn the_default_grid_is_41_points_over_the_box_of_the_arms_reach_above_the_floor() {
    let s = Spec::task(1).unwrap();
    assert_eq!(s.grid.n, DEFAULT_GRID);
    assert_eq!(DEFAULT_GRID, 41);
    let reach = 0.6 + 0.85 + 0.6;
    let [x0, x1, y0, y1] = s.grid.region;
    assert!((x0 + reach).abs() < 1e-12 && (x1 - reach).abs() < 1e-12);
    assert_eq!(y0, 0.0);
    assert!((y1 - (0.5 + reach)).abs() < 1e-12);
    assert_eq!(s.methods, methods::PAPER.to_vec());
    // An arm whose reach does not get down to the floor keeps its full box.
    let g = Grid::around_reach(&Arm::new(3.0, vec![0.5, 0.5]).unwrap(), 5);
    assert_eq!(g.region, [-1.0, 1.0, 2.0, 4.0]);
}

#[test]
fn the_canonical_obstacles_cell_succeeds_in_numerical_and_collides_in_none() {
    for (task, obstacle) in [(1, [0.5, 0.5]), (2, [0.6, 0.6])] {
        // 0.1 m steps, so the canonical obstacle is a cell centre.
        let s = spec(
            task,
            [0.2, 0.9, 0.2, 0.9],
            8,
            &[Method::NO_AVOIDANCE, Method::NUMERICAL],
        );
        let k = s.grid.nearest(obstacle).unwrap();
        let p = s.grid.point(k);
        assert!((p[0] - obstacle[0]).abs() < 1e-12 && (p[1] - obstacle[1]).abs() < 1e-12);
        let a = Atlas::run(s, None).unwrap();
        let none = a.outcome(k, Method::NO_AVOIDANCE).unwrap();
        let numerical = a.outcome(k, Method::NUMERICAL).unwrap();
        assert_eq!(none.class, Class::Collision, "task {task}: {none:?}");
        assert!(none.min_distance.unwrap() < 0.05);
        assert_eq!(
            numerical.class,
            Class::Success,
            "task {task}: {numerical:?}"
        );
        assert!(numerical.min_distance.unwrap() > 0.2);
    }
}

#[test]
fn a_cell_on_the_line_is_path_blocked_and_one_on_the_start_arm_is_start_overlap() {
    let scene = Scene::task(1).unwrap();
    let start = redundant_ik::Pose::new(&scene.arm, &scene.theta0).unwrap();
    let ee = start.end_effector();
    let mid = [0.5 * (ee[0] + 0.6), 0.5 * (ee[1] + 0.2)];
    let joint = start.joints()[1];
    for (centre, class) in [(mid, Class::PathBlocked), (joint, Class::StartOverlap)] {
        // A 3 x 3 grid whose middle cell is `centre`.
        let region = [
            centre[0] - 0.3,
            centre[0] + 0.3,
            centre[1] - 0.3,
            centre[1] + 0.3,
        ];
        let a = Atlas::run(spec(1, region, 3, &methods::PAPER), Some(nets())).unwrap();
        for (m, o) in a.methods.iter().zip(&a.cells[4].outcomes) {
            assert_eq!(o.class, class, "{m} at {centre:?}");
            // Path-blocked cells are still run and recorded; overlaps are not run.
            assert_eq!(o.final_error.is_some(), class == Class::PathBlocked, "{m}");
            assert_eq!(o.min_distance.is_some(), class == Class::PathBlocked, "{m}");
        }
    }
    // The post counts as the start arm too.
    let a = Atlas::run(
        spec(1, [-0.3, 0.3, 0.0, 0.6], 3, &[Method::NO_AVOIDANCE]),
        None,
    )
    .unwrap();
    assert_eq!(a.cells[4].outcomes[0].class, Class::StartOverlap);
}

#[test]
fn atlas_outcomes_equal_single_planner_runs_at_random_cells() {
    let a = small();
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    for _ in 0..6 {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        let k = (state % a.cells.len() as u64) as usize;
        let cell = &a.cells[k];
        for (&method, o) in a.methods.iter().zip(&cell.outcomes) {
            let mut scene = Scene::task(1).unwrap();
            scene.obstacles[0].centre = cell.centre;
            if o.class == Class::StartOverlap {
                continue;
            }
            let nets = (method != Method::NO_AVOIDANCE && method != Method::NUMERICAL)
                .then(|| nets() as Arc<dyn redundant_ik::Surrogate>);
            let run = Planner::run(scene, method, nets).unwrap().summary;
            assert_eq!(o.min_distance, run.min_distance, "cell {k} {method}");
            assert_eq!(o.final_error, Some(run.final_error), "cell {k} {method}");
            assert_eq!(
                o.out_of_range_steps, run.out_of_range_steps,
                "cell {k} {method}"
            );
            if o.class != Class::PathBlocked {
                let class = if run.collided {
                    Class::Collision
                } else if run.reached {
                    Class::Success
                } else {
                    Class::Missed
                };
                assert_eq!(o.class, class, "cell {k} {method}");
            }
        }
    }
}

#[test]
fn classes_mean_what_they_say() {
    let a = small();
    for cell in &a.cells {
        for o in &cell.outcomes {
            match o.class {
                Class::Success => {
                    assert!(o.min_distance.unwrap() >= a.radius);
                    assert!(o.final_error.unwrap() <= 5e-3);
                }
                Class::Collision => assert!(o.min_distance.unwrap() < a.radius),
                Class::Missed => {
                    assert!(o.min_distance.unwrap() >= a.radius);
                    assert!(o.final_error.unwrap() > 5e-3);
                }
                Class::Failed => assert!(o.error.is_some()),
                Class::Limit => panic!("the paper's arm has no joint limits to pass"),
                Class::SelfCollision => panic!("a planar arm checks no self-collision"),
                Class::PathBlocked | Class::StartOverlap => {}
            }
        }
    }
    // The small grid has something of nearly every kind.
    let none = a.summary_of(Method::NO_AVOIDANCE).unwrap();
    assert!(none.count(Class::Collision) > 0 && none.count(Class::Success) > 0);
    assert!(none.count(Class::StartOverlap) > 0 && none.count(Class::PathBlocked) > 0);
}

#[test]
fn summaries_count_every_cell_and_rate_the_avoidable_ones() {
    let a = small();
    let numerical = a
        .methods
        .iter()
        .position(|&m| m == Method::NUMERICAL)
        .unwrap();
    for (k, s) in a.summary.iter().enumerate() {
        assert_eq!(s.method, a.methods[k]);
        assert_eq!(s.counts.iter().sum::<usize>(), a.cells.len());
        let classes = |c: Class| a.cells.iter().filter(|x| x.outcomes[k].class == c).count();
        for c in Class::ALL {
            assert_eq!(s.count(c), classes(c), "{} {}", s.method, c.name());
        }
        let avoidable = a.cells.len() - classes(Class::StartOverlap) - classes(Class::PathBlocked);
        assert_eq!(s.avoidable.cells, avoidable);
        assert_eq!(s.avoidable.successes, classes(Class::Success));
        assert_eq!(
            s.success_rate(),
            Some(classes(Class::Success) as f64 / avoidable as f64)
        );
        // Inside and outside the v network's trained region split the avoidable cells.
        let (i, o) = (
            s.inside_trained_region.unwrap(),
            s.outside_trained_region.unwrap(),
        );
        assert_eq!(i.cells + o.cells, avoidable);
        assert_eq!(i.successes + o.successes, s.avoidable.successes);
        // Agreement with the numerical route, for the network methods only.
        let learned = s.method.uses_networks();
        assert_eq!(s.agreement.is_some(), learned);
        if let Some(g) = s.agreement {
            assert_eq!(
                g.both + g.numerical_only + g.method_only + g.neither,
                a.cells.len()
            );
            let ok =
                |c: &redundant_ik::atlas::Cell, m: usize| c.outcomes[m].class == Class::Success;
            let num_only = a
                .cells
                .iter()
                .filter(|c| ok(c, numerical) && !ok(c, k))
                .count();
            let method_only = a
                .cells
                .iter()
                .filter(|c| !ok(c, numerical) && ok(c, k))
                .count();
            assert_eq!((g.numerical_only, g.method_only), (num_only, method_only));
        }
    }
    assert_eq!(a.trained_region, Some([0.3, 0.8, 0.3, 0.8]));
}

#[test]
fn the_json_has_the_documented_shape() {
    let a = small();
    let v = serde_json::to_value(a).unwrap();
    assert_eq!(v["task"], 1);
    assert_eq!(v["grid"]["n"], 7);
    assert_eq!(v["grid"]["region"], serde_json::json!([0.1, 1.3, 0.1, 1.3]));
    assert_eq!(v["radius"], 0.05);
    assert_eq!(v["lambda"], 4.0);
    let paper: Vec<&str> = methods::PAPER.iter().map(|m| m.name()).collect();
    assert_eq!(v["methods"], serde_json::json!(paper));
    let cells = v["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 49);
    let names: Vec<&str> = Class::ALL.iter().map(|c| c.name()).collect();
    for (k, cell) in cells.iter().enumerate() {
        assert_eq!(cell["x"], a.cells[k].x());
        assert_eq!(cell["y"], a.cells[k].y());
        let outcomes = cell["outcomes"].as_object().unwrap();
        let mut keys: Vec<&str> = outcomes.keys().map(|s| s.as_str()).collect();
        keys.sort_unstable();
        let mut expected = paper.clone();
        expected.sort_unstable();
        assert_eq!(keys, expected);
        for o in outcomes.values() {
            assert!(names.contains(&o["class"].as_str().unwrap()), "{o}");
            let run = o["class"] != "start_overlap";
            assert_eq!(o["min_distance"].is_number(), run, "{o}");
            assert_eq!(o["final_error"].is_number(), run, "{o}");
            assert!(o["out_of_range_steps"].is_u64());
        }
    }
    for &m in &paper {
        let s = &v["summary"][m];
        assert!(s["success_rate"].is_number(), "{m}: {s}");
        let counts = s["counts"].as_object().unwrap();
        // Every class but self-collision, which a planar arm never has
        // (its count is written where it is not zero).
        assert_eq!(counts.len(), Class::COUNT - 1);
        let total: u64 = counts.values().map(|n| n.as_u64().unwrap()).sum();
        assert_eq!(total, 49);
        for c in names.iter().filter(|&&c| c != "self_collision") {
            assert!(counts.contains_key(*c), "{m}: no count of {c}");
        }
    }
    assert!(v["summary"]["case3"]["agreement"]["numerical_only"].is_u64());
    // In the text, every map lists the methods in the atlas's order.
    let text = serde_json::to_string(a).unwrap();
    assert!(
        text.contains(r#""outcomes":{"none":{"class":"#),
        "{}",
        &text[..400]
    );
    let at = |key: &str| text.rfind(&format!(r#""{key}":{{"success_rate""#)).unwrap();
    assert!(at("none") < at("numerical") && at("numerical") < at("case1"));
    assert!(v["summary"]["numerical"]["agreement"].is_null());
}

#[test]
fn a_job_in_chunks_and_across_threads_equals_the_whole_run() {
    let s = spec(
        2,
        [0.0, 1.6, 0.0, 1.6],
        6,
        &[Method::NUMERICAL, Method::CASE3],
    );
    let whole = Atlas::run(s.clone(), Some(nets())).unwrap();
    let mut job = Job::new(s.clone(), Some(nets())).unwrap();
    assert_eq!((job.done(), job.total()), (0, 36));
    let mut seen = vec![];
    while !job.is_done() {
        seen.push(job.advance(5));
    }
    assert_eq!(seen, [5, 10, 15, 20, 25, 30, 35, 36]);
    assert_eq!(job.finish().unwrap(), whole);
    #[cfg(not(target_family = "wasm"))]
    {
        let mut job = Job::new(s, Some(nets())).unwrap();
        while !job.is_done() {
            job.advance_parallel(7);
        }
        assert_eq!(job.finish().unwrap(), whole);
    }
}

#[test]
fn bad_specs_are_refused_with_an_error_naming_the_problem() {
    let ok = spec(1, [0.0, 1.0, 0.0, 1.0], 3, &[Method::NUMERICAL]);
    let refused = |s: Spec, nets: Option<Arc<Networks>>| Job::new(s, nets).unwrap_err();

    let mut s = ok.clone();
    s.scene.obstacles.clear();
    assert_eq!(refused(s, None), Error::NoObstacle);

    let mut s = ok.clone();
    s.methods.clear();
    assert!(
        matches!(refused(s, None), Error::OutOfRange { what, .. } if what == "number of methods")
    );

    let mut s = ok.clone();
    s.methods = vec![Method::CASE3];
    assert!(matches!(refused(s, None), Error::NetworksUnavailable(_)));

    for n in [0, 1, MAX_GRID + 1] {
        let e = Grid::new([0.0, 1.0, 0.0, 1.0], n).unwrap_err();
        assert!(matches!(e, Error::OutOfRange { what, .. } if what == "grid points per side"));
    }
    for region in [[1.0, 0.0, 0.0, 1.0], [0.0, 1.0, 1.0, 1.0]] {
        let e = Grid::new(region, 5).unwrap_err();
        assert_eq!(e, Error::EmptyRegion { region });
    }
    let e = Grid::new([f64::NAN, 1.0, 0.0, 1.0], 5).unwrap_err();
    assert!(matches!(e, Error::NonFinite { what } if what == "region x0"));
    let e = Grid::new([0.0, 1e300, 0.0, 1.0], 5).unwrap_err();
    assert!(matches!(e, Error::TooLarge { .. }));

    // A grid that bypassed Grid::new is checked when the job starts.
    let mut s = ok.clone();
    s.grid.n = 1;
    assert!(matches!(refused(s, None), Error::OutOfRange { .. }));

    // Networks for another arm are refused, naming both arms.
    let mut s = ok.clone();
    s.scene.arm = Arm::new(0.5, vec![0.6, 0.85, 0.7]).unwrap();
    s.methods = vec![Method::CASE2];
    assert!(matches!(
        refused(s, Some(nets())),
        Error::NetworksForAnotherArm { .. }
    ));

    // Finishing early is refused; duplicate methods are dropped.
    let mut s = ok;
    s.methods = vec![Method::NUMERICAL, Method::NUMERICAL];
    let mut job = Job::new(s, None).unwrap();
    job.advance(4);
    assert!(matches!(
        job.clone().finish(),
        Err(Error::OutOfRange { .. })
    ));
    job.advance(usize::MAX);
    assert_eq!(job.finish().unwrap().methods, [Method::NUMERICAL]);
}

#[test]
fn moving_an_obstacle_onto_the_post_or_past_the_list_is_refused_and_changes_nothing() {
    let mut p = Planner::new(Scene::task(1).unwrap(), Method::NUMERICAL, None).unwrap();
    let before = p.scene().clone();
    assert!(matches!(
        p.move_obstacle(0, [0.0, 0.2]),
        Err(Error::ObstacleOnPost { .. })
    ));
    assert!(matches!(
        p.move_obstacle(1, [1.0, 1.0]),
        Err(Error::OutOfRange { .. })
    ));
    assert!(matches!(
        p.move_obstacle(0, [f64::NAN, 1.0]),
        Err(Error::NonFinite { .. })
    ));
    assert_eq!(p.scene(), &before);
    p.move_obstacle(0, [0.9, 0.4]).unwrap();
    assert_eq!(p.scene().obstacles[0].centre, [0.9, 0.4]);
    assert_eq!(p.scene().obstacles[0].radius, before.obstacles[0].radius);
}

#[test]
fn an_atlas_read_back_from_its_json_is_the_same_atlas() {
    let a = small();
    let text = serde_json::to_string(a).unwrap();
    let back: Atlas = serde_json::from_str(&text).unwrap();
    assert_eq!(&back, a);
    // It lists its methods as `methods`; atlases written before that name
    // said `modes`, and still read back.
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert!(v.get("modes").is_none() && v["methods"].is_array());
    let methods = v.as_object_mut().unwrap().remove("methods").unwrap();
    v["modes"] = methods;
    assert_eq!(&serde_json::from_value::<Atlas>(v).unwrap(), a);
    // A file with a cell missing, or a method missing from a cell, is refused.
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["cells"].as_array_mut().unwrap().pop();
    assert!(serde_json::from_value::<Atlas>(v).is_err());
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    v["cells"][3]["outcomes"]
        .as_object_mut()
        .unwrap()
        .remove("case3");
    assert!(serde_json::from_value::<Atlas>(v).is_err());
}

#[test]
fn where_avoidance_mattered_is_where_the_arm_without_it_collides() {
    let a = small();
    let none = a
        .methods
        .iter()
        .position(|&m| m == Method::NO_AVOIDANCE)
        .unwrap();
    for c in &a.cells {
        let o = &c.outcomes[none];
        match c.avoidance_needed {
            Some(needed) => {
                assert!(o.class.avoidable());
                assert_eq!(needed, o.class == Class::Collision);
            }
            None => assert!(!o.class.avoidable()),
        }
    }
    let s = a.summary_of(Method::NO_AVOIDANCE).unwrap();
    assert_eq!(
        s.mattered.successes, 0,
        "without avoidance it never succeeds there"
    );
    assert!(s.mattered.cells > 0 && s.mattered.cells < s.avoidable.cells);
    // Without `none` among the methods the atlas still knows where it matters.
    let mut spec = Spec::task(1).unwrap();
    spec.grid = a.grid;
    spec.methods = vec![Method::NUMERICAL];
    let alone = Atlas::run(spec, None).unwrap();
    for (x, y) in alone.cells.iter().zip(&a.cells) {
        assert_eq!(x.avoidance_needed, y.avoidance_needed);
    }
}
