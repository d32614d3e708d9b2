//! An atlas drawn as a translucent layer under the arm: one class per cell,
//! in the colours of [`Class::colour`] (the command-line tool's SVG uses the
//! same), and the cell under the pointer outlined.

use web_sys::CanvasRenderingContext2d;

use super::style::{INK, LAYER_ALPHA};
use super::surface::View;
use crate::atlas::{Class, Grid};
use crate::error::Result;

/// The classes of one method's atlas, cell by cell.
pub struct Layer {
    grid: Grid,
    /// Index into [`Class::ALL`] per cell, rows from `y0`.
    classes: Vec<u8>,
    /// The cell to outline.
    pub hover: Option<usize>,
}

impl Layer {
    /// A layer over `grid`; `classes` holds one index into [`Class::ALL`]
    /// per cell.
    pub fn new(grid: Grid, classes: Vec<u8>) -> Result<Self> {
        Class::check_map(&grid, &classes, "atlas layer classes")?;
        Ok(Self {
            grid,
            classes,
            hover: None,
        })
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Draws the cells, each row as runs of one class.
    pub fn draw(&self, ctx: &CanvasRenderingContext2d, view: View) {
        let g = &self.grid;
        let n = g.n;
        let (dx, dy) = self.cell_size();
        ctx.set_global_alpha(LAYER_ALPHA);
        // Cell edges in whole pixels, each shared edge rounded once, so
        // neighbouring cells neither overlap (a darker seam at this alpha)
        // nor leave a gap.
        let edge_x = |i: usize| view.to_px([g.x(i) - dx / 2.0, 0.0]).0.round();
        let edge_y = |j: usize| view.to_px([0.0, g.y(j) - dy / 2.0]).1.round();
        for j in 0..n {
            let row = &self.classes[j * n..(j + 1) * n];
            let (bottom, top) = (edge_y(j), edge_y(j + 1));
            let mut i = 0;
            while i < n {
                let class = row[i];
                let end = i + row[i..].iter().take_while(|&&c| c == class).count();
                let (left, right) = (edge_x(i), edge_x(end));
                ctx.set_fill_style_str(Class::ALL[usize::from(class)].colour());
                ctx.fill_rect(left, top, right - left, bottom - top);
                i = end;
            }
        }
        ctx.set_global_alpha(1.0);
        if let Some(k) = self.hover.filter(|&k| k < g.cells()) {
            let p = g.point(k);
            let (x0, y1) = view.to_px([p[0] - dx / 2.0, p[1] + dy / 2.0]);
            let (x1, y0) = view.to_px([p[0] + dx / 2.0, p[1] - dy / 2.0]);
            ctx.set_stroke_style_str(INK);
            ctx.set_line_width(1.5);
            ctx.stroke_rect(x0, y1, x1 - x0, y0 - y1);
        }
    }

    fn cell_size(&self) -> (f64, f64) {
        let [x0, x1, y0, y1] = self.grid.region;
        let steps = (self.grid.n - 1) as f64;
        ((x1 - x0) / steps, (y1 - y0) / steps)
    }
}
