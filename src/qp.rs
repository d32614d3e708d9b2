//! A dense convex quadratic program solver for the tiny problems of the
//! `qp` method (`docs/methods.md`): the dual active-set method of Goldfarb
//! and Idnani (1983), the algorithm behind `quadprog`.
//!
//! Minimise `(1/2) x^T H x - g^T x` subject to `A x >= b`, with `H`
//! symmetric positive definite (`n x n`) and one row of `A` per constraint.
//!
//! Why by hand: the planner solves four of these per RK4 step (one per
//! stage), with at most a few dozen constraints of which a handful are
//! active. An interior-point solver (clarabel, measured through its Python
//! binding: about 17 µs for one such QP with 3 joints and 3 dampers, 5
//! iterations) would make a step some 70 µs, 200 times the numerical
//! route's 0.3 µs; `quadprog` on crates.io is GPL. The dual method starts
//! from the unconstrained minimum, which is where the planner usually is
//! (no damper binds), and adds one violated constraint at a time: a step
//! with no binding damper costs one Cholesky factorisation of `H` and one
//! pass over the constraints. The small systems are solved afresh at each
//! iteration rather than updated, which for at most a few active
//! constraints costs less than the bookkeeping of updates would.
//! `tests/qp.rs` checks the solutions against clarabel's on 10,000 random
//! problems.
//!
//! The workspace is kept by the caller and reused; it allocates only when a
//! problem is larger than every one before.

use crate::error::{Error, Result};

/// Scratch space of [`solve`], reused between calls.
#[derive(Debug, Clone, Default)]
pub struct Workspace {
    /// Cholesky factor of `H`, lower, row-major `n x n`.
    l: Vec<f64>,
    /// `H^-1 a_i` for each active constraint, `n` entries each.
    hinv_a: Vec<f64>,
    /// `H^-1 a_p` of the constraint being added.
    hp: Vec<f64>,
    /// The primal step direction.
    z: Vec<f64>,
    /// The unconstrained minimum `H^-1 g`.
    free: Vec<f64>,
    /// The active constraints, in the order they were added.
    active: Vec<usize>,
    /// Their multipliers.
    u: Vec<f64>,
    /// The dual step direction, one entry per active constraint.
    r: Vec<f64>,
    /// `S = A_W H^-1 A_W^T` and its Cholesky factor.
    s: Vec<f64>,
    /// Right-hand side and solution of the small systems.
    rhs: Vec<f64>,
}

/// What a solve found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Solution {
    /// Constraints active at the solution (`A x = b` with a positive
    /// multiplier).
    pub active: usize,
    /// Constraints added or dropped on the way.
    pub iterations: usize,
}

impl Workspace {
    /// Room for problems of `n` variables and `m` constraints: solving one
    /// that fits allocates nothing.
    pub fn with_capacity(n: usize, m: usize) -> Self {
        let _ = m;
        Self {
            l: vec![0.0; n * n],
            hinv_a: vec![0.0; n * n],
            hp: vec![0.0; n],
            z: vec![0.0; n],
            free: vec![0.0; n],
            active: Vec::with_capacity(n + 1),
            u: Vec::with_capacity(n + 1),
            r: vec![0.0; n],
            s: vec![0.0; n * n],
            rhs: vec![0.0; n],
        }
    }

    /// The indices of the constraints active at the last solution.
    pub fn active(&self) -> &[usize] {
        &self.active
    }

    /// Their multipliers (`>= 0`), in the same order.
    pub fn multipliers(&self) -> &[f64] {
        &self.u
    }
}

/// Grows `v` to at least `len` entries (allocates only when it must).
fn room(v: &mut Vec<f64>, len: usize) {
    if v.len() < len {
        v.resize(len, 0.0);
    }
}

/// In-place Cholesky factorisation of the symmetric `n x n` matrix in `a`
/// (row-major, lower triangle read): `a = L L^T`, `L` left in the lower
/// triangle. Fails on a matrix that is not (numerically) positive definite.
fn cholesky(a: &mut [f64], n: usize) -> Result<()> {
    for j in 0..n {
        let mut d = a[j * n + j];
        for k in 0..j {
            d -= a[j * n + k] * a[j * n + k];
        }
        if !(d > 0.0 && d.is_finite()) {
            return Err(Error::QpFailed {
                reason: "its Hessian H is not positive definite",
            });
        }
        let d = d.sqrt();
        a[j * n + j] = d;
        for i in j + 1..n {
            let mut s = a[i * n + j];
            for k in 0..j {
                s -= a[i * n + k] * a[j * n + k];
            }
            a[i * n + j] = s / d;
        }
    }
    Ok(())
}

