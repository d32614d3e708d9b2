//! One kinematics pass per pose: everything the planner reads about a joint
//! configuration, computed once.
//!
//! A [`Pose`] holds, for one `theta`, the sines and cosines of the absolute
//! link angles `phi_i = theta_1 + ... + theta_i`, the joint positions
//! `P(0)..P(n)` (eq. 1) and the Jacobian `J` (eq. 3). The obstacle vector
//! (eqs. 12-16), the clearance, the damping schedule, the manipulability, the
//! networks' inputs and the sample all read these; nothing recomputes a sine.
//! (The same idea as `openrr/k`'s cached link transforms.)
//!
//! A pose owns its buffers and [`Pose::update`] refills them in place, so a
//! planner that keeps its poses allocates nothing per step, for any number of
//! links.

use nalgebra::{DVector, Matrix2xX, Vector2};

use crate::arm::Arm;
use crate::error::Result;
use crate::geometry::segment_distance_squared;

/// The kinematics of an [`Arm`] as plain values (each a [`Pose`] computed
/// and read once): convenient, and allocating; the planner keeps poses.
impl Arm {
    /// Absolute link angles `phi_i = theta_1 + ... + theta_i`.
    pub fn absolute_angles(&self, theta: &DVector<f64>) -> Vec<f64> {
        theta
            .iter()
            .scan(0.0, |acc, &t| {
                *acc += t;
                Some(*acc)
            })
            .collect()
    }

    /// All joint positions `P(0), P(1), ..., P(n)`; the last is the end effector.
    pub fn joints(&self, theta: &DVector<f64>) -> Vec<Vector2<f64>> {
        Pose::lenient(self, theta.as_slice())
            .joints()
            .iter()
            .map(|p| Vector2::new(p[0], p[1]))
            .collect()
    }

    /// Forward kinematics `X = f(theta)`, eq. (1): the end effector `P(n)`.
    ///
    /// # Examples
    /// ```
    /// use redundant_ik::{Arm, nalgebra::DVector};
    /// use std::f64::consts::PI;
    /// let x = Arm::paper().forward(&DVector::from_vec(vec![PI / 12.0, PI / 2.0, -PI / 6.0]));
    /// assert!((x[0] - 1.555884).abs() < 1e-6 && (x[1] - 1.014851).abs() < 1e-6);
    /// ```
    pub fn forward(&self, theta: &DVector<f64>) -> Vector2<f64> {
        let x = Pose::lenient(self, theta.as_slice()).end_effector();
        Vector2::new(x[0], x[1])
    }

    /// Analytic Jacobian `J = dX/dtheta`, eq. (3), a `2 x n` matrix:
    /// `J[0][i] = sum_{k>=i} L_k cos phi_k`, `J[1][i] = -sum_{k>=i} L_k sin phi_k`.
    pub fn jacobian(&self, theta: &DVector<f64>) -> Matrix2xX<f64> {
        Matrix2xX::from_column_slice(Pose::lenient(self, theta.as_slice()).jacobian())
    }
}

/// The kinematics of one joint configuration of one arm.
#[derive(Debug, Clone, PartialEq)]
pub struct Pose {
    /// Joint angles `theta_1..theta_n`.
    theta: Vec<f64>,
    /// `sin phi_i`, `cos phi_i` of the absolute link angles.
    sin: Vec<f64>,
    cos: Vec<f64>,
    /// `P(0)..P(n)`; `P(n)` is the end effector.
    joints: Vec<[f64; 2]>,
    /// `J`, column-major `2 x n`: entries `2i` and `2i + 1` are column `i`
    /// (the layout of nalgebra's `Matrix2xX`).
    jac: Vec<f64>,
}

impl Pose {
    /// The pose of `arm` at `theta`. Fails if `theta` does not have one finite
    /// angle per link.
    pub fn new(arm: &Arm, theta: &[f64]) -> Result<Self> {
        arm.check_angles(theta)?;
        let mut pose = Self::zeros(arm.dof());
        pose.fill(arm, theta);
        Ok(pose)
    }

    /// The pose at `theta` for the convenience functions that return plain
    /// values (`Arm::forward`, ...): missing angles count as zero, extra ones
    /// are ignored, nothing is checked.
    pub(crate) fn lenient(arm: &Arm, theta: &[f64]) -> Self {
        let n = arm.dof();
        let mut pose = Self::zeros(n);
        if theta.len() == n {
            pose.fill(arm, theta);
        } else {
            let mut th = vec![0.0; n];
            for (t, x) in th.iter_mut().zip(theta) {
                *t = *x;
            }
            pose.fill(arm, &th);
        }
        pose
    }

