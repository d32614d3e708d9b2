//! Random straight-line tasks for any arm: what the training data of an arm
//! without the paper's two tasks is drawn from, and what trained networks
//! are checked on.
//!
//! A task is drawn as follows (all from one seeded generator, so the same
//! seed gives the same tasks on every machine):
//! - the start pose: `theta_1` uniform in `[-pi/2, pi/2]` (from the vertical),
//!   every further joint uniform in `[-2pi/3, 2pi/3]`; kept if every joint
//!   stays above the ground (`y >= 0.05 m`), the end effector lies between
//!   [`INNER`] and [`OUTER`] of the reach from `P(0)`, and the smallest
//!   singular value of `J` is at least [`MIN_SIGMA`] of the reach;
//! - the target: uniform in the same annulus above the ground, at least
//!   [`MIN_LENGTH`] of the reach from the start, and every point of the
//!   straight line to it inside the annulus (so the line is reachable);
//! - the paper's timing: 10 s at `dt = 0.1`, `lambda = 4`, open loop.
//!
//! Obstacles are drawn uniformly in a region ([`obstacle_region`]); the ones
//! that overlap the post are drawn again.

use nalgebra::DVector;

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::ik;
use crate::nn::rng::Rng;
use crate::obstacle::Obstacle;
use crate::scene::{Scene, PAPER_RADIUS};

/// Start poses and targets keep at least this share of the reach from `P(0)`.
pub const INNER: f64 = 0.3;
/// ... and at most this share (away from the stretched, singular boundary).
pub const OUTER: f64 = 0.85;
/// A line is at least this share of the reach long.
pub const MIN_LENGTH: f64 = 0.25;
/// Start poses need `sigma_min(J)` of at least this share of the reach.
pub const MIN_SIGMA: f64 = 0.12;
/// Joints and targets stay this high above the ground (m).
pub const GROUND: f64 = 0.05;
/// Draws allowed per task before giving up (a degenerate arm).
const MAX_DRAWS: usize = 100_000;

/// The box obstacles are drawn from for an arm: `[x0, y0]` and `[x1, y1]`
/// spanning 0.8 of the reach around `P(0)`, above the ground.
pub fn obstacle_region(arm: &Arm) -> ([f64; 2], [f64; 2]) {
    let r = 0.8 * arm.max_reach();
    let post = arm.post();
    ([-r, (post - r).max(GROUND)], [r, post + r])
}

fn in_annulus(arm: &Arm, p: [f64; 2]) -> bool {
    let base = arm.base();
    let r = (p[0] - base[0]).hypot(p[1] - base[1]);
    let reach = arm.max_reach();
    p[1] >= GROUND && r >= (INNER * reach).max(arm.min_reach() + 0.05 * reach) && r <= OUTER * reach
}

/// A random start pose of `arm` (see the module documentation).
pub fn random_pose(arm: &Arm, rng: &mut Rng) -> Result<Vec<f64>> {
    let reach = arm.max_reach();
    for _ in 0..MAX_DRAWS {
        let theta: Vec<f64> = (0..arm.dof())
            .map(|i| {
                let half = if i == 0 {
                    std::f64::consts::FRAC_PI_2
                } else {
                    2.0 * std::f64::consts::FRAC_PI_3
                };
                rng.range(-half, half)
            })
            .collect();
        let t = DVector::from_column_slice(&theta);
        let joints = arm.joints(&t);
        if joints.iter().any(|p| p[1] < GROUND) {
            continue;
        }
        let ee = joints[joints.len() - 1];
        if !in_annulus(arm, [ee[0], ee[1]]) {
            continue;
        }
        if ik::smallest_singular_value(&arm.jacobian(&t)) < MIN_SIGMA * reach {
            continue;
        }
        return Ok(theta);
    }
    Err(Error::Training(
        "random tasks: no start pose of this arm keeps its joints above the ground".into(),
    ))
}

/// A random straight-line task for `arm` without obstacles (see the module
/// documentation).
pub fn random_task(arm: &Arm, rng: &mut Rng) -> Result<Scene> {
    let reach = arm.max_reach();
    let base = arm.base();
    for _ in 0..100 {
        let theta0 = random_pose(arm, rng)?;
        let start = arm.forward(&DVector::from_column_slice(&theta0));
        for _ in 0..200 {
            let target = [
                rng.range(base[0] - OUTER * reach, base[0] + OUTER * reach),
                rng.range(GROUND, base[1] + OUTER * reach),
            ];
            let (dx, dy) = (target[0] - start[0], target[1] - start[1]);
            if dx.hypot(dy) < MIN_LENGTH * reach {
                continue;
            }
            let inside = (0..=20).all(|k| {
                let s = f64::from(k) / 20.0;
                in_annulus(arm, [start[0] + s * dx, start[1] + s * dy])
            });
            if !inside {
                continue;
            }
            // The paper's timing and gains (Task 1's), this arm, pose and line.
            return Ok(Scene {
                arm: arm.clone(),
                theta0,
                target,
                obstacles: Vec::new(),
                ..Scene::task1()
            });
        }
    }
    Err(Error::Training(
        "random tasks: no straight line of this arm stays inside its reach".into(),
    ))
}

