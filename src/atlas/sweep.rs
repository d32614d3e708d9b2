//! The atlas's runs a cell at a time, for every arm ([`Sweep`]): one
//! planner per method, built once, whose first obstacle is moved to each
//! cell's centre and which is reset to `t = 0` for each run, keeping only
//! the run's summary (nothing is allocated per run but the cell's record).
//! A caller advances it in chunks to report progress and to cancel between
//! them: the command-line tool all at once (across its cores), a Web
//! Worker a row at a time. What differs by arm is [`Mapped`]: where the
//! grid lies (the plane of a planar arm; an axis-aligned plane in space),
//! what decides `start_overlap` and `path_blocked` before any run, and how
//! the obstacle is moved. One job advances it ([`super::Chunked`]), which
//! the planar atlas ([`super::Job`]) and the slice atlas in space
//! ([`super::space::SliceJob`]) name.

use super::{Cell, Class, Grid, Outcome};
use crate::error::{Error, Result};
use crate::planner::{Method, Networks, Planned, Planner, SceneOf};

/// What the atlas needs of an arm beyond the planner's.
pub trait Mapped<const M: usize, const D: usize = M>: Planned<M> {
    /// Where the grid's cells lie.
    type Surface: Copy + Send + Sync + std::fmt::Debug;
    /// What decides, before any run, whether an obstacle touches the arm
    /// at the start or the hand's path.
    type Geometry: Clone + Send + Sync + std::fmt::Debug;
    /// The point of `surface` at grid coordinates `(u, v)`.
    fn point(surface: Self::Surface, u: f64, v: f64) -> [f64; D];
    /// The geometry of `scene` for an obstacle of `radius`.
    fn geometry(scene: &Self::Scene, radius: f64) -> Result<Self::Geometry>;
    /// [`Class::StartOverlap`], [`Class::PathBlocked`] or neither (`None`)
    /// for the obstacle centred on `centre`.
    fn classify(geometry: &Self::Geometry, centre: [f64; D]) -> Option<Class>;
    /// Moves the first obstacle of `p`'s scene to `centre` (its radius
    /// kept).
    fn place(p: &mut Planner<Self, M>, centre: [f64; D]) -> Result<()>;
}

/// The runs of an atlas, a chunk of cells at a time.
#[derive(Clone)]
pub struct Sweep<A: Mapped<M, D>, const M: usize, const D: usize = M> {
    surface: A::Surface,
    grid: Grid,
    geometry: A::Geometry,
    /// How many of the planners are the atlas's methods (a further one,
    /// without avoidance, says where avoidance matters).
    methods: usize,
    planners: Vec<Planner<A, M>>,
    cells: Vec<Cell<D>>,
}

impl<A: Mapped<M, D>, const M: usize, const D: usize> std::fmt::Debug for Sweep<A, M, D> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Sweep")
            .field("surface", &self.surface)
            .field("grid", &self.grid)
            .field("methods", &self.methods)
            .field("done", &self.cells.len())
            .finish_non_exhaustive()
    }
}

impl<A: Mapped<M, D>, const M: usize, const D: usize> Sweep<A, M, D> {
    /// One planner per method on `scene` (the learned ones with
    /// `networks`), and one without avoidance where `none` is not among
    /// them; refused for an empty or repeated list of methods, a learned
    /// method without networks, or a scene a planner refuses.
    pub(super) fn new(
        scene: &A::Scene,
        surface: A::Surface,
        grid: Grid,
        methods: &[Method],
        networks: Option<Networks<A, M>>,
        radius: f64,
    ) -> Result<Self>
    where
        A::Scene: SceneOf<A, M>,
    {
        grid.validate()?;
        if methods.is_empty() {
            return Err(Error::OutOfRange {
                what: "number of methods".into(),
                value: 0.0,
                min: 1.0,
                max: crate::planner::methods::ALL.len() as f64,
            });
        }
        let geometry = A::geometry(scene, radius)?;
        let mut planners = methods
            .iter()
            .map(|&m| {
                let nets = networks.clone().filter(|_| m.uses_networks());
                Planner::new(scene.clone(), m, nets)
            })
            .collect::<Result<Vec<_>>>()?;
        if !methods.contains(&Method::NO_AVOIDANCE) {
            planners.push(Planner::new(scene.clone(), Method::NO_AVOIDANCE, None)?);
        }
        Ok(Self {
            surface,
            grid,
            geometry,
            methods: methods.len(),
            planners,
            cells: Vec::with_capacity(grid.cells()),
        })
    }

    /// Cells in the grid.
    pub fn total(&self) -> usize {
        self.grid.cells()
    }

