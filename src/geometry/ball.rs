//! An obstacle of any dimension: a ball, its centre the paper's obstacle
//! point `O` of eq. (16) and its radius what decides a collision. In the
//! plane a disc ([`crate::Obstacle`], `M = 2`), in space a sphere
//! ([`crate::space::Sphere`], `M = 3`); each kind of arm checks its own
//! (clear of the fixed base) where it lives.

use serde::{Deserialize, Serialize};

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
