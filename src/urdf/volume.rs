//! The volumes of a chain's links, made from their collision geometry: a
//! sphere is the sphere; a cylinder the capsule on its axis with its
//! radius, which contains it; a box the capsule on its longest side whose
//! radius is half the diagonal of the other two, which contains it; a mesh
//! the capsule fitted around its vertices when the file can be read
//! (STL), its axis the vertices' principal one and its radius the largest
//! distance from that axis, the segment as short as that radius allows
//! (every vertex inside); and a link without collision geometry, or whose
//! mesh cannot be read, the segment from its frame's origin to the next
//! moving joint's with a default radius, with a warning naming it. Every
//! volume says how it was made.

use serde::Serialize;

use super::chain::UrdfChain;
use super::{stl, Geometry, Urdf, Vec3};

/// A volume in the frame of the moving joint that moves it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Volume {
    /// The link it belongs to.
    pub link: String,
    /// The moving joint that moves it, from 1 (0: the base).
    pub moved_by: usize,
    /// One end of its segment (a sphere's centre: both ends).
    pub a: Vec3,
    /// The other end.
    pub b: Vec3,
    /// Its radius (m).
    pub radius: f64,
    /// How it was made.
    pub source: Source,
}

/// How a volume was made.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// A `<sphere>`.
    Sphere,
    /// The capsule that contains a `<cylinder>`.
    Cylinder,
    /// The capsule that contains a `<box>`.
    Box,
    /// The capsule fitted around a mesh's vertices.
    Mesh(String),
    /// The segment to the next joint, for a link without geometry or with
    /// a mesh that could not be read.
    Segment,
}

/// The volumes of `chain`'s links, with the warnings of the links that
/// got a segment; `mesh` gives a mesh file's bytes for its URDF filename
/// (`None`: not at hand), and `radius` is a segment's radius.
pub fn volumes(
    urdf: &Urdf,
    chain: &UrdfChain,
    mesh: &dyn Fn(&str) -> Option<Vec<u8>>,
    radius: f64,
) -> (Vec<Volume>, Vec<String>) {
    let mut out = Vec::new();
    let mut warnings = Vec::new();
    for l in &chain.links {
        let Some(link) = urdf.link(&l.name) else {
            continue;
        };
        let mut made = 0;
        for c in &link.collisions {
            let frame = l.frame.then(&c.origin);
            let at = |p: Vec3| frame.apply(p);
            let (a, b, r, source) = match &c.geometry {
                Geometry::Sphere { radius } => {
                    let p = at([0.0; 3]);
                    (p, p, *radius, Source::Sphere)
                }
                Geometry::Cylinder { radius, length } => (
                    at([0.0, 0.0, -0.5 * length]),
                    at([0.0, 0.0, 0.5 * length]),
                    *radius,
                    Source::Cylinder,
                ),
                Geometry::Box { size } => {
                    let k = (0..3)
                        .max_by(|&i, &j| size[i].total_cmp(&size[j]))
                        .unwrap_or(0);
                    let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                    let mut e = [0.0; 3];
                    e[k] = 0.5 * size[k];
                    let r = 0.5 * size[i].hypot(size[j]);
                    (at(e.map(|x| -x)), at(e), r, Source::Box)
                }
                Geometry::Mesh { filename, scale } => {
                    match mesh(filename).map(|bytes| stl::vertices(&bytes)) {
                        Some(Ok(v)) if !v.is_empty() => {
                            let scaled: Vec<Vec3> = v
                                .iter()
                                .map(|p| std::array::from_fn(|k| p[k] * scale[k]))
                                .collect();
                            let (a, b, r) = capsule_around(&scaled);
                            (at(a), at(b), r, Source::Mesh(filename.clone()))
                        }
                        other => {
                            let why = match other {
                                None => "not at hand".to_string(),
                                Some(Err(e)) => e.to_string(),
                                Some(Ok(_)) => "no vertex".to_string(),
                            };
                            warnings.push(format!(
                                "link '{}': its mesh '{}' cannot be read ({why}): the segment to the next joint stands in",
                                crate::error::clip(&l.name),
                                crate::error::clip(filename)
                            ));
                            continue;
                        }
                    }
                }
            };
            made += 1;
            out.push(Volume {
                link: l.name.clone(),
                moved_by: l.moved_by,
                a,
                b,
                radius: r,
                source,
            });
        }
        if made == 0 {
            // The segment from the link's origin to the next moving
            // joint's (or the tip's), both in the frame that moves it.
            let end = match chain.joints.get(l.moved_by) {
                Some(j) => j.origin.translation,
                None => chain.tip_frame.translation,
            };
            let start = l.frame.translation;
            if start != end {
                if link.collisions.is_empty() {
                    warnings.push(format!(
                        "link '{}' has no collision geometry: the segment to the next joint stands in, radius {radius} m",
                        crate::error::clip(&l.name)
                    ));
                }
                out.push(Volume {
                    link: l.name.clone(),
                    moved_by: l.moved_by,
                    a: start,
                    b: end,
                    radius,
                    source: Source::Segment,
                });
            }
        }
    }
    (out, warnings)
}

