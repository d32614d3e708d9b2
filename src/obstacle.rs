//! The null-space vector for obstacle avoidance, paper section III:
//! triangle areas between each moving link and the obstacle point, eqs.
//! (12)-(16), and their gradient, eqs. (14)-(15).

use std::str::FromStr;

use nalgebra::{DMatrix, DVector, Vector2};

use crate::arm::{number_list, Arm};
use crate::error::{coordinate, positive, Error, Result};
use crate::geometry::{self, point_segment_distance, Ball};
use crate::kinematics::Pose;

/// A disc obstacle: a ball in the plane. Its centre is the point `O` of
/// eq. (16); the radius only decides what counts as a collision.
pub type Obstacle = Ball<2>;

impl Ball<2> {
    /// A disc at `(x, y)` with radius `radius`.
    pub fn new(x: f64, y: f64, radius: f64) -> Self {
        Self {
            centre: [x, y],
            radius,
        }
    }

    /// The centre as a vector.
    pub fn point(&self) -> Vector2<f64> {
        Vector2::new(self.centre[0], self.centre[1])
    }

    /// Checks the obstacle is finite, has a positive radius and stays clear of
    /// the base post (the segment from `(0, 0)` to `P(0)`), which cannot move
    /// out of its way.
    pub fn validate(&self, arm: &Arm) -> Result<()> {
        coordinate("obstacle x", self.centre[0])?;
        coordinate("obstacle y", self.centre[1])?;
        positive("obstacle radius", self.radius)?;
        coordinate("obstacle radius", self.radius)?;
        let d = point_segment_distance(&self.point(), &Vector2::zeros(), &arm.base());
        if d <= self.radius {
            return Err(Error::ObstacleOnPost {
                x: self.centre[0],
                y: self.centre[1],
                radius: self.radius,
            });
        }
        Ok(())
    }
}

/// An obstacle as people write it: on the command line
/// (`--obstacle X,Y` or `X,Y,R`) and in the page's address
/// (`obstacles=x,y,r;x,y`). The radius may be left out; whoever places the
/// obstacle gives the default.
pub type Placement = geometry::Placement<2>;

/// `X,Y` or `X,Y,R`, finite numbers.
impl FromStr for Placement {
    type Err = Error;
    fn from_str(text: &str) -> Result<Self> {
        let syntax = |expected: String| Error::Syntax {
            what: "obstacle",
            text: text.to_string(),
            expected,
        };
        match number_list(text).map_err(&syntax)?[..] {
            [x, y] => Ok(Self {
                centre: [x, y],
                radius: None,
            }),
            [x, y, r] => Ok(Self {
                centre: [x, y],
                radius: Some(r),
            }),
            ref other => Err(syntax(format!(
                "expected x,y or x,y,r, got {} numbers",
                other.len()
            ))),
        }
    }
}

/// Obstacles written `x,y,r;x,y,r;...` (each radius optional; empty parts
/// are skipped, so a trailing `;` is fine).
pub fn parse_placements(text: &str) -> Result<Vec<Placement>> {
    text.split(';')
        .filter(|p| !p.trim().is_empty())
        .map(str::parse)
        .collect()
}

/// `D_k = det[O - P(k-1), P(k) - P(k-1)]` for every moving link `k = 1..n`,
/// eq. (16); `V_k = |D_k|` (eq. 12) is twice the area of the triangle between
/// link `k` and `O`.
pub fn triangle_determinants(joints: &[Vector2<f64>], o: &Vector2<f64>) -> Vec<f64> {
    joints
        .windows(2)
        .map(|w| {
            let a = o - w[0];
            let b = w[1] - w[0];
            a[0] * b[1] - a[1] * b[0]
        })
        .collect()
}

/// Analytic `dD_k / dtheta_i` as an `n x n` matrix (row `k`, column `i`).
///
/// With `a_k = O - P(k-1)` and `b_k = P(k) - P(k-1) = L_k (sin phi_k, cos phi_k)`,
/// `D_k = det[a_k, b_k]` and `dD_k/dtheta_i = det[da_k, b_k] + det[a_k, db_k]`
/// for `i <= k`, where `db_k/dtheta_i = t_k = L_k (cos phi_k, -sin phi_k)` and
/// `da_k/dtheta_i = -dP(k-1)/dtheta_i = -(J_i - J_k)` (`J_i` is column `i` of
/// the Jacobian, `J_i = sum_{m>=i} t_m`). Hence
/// `dD_k/dtheta_i = c_k - det[J_i, b_k]` with `c_k = det[a_k, t_k] + det[J_k, b_k]`.
/// `D_k` depends only on `theta_1..theta_k`, so the matrix is lower triangular.
pub fn determinant_gradient(arm: &Arm, theta: &DVector<f64>, o: &Vector2<f64>) -> DMatrix<f64> {
    let n = arm.dof();
    let pose = Pose::lenient(arm, theta.as_slice());
    let o = [o[0], o[1]];
    let mut g = DMatrix::zeros(n, n);
    for k in 0..n {
        let link = Link::at(arm, &pose, k, o);
        for i in 0..=k {
            g[(k, i)] = link.c - det(column(&pose, i), link.b);
        }
    }
    g
}

