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
//!
//! The ground, where a scene asks for it (`--floor`), gives pairs of the
//! same form: the floor `y = 0` is a half-plane (for every link, `p` its
//! lower end, `O = (p_x, 0)`, `c = p_y`, `n = (0, 1)`), the post a segment
//! `(0, 0)-(0, L0)` (for every link but the first, which stands on it, `p`
//! and `O` the closest points of link and post, `c = |p - O|`,
//! `n = (p - O) / c`; a link that crosses the post has `c` minus the
//! shorter way back across it).

use crate::geometry::{closest_parameter, closest_point};
use crate::kinematics::Pose;
use crate::obstacle::Obstacle;

/// What a link keeps clear of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Against {
    /// The scene's obstacle disc of this index.
    Disc(usize),
    /// The floor, `y = 0`.
    Floor,
    /// The post, `(0, 0)-(0, L0)`.
    Post,
}

/// One link and one obstacle, at one pose.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Pair {
    /// The link, from 0 (`P(0) P(1)`, the first moving link).
    pub link: usize,
    /// What it keeps clear of.
    pub against: Against,
    /// The point `p` of the link closest to the obstacle's centre.
    pub point: [f64; 2],
    /// The obstacle's centre `O` (for the ground, its point closest to
    /// the link).
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
            against: Against::Disc(index),
            point: p,
            centre: o,
            clearance: d - ob.radius,
            normal,
        }
    }

    /// The pair of `link` and the floor `y = 0`: its lower end.
    pub fn floor(pose: &Pose, link: usize) -> Self {
        let joints = pose.joints();
        let (a, b) = (joints[link], joints[link + 1]);
        let p = if b[1] < a[1] { b } else { a };
        Self {
            link,
            against: Against::Floor,
            point: p,
            centre: [p[0], 0.0],
            clearance: p[1],
            normal: [0.0, 1.0],
        }
    }

    /// The pair of `link` (not the first, which stands on the post) and the
    /// post `(0, 0)-(0, post)`. Two segments that do not cross are closest
    /// at an end of one of them; one that crosses the post has the
    /// clearance minus the shorter way back, its end nearer the post.
    pub fn post(pose: &Pose, link: usize, post: f64) -> Self {
        let joints = pose.joints();
        let (a, b) = (joints[link], joints[link + 1]);
        let (bottom, top) = ([0.0, 0.0], [0.0, post]);
        // Candidates (point on the link, point on the post).
        let candidates = [
            (a, closest_point(a, bottom, top)),
            (b, closest_point(b, bottom, top)),
            (closest_point(bottom, a, b), bottom),
            (closest_point(top, a, b), top),
        ];
        let dist = |(p, o): &([f64; 2], [f64; 2])| (p[0] - o[0]).hypot(p[1] - o[1]);
        let (mut p, mut o) = candidates[0];
        for c in &candidates[1..] {
            if dist(c) < dist(&(p, o)) {
                (p, o) = *c;
            }
        }
        let d = dist(&(p, o));
        // The link crosses the post where its ends lie on both sides of
        // x = 0 at a height within the post.
        let crosses = a[0] * b[0] < 0.0 && {
            let s = a[0] / (a[0] - b[0]);
            let y = a[1] + s * (b[1] - a[1]);
            (0.0..=post).contains(&y)
        };
        let (clearance, normal) = if crosses {
            // Back across: the end nearer x = 0, pushed to its side.
            let end = if a[0].abs() < b[0].abs() { a } else { b };
            p = end;
            o = [0.0, end[1].clamp(0.0, post)];
            (-end[0].abs(), [-end[0].signum(), 0.0])
        } else if d > 0.0 {
            (d, [(p[0] - o[0]) / d, (p[1] - o[1]) / d])
        } else {
            (0.0, [if p[0] < 0.0 { -1.0 } else { 1.0 }, 0.0])
        };
        Self {
            link,
            against: Against::Post,
            point: p,
            centre: o,
            clearance,
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

    /// Appends the pairs of the ground with clearance below `within`: the
    /// floor for every link, the post `(0, 0)-(0, post)` for every link but
    /// the first.
    pub fn add_ground(&mut self, pose: &Pose, post: f64, within: f64) {
        for k in 0..pose.dof() {
            let pair = Pair::floor(pose, k);
            if pair.clearance < within {
                self.pairs.push(pair);
            }
        }
        for k in 1..pose.dof() {
            let pair = Pair::post(pose, k, post);
            if pair.clearance < within {
                self.pairs.push(pair);
            }
        }
    }

    /// The pairs, obstacle by obstacle, each from the first link, then the
    /// ground's (floor, then post).
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
