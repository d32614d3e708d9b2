//! The arm model: what the planner, the methods and self-motion need of an
//! arm, for a task of `M` coordinates (the hand in the plane, `M = 2`; the
//! hand in space, `M = 3`).
//!
//! Every arm is a serial chain. The kinematics pass stays two
//! implementations behind this one interface, with static dispatch: the
//! planar arm's eqs. (1)-(3) with the closed-form `2 x 2` solve of eq. (18)
//! (about 25 ns a pose, `docs/speed.md`), and the chain in space's
//! modified-DH pass with a `3 x 3` Cholesky solve. Nothing above this
//! trait knows which one ran: a method's rule, the RK4 step and
//! self-motion are written once, generic over `A: Model<M>`.
//!
//! The task dimension is a const parameter so that the hand's full pose
//! (`M = 6`) is one more implementation, not another fork.

/// `impl Scene<$arm> for $scene`: the getters of the fields every
/// scene has, and its own `validate`.
macro_rules! scene_of {
    ($scene:ty, $arm:ty) => {
        impl $crate::model::Scene<$arm> for $scene {
            fn arm(&self) -> &$arm {
                &self.arm
            }
            fn params(&self) -> &$crate::scene::Params {
                &self.params
            }
            fn params_mut(&mut self) -> &mut $crate::scene::Params {
                &mut self.params
            }
            fn damping(&self) -> Option<$crate::ik::DampingSchedule> {
                self.damping
            }
            fn damping_mut(&mut self) -> &mut Option<$crate::ik::DampingSchedule> {
                &mut self.damping
            }
            fn weighting(&self) -> $crate::scene::JointWeighting {
                self.weighting
            }
            fn theta0(&self) -> &[f64] {
                &self.theta0
            }
            fn dt(&self) -> f64 {
                self.dt
            }
            fn tf(&self) -> f64 {
                self.tf
            }
            fn feedback_gain(&self) -> f64 {
                self.feedback_gain
            }
            fn steps(&self) -> usize {
                <$scene>::steps(self)
            }
            fn validate(&self) -> $crate::error::Result<()> {
                <$scene>::validate(self)
            }
        }
    };
}

mod plane;
mod pose;
mod space;

use std::fmt::Debug;

use crate::arm::{JointLimits, RateLimits};
use crate::error::Result;
use crate::ik::DampingSchedule;
use crate::scene::{JointWeighting, Param, Params};

