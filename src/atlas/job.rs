//! An atlas being computed a chunk of cells at a time, for every arm
//! ([`Chunked`]): the one [`Sweep`] and what the finished atlas records
//! beside its cells ([`Head`]). The planar atlas's [`super::Job`] and the
//! slice atlas's [`super::space::SliceJob`] name it; a caller advances it
//! in chunks to report progress and to cancel between them (the
//! command-line tool across its cores, a Web Worker a row at a time).

use super::{Cell, Grid, Mapped, Sweep};
use crate::error::Result;

/// What an atlas records beside its cells, and how it is made from them.
pub trait Head<const D: usize>: Sized + Send {
    /// The finished atlas.
    type Atlas;
    /// The cells' name in the refusal of an atlas finished too early.
    const CELLS: &'static str;
    /// The atlas of `cells`, every cell of `grid` computed.
    fn finish(self, grid: Grid, cells: Vec<Cell<D>>) -> Result<Self::Atlas>;
}

/// An atlas being computed, a chunk of cells at a time: the runs
/// ([`Sweep`]) and the head `H` of its file.
#[derive(Debug, Clone)]
pub struct Chunked<A: Mapped<M, D>, const M: usize, const D: usize, H> {
    sweep: Sweep<A, M, D>,
    head: H,
}

impl<A: Mapped<M, D>, const M: usize, const D: usize, H: Head<D>> Chunked<A, M, D, H> {
    /// The job of `sweep`, to be finished with `head`.
    pub(super) fn of_sweep(sweep: Sweep<A, M, D>, head: H) -> Self {
        Self { sweep, head }
    }

    /// Cells in the grid.
    pub fn total(&self) -> usize {
        self.sweep.total()
    }

    /// Cells computed so far.
    pub fn done(&self) -> usize {
        self.sweep.done()
    }

    /// Whether every cell is computed.
    pub fn is_done(&self) -> bool {
        self.sweep.is_done()
    }

    /// Points per side: a row is a sensible chunk.
    pub fn row(&self) -> usize {
        self.sweep.row()
    }

    /// Computes up to `cells` more cells on this thread, in order; returns
    /// how many are done in all.
    pub fn advance(&mut self, cells: usize) -> usize {
        self.sweep.advance(cells)
    }

    /// [`Self::advance`] across the machine's cores (rayon); the cells
    /// equal those of the one-thread path.
    #[cfg(all(feature = "parallel", not(target_family = "wasm")))]
    pub fn advance_parallel(&mut self, cells: usize) -> usize {
        self.sweep.advance_parallel(cells)
    }

    /// The atlas; refused while cells are missing.
    pub fn finish(self) -> Result<H::Atlas> {
        let grid = *self.sweep.grid();
        let cells = self.sweep.cells(H::CELLS)?;
        self.head.finish(grid, cells)
    }

    /// Computes every cell left (across the machine's cores with the
    /// feature `parallel`) and finishes.
    pub fn to_end(mut self) -> Result<H::Atlas> {
        #[cfg(all(feature = "parallel", not(target_family = "wasm")))]
        self.advance_parallel(usize::MAX);
        #[cfg(not(all(feature = "parallel", not(target_family = "wasm"))))]
        self.advance(usize::MAX);
        self.finish()
    }
}
