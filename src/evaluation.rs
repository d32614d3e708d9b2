//! Evaluating trained networks against the numerical route: accuracy on
//! fresh samples and the outcomes of the paper's tasks, as `redundant-ik
//! eval` and the tests report them. Behind the `eval` feature (on with the
//! command-line tool), so the page's build does not carry it.

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::error::Result;
use crate::networks::{NetKind, Networks};
use crate::planner::{methods, Method, Planner, Surrogate};
use crate::scene::Scene;
use crate::training::{self, sampling, Visited};

/// Median, 99th percentile and largest of a set of errors.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ErrorStats {
    /// Number of samples.
    pub samples: usize,
    /// Median.
    pub median: f64,
    /// 99th percentile.
    pub p99: f64,
    /// Largest.
    pub max: f64,
}

impl ErrorStats {
    /// Statistics of `errors` (NaN counts as the largest).
    pub fn of(mut errors: Vec<f64>) -> Self {
        errors.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Greater));
        let n = errors.len();
        let at = |q: f64| {
            if n == 0 {
                f64::NAN
            } else {
                errors[((q * (n - 1) as f64).round() as usize).min(n - 1)]
            }
        };
        Self {
            samples: n,
            median: at(0.5),
            p99: at(0.99),
            max: at(1.0),
        }
    }
}

/// Relative Frobenius error `|Phi_net - Phi| / |Phi|` at each pose.
pub fn phi_relative_errors(nets: &Networks, samples: &[Visited]) -> Result<Vec<f64>> {
    let arm = nets.arm();
    let mut out = Vec::with_capacity(samples.len());
    let mut y = vec![0.0; 2 * arm.dof()];
    for s in samples {
        let exact = sampling::phi_target(arm, &s.theta)?;
        nets.phi_into(&s.theta, &mut y)?;
        out.push(rel(&y, &exact));
    }
    Ok(out)
}

/// Relative error `|g_net - g| / |g|` at each pose and obstacle point, `g`
/// with the sign smoothing the `v` file was trained with.
pub fn v_relative_errors(nets: &Networks, samples: &[Visited]) -> Result<Vec<f64>> {
    let arm = nets.arm();
    let mut out = Vec::with_capacity(samples.len());
    let mut y = vec![0.0; arm.dof()];
    let eps = nets.v_file().training.sampling.sign_smoothing;
    for s in samples {
        let exact = sampling::v_target(arm, &s.theta, s.obstacle, eps);
        nets.area_gradient_into(&s.theta, s.obstacle, &mut y)?;
        out.push(rel(&y, &exact));
    }
    Ok(out)
}

/// A fresh test set drawn as the `net` file's training data was, with another seed.
pub fn fresh_samples(nets: &Networks, net: NetKind, n: usize, seed: u64) -> Result<Vec<Visited>> {
    let file = match net {
        NetKind::Phi => nets.phi_file(),
        NetKind::V => nets.v_file(),
    };
    training::draw_samples(nets.arm(), &file.training.sampling, n, seed)
}

fn rel(y: &[f64], exact: &[f64]) -> f64 {
    let num: f64 = y.iter().zip(exact).map(|(a, b)| (a - b) * (a - b)).sum();
    let den: f64 = exact.iter().map(|b| b * b).sum();
    (num / den.max(1e-300)).sqrt()
}

/// One planner run's outcome, as `eval` reports it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TaskOutcome {
    /// Paper task (1 or 2).
    pub task: u32,
    /// Method run (`mode` in reports written before this name).
    #[serde(alias = "mode")]
    pub method: Method,
    /// Obstacle centre.
    pub obstacle: [f64; 2],
    /// Closed-loop gain `K` (0 = open loop).
    pub feedback_gain: f64,
    /// Newton-Schulz steps on the learned `Phi` (absent: none, the paper's).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub refine: u32,
    /// Smallest link-to-obstacle-centre distance.
    pub min_distance: f64,
    /// Whether a link entered the obstacle disc.
    pub collided: bool,
    /// Final end-effector error (m).
    pub final_error: f64,
    /// Steps where a network's input left its trained range.
    pub out_of_range_steps: usize,
    /// Error message when the run failed.
    pub error: Option<String>,
    /// Ran to the end, no collision and final error within
    /// [`crate::planner::REACH_TOLERANCE`] (the run's
    /// [`crate::planner::Summary::success`]).
    #[serde(default)]
    pub success: bool,
}

