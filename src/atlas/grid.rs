//! The grid of obstacle centres.

use serde::{Deserialize, Serialize};

use crate::arm::Arm;
use crate::error::{coordinate, Error, Result};

/// Points per side of the default grid.
pub const DEFAULT_GRID: usize = 41;

/// Most points per side (201 x 201 is 40,401 cells, a few seconds per method).
pub const MAX_GRID: usize = 201;

/// `n x n` obstacle centres over the region `x0..x1 x y0..y1`, both ends
/// included: point `i` of a row is `x0 + i (x1 - x0) / (n - 1)`, likewise
/// for the rows in y.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Grid {
    /// `[x0, x1, y0, y1]` in metres.
    pub region: [f64; 4],
    /// Points per side.
    pub n: usize,
}

impl Grid {
    /// A checked grid: a finite region with `x0 < x1` and `y0 < y1`, and 2
    /// to [`MAX_GRID`] points per side.
    pub fn new(region: [f64; 4], n: usize) -> Result<Self> {
        let g = Self { region, n };
        g.validate()?;
        Ok(g)
    }

    /// Points per side as a script passes them (a number): a whole number
    /// from 2 to [`MAX_GRID`].
    pub fn points_per_side(n: f64) -> Result<usize> {
        const WHAT: &str = "grid points per side";
        crate::error::within(WHAT, n, 2.0, MAX_GRID as f64)?;
        if n.fract() != 0.0 {
            return Err(Error::OutOfRange {
                what: format!("{WHAT} (a whole number)"),
                value: n,
                min: 2.0,
                max: MAX_GRID as f64,
            });
        }
        Ok(n as usize)
    }

    /// The default region for an arm: the box around its reach, the disc of
    /// radius `L1 + ... + Ln` about the top of the post, cut at the floor
    /// the post stands on (`y >= 0`). Wherever else an obstacle sits, no
    /// link can touch it.
    pub fn around_reach(arm: &Arm, n: usize) -> Self {
        let r = arm.max_reach();
        let post = arm.post();
        Self {
            region: [-r, r, (post - r).max(0.0), post + r],
            n,
        }
    }

    /// Checks the region and the size.
    pub fn validate(&self) -> Result<()> {
        let [x0, x1, y0, y1] = self.region;
        for (what, v) in [
            ("region x0", x0),
            ("region x1", x1),
            ("region y0", y0),
            ("region y1", y1),
        ] {
            coordinate(what, v)?;
        }
        if !(x0 < x1 && y0 < y1) {
            return Err(Error::EmptyRegion {
                region: self.region,
            });
        }
        if !(2..=MAX_GRID).contains(&self.n) {
            return Err(Error::OutOfRange {
                what: "grid points per side".into(),
                value: self.n as f64,
                min: 2.0,
                max: MAX_GRID as f64,
            });
        }
        Ok(())
    }

    /// Number of cells, `n^2`.
    pub fn cells(&self) -> usize {
        self.n * self.n
    }

    /// Point `i` along x.
    pub fn x(&self, i: usize) -> f64 {
        let [x0, x1, ..] = self.region;
        x0 + i as f64 * (x1 - x0) / (self.n - 1) as f64
    }

    /// Point `j` along y.
    pub fn y(&self, j: usize) -> f64 {
        let [.., y0, y1] = self.region;
        y0 + j as f64 * (y1 - y0) / (self.n - 1) as f64
    }

    /// The centre of cell `index = j n + i` (rows from `y0`, each from `x0`).
    pub fn point(&self, index: usize) -> [f64; 2] {
        [self.x(index % self.n), self.y(index / self.n)]
    }

    /// The cell whose centre is nearest to `p`, if `p` lies within half a
    /// cell of the grid.
    pub fn nearest(&self, p: [f64; 2]) -> Option<usize> {
        let [x0, x1, y0, y1] = self.region;
        let steps = (self.n - 1) as f64;
        let fi = ((p[0] - x0) / (x1 - x0) * steps).round();
        let fj = ((p[1] - y0) / (y1 - y0) * steps).round();
        if !(fi >= 0.0 && fi <= steps && fj >= 0.0 && fj <= steps) {
            return None;
        }
        Some(fj as usize * self.n + fi as usize)
    }
}