    /// Buffers for an `n`-link arm, all zero (not yet a pose of any arm).
    pub(crate) fn zeros(n: usize) -> Self {
        Self {
            theta: vec![0.0; n],
            sin: vec![0.0; n],
            cos: vec![0.0; n],
            joints: vec![[0.0; 2]; n + 1],
            jac: vec![0.0; 2 * n],
        }
    }

    /// Recomputes the pose for `theta` in place (no allocation). Fails,
    /// leaving the pose unchanged, if `theta` or `arm` has a different
    /// number of joints than the pose. Angles are not checked for
    /// finiteness: NaN gives NaN joints, which the planner's step rejects.
    pub fn update(&mut self, arm: &Arm, theta: &[f64]) -> Result<()> {
        let n = self.dof();
        crate::error::pose_counts(n, arm.dof(), theta.len())?;
        self.fill(arm, theta);
        Ok(())
    }

    /// The one kinematics pass: absolute angles and their sines and cosines,
    /// joints `P(k) = P(k-1) + L_k (sin phi_k, cos phi_k)` (eq. 1) and the
    /// Jacobian columns `J_i = sum_{k>=i} L_k (cos phi_k, -sin phi_k)` (eq. 3).
    /// Lengths were checked by the caller.
    fn fill(&mut self, arm: &Arm, theta: &[f64]) {
        let n = self.theta.len();
        let links = &arm.links()[..n];
        let theta = &theta[..n];
        let (sin, cos) = (&mut self.sin[..n], &mut self.cos[..n]);
        let joints = &mut self.joints[..n + 1];
        self.theta.copy_from_slice(theta);
        let mut phi = 0.0;
        let (mut x, mut y) = (0.0, arm.post());
        joints[0] = [x, y];
        for i in 0..n {
            phi += theta[i];
            let (s, c) = sin_cos(phi);
            sin[i] = s;
            cos[i] = c;
            x += links[i] * s;
            y += links[i] * c;
            joints[i + 1] = [x, y];
        }
        let jac = &mut self.jac[..2 * n];
        let (mut jx, mut jy) = (0.0, 0.0);
        for i in (0..n).rev() {
            jx += links[i] * cos[i];
            jy += links[i] * sin[i];
            jac[2 * i] = jx;
            jac[2 * i + 1] = -jy;
        }
    }

    /// Number of joints `n`.
    #[inline]
    pub fn dof(&self) -> usize {
        self.theta.len()
    }

    /// Joint angles.
    #[inline]
    pub fn theta(&self) -> &[f64] {
        &self.theta
    }

    /// `sin phi_i` of the absolute link angles.
    #[inline]
    pub fn sin(&self) -> &[f64] {
        &self.sin
    }

    /// `cos phi_i` of the absolute link angles.
    #[inline]
    pub fn cos(&self) -> &[f64] {
        &self.cos
    }

    /// Joint positions `P(0)..P(n)`.
    #[inline]
    pub fn joints(&self) -> &[[f64; 2]] {
        &self.joints
    }

    /// End effector `X = P(n)`.
    #[inline]
    pub fn end_effector(&self) -> [f64; 2] {
        self.joints[self.joints.len() - 1]
    }

    /// `J`, column-major (`[J_00, J_10, J_01, J_11, ...]`).
    #[inline]
    pub fn jacobian(&self) -> &[f64] {
        &self.jac
    }

    /// `J J^T` as `(a11, a12, a22)`.
    #[inline]
    pub fn jjt(&self) -> [f64; 3] {
        jjt(&self.jac)
    }

    /// Smallest singular value of `J`.
    pub fn sigma_min(&self) -> f64 {
        smallest_singular_value(self.jjt())
    }

    /// Yoshikawa's manipulability `sqrt(det(J J^T))`.
    pub fn manipulability(&self) -> f64 {
        let [a, b, c] = self.jjt();
        (a * c - b * b).max(0.0).sqrt()
    }