impl TaskOutcome {
    /// Whether the run succeeded ([`TaskOutcome::success`]).
    pub fn success(&self) -> bool {
        self.success
    }
}

/// Runs `method` on paper task `task` with its obstacle moved to `obstacle`
/// (if given) and closed-loop gain `feedback_gain`.
pub fn run_task(
    nets: &Networks,
    task: u32,
    method: Method,
    obstacle: Option<[f64; 2]>,
    feedback_gain: f64,
) -> Result<TaskOutcome> {
    run_task_refined(nets, task, method, obstacle, feedback_gain, 0)
}

/// [`run_task`] with `refine` Newton-Schulz steps on the learned `Phi`
/// (the scene's `refine` parameter, [`crate::planner::methods::REFINE`]).
pub fn run_task_refined(
    nets: &Networks,
    task: u32,
    method: Method,
    obstacle: Option<[f64; 2]>,
    feedback_gain: f64,
    refine: u32,
) -> Result<TaskOutcome> {
    let mut scene = Scene::task(task)?;
    scene.set_param(&crate::planner::methods::REFINE, f64::from(refine))?;
    if let Some(o) = obstacle {
        for ob in &mut scene.obstacles {
            ob.centre = o;
        }
    }
    // Bad input is refused, not recorded as a failed run.
    crate::scene::validate_gain(feedback_gain, scene.dt)?;
    scene.feedback_gain = feedback_gain;
    let centre = scene.obstacles.first().map_or([f64::NAN; 2], |o| o.centre);
    let surrogate: Arc<dyn Surrogate> = Arc::new(nets.clone());
    let mut out = TaskOutcome {
        task,
        method,
        obstacle: centre,
        feedback_gain,
        refine,
        min_distance: f64::NAN,
        collided: false,
        final_error: f64::NAN,
        out_of_range_steps: 0,
        error: None,
        success: false,
    };
    match Planner::run(scene, method, Some(surrogate)) {
        Ok(run) => {
            let s = run.summary;
            out.min_distance = s.min_distance.unwrap_or(f64::INFINITY);
            out.collided = s.collided;
            out.final_error = s.final_error;
            out.out_of_range_steps = s.out_of_range_steps;
            out.success = s.success;
        }
        Err(e) => out.error = Some(e.to_string()),
    }
    Ok(out)
}

/// The paper's five methods on both paper tasks with their canonical obstacles,
/// `refine` steps on the learned `Phi`.
pub fn task_outcomes(nets: &Networks, feedback_gain: f64, refine: u32) -> Result<Vec<TaskOutcome>> {
    let mut out = Vec::new();
    for task in [1, 2] {
        for method in methods::PAPER {
            out.push(run_task_refined(
                nets,
                task,
                method,
                None,
                feedback_gain,
                refine,
            )?);
        }
    }
    Ok(out)
}

/// The generalisation scenes of `docs/networks.md`: ten obstacle positions
/// other than the canonical ones, inside the trained obstacle region, with
/// the task each is run on.
pub const GENERALISATION_SCENES: [(u32, [f64; 2]); 10] = [
    (1, [0.45, 0.55]),
    (1, [0.55, 0.45]),
    (1, [0.40, 0.60]),
    (1, [0.60, 0.50]),
    (1, [0.50, 0.65]),
    (2, [0.55, 0.65]),
    (2, [0.65, 0.55]),
    (2, [0.70, 0.60]),
    (2, [0.60, 0.70]),
    (2, [0.65, 0.65]),
];

fn is_zero(k: &u32) -> bool {
    *k == 0
}
