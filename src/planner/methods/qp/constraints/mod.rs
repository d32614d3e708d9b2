//! The constraints of the `qp` method, one file each (as mink keeps each
//! limit in its own file behind `Limit.compute_qp_inequalities -> (G, h)`):
//! every [`Constraint`] writes its rows `G theta_dot <= h` for a pose into
//! the program's [`Rows`].
//!
//! **Adding a constraint** is one new file here that defines its type, its
//! [`ConstraintInfo`] and its [`Entry`], and its line in
//! [`register!`](self) below. The program (`qp/mod.rs`) builds every
//! constraint of [`ALL`] once per planner and asks each for its rows at
//! every rate evaluation, in the order of [`ALL`].
//!
//! A constraint is written once for every arm model ([`Constraint<A, M>`]
//! over [`crate::model::Model`]); [`Entry::build`] builds it for the planar
//! arm and [`Entry::space`] for a chain in space, and the program stacks
//! them in the same order for both.

use crate::arm::Arm;
use crate::error::Result;
use crate::model::Model;
use crate::planner::methods::Context;
use crate::scene::Param;
use crate::space::{Chain, PoseChain};

/// One line per constraint, in the order of the program's rows: declares
/// the constraint's module and puts its entry into [`ALL`].
macro_rules! register {
    ($($module:ident :: $entry:ident),+ $(,)?) => {
        $(mod $module; pub use $module::$entry;)+
        /// Every constraint of the `qp` method, in the order of its rows.
        pub static ALL: &[&Entry] = &[$(&$entry),+];
    };
}

register! {
    damper::DAMPER,
    joint_limit::JOINT_LIMIT,
    rate_limit::RATE_BOUNDS,
}

pub use damper::{DAMPER_GAIN, SELF_DAMPER_GAIN, SELF_INFLUENCE, SELF_STOP_DISTANCE};
pub use joint_limit::{LIMIT_GAIN, LIMIT_INFLUENCE, LIMIT_STOP};
pub use rate_limit::RATE_LIMIT;

/// What a constraint is, for people and for the code that lists them.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct ConstraintInfo {
    /// The name in code and messages (`damper`, `rate_limit`).
    pub name: &'static str,
    /// The name people read (the literature's term).
    pub label: &'static str,
    /// Its rows, in one line.
    pub description: &'static str,
    /// The scene's parameters it reads.
    pub params: &'static [&'static Param],
}

/// A constraint's registration: what it is and how to build it, with its
/// scratch space, for an arm of `n` joints.
pub struct Entry {
    /// What the constraint is.
    pub info: ConstraintInfo,
    /// Builds the constraint for an `n`-joint planar arm.
    pub build: Build<Arm, 2>,
    /// Builds the constraint for an `n`-joint chain in space.
    pub space: Build<Chain, 3>,
    /// Builds it for an `n`-joint chain whose task is its hand's pose.
    pub pose: Build<PoseChain, 6>,
}

/// How a constraint is built, with its scratch space, for an `n`-joint
/// arm `A`.
pub type Build<A, const M: usize> = fn(n: usize) -> Box<dyn Constraint<A, M>>;

/// One kind of linear inequality on the joint rates of an arm `A` (the
/// planar arm by default): its rows `G theta_dot <= h` at a pose, appended
/// to the program's [`Rows`] with no allocation (the constraint owns its
/// scratch space, the program the rows).
pub trait Constraint<A: Model<M> = Arm, const M: usize = 2>: Send + Sync {
    /// Appends this constraint's rows at `pose` (the scene's obstacles and
    /// parameters from `cx`) to `rows`; the rows already there are left as
    /// they are.
    fn rows(&mut self, cx: &Context<'_, A, M>, pose: &A::Pose, rows: &mut Rows) -> Result<()>;

    /// A copy with its own scratch space (a cloned planner steps on its own).
    fn boxed_clone(&self) -> Box<dyn Constraint<A, M>>;

    /// What it is.
    fn info(&self) -> &'static ConstraintInfo;
}

impl<A: Model<M>, const M: usize> Clone for Box<dyn Constraint<A, M>> {
    fn clone(&self) -> Self {
        self.boxed_clone()
    }
}

/// Rows `G theta_dot <= h` of a program over `n` joint rates: `G` row-major
/// (`n` columns), one bound `h` per row. Kept by the program and reused:
/// pushing a row allocates only when there are more rows than ever before.
#[derive(Debug, Clone, Default)]
pub struct Rows {
    n: usize,
    g: Vec<f64>,
    h: Vec<f64>,
}

impl Rows {
    /// Room for `m` rows of `n` columns.
    pub fn with_capacity(n: usize, m: usize) -> Self {
        Self {
            n,
            g: Vec::with_capacity(m * n),
            h: Vec::with_capacity(m),
        }
    }

    /// No rows, each of `n` columns from now on.
    pub fn clear(&mut self, n: usize) {
        self.n = n;
        self.g.clear();
        self.h.clear();
    }

    /// Appends a row with bound `h` and returns its coefficients (`n`
    /// zeros) to be filled in: the row reads `row . theta_dot <= h`.
    pub fn push(&mut self, h: f64) -> &mut [f64] {
        let at = self.g.len();
        self.g.resize(at + self.n, 0.0);
        self.h.push(h);
        &mut self.g[at..]
    }

    /// The columns of each row (the joints).
    pub fn columns(&self) -> usize {
        self.n
    }

    /// How many rows.
    pub fn len(&self) -> usize {
        self.h.len()
    }

    /// Whether there is no row.
    pub fn is_empty(&self) -> bool {
        self.h.is_empty()
    }

    /// `G`, row-major (`len() x columns()`).
    pub fn g(&self) -> &[f64] {
        &self.g
    }

    /// The bounds `h`, one per row.
    pub fn h(&self) -> &[f64] {
        &self.h
    }

    /// The bounds, to be changed in place (the program's relaxation).
    pub fn h_mut(&mut self) -> &mut [f64] {
        &mut self.h
    }

    /// Row `i`: its coefficients and its bound.
    pub fn row(&self, i: usize) -> (&[f64], f64) {
        (&self.g[i * self.n..(i + 1) * self.n], self.h[i])
    }

    /// The rows in order, each as its coefficients and its bound.
    pub fn iter(&self) -> impl Iterator<Item = (&[f64], f64)> + '_ {
        self.g
            .chunks_exact(self.n.max(1))
            .zip(self.h.iter().copied())
    }

    /// Whether `theta_dot` breaks a row: `G_i . theta_dot > h_i` for some
    /// `i` (exactly, with no tolerance).
    pub fn broken_by(&self, theta_dot: &[f64]) -> bool {
        self.iter().any(|(row, h)| {
            let rate: f64 = row.iter().zip(theta_dot).map(|(g, t)| g * t).sum();
            rate > h
        })
    }
}