/// Solves `L L^T x = x` in place with the factor of [`cholesky`].
fn cholesky_solve(l: &[f64], n: usize, x: &mut [f64]) {
    for i in 0..n {
        let mut s = x[i];
        for k in 0..i {
            s -= l[i * n + k] * x[k];
        }
        x[i] = s / l[i * n + i];
    }
    for i in (0..n).rev() {
        let mut s = x[i];
        for k in i + 1..n {
            s -= l[k * n + i] * x[k];
        }
        x[i] = s / l[i * n + i];
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Recomputes the solution from its active set in one solve, rather than
/// as the sum of the steps that found it (whose rounding errors add up
/// over many steps on an ill-conditioned `H`): with `x_0 = H^-1 g`, the
/// multipliers solve `S u = b_W - A_W x_0`, `S = A_W H^-1 A_W^T`, and
/// `x = x_0 + H^-1 A_W^T u`. Left as it was if `S` turns out singular.
fn polish(ws: &mut Workspace, a: &[f64], b: &[f64], x: &mut [f64]) {
    let n = x.len();
    let k = ws.active.len();
    if k == 0 {
        return;
    }
    let s = &mut ws.s[..k * k];
    let rhs = &mut ws.rhs[..k];
    for (i, &wi) in ws.active.iter().enumerate() {
        let row = &a[wi * n..(wi + 1) * n];
        for j in 0..=i {
            let v = dot(row, &ws.hinv_a[j * n..(j + 1) * n]);
            s[i * k + j] = v;
            s[j * k + i] = v;
        }
        rhs[i] = b[wi] - dot(row, &ws.free[..n]);
    }
    if cholesky(s, k).is_err() {
        return;
    }
    cholesky_solve(s, k, rhs);
    x.copy_from_slice(&ws.free[..n]);
    ws.u.copy_from_slice(rhs);
    // Two rounds of iterative refinement on the active constraints'
    // residual (S is as ill-conditioned as H when the slack weight is large).
    for round in 0..3 {
        for (j, uj) in ws.rhs[..k].iter().enumerate() {
            for (xi, hi) in x.iter_mut().zip(&ws.hinv_a[j * n..(j + 1) * n]) {
                *xi += uj * hi;
            }
        }
        if round == 2 {
            break;
        }
        let rhs = &mut ws.rhs[..k];
        for (i, &wi) in ws.active.iter().enumerate() {
            rhs[i] = b[wi] - dot(&a[wi * n..(wi + 1) * n], x);
        }
        cholesky_solve(&ws.s[..k * k], k, rhs);
        for (u, d) in ws.u.iter_mut().zip(rhs.iter()) {
            *u += d;
        }
    }
}

/// Solves the quadratic program into `x` (`n` entries): `h` is `H`
/// (row-major `n x n`), `g` the linear term, `a` the constraint rows
/// (row-major `m x n`) and `b` their bounds (`m` entries). Fails with
/// [`Error::Infeasible`] when no `x` satisfies every constraint (the
/// workspace then holds the constraints that were active when that was
/// found), and with [`Error::QpFailed`] when `H` is not positive definite,
/// the active constraints turn out dependent, or the iterations do not
/// converge.
pub fn solve(
    ws: &mut Workspace,
    h: &[f64],
    g: &[f64],
    a: &[f64],
    b: &[f64],
    x: &mut [f64],
) -> Result<Solution> {
    let n = x.len();
    let m = b.len();
    if h.len() != n * n || g.len() != n || a.len() != m * n {
        return Err(Error::DimensionMismatch {
            what: "quadratic program (H n x n, g n, A m x n)".into(),
            expected: n * n + n + m * n,
            found: h.len() + g.len() + a.len(),
        });
    }
    room(&mut ws.l, n * n);
    room(&mut ws.hp, n);
    room(&mut ws.z, n);
    room(&mut ws.free, n);
    room(&mut ws.hinv_a, n * n);
    room(&mut ws.s, n * n);
    room(&mut ws.rhs, n);
    room(&mut ws.r, n);
    ws.active.clear();
    ws.u.clear();
    let l = &mut ws.l[..n * n];
    l.copy_from_slice(h);
    cholesky(l, n)?;
    // The unconstrained minimum, H x = g.
    x.copy_from_slice(g);
    cholesky_solve(l, n, x);
    ws.free[..n].copy_from_slice(x);

    let row = |i: usize| &a[i * n..(i + 1) * n];
    // A constraint counts as violated below this slack, relative to its
    // scale (the size of its terms).
    let tolerance = |i: usize, x: &[f64]| {
        let scale = row(i)
            .iter()
            .zip(x.iter())
            .map(|(ai, xi)| (ai * xi).abs())
            .fold(b[i].abs(), f64::max);
        1e-12 * scale.max(1e-12)
    };
    let max_iterations = 10 * (m + n) + 20;
    let mut iterations = 0;
    loop {
        // The most violated constraint not yet active.
        let mut worst = None;
        let mut worst_slack = 0.0;
        for (i, &bi) in b.iter().enumerate() {
            if ws.active.contains(&i) {
                continue;
            }
            let slack = dot(row(i), x) - bi;
            if slack < -tolerance(i, x) && slack < worst_slack {
                worst = Some(i);
                worst_slack = slack;
            }
        }
        let Some(p) = worst else {
            polish(ws, a, b, x);
            return Ok(Solution {
                active: ws.active.len(),
                iterations,
            });
        };
        let ap = row(p);
        let mut up = 0.0;
        // Steps towards satisfying constraint p, dropping active ones whose
        // multipliers would turn negative, until p is active.
        loop {
            iterations += 1;
            if iterations > max_iterations {
                return Err(Error::QpFailed {
                    reason: "the active-set iterations did not converge (degenerate constraints)",
                });
            }
            let k = ws.active.len();
            let hp = &mut ws.hp[..n];
            hp.copy_from_slice(ap);
            cholesky_solve(&ws.l[..n * n], n, hp);
            // r = S^-1 A_W H^-1 a_p, S = A_W H^-1 A_W^T.
            let r = &mut ws.r[..k];
            if k > 0 {
                let s = &mut ws.s[..k * k];
                for (i, &wi) in ws.active.iter().enumerate() {
                    for j in 0..=i {
                        let v = dot(row(wi), &ws.hinv_a[j * n..(j + 1) * n]);
                        s[i * k + j] = v;
                        s[j * k + i] = v;
                    }
                    r[i] = dot(row(wi), hp);
                }
                cholesky(s, k).map_err(|_| Error::QpFailed {
                    reason: "its active constraints depend on each other",
                })?;
                cholesky_solve(s, k, r);
            }
            // z = H^-1 a_p - sum_j r_j H^-1 a_j: the primal direction.
            let z = &mut ws.z[..n];
            z.copy_from_slice(hp);
            for (j, rj) in r.iter().enumerate() {
                for (zi, hi) in z.iter_mut().zip(&ws.hinv_a[j * n..(j + 1) * n]) {
                    *zi -= rj * hi;
                }
            }
            // The partial step: the first active multiplier to reach zero.
            let mut t1 = f64::INFINITY;
            let mut drop = None;
            for (j, (&rj, &uj)) in r.iter().zip(&ws.u).enumerate() {
                if rj > 1e-14 * (1.0 + uj.abs()) {
                    let t = uj / rj;
                    if t < t1 {
                        t1 = t;
                        drop = Some(j);
                    }
                }
            }
            // The full step: constraint p becomes active. a_p^T z is the
            // Schur complement of S in [S, A_W H^-1 a_p; ., a_p^T H^-1 a_p]:
            // zero when a_p depends on the active rows.
            let apz = dot(ap, z);
            let aphp = dot(ap, hp);
            let slack = dot(ap, x) - b[p];
            // With n constraints active, any other depends on them.
            let t2 = if k < n && apz > 1e-13 * aphp.abs() && apz > 0.0 {
                -slack / apz
            } else {
                f64::INFINITY
            };
            if !t1.is_finite() && !t2.is_finite() {
                return Err(Error::Infeasible {
                    constraints: m,
                    active: ws.active.len(),
                });
            }
            let t = t1.min(t2);
            if t2.is_finite() {
                for (xi, zi) in x.iter_mut().zip(z.iter()) {
                    *xi += t * zi;
                }
            }
            for (uj, rj) in ws.u.iter_mut().zip(r.iter()) {
                *uj -= t * rj;
            }
            up += t;
            if t2 <= t1 {
                // Constraint p joins the active set.
                let hinv = &mut ws.hinv_a[k * n..(k + 1) * n];
                hinv.copy_from_slice(&ws.hp[..n]);
                ws.active.push(p);
                ws.u.push(up);
                break;
            }
            // An active constraint leaves.
            let j = drop.unwrap_or(0);
            ws.active.remove(j);
            ws.u.remove(j);
            ws.hinv_a.copy_within((j + 1) * n..k * n, j * n);
        }
    }
}
