//! An obstacle of any dimension: a ball, its centre the paper's obstacle
//! point `O` of eq. (16) and its radius what decides a collision. In the
//! plane a disc ([`crate::Obstacle`], `M = 2`), in space a sphere
//! ([`crate::space::Sphere`], `M = 3`); each kind of arm checks its own
//! (clear of the fixed base) where it lives.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// Most balls a scene holds: the planar arm's discs, the spheres in space.
pub const MAX_BALLS: usize = 8;

/// A ball of dimension `M`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(bound(
    serialize = "[f64; M]: Serialize",
    deserialize = "[f64; M]: Deserialize<'de>"
))]
pub struct Ball<const M: usize> {
    /// The centre (m).
    pub centre: [f64; M],
    /// The radius (m).
    pub radius: f64,
}

impl<const M: usize> Ball<M> {
    /// The balls of a flat list, `M + 1` numbers each (the centre, then
    /// the radius, in m), as scripts and Python pass them: refused with a
    /// reason when the count is not a whole number of balls or there are
    /// more than [`MAX_BALLS`]. Each ball's own checks are its scene's.
    pub fn from_flat(flat: &[f64]) -> Result<Vec<Self>> {
        let (what, each) = match M {
            2 => ("obstacles", "three numbers per obstacle: x, y, r"),
            _ => ("spheres", "four numbers per sphere: x, y, z, r"),
        };
        if !flat.len().is_multiple_of(M + 1) {
            return Err(Error::Syntax {
                what,
                text: format!("{} numbers", flat.len()),
                expected: each.into(),
            });
        }
        let count = flat.len() / (M + 1);
        if count > MAX_BALLS {
            return Err(Error::OutOfRange {
                what: format!("number of {what}"),
                value: count as f64,
                min: 0.0,
                max: MAX_BALLS as f64,
            });
        }
        Ok(flat
            .chunks_exact(M + 1)
            .map(|c| Ball {
                centre: std::array::from_fn(|k| c[k]),
                radius: c[M],
            })
            .collect())
    }
}

/// A ball as people write it, on the command line and in the page's
/// address: its centre's coordinates and, if written, its radius (whoever
/// places it gives the default).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement<const M: usize> {
    /// The centre (m).
    pub centre: [f64; M],
    /// The radius, if written (m).
    pub radius: Option<f64>,
}

impl<const M: usize> Placement<M> {
    /// The ball, with `default_radius` where none was written.
    pub fn ball(self, default_radius: f64) -> Ball<M> {
        Ball {
            centre: self.centre,
            radius: self.radius.unwrap_or(default_radius),
        }
    }
}
