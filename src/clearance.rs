//! Link-obstacle pairs: the geometry that the methods beyond the paper read
//! (`docs/methods.md`), computed once per pose.
//!
//! Link `k` is the segment `P(k-1) P(k)` (`k = 1..n`; the post does not
//! move and is not a link). For an obstacle disc `(O_j, r_j)`, `p` is the
//! point of link `k` closest to `O_j`, `d = |p - O_j|`, the clearance
//! `c = d - r_j`, the unit normal `n = (p - O_j) / d`, and `J_p` the `2 x n`
//! Jacobian of `p` held fixed on the link: column `i <= k` is
//! `(p_y - P(i-1)_y, -(p_x - P(i-1)_x))` in this crate's angle convention
//! (angles grow clockwise, from the vertical towards +X1), zero for `i > k`.
//! Then the clearance changes at `dc/dt = n^T J_p theta_dot` (the closest
//! point may slide along the link, but to first order that does not change
//! the distance).

use crate::geometry::closest_parameter;
use crate::kinematics::Pose;
use crate::obstacle::Obstacle;

/// One link and one obstacle, at one pose.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Pair {
    /// The link, from 0 (`P(0) P(1)`, the first moving link).
    pub link: usize,
    /// The obstacle's index in the scene.
    pub obstacle: usize,
    /// The point `p` of the link closest to the obstacle's centre.
    pub point: [f64; 2],
    /// The obstacle's centre `O`.
    pub centre: [f64; 2],
    /// `c = |p - O| - r`: negative when the link is inside the disc.
    pub clearance: f64,
    /// `n = (p - O) / |p - O|`, pointing from the centre to the link; where
    /// the centre lies on the link itself, the link's left normal.
    pub normal: [f64; 2],
}

impl Pair {
    /// The pair of `link` and obstacle `index` at `pose`.
    pub fn at(pose: &Pose, link: usize, index: usize, ob: &Obstacle) -> Self {
        let joints = pose.joints();
        let (a, b) = (joints[link], joints[link + 1]);
        let o = ob.centre;
        let s = closest_parameter(o, a, b);
        let p = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
        let (dx, dy) = (p[0] - o[0], p[1] - o[1]);
        let d = dx.hypot(dy);
        let normal = if d > 0.0 {
            [dx / d, dy / d]
        } else {
            // The centre on the link: any unit vector will do; the link's
            // left normal keeps the rates finite and points off the link.
            let (lx, ly) = (b[0] - a[0], b[1] - a[1]);
            let len = lx.hypot(ly).max(f64::MIN_POSITIVE);
            [-ly / len, lx / len]
        };
        Self {
            link,
            obstacle: index,
            point: p,
            centre: o,
            clearance: d - ob.radius,
            normal,
        }
    }

    /// `n^T J_p` into `row` (`n` entries): how fast the clearance changes
    /// per unit rate of each joint, `dc/dt = row . theta_dot`.
    #[inline]
    pub fn rate_row(&self, pose: &Pose, row: &mut [f64]) {
        let joints = pose.joints();
        let (p, nv) = (self.point, self.normal);
        for (i, r) in row.iter_mut().enumerate() {
            *r = if i <= self.link {
                let q = joints[i];
                nv[0] * (p[1] - q[1]) - nv[1] * (p[0] - q[0])
            } else {
                0.0
            };
        }
    }

    /// `J_p`, column-major `2 x n` (as [`Pose::jacobian`]), into `out`
    /// (`2n` entries).
    pub fn point_jacobian(&self, pose: &Pose, out: &mut [f64]) {
        let joints = pose.joints();
        let p = self.point;
        for (i, col) in out.chunks_exact_mut(2).enumerate() {
            if i <= self.link {
                let q = joints[i];
                col[0] = p[1] - q[1];
                col[1] = -(p[0] - q[0]);
            } else {
                col[0] = 0.0;
                col[1] = 0.0;
            }
        }
    }
}

/// The link-obstacle pairs of a pose whose clearance is below a distance,
/// kept in a buffer that is reused: refreshing them allocates only when
/// there are more pairs than ever before.
#[derive(Debug, Clone, Default)]
pub struct Pairs {
    pairs: Vec<Pair>,
}

impl Pairs {
    /// Room for `capacity` pairs.
    pub fn with_capacity(capacity: usize) -> Self {
        Self {
            pairs: Vec::with_capacity(capacity),
        }
    }

    /// Every pair of `pose` and `obstacles` with clearance below `within`
    /// (every pair when `within` is infinite).
    pub fn update(&mut self, pose: &Pose, obstacles: &[Obstacle], within: f64) {
        self.pairs.clear();
        for (j, ob) in obstacles.iter().enumerate() {
            for k in 0..pose.dof() {
                let pair = Pair::at(pose, k, j, ob);
                if pair.clearance < within {
                    self.pairs.push(pair);
                }
            }
        }
    }

    /// The pairs, obstacle by obstacle, each from the first link.
    pub fn as_slice(&self) -> &[Pair] {
        &self.pairs
    }

    /// The pair with the smallest clearance, if any.
    pub fn closest(&self) -> Option<&Pair> {
        self.pairs
            .iter()
            .min_by(|a, b| a.clearance.total_cmp(&b.clearance))
    }

    /// Whether there is no pair.
    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// How many pairs.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }
}