    /// Cells computed so far.
    pub fn done(&self) -> usize {
        self.cells.len()
    }

    /// Whether every cell is computed.
    pub fn is_done(&self) -> bool {
        self.done() == self.total()
    }

    /// Points per side: a row is a sensible chunk.
    pub fn row(&self) -> usize {
        self.grid.n
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// The centre of cell `index` (rows in `v`, each from `u0`).
    pub fn centre(&self, index: usize) -> [f64; D] {
        let [u, v] = self.grid.point(index);
        A::point(self.surface, u, v)
    }

    /// Computes up to `cells` more cells on this thread, in order; returns
    /// how many are done in all.
    pub fn advance(&mut self, cells: usize) -> usize {
        let end = self.done().saturating_add(cells).min(self.total());
        for index in self.done()..end {
            let centre = self.centre(index);
            let cell = run_cell(&mut self.planners, self.methods, &self.geometry, centre);
            self.cells.push(cell);
        }
        self.done()
    }

    /// [`Self::advance`] across the machine's cores (rayon): each thread
    /// runs its cells with its own copy of the planners; the cells equal
    /// those of the one-thread path (each run is deterministic).
    #[cfg(all(feature = "parallel", not(target_family = "wasm")))]
    pub fn advance_parallel(&mut self, cells: usize) -> usize
    where
        A::Pose: Send,
    {
        use rayon::prelude::*;
        let end = self.done().saturating_add(cells).min(self.total());
        let (planners, geometry, methods) = (&self.planners, &self.geometry, self.methods);
        let this = &*self;
        let new: Vec<Cell<D>> = (self.done()..end)
            .into_par_iter()
            .map_init(
                || planners.clone(),
                |p, index| run_cell(p, methods, geometry, this.centre(index)),
            )
            .collect();
        self.cells.extend(new);
        self.done()
    }

    /// The cells; refused while some are missing (`what` names them).
    pub(super) fn cells(self, what: &str) -> Result<Vec<Cell<D>>> {
        if !self.is_done() {
            return Err(Error::OutOfRange {
                what: what.into(),
                value: self.done() as f64,
                min: self.total() as f64,
                max: self.total() as f64,
            });
        }
        Ok(self.cells)
    }
}

/// Runs every planner with the obstacle centred on `centre`: the first
/// `methods` are the atlas's methods, a further one the arm without
/// avoidance.
fn run_cell<A: Mapped<M, D>, const M: usize, const D: usize>(
    planners: &mut [Planner<A, M>],
    methods: usize,
    geometry: &A::Geometry,
    centre: [f64; D],
) -> Cell<D> {
    let class = A::classify(geometry, centre);
    let mut outcomes: Vec<Outcome> = match class {
        Some(Class::StartOverlap) => planners.iter().map(|_| Outcome::not_run()).collect(),
        blocked => planners
            .iter_mut()
            .map(|p| run_one(p, centre, blocked.is_some()))
            .collect(),
    };
    let bare = planners
        .iter()
        .position(|p| p.method() == Method::NO_AVOIDANCE);
    let avoidance_needed = match (class, bare) {
        (None, Some(k)) => Some(outcomes[k].class == Class::Collision),
        _ => None,
    };
    outcomes.truncate(methods);
    Cell {
        centre,
        outcomes,
        avoidance_needed,
    }
}

/// One run from `t = 0` with the obstacle at `centre`, to the end or to
/// the first error; the planner is left at the end of the run.
fn run_one<A: Mapped<M, D>, const M: usize, const D: usize>(
    p: &mut Planner<A, M>,
    centre: [f64; D],
    path_blocked: bool,
) -> Outcome {
    if A::place(p, centre).is_err() {
        // Only what classify() calls start_overlap can refuse it.
        return Outcome::not_run();
    }
    p.reset();
    let error = p.summary_to_end().err().map(|e| e.to_string());
    let s = p.summary();
    let class = if path_blocked {
        Class::PathBlocked
    } else if error.is_some() {
        Class::Failed
    } else if s.success {
        Class::Success
    } else if s.collided {
        Class::Collision
    } else if s.self_collision_steps > 0 {
        Class::SelfCollision
    } else if s.limit_steps > 0 {
        Class::Limit
    } else {
        Class::Missed
    };
    Outcome {
        class,
        min_distance: s.min_distance,
        min_clearance: s.min_clearance,
        final_error: Some(s.final_error),
        out_of_range_steps: s.out_of_range_steps,
        limit_steps: s.limit_steps,
        relaxed_steps: s.relaxed_steps,
        error,
    }
}
