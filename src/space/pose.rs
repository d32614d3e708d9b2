//! One kinematics pass per pose of a spatial [`Chain`]: every joint's frame
//! (its rotation and origin in the world), the hand, and the `3 x n`
//! positional Jacobian of the hand, computed once; point Jacobians of any
//! point of the volume read them.
//!
//! The Jacobian's column `i` is `z_i x (p - o_i)` (joint `i` turns about
//! the axis `z_i` through `o_i`; Siciliano et al. 2009, eq. 3.30): exact,
//! with no differencing. A pose owns its buffers and [`SpacePose::update`]
//! refills them, so a planner that keeps its poses allocates nothing.

use super::chain::{Chain, Segment};
use crate::error::{Error, Result};
use crate::kinematics::sin_cos;

/// A 3-vector.
pub type Vec3 = [f64; 3];

/// The kinematics of one joint configuration of one spatial chain.
#[derive(Debug, Clone, PartialEq)]
pub struct SpacePose {
    theta: Vec<f64>,
    /// Each joint frame's rotation, by columns: `x_i`, `y_i`, `z_i`.
    frames: Vec<[Vec3; 3]>,
    /// The points: the base's origin, each joint frame's origin, the flange.
    points: Vec<Vec3>,
    /// `J`, column-major `3 x n`: entries `3i..3i + 3` are column `i`.
    jac: Vec<f64>,
    /// `J J^T`, by rows: computed once per pose (eq. 18's solve, the
    /// damping schedule's smallest singular value and the manipulability
    /// all read it).
    jjt: [[f64; 3]; 3],
    /// Which joints slide along their axis (a URDF's prismatic joints)
    /// instead of turning about it.
    prismatic: Vec<bool>,
}

impl SpacePose {
    /// The pose of `chain` at `theta`; fails if `theta` does not have one
    /// finite angle per joint.
    pub fn new(chain: &Chain, theta: &[f64]) -> Result<Self> {
        chain.check_angles(theta)?;
        let mut pose = Self::of(chain);
        pose.fill(chain, theta);
        Ok(pose)
    }

    /// Buffers for a pose of `chain`, all zero: its joints, and the ends of
    /// its volumes where it has volumes of its own (a chain of joint
    /// frames).
    pub fn of(chain: &Chain) -> Self {
        let mut pose = Self::zeros(chain.dof());
        pose.points.resize(chain.point_count(), [0.0; 3]);
        for (p, j) in pose.prismatic.iter_mut().zip(chain.joint_frames()) {
            *p = j.prismatic;
        }
        pose
    }

    /// Buffers for an `n`-joint chain, all zero.
    pub fn zeros(n: usize) -> Self {
        Self {
            theta: vec![0.0; n],
            frames: vec![[[0.0; 3]; 3]; n],
            points: vec![[0.0; 3]; n + 2],
            jac: vec![0.0; 3 * n],
            jjt: [[0.0; 3]; 3],
            prismatic: vec![false; n],
        }
    }

    /// Recomputes the pose for `theta` in place (no allocation); fails,
    /// leaving it unchanged, if `theta` or `chain` has another number of
    /// joints. Angles are not checked for finiteness (NaN gives NaN).
    pub fn update(&mut self, chain: &Chain, theta: &[f64]) -> Result<()> {
        let n = self.dof();
        if self.points.len() != chain.point_count() && chain.dof() == n {
            return Err(Error::DimensionMismatch {
                what: "points of this pose (SpacePose::of gives a chain's)".into(),
                expected: chain.point_count(),
                found: self.points.len(),
            });
        }
        crate::error::pose_counts(n, chain.dof(), theta.len())?;
        self.fill(chain, theta);
        Ok(())
    }