/// An arm whose hand has `M` coordinates: its pose (one kinematics pass,
/// with its own scratch space), its scene, and the small dense solves
/// that specialise by dimension.
pub trait Model<const M: usize>: PhiAlgebra<M> + Clone + Debug + Send + Sync + 'static {
    /// The kinematics of one configuration, updated in place.
    type Pose: Clone + Debug + Send + Sync;
    /// A planning problem for this arm: the arm, its start, its path, its
    /// obstacles and the methods' parameters.
    type Scene: Scene<Self> + Clone + Debug + Send + Sync;
    /// One link (a capsule) and one obstacle at a pose: what the methods
    /// beyond the paper read.
    type Pair: Clearance<Self::Pose> + Copy + Debug + Send + Sync;
    /// The pairs of a pose within a distance, in a buffer that is reused.
    type Pairs: Clone + Debug + Send + Sync;
    /// A point of the arm's space (`[f64; 2]` in the plane, `[f64; 3]` in
    /// space): the joints, the obstacles' centres, a pull on an elbow. The
    /// task's `M` coordinates are the point's for the hand's position and
    /// six for its pose.
    type Point: Point;

    /// The number of joints `n`.
    fn dof(&self) -> usize;
    /// A pose of the arm's size, to be updated.
    fn pose(&self) -> Self::Pose;
    /// `pose` at `theta` (one kinematics pass); refused for a wrong length
    /// or a non-finite angle.
    fn update(&self, pose: &mut Self::Pose, theta: &[f64]) -> Result<()>;
    /// The joint limits, if the arm has them.
    fn joint_limits(&self) -> Option<&JointLimits>;
    /// The joints' own rate limits, if the arm has them.
    fn rate_limits(&self) -> Option<&RateLimits>;

    /// The obstacles' centres: the points `O` of eqs. (14)-(16).
    fn obstacle_centres(scene: &Self::Scene) -> impl Iterator<Item = Self::Point> + '_;
    /// The exact obstacle vector of eqs. (14)-(16) summed over the
    /// scene's obstacles, `v = (lambda / 4) sum_O g(theta, O)`, each
    /// area gradient's sign smoothed by `eps`; `scratch` has `n` entries.
    fn obstacle_vector_into(
        scene: &Self::Scene,
        pose: &Self::Pose,
        lambda: f64,
        eps: f64,
        scratch: &mut [f64],
        v: &mut [f64],
    );

    /// A pairs buffer with room for the pairs an `n`-joint arm has with a
    /// few obstacles, so that refreshing it allocates nothing.
    fn pairs(n: usize) -> Self::Pairs;
    /// How many pairs [`Model::pairs`] has room for.
    fn most_pairs(n: usize) -> usize;
    /// Every pair of `pose` closer than `within`: the scene's obstacles'
    /// (obstacle by obstacle, each from the first link), then the ground's
    /// where the scene has one.
    fn update_pairs(scene: &Self::Scene, pose: &Self::Pose, within: f64, pairs: &mut Self::Pairs);
    /// The pairs [`Model::update_pairs`] found.
    fn pair_list(pairs: &Self::Pairs) -> &[Self::Pair];

    /// The angles the pose was computed at.
    fn theta(pose: &Self::Pose) -> &[f64];
    /// The hand `X(theta)`.
    fn hand(pose: &Self::Pose) -> [f64; M];
    /// The hand's Jacobian, column-major `M x n` (`M` entries per joint).
    fn jacobian(pose: &Self::Pose) -> &[f64];
    /// The smallest singular value of `J` (what the damping schedule reads).
    fn sigma_min(pose: &Self::Pose) -> f64;
    /// Yoshikawa's manipulability `w = sqrt(det(J J^T))`.
    fn manipulability(pose: &Self::Pose) -> f64;
    /// `grad w` (`n` entries) into `out`, `w` floored at `floor` where a
    /// singular pose leaves its gradient undefined.
    fn manipulability_gradient_into(pose: &Self::Pose, floor: f64, out: &mut [f64]);
    /// The position `P(k)` of joint `k` (`0 <= k <= n`: `P(n)` is the
    /// hand; `1 <= k < n` an elbow).
    fn joint_point(pose: &Self::Pose, k: usize) -> Self::Point;
    /// `v = J_k^T f` into `v`, or a damped inverse of `J_k` where the
    /// transpose is too weak: the joint rates that move `P(k)` along a
    /// force `f` (the joints before `k` move it, the others not).
    fn pull(pose: &Self::Pose, k: usize, f: Self::Point, v: &mut [f64]);

    /// The diagonal of the task's metric `Z` (eqs. 6-7): all ones (`Z = I`)
    /// but for the pose task's orientation rows.
    #[inline]
    fn task_weights(pose: &Self::Pose) -> [f64; M] {
        let _ = pose;
        [1.0; M]
    }
    /// The task's error `a - b` (what the feedback `K (X_ref - X)` and the
    /// tracking error read): the difference of the coordinates, for a
    /// hand's position; for a hand's pose the position's difference and
    /// the rotation vector of `R_a R_b^T`.
    #[inline]
    fn task_error(a: [f64; M], b: [f64; M]) -> [f64; M] {
        std::array::from_fn(|k| a[k] - b[k])
    }
    /// How far task point `a` is from `b`: the hand's distance (m) and,
    /// for a pose, the angle of the rotation between them (rad).
    #[inline]
    fn errors(a: [f64; M], b: [f64; M]) -> (f64, Option<f64>) {
        (distance(a, b), None)
    }
    /// The task's point at fraction `s` of the shortest path from `a` to
    /// `b` and its rate `d/ds` (the straight line; for a pose, the
    /// position's line and the orientation turning about one axis at a
    /// constant rate, the rate an angular velocity).
    #[inline]
    fn geodesic(a: [f64; M], b: [f64; M], s: f64) -> ([f64; M], [f64; M]) {
        straight(a, b, s)
    }

    /// Eq. (18): `(J J^T + delta I) varphi = Xdot - J v`,
    /// `theta_dot = J^T varphi + v`, into `out` (`v` has `n` entries).
    fn eq18(
        pose: &Self::Pose,
        xdot: [f64; M],
        v: &[f64],
        delta: f64,
        out: &mut [f64],
    ) -> Result<()>;
    /// `(J J^T + delta I)^-1 b`: the small symmetric solve of eq. (18)
    /// (closed form for `M = 2`, Cholesky for 3).
    fn solve_jjt(pose: &Self::Pose, delta: f64, b: [f64; M]) -> Result<[f64; M]>;
    /// Eq. (18) weighted by a diagonal `W` given as its inverse `winv`:
    /// `(J W^-1 J^T + delta I) varphi = Xdot - J W^-1 v`,
    /// `theta_dot = W^-1 (J^T varphi + v)`.
    fn eq18_weighted(
        pose: &Self::Pose,
        winv: &[f64],
        xdot: [f64; M],
        v: &[f64],
        delta: f64,
        out: &mut [f64],
    ) -> Result<()>;
}