    /// The gradient of [`Pose::manipulability`] `w = sqrt(det(J J^T))` into
    /// `out` (`n` entries), analytically: with `T_m = P(n) - P(m)` (the
    /// hand seen from joint `m + 1`), `J_i = (T_i.y, -T_i.x)` and
    /// `dJ_i/dtheta_j = -T_max(i,j)`, so
    /// `d det/dtheta_j = a22 da11 + a11 da22 - 2 a12 da12` with
    /// `da11 = -2 sum_i J_i.x T_m.x`, `da22 = -2 sum_i J_i.y T_m.y`,
    /// `da12 = -sum_i (T_m.x J_i.y + J_i.x T_m.y)`, and
    /// `dw/dtheta_j = (d det/dtheta_j) / (2 w)`. `w` is floored at `floor`
    /// (m^2): at a singular pose `w` is 0 and not differentiable.
    pub fn manipulability_gradient_into(&self, floor: f64, out: &mut [f64]) {
        let n = self.dof();
        let [a11, a12, a22] = self.jjt();
        let w = (a11 * a22 - a12 * a12).max(0.0).sqrt().max(floor);
        let hand = self.joints[n];
        let tail = |m: usize| [hand[0] - self.joints[m][0], hand[1] - self.joints[m][1]];
        for (j, o) in out.iter_mut().enumerate().take(n) {
            let (mut d11, mut d12, mut d22) = (0.0, 0.0, 0.0);
            for (i, col) in self.jac.chunks_exact(2).enumerate() {
                let t = tail(i.max(j));
                d11 -= 2.0 * col[0] * t[0];
                d22 -= 2.0 * col[1] * t[1];
                d12 -= t[0] * col[1] + col[0] * t[1];
            }
            *o = (a22 * d11 + a11 * d22 - 2.0 * a12 * d12) / (2.0 * w);
        }
    }

    /// Smallest distance from `o` to the moving link segments `P(k-1)-P(k)`
    /// (the post is not counted).
    pub fn clearance(&self, o: [f64; 2]) -> f64 {
        self.joints
            .windows(2)
            .map(|w| segment_distance_squared(o, w[0], w[1]))
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }
}

/// `J J^T` of a column-major `2 x n` Jacobian, as `(a11, a12, a22)`.
#[inline]
pub fn jjt(jac: &[f64]) -> [f64; 3] {
    let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
    for col in jac.chunks_exact(2) {
        a += col[0] * col[0];
        b += col[0] * col[1];
        c += col[1] * col[1];
    }
    [a, b, c]
}

/// Smallest singular value of `J` from `J J^T = (a11, a12, a22)`: the square
/// root of the smaller eigenvalue of the symmetric 2x2 matrix, in closed form.
#[inline]
pub fn smallest_singular_value([p, q, r]: [f64; 3]) -> f64 {
    let mean = 0.5 * (p + r);
    let radius = (0.25 * (p - r) * (p - r) + q * q).sqrt();
    (mean - radius).max(0.0).sqrt()
}

/// The velocity (manipulability) ellipse `{J theta_dot : |theta_dot| <= 1}`
/// of a pose from `J J^T = (a11, a12, a22)` (Yoshikawa 1985): its axes are
/// the unit eigenvectors of `J J^T`, the major first, and its half-lengths
/// the square roots of their eigenvalues, the singular values
/// `sigma_1 >= sigma_2` of `J` (their product is the manipulability
/// `sqrt(det(J J^T))`). The force ellipse `{f : |J^T f| <= 1}` has the same
/// axes with half-lengths `1 / sigma_i`. The major axis is at the angle
/// `phi = atan2(2 a12, a11 - a22) / 2`.
pub fn velocity_ellipse([p, q, r]: [f64; 3]) -> ([[f64; 2]; 2], [f64; 2]) {
    let mean = 0.5 * (p + r);
    let radius = (0.25 * (p - r) * (p - r) + q * q).sqrt();
    let (s, c) = sin_cos(0.5 * (2.0 * q).atan2(p - r));
    (
        [[c, s], [-s, c]],
        [
            (mean + radius).max(0.0).sqrt(),
            (mean - radius).max(0.0).sqrt(),
        ],
    )
}

