//! The dense quadratic program solver of the `qp` method (`src/qp.rs`,
//! Goldfarb-Idnani) against clarabel, an interior-point solver, on random
//! feasible problems of the sizes the method poses: up to 8 variables and 48
//! constraints, and on the method's own programs near joint limits (the
//! joint-limit dampers and the arm's rate limits among the rows). Native
//! only (clarabel is a native dev-dependency).
#![cfg(not(target_family = "wasm"))]

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT, SolverStatus, ZeroConeT,
};
use redundant_ik::nn::Rng;
use redundant_ik::qp::{self, Workspace};
use redundant_ik::Error;

/// A random problem of the `qp` method's shape: a 2 x n Jacobian `J`, a
/// preferred rate `v`, a task velocity `xdot`, the slack weight `w`, and `m`
/// damper rows `A theta_dot >= b` feasible at a random point.
struct Problem {
    n: usize,
    j: Vec<f64>,
    v: Vec<f64>,
    xdot: [f64; 2],
    w: f64,
    a: Vec<f64>,
    b: Vec<f64>,
}

impl Problem {
    fn random(rng: &mut Rng, n: usize, m: usize, w: f64) -> Self {
        let j: Vec<f64> = (0..2 * n).map(|_| rng.range(-1.5, 1.5)).collect();
        let v: Vec<f64> = (0..n).map(|_| rng.range(-2.0, 2.0)).collect();
        let xdot = [rng.range(-0.3, 0.3), rng.range(-0.3, 0.3)];
        let x0: Vec<f64> = (0..n).map(|_| rng.range(-1.0, 1.0)).collect();
        let mut a = Vec::with_capacity(m * n);
        let mut b = Vec::with_capacity(m);
        for _ in 0..m {
            // Rows like n^T J_p: the first k entries of a random row (a link
            // moves with the joints before it only).
            let k = 1 + rng.below(n);
            let row: Vec<f64> = (0..n)
                .map(|i| if i < k { rng.range(-1.0, 1.0) } else { 0.0 })
                .collect();
            let at_x0: f64 = row.iter().zip(&x0).map(|(p, q)| p * q).sum();
            b.push(at_x0 - rng.range(0.0, 0.5));
            a.extend(row);
        }
        Self {
            n,
            j,
            v,
            xdot,
            w,
            a,
            b,
        }
    }

    /// The task slack eliminated, as `qp::solve` takes it:
    /// `H = I + w J^T J`, `g = v + w J^T xdot`.
    fn reduced(&self) -> (Vec<f64>, Vec<f64>) {
        let (n, j, w) = (self.n, &self.j, self.w);
        let mut h = vec![0.0; n * n];
        for r in 0..n {
            for c in 0..n {
                let jtj = j[2 * r] * j[2 * c] + j[2 * r + 1] * j[2 * c + 1];
                h[r * n + c] = f64::from(u8::from(r == c)) + w * jtj;
            }
        }
        let g = (0..n)
            .map(|r| self.v[r] + w * (j[2 * r] * self.xdot[0] + j[2 * r + 1] * self.xdot[1]))
            .collect();
        (h, g)
    }