    /// The one pass: frame `i = frame (i-1) Rx(alpha) Tx(a) Rz(theta_i +
    /// offset) Tz(d)` for a chain of rows, `frame (i-1) F_i Rz(theta_i)`
    /// for one of joint frames; the flange, then the Jacobian's columns.
    fn fill(&mut self, chain: &Chain, theta: &[f64]) {
        let n = self.theta.len();
        self.theta.copy_from_slice(&theta[..n]);
        let (rot, origin) = chain.base();
        // The base's axes as columns.
        let mut axes: [Vec3; 3] = [
            [rot[0][0], rot[1][0], rot[2][0]],
            [rot[0][1], rot[1][1], rot[2][1]],
            [rot[0][2], rot[1][2], rot[2][2]],
        ];
        let base = axes;
        let mut o = origin;
        self.points[0] = o;
        for (i, (row, &(sa, ca))) in chain.rows().iter().zip(chain.twists()).enumerate() {
            // Tx(a) along the previous x, then Rx(alpha).
            o = add(o, scale(axes[0], row.a));
            let y = add(scale(axes[1], ca), scale(axes[2], sa));
            let z = add(scale(axes[1], -sa), scale(axes[2], ca));
            let x = axes[0];
            // Rz(theta + offset).
            let (st, ct) = sin_cos(self.theta[i] + row.offset);
            let xi = add(scale(x, ct), scale(y, st));
            let yi = add(scale(x, -st), scale(y, ct));
            axes = [xi, yi, z];
            // Tz(d) along the new z.
            o = add(o, scale(z, row.d));
            self.frames[i] = axes;
            self.points[i + 1] = o;
        }
        for (i, j) in chain.joint_frames().iter().enumerate() {
            // F_i: its translation along the previous axes, its rotation's
            // columns in them; then Rz(theta).
            o = add(o, in_frame(&axes, j.translation));
            let [x, y, z]: [Vec3; 3] = std::array::from_fn(|c| {
                in_frame(
                    &axes,
                    [j.rotation[0][c], j.rotation[1][c], j.rotation[2][c]],
                )
            });
            self.prismatic[i] = j.prismatic;
            if j.prismatic {
                // Tz(q): along the new z.
                axes = [x, y, z];
                o = add(o, scale(z, self.theta[i]));
            } else {
                let (st, ct) = sin_cos(self.theta[i]);
                axes = [
                    add(scale(x, ct), scale(y, st)),
                    add(scale(x, -st), scale(y, ct)),
                    z,
                ];
            }
            self.frames[i] = axes;
            self.points[i + 1] = o;
        }
        let f = chain.flange();
        let hand = add(
            o,
            add(
                add(scale(axes[0], f[0]), scale(axes[1], f[1])),
                scale(axes[2], f[2]),
            ),
        );
        self.points[n + 1] = hand;
        // The ends of the volumes of a chain of joint frames, each in the
        // frame of the joint that moves it (the base's for none).
        for (k, v) in chain.volumes().iter().enumerate() {
            let (axes, o) = match v.moved_by {
                0 => (&base, self.points[0]),
                j => (&self.frames[j - 1], self.points[j]),
            };
            self.points[n + 2 + 2 * k] = add(o, in_frame(axes, v.a));
            self.points[n + 3 + 2 * k] = add(o, in_frame(axes, v.b));
        }
        for i in 0..n {
            let col = self.column(i, hand);
            self.jac[3 * i..3 * i + 3].copy_from_slice(&col);
        }
        let mut a = [[0.0; 3]; 3];
        for col in self.jac.chunks_exact(3) {
            for r in 0..3 {
                for c in 0..3 {
                    a[r][c] += col[r] * col[c];
                }
            }
        }
        self.jjt = a;
    }

    /// Number of joints `n`.
    #[inline]
    pub fn dof(&self) -> usize {
        self.theta.len()
    }

    /// The joint angles.
    #[inline]
    pub fn theta(&self) -> &[f64] {
        &self.theta
    }

    /// Joint `i`'s frame (from 0: joint 1), its axes as columns `x, y, z`.
    #[inline]
    pub fn frame(&self, i: usize) -> [Vec3; 3] {
        self.frames[i]
    }

    /// Joint `i`'s axis `z_i` (from 0: joint 1) in the world.
    #[inline]
    pub fn axis(&self, i: usize) -> Vec3 {
        self.frames[i][2]
    }