/// Euclidean distance between two points (in the plane exactly
/// `sqrt(dx^2 + dy^2)`, the published numbers).
#[inline]
pub fn distance<const M: usize>(a: [f64; M], b: [f64; M]) -> f64 {
    let mut sum = 0.0;
    for k in 0..M {
        let d = a[k] - b[k];
        sum += d * d;
    }
    sum.sqrt()
}

/// The straight line from `a` to `b`: `a + s (b - a)` and its rate `b - a`.
#[inline]
pub fn straight<const M: usize>(a: [f64; M], b: [f64; M], s: f64) -> ([f64; M], [f64; M]) {
    let d: [f64; M] = std::array::from_fn(|k| b[k] - a[k]);
    (std::array::from_fn(|k| a[k] + s * d[k]), d)
}

/// A point of an arm's space: a fixed-size array of coordinates.
pub trait Point:
    Copy
    + Debug
    + Default
    + PartialEq
    + Send
    + Sync
    + AsRef<[f64]>
    + AsMut<[f64]>
    + serde::Serialize
    + serde::de::DeserializeOwned
    + 'static
{
}

impl<const D: usize> Point for [f64; D] where
    [f64; D]: Default + serde::Serialize + serde::de::DeserializeOwned
{
}

/// The learned route's small dense algebra (eqs. 19-21), which
/// specialises by the task's dimension `M`: `Phi` is row-major `n x M`,
/// `J` column-major `M x n`, `W^-1` a diagonal (`None`: `W = I`).
pub trait PhiAlgebra<const M: usize> {
    /// Newton-Schulz steps refining a learned `Phi` toward `J+`; `false`
    /// where they are not sure to converge (the exact route stands in).
    fn refine_phi(phi: &mut [f64], jac: &[f64], steps: u32) -> Result<bool>;
    /// Damps an undamped `Phi_0` by a constant `delta` in place.
    fn damp_phi(phi: &mut [f64], delta: f64) -> Result<()>;
    /// Weights an undamped `Phi_0` by `W` and damps it by `delta`, in place.
    fn weight_phi(phi: &mut [f64], jac: &[f64], winv: &[f64], delta: f64) -> Result<()>;
    /// Eq. (20), weighted where `winv` is given: the exact
    /// `W^-1 J^T (J W^-1 J^T + delta I)^-1` into `out`.
    fn phi_into(jac: &[f64], winv: Option<&[f64]>, delta: f64, out: &mut [f64]) -> Result<()>;
    /// Eq. (21): `theta_dot = Phi (Xdot - J W^-1 v) + W^-1 v` into `out`.
    fn eq21(
        phi: &[f64],
        jac: &[f64],
        winv: Option<&[f64]>,
        xdot: [f64; M],
        v: &[f64],
        out: &mut [f64],
    ) -> Result<()>;
}

/// A link and what it keeps clear of, at a pose.
pub trait Clearance<P> {
    /// The signed distance between the link's surface and the obstacle's
    /// (m; negative inside).
    fn clearance(&self) -> f64;
    /// `n^T J_p` into `row` (`n` entries): how fast the clearance grows per
    /// unit rate of each joint.
    fn row_into(&self, pose: &P, row: &mut [f64]);
    /// Whether the obstacle is another link of the same arm
    /// (self-collision), which the QP's dampers hold with their own gains.
    fn is_self(&self) -> bool {
        false
    }
}

/// The pair of `pairs` with the smallest clearance, if any.
pub fn closest<P, C: Clearance<P>>(pairs: &[C]) -> Option<&C> {
    pairs
        .iter()
        .min_by(|a, b| a.clearance().total_cmp(&b.clearance()))
}

/// What every method's rule and the planner read of a scene, whatever the
/// arm.
pub trait Scene<A> {
    /// The arm.
    fn arm(&self) -> &A;
    /// The methods' parameters that differ from their defaults.
    fn params(&self) -> &Params;
    /// The parameters, to set one.
    fn params_mut(&mut self) -> &mut Params;
    /// The damping schedule, if any.
    fn damping(&self) -> Option<DampingSchedule>;
    /// The damping schedule, to switch it.
    fn damping_mut(&mut self) -> &mut Option<DampingSchedule>;
    /// How the methods of eq. (5) use the joint limits.
    fn weighting(&self) -> JointWeighting;
    /// The joint angles at `t = 0` (rad).
    fn theta0(&self) -> &[f64];
    /// The Runge-Kutta step (s).
    fn dt(&self) -> f64;
    /// The final time (s).
    fn tf(&self) -> f64;
    /// The closed-loop gain `K` (0: the paper's open loop).
    fn feedback_gain(&self) -> f64;
    /// The number of RK4 steps, `tf / dt`.
    fn steps(&self) -> usize;
    /// Checks every field; the first problem found is returned.
    fn validate(&self) -> Result<()>;

    /// The value of parameter `p` (its default unless set).
    #[inline]
    fn value(&self, p: &'static Param) -> f64 {
        self.params().get(p)
    }
}