/// The capsule `(a, b, r)` around `points` (at least one): its axis the
/// distinct points' principal direction through their mean, its radius the largest
/// distance from that axis, its segment the shortest on the axis that
/// keeps every point within `r` of it.
pub fn capsule_around(points: &[Vec3]) -> (Vec3, Vec3, f64) {
    // Each point once (a mesh repeats a vertex in every triangle that has
    // it, which would weigh the axis towards the busy corners).
    let mut unique = points.to_vec();
    unique.sort_by(|a, b| {
        a[0].total_cmp(&b[0])
            .then(a[1].total_cmp(&b[1]))
            .then(a[2].total_cmp(&b[2]))
    });
    unique.dedup();
    let points = &unique[..];
    let n = points.len() as f64;
    let mean: Vec3 = std::array::from_fn(|k| points.iter().map(|p| p[k]).sum::<f64>() / n);
    let mut cov = [[0.0; 3]; 3];
    for p in points {
        let d: Vec3 = std::array::from_fn(|k| p[k] - mean[k]);
        for r in 0..3 {
            for c in 0..3 {
                cov[r][c] += d[r] * d[c];
            }
        }
    }
    let axis = principal(cov);
    let along = |p: &Vec3| (0..3).map(|k| (p[k] - mean[k]) * axis[k]).sum::<f64>();
    let off = |p: &Vec3| {
        let t = along(p);
        (0..3)
            .map(|k| (p[k] - mean[k] - t * axis[k]).powi(2))
            .sum::<f64>()
            .sqrt()
    };
    let r = points.iter().map(off).fold(0.0, f64::max);
    // Each point is inside while its axial place is within the segment
    // widened by sqrt(r^2 - d^2) at each end.
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in points {
        let (t, d) = (along(p), off(p));
        let slack = (r * r - d * d).max(0.0).sqrt();
        lo = lo.min(t + slack);
        hi = hi.max(t - slack);
    }
    if lo > hi {
        let mid = 0.5 * (lo + hi);
        (lo, hi) = (mid, mid);
    }
    let at = |t: f64| std::array::from_fn(|k| mean[k] + t * axis[k]);
    (at(lo), at(hi), r)
}

/// The unit eigenvector of the largest eigenvalue of the symmetric `a`
/// (by power iteration from the column of largest norm; `x` for a zero
/// matrix).
fn principal(a: [[f64; 3]; 3]) -> Vec3 {
    let norm = |v: Vec3| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let cols: [Vec3; 3] = std::array::from_fn(|c| [a[0][c], a[1][c], a[2][c]]);
    let mut v = cols
        .into_iter()
        .max_by(|x, y| norm(*x).total_cmp(&norm(*y)))
        .unwrap_or([1.0, 0.0, 0.0]);
    if norm(v).is_nan() || norm(v) <= 0.0 {
        return [1.0, 0.0, 0.0];
    }
    for _ in 0..100 {
        let w: Vec3 = std::array::from_fn(|r| (0..3).map(|c| a[r][c] * v[c]).sum());
        let nw = norm(w);
        if nw.is_nan() || nw <= 0.0 {
            break;
        }
        v = w.map(|x| x / nw);
    }
    let nv = norm(v);
    v.map(|x| x / nv)
}