    /// clarabel's solution of the problem as the method states it, over
    /// `(theta_dot, s)`: minimise `(1/2)|theta_dot - v|^2 + (w/2)|s|^2`
    /// subject to `J theta_dot + s = xdot` and `A theta_dot >= b`, at tight
    /// tolerances; `None` if clarabel does not report a solve.
    fn clarabel(&self) -> Option<Vec<f64>> {
        let (n, m) = (self.n, self.b.len());
        let p: Vec<Vec<f64>> = (0..n + 2)
            .map(|i| {
                (0..n + 2)
                    .map(|c| match (i == c, i < n) {
                        (true, true) => 1.0,
                        (true, false) => self.w,
                        _ => 0.0,
                    })
                    .collect()
            })
            .collect();
        let q: Vec<f64> = self.v.iter().map(|x| -x).chain([0.0, 0.0]).collect();
        // J theta_dot + s = xdot (zero cone), then -A theta_dot + t = -b (t >= 0).
        let mut rows: Vec<Vec<f64>> = (0..2)
            .map(|r| {
                (0..n + 2)
                    .map(|c| {
                        if c < n {
                            self.j[2 * c + r]
                        } else {
                            f64::from(u8::from(c - n == r))
                        }
                    })
                    .collect()
            })
            .collect();
        for i in 0..m {
            rows.push(
                (0..n + 2)
                    .map(|c| if c < n { -self.a[i * n + c] } else { 0.0 })
                    .collect(),
            );
        }
        let rhs: Vec<f64> = self
            .xdot
            .iter()
            .copied()
            .chain(self.b.iter().map(|x| -x))
            .collect();
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .tol_gap_abs(1e-14)
            .tol_gap_rel(1e-14)
            .tol_feas(1e-14)
            .tol_ktratio(1e-12)
            .max_iter(300)
            .build()
            .unwrap();
        let cones = [ZeroConeT(2), NonnegativeConeT(m)];
        let mut solver = DefaultSolver::new(
            &CscMatrix::from(&p).to_triu(),
            &q,
            &CscMatrix::from(&rows),
            &rhs,
            &cones,
            settings,
        )
        .ok()?;
        solver.solve();
        if !matches!(
            solver.solution.status,
            SolverStatus::Solved | SolverStatus::AlmostSolved
        ) {
            return None;
        }
        // The constraints clarabel finds active (a positive multiplier),
        // then the KKT system on them solved exactly (LU with full
        // pivoting): an interior-point method stops within its tolerances
        // of the vertex (1e-8 off in the constraints), which the slack
        // weight of 1e6 magnifies in the rates.
        let z = &solver.solution.z[2..];
        let zmax = z.iter().fold(1.0f64, |a, &b| a.max(b));
        let active: Vec<usize> = (0..m).filter(|&i| z[i] > 1e-7 * zmax).collect();
        let (h, g) = self.reduced();
        let k = active.len();
        let mut kkt = nalgebra::DMatrix::zeros(n + k, n + k);
        let mut rhs = nalgebra::DVector::zeros(n + k);
        for r in 0..n {
            for c in 0..n {
                kkt[(r, c)] = h[r * n + c];
            }
            rhs[r] = g[r];
        }
        for (i, &wi) in active.iter().enumerate() {
            for c in 0..n {
                kkt[(n + i, c)] = self.a[wi * n + c];
                kkt[(c, n + i)] = -self.a[wi * n + c];
            }
            rhs[n + i] = self.b[wi];
        }
        let exact = kkt.full_piv_lu().solve(&rhs)?;
        let x = exact.as_slice()[..n].to_vec();
        // A reference only where it is one: feasible, and its multipliers
        // not negative (else clarabel's tolerances left the active set in
        // doubt).
        let feasible = self.violation(&x) <= 1e-11;
        let dual = exact.as_slice()[n..].iter().all(|&u| u >= -1e-9 * zmax);
        (feasible && dual).then_some(x)
    }

    /// The largest violation of a constraint at `x`, relative to its scale.
    fn violation(&self, x: &[f64]) -> f64 {
        let n = self.n;
        (0..self.b.len())
            .map(|i| {
                let row = &self.a[i * n..(i + 1) * n];
                let ax: f64 = row.iter().zip(x).map(|(p, q)| p * q).sum();
                (self.b[i] - ax) / (1.0 + self.b[i].abs())
            })
            .fold(0.0, f64::max)
    }

    /// The largest breach of the KKT conditions at `x` with the solver's
    /// active set and multipliers: stationarity `H x - g - A_W^T u = 0`
    /// (relative to the size of its terms), `u >= 0`, feasibility.
    fn kkt_breach(&self, x: &[f64], active: &[usize], u: &[f64]) -> f64 {
        let n = self.n;
        let (h, g) = self.reduced();
        let mut worst = self.violation(x);
        for r in 0..n {
            let mut res = -g[r];
            let mut scale = g[r].abs();
            for c in 0..n {
                res += h[r * n + c] * x[c];
                scale = scale.max((h[r * n + c] * x[c]).abs());
            }
            for (&wi, &ui) in active.iter().zip(u) {
                res -= self.a[wi * n + r] * ui;
                scale = scale.max((self.a[wi * n + r] * ui).abs());
            }
            worst = worst.max(res.abs() / scale.max(1.0));
        }
        let umax = u.iter().fold(1.0f64, |a, &b| a.max(b));
        for &ui in u {
            worst = worst.max(-ui / umax);
        }
        worst
    }
}