#[inline]
fn det(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

#[inline]
fn column(pose: &Pose, i: usize) -> [f64; 2] {
    let j = pose.jacobian();
    [j[2 * i], j[2 * i + 1]]
}

/// What link `k` contributes: `D_k` (eq. 16), `b_k` and `c_k` (see
/// [`determinant_gradient`]).
struct Link {
    d: f64,
    b: [f64; 2],
    c: f64,
}

impl Link {
    #[inline]
    fn at(arm: &Arm, pose: &Pose, k: usize, o: [f64; 2]) -> Self {
        let (p0, p1) = (pose.joints()[k], pose.joints()[k + 1]);
        let a = [o[0] - p0[0], o[1] - p0[1]];
        let b = [p1[0] - p0[0], p1[1] - p0[1]];
        let l = arm.links()[k];
        let t = [l * pose.cos()[k], -l * pose.sin()[k]];
        Self {
            d: det(a, b),
            b,
            c: det(a, t) + det(column(pose, k), b),
        }
    }
}

/// The obstacle-avoidance gradient for one obstacle point with `lambda = 4`:
/// `g_i = sum_k sign(D_k) dD_k/dtheta_i` (eq. 15, zero where `D_k = 0`), so
/// that `v = (lambda / 4) g`. This is the quantity the paper's second network
/// learns; it does not depend on `lambda`.
pub fn area_gradient(arm: &Arm, theta: &DVector<f64>, o: &Vector2<f64>) -> DVector<f64> {
    area_gradient_smoothed(arm, theta, o, 0.0)
}

/// [`area_gradient`] with the sign of eq. (15) smoothed by `eps` (m^2):
/// `sign(D)` becomes `D / sqrt(D^2 + eps^2)` ([`smoothed_sign`]).
pub fn area_gradient_smoothed(
    arm: &Arm,
    theta: &DVector<f64>,
    o: &Vector2<f64>,
    eps: f64,
) -> DVector<f64> {
    let pose = Pose::lenient(arm, theta.as_slice());
    let mut g = DVector::zeros(arm.dof());
    area_gradient_into(arm, &pose, [o[0], o[1]], eps, g.as_mut_slice());
    g
}

/// The sign of `D_k` in eq. (15), smoothed by `eps >= 0` (m^2):
/// `D / sqrt(D^2 + eps^2)`, or `sign(D)` (0 at 0) when `eps = 0`, the paper's.
///
/// The paper's criterion is the sum of the triangles' unsigned areas, so
/// its gradient jumps wherever the obstacle crosses the line of a link
/// (`D_k` changes sign): the joint rates jump, and a network cannot fit
/// the jump (`docs/learning.md`). Smoothing turns the criterion into
/// `sum_k sqrt(D_k^2 + eps^2)`, whose gradient this is; `eps` is a
/// parameter of the criterion itself, for the exact and the learned route
/// alike ([`crate::planner::methods::SIGN_SMOOTHING`]).
#[inline]
pub fn smoothed_sign(d: f64, eps: f64) -> f64 {
    if eps > 0.0 {
        d / d.hypot(eps)
    } else if d > 0.0 {
        1.0
    } else if d < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// [`area_gradient_smoothed`] from a [`Pose`], allocation-free and in
/// `O(n)`: with `s_k` the (smoothed) sign of `D_k` and
/// [`determinant_gradient`]'s `dD_k/dtheta_i = c_k - det[J_i, b_k]`,
/// `g_i = sum_{k>=i} s_k c_k - det[J_i, sum_{k>=i} s_k b_k]`: two suffix
/// sums. Writes `min(n, out.len())` entries; `pose` must be a pose of `arm`.
#[inline]
pub fn area_gradient_into(arm: &Arm, pose: &Pose, o: [f64; 2], eps: f64, out: &mut [f64]) {
    let n = pose.dof().min(arm.dof());
    let (mut sc, mut sb) = (0.0, [0.0, 0.0]);
    for k in (0..n).rev() {
        let link = Link::at(arm, pose, k, o);
        let s = smoothed_sign(link.d, eps);
        sc += s * link.c;
        sb = [sb[0] + s * link.b[0], sb[1] + s * link.b[1]];
        if let Some(g) = out.get_mut(k) {
            *g = sc - det(column(pose, k), sb);
        }
    }
}

/// Null-space vector for obstacle avoidance, eqs. (14)-(15), summed over all
/// obstacle points: `v_i = (lambda / 4) sum_O sum_k dV_k/dtheta_i`.
pub fn null_space_vector(
    arm: &Arm,
    theta: &DVector<f64>,
    obstacles: &[Obstacle],
    lambda: f64,
) -> DVector<f64> {
    let pose = Pose::lenient(arm, theta.as_slice());
    let mut v = DVector::zeros(arm.dof());
    let mut g = vec![0.0; arm.dof()];
    null_space_vector_into(arm, &pose, obstacles, lambda, 0.0, &mut g, v.as_mut_slice());
    v
}

/// [`null_space_vector`] from a [`Pose`], with the sign smoothed by `eps`
/// ([`smoothed_sign`]), allocation-free: `scratch` and `v` have `n`
/// entries each.
pub fn null_space_vector_into(
    arm: &Arm,
    pose: &Pose,
    obstacles: &[Obstacle],
    lambda: f64,
    eps: f64,
    scratch: &mut [f64],
    v: &mut [f64],
) {
    v.iter_mut().for_each(|x| *x = 0.0);
    for ob in obstacles {
        area_gradient_into(arm, pose, ob.centre, eps, scratch);
        for (vi, gi) in v.iter_mut().zip(scratch.iter()) {
            *vi += gi;
        }
    }
    let scale = lambda / 4.0;
    v.iter_mut().for_each(|x| *x *= scale);
}

/// Clearance: the smallest distance from `o` to the moving link segments
/// `P(k-1)-P(k)`, `k = 1..n` (the post is not counted).
pub fn clearance(joints: &[Vector2<f64>], o: &Vector2<f64>) -> f64 {
    joints
        .windows(2)
        .map(|w| point_segment_distance(o, &w[0], &w[1]))
        .fold(f64::INFINITY, f64::min)
}