/// `(sin x, cos x)`, within one unit in the last place of the C library's,
/// and about three times faster for the angles an arm takes.
///
/// The trigonometry of the joint angles was a third of a numerical rate
/// evaluation through libm (`sincos` is a call that the compiler cannot
/// inline or overlap). This is fdlibm's method, inlined and branch-free:
/// Cody-Waite reduction `x = q pi/2 + r`, `|r| <= pi/4`, with `pi/2` split in
/// three parts (exact products for `|q| < 2^20`), fdlibm's `__kernel_sin`
/// and `__kernel_cos` polynomials on `r`, and the quadrant `q mod 4` choosing
/// and signing the results. Arguments beyond `|x| = 2^19 pi/2` (about 8e5
/// rad, no arm's) are first taken modulo `2 pi` (`%` is exact; the rounded
/// `2 pi` errs by about `x / 2 pi` ulps, 1e-10 rad at 8e5) instead of by
/// the C library's exact reduction, whose tables and long arithmetic
/// (`rem_pio2_large`) were 7.6 KB of the page's module (about 3 KB
/// gzipped); NaN and infinity give NaN.
#[inline]
#[allow(clippy::excessive_precision)] // fdlibm's published digits
pub fn sin_cos(x: f64) -> (f64, f64) {
    const FRAC_2_PI: f64 = std::f64::consts::FRAC_2_PI;
    const PIO2_1: f64 = 1.570_796_326_734_125_614_17e0;
    const PIO2_2: f64 = 6.077_100_506_303_965_976_60e-11;
    const PIO2_3: f64 = 2.022_266_248_711_166_455_80e-21;
    const SHIFT: f64 = 6_755_399_441_055_744.0;
    const LIMIT: f64 = 823_549.661_225_781_2; // 2^19 pi/2
    if x.abs() > LIMIT || x.is_nan() {
        return sin_cos_large(x);
    }
    let qd = x * FRAC_2_PI + SHIFT;
    let q = qd.to_bits();
    let qf = qd - SHIFT;
    let r = ((x - qf * PIO2_1) - qf * PIO2_2) - qf * PIO2_3;
    let (s, c) = kernel_sin_cos(r);
    // Quadrant: sin x = (s, c, -s, -c)[q mod 4], cos x = (c, -s, -c, s)[q mod 4].
    let swap = q & 1 == 1;
    let (s, c) = if swap { (c, s) } else { (s, c) };
    let sin_neg = q & 2 == 2;
    let cos_neg = (q.wrapping_add(1)) & 2 == 2;
    (if sin_neg { -s } else { s }, if cos_neg { -c } else { c })
}

/// [`sin_cos`] of an argument beyond its range, taken modulo `2 pi` first
/// (NaN and infinity give NaN), out of line and cold.
#[cold]
#[inline(never)]
fn sin_cos_large(x: f64) -> (f64, f64) {
    let r = x % std::f64::consts::TAU;
    if r.is_nan() {
        (f64::NAN, f64::NAN)
    } else {
        sin_cos(r)
    }
}

/// fdlibm's `__kernel_sin` and `__kernel_cos` on `|r| <= pi/4` (the low part
/// of the reduced argument dropped: under one ulp).
#[inline(always)]
#[allow(clippy::excessive_precision)] // fdlibm's published digits
fn kernel_sin_cos(r: f64) -> (f64, f64) {
    const S1: f64 = -1.666_666_666_666_663_243_48e-1;
    const S2: f64 = 8.333_333_333_322_489_461_24e-3;
    const S3: f64 = -1.984_126_982_985_794_931_34e-4;
    const S4: f64 = 2.755_731_370_707_006_767_89e-6;
    const S5: f64 = -2.505_076_025_340_686_341_95e-8;
    const S6: f64 = 1.589_690_995_211_550_102_21e-10;
    const C1: f64 = 4.166_666_666_666_660_190_37e-2;
    const C2: f64 = -1.388_888_888_887_410_957_49e-3;
    const C3: f64 = 2.480_158_728_947_672_941_78e-5;
    const C4: f64 = -2.755_731_435_139_066_330_35e-7;
    const C5: f64 = 2.087_572_321_298_174_827_90e-9;
    const C6: f64 = -1.135_964_755_778_819_482_65e-11;
    let z = r * r;
    let w = z * z;
    // sin r = r + r^3 (S1 + z (S2 + ...)), split for overlap as fdlibm does.
    let ps = S2 + z * (S3 + z * S4) + z * w * (S5 + z * S6);
    let sin = r + r * z * (S1 + z * ps);
    // cos r = 1 - z/2 + z^2 (C1 + z (C2 + ...)), with fdlibm's care for the
    // rounding of 1 - z/2.
    let pc = z * (C1 + z * C2 + w * C3) + w * w * (C4 + z * C5 + w * C6);
    let hz = 0.5 * z;
    let one_minus = 1.0 - hz;
    let cos = one_minus + (((1.0 - one_minus) - hz) + z * pc);
    (sin, cos)
}