#[test]
fn the_active_set_solver_agrees_with_clarabel_on_10000_random_feasible_problems() {
    let mut rng = Rng::new(2026);
    let mut ws = Workspace::default();
    let (mut compared, mut constrained, mut worst, mut breach) = (0, 0, 0.0f64, 0.0f64);
    let mut case = 0;
    while compared < 10_000 {
        case += 1;
        assert!(
            case <= 12_500,
            "clarabel gave a usable reference in only {compared} of {case}"
        );
        let n = 2 + rng.below(7); // 2 to 8 variables
        let m = rng.below(49); // 0 to 48 constraints
                               // The method's slack weight is 1e6; smaller weights too.
        let w = [1.0, 1e3, 1e6][rng.below(3)];
        let problem = Problem::random(&mut rng, n, m, w);
        let (h, g) = problem.reduced();
        let mut x = vec![0.0; n];
        let sol = qp::solve(&mut ws, &h, &g, &problem.a, &problem.b, &mut x).unwrap();
        // Every solution carries its own certificate: the KKT conditions
        // hold (a strictly convex problem has one minimum, and they
        // identify it).
        let kkt = problem.kkt_breach(&x, ws.active(), ws.multipliers());
        breach = breach.max(kkt);
        assert!(
            kkt < 1e-8,
            "case {case} (n {n}, m {m}, w {w}): KKT breached by {kkt:.1e}: viol {:.1e}, u {:?}",
            problem.violation(&x),
            ws.multipliers()
        );
        let Some(reference) = problem.clarabel() else {
            continue;
        };
        compared += 1;
        constrained += usize::from(sol.active > 0);
        let err = x
            .iter()
            .zip(&reference)
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max);
        worst = worst.max(err);
        assert!(
            err < 1e-8,
            "case {case} (n {n}, m {m}, w {w}, {} active): {x:?} against clarabel's {reference:?}",
            sol.active
        );
    }
    eprintln!(
        "{compared} of {case} problems compared ({constrained} with active constraints): \
         largest difference {worst:.1e}, largest KKT breach {breach:.1e}"
    );
    assert!(
        constrained >= 5_000,
        "only {constrained} problems had an active constraint"
    );
}

#[test]
fn contradictory_constraints_are_infeasible_and_say_so() {
    // x >= 1 and -x >= 0 (x <= 0) in one variable: no x satisfies both.
    let mut ws = Workspace::default();
    let mut x = [0.0];
    let err = qp::solve(&mut ws, &[1.0], &[0.0], &[1.0, -1.0], &[1.0, 0.0], &mut x).unwrap_err();
    assert!(
        matches!(err, Error::Infeasible { constraints: 2, .. }),
        "{err}"
    );
    // A Hessian that is not positive definite is refused.
    let err = qp::solve(&mut ws, &[-1.0], &[0.0], &[], &[], &mut x).unwrap_err();
    assert!(matches!(err, Error::QpFailed { .. }), "{err:?}");
}

#[test]
fn a_failed_program_says_the_program_failed_and_why_not_that_the_pose_is_singular() {
    // A Hessian that is not positive definite: the solver's failure, not
    // the arm's pose.
    let mut ws = Workspace::default();
    let mut x = [0.0; 2];
    let h = [1.0, 2.0, 2.0, 1.0]; // eigenvalues 3 and -1
    let err = qp::solve(&mut ws, &h, &[0.0, 0.0], &[], &[], &mut x).unwrap_err();
    let message = err.to_string();
    assert!(matches!(err, Error::QpFailed { .. }), "{err:?}");
    assert!(!message.contains("singular pose"), "{message}");
    assert!(message.contains("quadratic program"), "{message}");
    assert!(message.contains("not positive definite"), "{message}");
}