/// An obstacle centre uniform in `[min, max]`, clear of the post (radius
/// [`PAPER_RADIUS`]).
pub fn random_obstacle(arm: &Arm, min: [f64; 2], max: [f64; 2], rng: &mut Rng) -> Result<Obstacle> {
    for _ in 0..MAX_DRAWS {
        let o = Obstacle::new(
            rng.range(min[0], max[0]),
            rng.range(min[1], max[1]),
            PAPER_RADIUS,
        );
        if o.validate(arm).is_ok() {
            return Ok(o);
        }
    }
    Err(Error::Training(
        "random tasks: the obstacle region lies on the post".into(),
    ))
}

/// Whether a run ended clear of every obstacle and within
/// [`crate::planner::REACH_TOLERANCE`] of its target: the atlas's `success`.
pub fn succeeded(summary: &crate::planner::Summary) -> bool {
    summary.success
}

/// `count` random tasks of `arm`, each with one obstacle in `[min, max]`
/// that matters: without avoidance (`none`) a link hits it, while the
/// numerical route avoids it and ends within 5 mm of the target. What
/// trained networks are checked on ([`check`]); `seed` picks them.
pub fn avoidance_tasks(
    arm: &Arm,
    count: usize,
    region: ([f64; 2], [f64; 2]),
    seed: u64,
) -> Result<Vec<Scene>> {
    use crate::planner::{Method, Planner};
    let mut rng = Rng::new(seed);
    let mut out = Vec::with_capacity(count);
    let mut draws = 0usize;
    while out.len() < count {
        draws += 1;
        if draws > 200 * count + 1000 {
            return Err(Error::Training(format!(
                "random tasks: found only {} of {count} tasks where the obstacle matters",
                out.len()
            )));
        }
        let mut scene = random_task(arm, &mut rng)?;
        scene.obstacles = vec![random_obstacle(arm, region.0, region.1, &mut rng)?];
        let run = |method| Planner::run_summary(scene.clone(), method, None);
        let (Ok(none), Ok(numerical)) = (run(Method::NO_AVOIDANCE), run(Method::NUMERICAL)) else {
            continue;
        };
        // Not at the start already, and hit without avoidance.
        let start = Planner::new(scene.clone(), Method::NO_AVOIDANCE, None)?;
        if start.sample().collision || !none.collided || !succeeded(&numerical) {
            continue;
        }
        out.push(scene);
    }
    Ok(out)
}

/// How a method fared on a set of tasks ([`check`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Check {
    /// Method name.
    pub method: &'static str,
    /// Tasks run.
    pub tasks: usize,
    /// Runs that ended clear and within 5 mm ([`succeeded`]).
    pub succeeded: usize,
    /// Runs in which a link entered the obstacle.
    pub collided: usize,
    /// Runs that stopped with an error (a singular pose).
    pub failed: usize,
    /// Median distance from the target at the end (m), over the runs that
    /// went through.
    pub median_final_error: Option<f64>,
}

/// Runs every scene in `method` with `networks` and counts the outcomes.
pub fn check(
    scenes: &[Scene],
    method: crate::planner::Method,
    networks: Option<std::sync::Arc<dyn crate::planner::Surrogate>>,
) -> Check {
    use crate::planner::Planner;
    let mut errors = Vec::with_capacity(scenes.len());
    let (mut succeeded_runs, mut collided, mut failed) = (0, 0, 0);
    for scene in scenes {
        match Planner::run_summary(scene.clone(), method, networks.clone()) {
            Ok(s) => {
                succeeded_runs += usize::from(succeeded(&s));
                collided += usize::from(s.collided);
                errors.push(s.final_error);
            }
            Err(_) => failed += 1,
        }
    }
    errors.sort_by(f64::total_cmp);
    Check {
        method: method.name(),
        tasks: scenes.len(),
        succeeded: succeeded_runs,
        collided,
        failed,
        median_final_error: (!errors.is_empty()).then(|| errors[errors.len() / 2]),
    }
}
