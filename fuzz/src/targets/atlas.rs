//! The `atlas` target.

use std::sync::Arc;

use arbitrary::Unstructured;
use redundant_ik::atlas::{Grid, Job, Spec};
use redundant_ik::ik::DampingSchedule;
use redundant_ik::Scene;

use super::checks::shipped;
use super::gen::{method, num, num_in, point, small};

/// Small atlases (2 x 2 or 3 x 3 cells, up to 8 steps per run) of a paper
/// task or an arbitrary scene, over an arbitrary region, in arbitrary
/// methods, with or without networks, advanced in arbitrary chunks. A job
/// that starts finishes with one outcome per cell and method, and its
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
        // Refused values leave the scene as it was, as in the page.
        let _ = scene.set_param(&redundant_ik::planner::methods::LAMBDA, num(&mut u));
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
    let mut methods = Vec::new();
    for _ in 0..small(&mut u, 6) {
        methods.push(method(&mut u));
    }
    let networks = u
        .arbitrary()
        .unwrap_or(true)
        .then(|| Arc::new(shipped().clone()));
    let spec = Spec {
        scene,
        grid,
        methods,
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
        assert_eq!(cell.outcomes.len(), atlas.methods.len());
    }
    for s in &atlas.summary {
        assert_eq!(
            s.counts.iter().sum::<usize>(),
            total,
            "a summary lost cells"
        );
    }
}