#[test]
fn without_binding_constraints_the_solution_is_the_unconstrained_minimum() {
    let mut ws = Workspace::default();
    let h = [2.0, 0.5, 0.5, 1.0];
    let g = [1.0, -1.0];
    let mut x = [0.0; 2];
    // Constraints far from the minimum.
    let sol = qp::solve(
        &mut ws,
        &h,
        &g,
        &[1.0, 0.0, 0.0, 1.0],
        &[-10.0, -10.0],
        &mut x,
    )
    .unwrap();
    assert_eq!(sol.active, 0);
    // H x = g by Cramer's rule: det H = 2 - 0.25.
    let det = 1.75;
    assert!((x[0] - (g[0] * h[3] - h[1] * g[1]) / det).abs() < 1e-15);
    assert!((x[1] - (h[0] * g[1] - h[2] * g[0]) / det).abs() < 1e-15);
}

#[test]
fn the_qp_methods_own_programs_near_joint_limits_agree_with_clarabel() {
    use redundant_ik::nalgebra::{DVector, Vector2};
    use redundant_ik::planner::methods::constraints::{self, Rows};
    use redundant_ik::planner::methods::{Context, QP, SLACK_WEIGHT};
    use redundant_ik::{Obstacle, Planner, Pose, Scene};
    let mut rng = Rng::new(77);
    let mut scene = Scene::task1();
    scene.obstacles = vec![Obstacle::new(0.8, 0.9, 0.05), Obstacle::new(0.3, 1.3, 0.05)];
    scene.arm = scene
        .arm
        .clone()
        .with_limits(
            Some("-1.2:1.2,-0.3:2.0,-2.0:0.4".parse().unwrap()),
            Some("1.0,0.8,1.2".parse().unwrap()),
        )
        .unwrap();
    let planner = Planner::new(scene.clone(), QP, None).unwrap();
    let w = scene.param(&SLACK_WEIGHT);
    let (mut compared, mut limit_rows) = (0, 0);
    for _ in 0..2000 {
        // Poses within the limits, many within the dampers' 0.9 rad.
        let theta: Vec<f64> = scene
            .arm
            .joint_limits()
            .unwrap()
            .ranges()
            .iter()
            .map(|&[lo, hi]| rng.range(lo + 0.01, hi - 0.01))
            .collect();
        let Ok(pose) = Pose::new(&scene.arm, &theta) else {
            continue;
        };
        let xdot = [rng.range(-0.2, 0.2), rng.range(-0.2, 0.2)];
        let cx: Context = Context {
            scene: &scene,
            networks: None,
        };
        let mut rows = Rows::default();
        rows.clear(3);
        for entry in constraints::ALL {
            (entry.build)(3).rows(&cx, &pose, &mut rows).unwrap();
        }
        let th = DVector::from_vec(theta.clone());
        let v = planner
            .null_space(th.as_slice())
            .map(DVector::from_vec)
            .unwrap();
        let problem = Problem {
            n: 3,
            j: pose.jacobian().to_vec(),
            v: v.as_slice().to_vec(),
            xdot,
            w,
            a: rows.g().iter().map(|g| -g).collect(),
            b: rows.h().iter().map(|h| -h).collect(),
        };
        // Feasible at theta_dot = 0 (no row asks a joint or link to move
        // away): the program the method solves without relaxing.
        if rows.h().iter().any(|&h| h < 0.0) {
            continue;
        }
        let Some(reference) = problem.clarabel() else {
            continue;
        };
        let rates = planner
            .theta_dot(
                th.as_slice(),
                [(Vector2::from(xdot))[0], (Vector2::from(xdot))[1]],
            )
            .map(DVector::from_vec)
            .unwrap();
        let err = rates
            .iter()
            .zip(&reference)
            .map(|(p, q)| (p - q).abs())
            .fold(0.0, f64::max);
        assert!(
            err < 1e-7,
            "{theta:?}: {rates} against clarabel's {reference:?}"
        );
        compared += 1;
        // Rows of the joint-limit dampers: a single +-1 entry bounded below
        // the rate limit.
        limit_rows += rows
            .iter()
            .filter(|(g, h)| g.iter().filter(|x| **x != 0.0).count() == 1 && *h < 0.8)
            .count();
    }
    assert!(compared > 1000, "{compared}");
    assert!(limit_rows > 500, "only {limit_rows} joint-limit rows");
}
