//! The slice atlas a cell at a time (`SliceJob`: one planner per method,
//! its sphere moved and the planner reset for every cell) is the atlas of
//! a new planner on a copy of the scene for every cell and method, to the
//! last bit, whatever the chunks it is advanced in.

use std::sync::Arc;

use redundant_ik::atlas::space::{default_region, slice, Plane, SliceAtlas, SliceJob};
use redundant_ik::atlas::{Cell, Class, Grid, Outcome};
use redundant_ik::networks::space::{SpaceNetworkSet, SpaceNetworks};
use redundant_ik::planner::{methods, REACH_TOLERANCE};
use redundant_ik::planner::{Networks, Planner};
use redundant_ik::scene::SpaceScene;
use redundant_ik::space::{clearance, SpacePose, Sphere};
use redundant_ik::Method;

/// The atlas as the definition says, one new planner per cell and method
/// (what `slice` computed before the job existed).
fn fresh(
    scene: &SpaceScene,
    plane: Plane,
    grid: Grid,
    methods: &[Method],
    nets: Option<&Arc<SpaceNetworks>>,
) -> SliceAtlas {
    let radius = scene.obstacles[0].radius;
    let pose = SpacePose::new(&scene.arm, &scene.theta0).unwrap();
    let [u0, u1, v0, v1] = grid.region;
    let step = |a: f64, b: f64, i: usize| a + (b - a) * i as f64 / (grid.n - 1) as f64;
    let mut cells = Vec::new();
    for j in 0..grid.n {
        for i in 0..grid.n {
            let c = plane.point(step(u0, u1, i), step(v0, v1, j));
            let sphere = Sphere::new(c, radius);
            let pre = if sphere.validate(&scene.arm).is_err()
                || clearance(&scene.arm, &pose, &[sphere]) <= 0.0
            {
                Some(Class::StartOverlap)
            } else {
                let d = scene.path.distance_to(c, scene.start(), scene.target);
                (d <= radius + scene.arm.radius()).then_some(Class::PathBlocked)
            };
            let mut s = scene.clone();
            s.obstacles[0] = sphere;
            let outcomes = methods.iter().map(|&m| run(&s, m, pre, nets)).collect();
            // Whether avoidance matters here: the arm without it collides.
            let avoidance_needed = pre
                .is_none()
                .then(|| run(&s, Method::NO_AVOIDANCE, pre, None).class == Class::Collision);
            cells.push(Cell {
                centre: c,
                outcomes,
                avoidance_needed,
            });
        }
    }
    SliceAtlas {
        arm: None,
        plane,
        grid,
        radius,
        methods: methods.to_vec(),
        cells,
    }
}

fn run(
    s: &SpaceScene,
    m: Method,
    pre: Option<Class>,
    nets: Option<&Arc<SpaceNetworks>>,
) -> Outcome {
    let blank = Outcome {
        class: Class::StartOverlap,
        min_distance: None,
        min_clearance: None,
        final_error: None,
        out_of_range_steps: 0,
        limit_steps: 0,
        relaxed_steps: 0,
        error: None,
    };
    if pre == Some(Class::StartOverlap) {
        return blank;
    }
    let nets = nets.filter(|_| m.uses_networks()).cloned();
    let mut p = Planner::new(s.clone(), m, nets.map(|n| n as Networks<_, 3>)).unwrap();
    // To the end or to the first error; the summary is the run's so far.
    let error = p.summary_to_end().err().map(|e| e.to_string());
    let r = p.summary();
    let class = pre.unwrap_or(if error.is_some() {
        Class::Failed
    } else if r.collision_steps > 0 {
        Class::Collision
    } else if r.limit_steps > 0 {
        Class::Limit
    } else if r.final_error > REACH_TOLERANCE {
        Class::Missed
    } else {
        Class::Success
    });
    Outcome {
        class,
        min_distance: r.min_distance,
        min_clearance: r.min_clearance,
        final_error: Some(r.final_error),
        out_of_range_steps: r.out_of_range_steps,
        limit_steps: r.limit_steps,
        relaxed_steps: r.relaxed_steps,
        error,
    }
}

/// Every method that runs in space on the arm `key` (the learned ones
/// where it has networks).
fn every_method(nets: bool) -> Vec<Method> {
    methods::ALL
        .iter()
        .copied()
        .filter(|m| m.in_space() && (nets || !m.uses_networks()))
        .collect()
}

/// The job advanced in uneven chunks, and `slice`, equal the fresh atlas.
fn check(key: &str, nets: Option<Arc<SpaceNetworks>>, n: usize) {
    let scene = SpaceScene::by_key(key).unwrap();
    let plane = Plane::through_line(&scene);
    let grid = Grid::new(default_region(&scene, plane), n).unwrap();
    let methods = every_method(nets.is_some());
    let expected = fresh(&scene, plane, grid, &methods, nets.as_ref());
    let mut job = SliceJob::new(&scene, plane, grid, &methods, nets.as_ref()).unwrap();
    assert_eq!((job.total(), job.done(), job.row()), (n * n, 0, n));
    assert!(
        job.clone().finish().is_err(),
        "refused while cells are missing"
    );
    let mut chunks = [3, 1, 7].into_iter().cycle();
    while !job.is_done() {
        let before = job.done();
        let done = job.advance(chunks.next().unwrap());
        assert!(done > before && done <= job.total());
    }
    assert_eq!(job.advance(5), n * n, "nothing past the end");
    let a = job.finish().unwrap();
    assert_eq!(a, expected, "{key}: the job against new planners");
    let run = a.cells.iter().flat_map(|c| &c.outcomes);
    assert!(
        run.filter(|o| o.class != Class::StartOverlap).count() > n * n,
        "{key}: most cells run"
    );
    let b = slice(&scene, plane, grid, &methods, nets.as_ref()).unwrap();
    assert_eq!(b, expected, "{key}: slice");
}

#[test]
fn the_pandas_job_is_the_atlas_of_new_planners_in_every_method() {
    let nets = SpaceNetworkSet::PandaReach.load().unwrap();
    check("panda", Some(nets), 5);
}

#[test]
fn the_iiwas_job_is_the_atlas_of_new_planners_in_every_method() {
    check("iiwa14", None, 5);
}

#[test]
fn a_planner_reset_with_its_sphere_moved_runs_as_a_new_one() {
    let scene = SpaceScene::by_key("panda").unwrap();
    let mut p = Planner::new(scene.clone(), methods::QP, None).unwrap();
    let first = p.summary_to_end().unwrap();
    let moved = Sphere::new([0.45, 0.1, 0.5], 0.06);
    p.set_sphere(0, moved).unwrap();
    assert!(p.sample().clearance.is_some());
    p.reset();
    assert_eq!(p.time(), 0.0);
    let mut s = scene.clone();
    s.obstacles[0] = moved;
    let direct = Planner::new(s.clone(), methods::QP, None).unwrap();
    assert_eq!(p.sample(), direct.sample());
    assert_eq!(
        p.summary_to_end().unwrap(),
        direct.run_to_end().unwrap().summary
    );
    // Back to the first sphere: the first run again.
    p.set_sphere(0, scene.obstacles[0]).unwrap();
    p.reset();
    assert_eq!(p.summary_to_end().unwrap(), first);
    // A sphere on the base or past the end is refused, changing nothing.
    let on_base = Sphere::new(scene.arm.base().1, 0.05);
    assert!(p.set_sphere(0, on_base).is_err());
    assert!(p.set_sphere(2, moved).is_err());
    assert_eq!(p.scene().obstacles, scene.obstacles);
}
