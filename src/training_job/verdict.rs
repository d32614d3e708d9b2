//! The verdict of a training job's check: whether trained networks pass
//! it, in which loop, and what fails.

use serde::Serialize;

use super::{Report, Which, CHECK_LOOPS};
use crate::planner::Method;

/// Share of the tasks the numerical route succeeds on that a network case
/// must succeed on too (with the drift corrected) to pass the check.
pub const PASS_SHARE: f64 = 0.5;

/// Whether trained networks pass their own check, in at least one of the
/// loops they were checked in ([`CHECK_LOOPS`]: open or closed, unrefined
/// or refined; the loop that passes is named): on the paper's arm, the
/// network cases that use them reach both of the paper's targets without
/// collision (the tasks the paper's arm is trained on); on another arm,
/// each of those cases succeeds on at least [`PASS_SHARE`] of the random
/// tasks the numerical route succeeds on in the same loop. Networks that
/// fail it are not swapped in unless the user asks.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Verdict {
    /// Whether they pass.
    pub passed: bool,
    /// What was checked (and in which loop they passed).
    pub checked: String,
    /// What failed, one sentence each (empty when they pass): in the last
    /// loop checked (closed, refined) when no loop passes.
    pub failures: Vec<String>,
}

/// "open loop" or "the drift corrected", and the refinement, for messages.
fn describe_loop(feedback: f64, refine: u32) -> String {
    let lp = if feedback > 0.0 {
        "with the drift corrected"
    } else {
        "open loop"
    };
    match refine {
        0 => lp.to_string(),
        k => format!("{lp}, {k} refinement steps"),
    }
}

impl Verdict {
    /// The verdict on `report` for networks `which` were trained.
    pub fn of(report: &Report, which: Which) -> Self {
        let cases: &[Method] = match which {
            Which::Both => &[Method::CASE1, Method::CASE2, Method::CASE3],
            Which::Phi => &[Method::CASE1, Method::CASE3],
            Which::V => &[Method::CASE2, Method::CASE3],
        };
        let labels = cases
            .iter()
            .map(|m| m.label())
            .collect::<Vec<_>>()
            .join(", ");
        let checked = if !report.paper_tasks.is_empty() {
            format!("{labels} on the paper's Tasks 1 and 2")
        } else if let Some(n) = report.random_tasks.first() {
            format!("{labels} on {} random tasks of this arm", n.check.tasks)
        } else {
            return Self {
                passed: true,
                checked: "nothing: this arm has no task in which the obstacle matters".into(),
                failures: Vec::new(),
            };
        };
        let mut failures = Vec::new();
        for (feedback, refine) in CHECK_LOOPS {
            failures = Self::failures(report, cases, feedback, refine);
            if failures.is_empty() {
                return Self {
                    passed: true,
                    checked: format!("{checked} ({})", describe_loop(feedback, refine)),
                    failures,
                };
            }
        }
        Self {
            passed: false,
            checked,
            failures,
        }
    }

    /// What fails in one loop. Case 2 runs the exact `Phi`, so its
    /// unrefined runs stand for every refinement.
    fn failures(report: &Report, cases: &[Method], feedback: f64, refine: u32) -> Vec<String> {
        let in_loop = |k: f64, r: u32, method: Method| {
            k == feedback && (r == refine || (r == 0 && !method.networks().phi))
        };
        let lp = describe_loop(feedback, refine);
        let mut failures = Vec::new();
        if !report.paper_tasks.is_empty() {
            for t in &report.paper_tasks {
                if cases.contains(&t.method)
                    && in_loop(t.feedback_gain, t.refine, t.method)
                    && !t.success()
                {
                    failures.push(format!(
                        "{} misses Task {} {lp} ({}, {:.1} mm from the target)",
                        t.method.label(),
                        t.task,
                        if t.collided {
                            "collides"
                        } else {
                            "no collision"
                        },
                        t.final_error * 1000.0
                    ));
                }
            }
            return failures;
        }
        let Some(numerical) = report
            .random_tasks
            .iter()
            .find(|r| r.feedback == feedback && r.check.method == Method::NUMERICAL.name())
        else {
            return failures;
        };
        let wanted = (PASS_SHARE * numerical.check.succeeded as f64).ceil() as usize;
        for r in &report.random_tasks {
            let Some(&case) = cases.iter().find(|m| m.name() == r.check.method) else {
                continue;
            };
            if in_loop(r.feedback, r.refine, case) && r.check.succeeded < wanted.max(1) {
                failures.push(format!(
                    "{} succeeds on {} of {} random tasks {lp} (the numerical route on {})",
                    case.label(),
                    r.check.succeeded,
                    r.check.tasks,
                    numerical.check.succeeded
                ));
            }
        }
        failures
    }
}
