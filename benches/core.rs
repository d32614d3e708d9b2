//! Cost of the numerical route: one `theta_dot` evaluation and one whole
//! Task 1 run (100 RK4 steps, 400 evaluations).
//!
//! `cargo bench --bench core`

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use redundant_ik::nalgebra::Vector2;
use redundant_ik::{Method, Planner, Scene};

fn theta_dot(c: &mut Criterion) {
    let scene = Scene::task1();
    let xdot = Vector2::new(-0.0955884, -0.0814851);
    for method in [Method::NO_AVOIDANCE, Method::NUMERICAL] {
        let mut p = Planner::new(scene.clone(), method, None).unwrap();
        let th = scene.theta0.clone();
        let mut out = [0.0; 3];
        c.bench_function(&format!("theta_dot/{method}"), |b| {
            b.iter(|| {
                p.theta_dot_into(black_box(&th), black_box([xdot[0], xdot[1]]), &mut out)
                    .unwrap()
            })
        });
    }
}

fn task1_run(c: &mut Criterion) {
    for method in [Method::NO_AVOIDANCE, Method::NUMERICAL] {
        c.bench_function(&format!("task1_run/{method}"), |b| {
            b.iter(|| Planner::run(black_box(Scene::task1()), method, None).unwrap())
        });
    }
}

criterion_group!(benches, theta_dot, task1_run);
criterion_main!(benches);