    /// Whether joint `i` (from 0) slides along its axis (prismatic).
    #[inline]
    pub fn is_prismatic(&self, i: usize) -> bool {
        self.prismatic[i]
    }

    /// The velocity of a point `p` that joint `i` (from 0) carries, per
    /// unit rate of the joint: `z_i x (p - o_i)` for a joint that turns,
    /// `z_i` for one that slides. Column `i` of every point Jacobian.
    #[inline]
    pub fn column(&self, i: usize, p: Vec3) -> Vec3 {
        if self.prismatic[i] {
            self.frames[i][2]
        } else {
            cross(self.frames[i][2], sub(p, self.points[i + 1]))
        }
    }

    /// The points: the base's origin (0), joint frame `i`'s origin (`i`,
    /// from 1), the flange (`n + 1`).
    #[inline]
    pub fn points(&self) -> &[Vec3] {
        &self.points[..self.theta.len() + 2]
    }

    /// Joint `i`'s origin (from 0: joint 1): the point its axis goes through.
    #[inline]
    pub fn joint_origin(&self, i: usize) -> Vec3 {
        self.points[i + 1]
    }

    /// The hand (the flange's origin): the task's point.
    #[inline]
    pub fn hand(&self) -> Vec3 {
        self.points[self.theta.len() + 1]
    }

    /// `J`, column-major `3 x n`.
    #[inline]
    pub fn jacobian(&self) -> &[f64] {
        &self.jac
    }

    /// A segment's ends in the world.
    #[inline]
    pub fn segment(&self, s: &Segment) -> (Vec3, Vec3) {
        (self.points[s.from], self.points[s.to])
    }

    /// The Jacobian of a point `p` carried by the first `moved_by` joints
    /// (a point of a segment: [`Segment::moved_by`]) into `out`
    /// (column-major `3 x n`; zero columns for the joints that do not move
    /// it): column `i` is `z_i x (p - o_i)`.
    pub fn point_jacobian_into(&self, p: Vec3, moved_by: usize, out: &mut [f64]) {
        let n = self.dof();
        for i in 0..n {
            let col = if i < moved_by {
                self.column(i, p)
            } else {
                [0.0; 3]
            };
            out[3 * i..3 * i + 3].copy_from_slice(&col);
        }
    }

    /// The velocity of point `p` carried by the first `moved_by` joints at
    /// joint rates `rates`: `J_p rates`, without forming `J_p`.
    pub fn point_velocity(&self, p: Vec3, moved_by: usize, rates: &[f64]) -> Vec3 {
        let mut v = [0.0; 3];
        for (i, &r) in rates.iter().enumerate().take(moved_by.min(self.dof())) {
            v = add(v, scale(self.column(i, p), r));
        }
        v
    }

    /// `J J^T`, symmetric `3 x 3`, by rows (computed with the pose).
    #[inline]
    pub fn jjt(&self) -> [[f64; 3]; 3] {
        self.jjt
    }
}

impl AsRef<SpacePose> for SpacePose {
    fn as_ref(&self) -> &SpacePose {
        self
    }
}

/// The vector `v` of a frame whose axes are `axes` (columns), in the
/// world: `x v_0 + y v_1 + z v_2`.
#[inline]
fn in_frame(axes: &[Vec3; 3], v: Vec3) -> Vec3 {
    add(
        add(scale(axes[0], v[0]), scale(axes[1], v[1])),
        scale(axes[2], v[2]),
    )
}

#[inline]
pub(crate) fn add(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline]
pub(crate) fn sub(a: Vec3, b: Vec3) -> Vec3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline]
pub(crate) fn scale(a: Vec3, s: f64) -> Vec3 {
    [a[0] * s, a[1] * s, a[2] * s]
}

#[inline]
pub(crate) fn dot(a: Vec3, b: Vec3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
pub(crate) fn cross(a: Vec3, b: Vec3) -> Vec3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline]
pub(crate) fn norm(a: Vec3) -> f64 {
    dot(a, a).sqrt()
}
