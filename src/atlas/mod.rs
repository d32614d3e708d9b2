//! The robustness atlas: the paper's task run with its (first) obstacle
//! centred on every point of a grid over the workspace, in every chosen
//! method, each outcome classified. The paper shows two obstacle positions and
//! calls the approach robust; the atlas maps where the networks, and the
//! triangle-area criterion of eqs. (12)-(16) itself, keep the arm clear.
//!
//! A run is never cut short at its first collision, so `min_distance` is the
//! run's true minimum over its samples. Each method keeps one planner and
//! moves the obstacle with [`Planner::move_obstacle`], so the runs allocate
//! nothing. The work is done in chunks ([`Chunked::advance`]) so that a caller
//! can report progress and cancel between them: a progress bar in the
//! command-line tool, a Web Worker's messages in the page.

mod geometry;
mod grid;
mod job;
mod read;
pub mod space;
mod summary;
mod sweep;

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::networks::Networks;
use crate::planner::{methods, Method, Planner, Surrogate};
use crate::scene::Scene;

pub use geometry::unavoidable;
pub use geometry::PlaneGeometry;
pub use grid::{Grid, DEFAULT_GRID, MAX_GRID};
pub use job::{Chunked, Head};
#[cfg(feature = "figure")]
pub(crate) use summary::summarise;
pub use summary::{Agreement, Clearance, MethodSummary, Rate};
pub use sweep::{Mapped, Sweep};

/// What happened with the obstacle centred on one cell, in one method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Class {
    /// The disc touches the arm at `t = 0`, or the base post: nothing is run.
    StartOverlap,
    /// The disc covers a point of the straight line the end effector must
    /// follow, so no method can avoid it (still run and recorded).
    PathBlocked,
    /// No collision, and the target reached within 5 mm.
    Success,
    /// A link entered the disc.
    Collision,
    /// No collision, but a joint went past its position limits (only an
    /// arm with limits).
    Limit,
    /// No collision, but the end effector ended more than 5 mm from the target.
    Missed,
    /// The run stopped with an error (e.g. diverging at a singular pose).
    Failed,
    /// No collision with an obstacle, but two capsules of the chain met
    /// (only a chain that checks self-collision).
    SelfCollision,
}

impl Class {
    /// Checks a map of classes on `grid`, as the page's layers take one
    /// (the plane's and a slice's in space): the grid valid, one class per
    /// cell (rows from `y0`, each from `x0`), each an index into
    /// [`Class::ALL`]; `what` names the map in the error.
    pub fn check_map(grid: &Grid, classes: &[u8], what: &str) -> Result<()> {
        grid.validate()?;
        if classes.len() != grid.cells() {
            return Err(Error::DimensionMismatch {
                what: what.into(),
                expected: grid.cells(),
                found: classes.len(),
            });
        }
        match classes
            .iter()
            .find(|&&c| usize::from(c) >= Class::ALL.len())
        {
            Some(&bad) => Err(Error::OutOfRange {
                what: "atlas class index".into(),
                value: f64::from(bad),
                min: 0.0,
                max: (Class::ALL.len() - 1) as f64,
            }),
            None => Ok(()),
        }
    }

    /// How many classes there are.
    pub const COUNT: usize = 8;

    /// Every class, in the order of the legends.
    pub const ALL: [Class; Class::COUNT] = [
        Class::Success,
        Class::Collision,
        Class::Limit,
        Class::Missed,
        Class::Failed,
        Class::PathBlocked,
        Class::StartOverlap,
        Class::SelfCollision,
    ];

    /// The name used in JSON and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Class::StartOverlap => "start_overlap",
            Class::PathBlocked => "path_blocked",
            Class::Success => "success",
            Class::Collision => "collision",
            Class::Limit => "limit",
            Class::Missed => "missed",
            Class::Failed => "failed",
            Class::SelfCollision => "self_collision",
        }
    }

    /// What the class means, for legends.
    pub fn label(self) -> &'static str {
        match self {
            Class::StartOverlap => "on the arm at t = 0: not run",
            Class::PathBlocked => "on the path: unavoidable",
            Class::Success => "clear, target reached",
            Class::Collision => "collision",
            Class::Limit => "clear, past a joint limit",
            Class::Missed => "clear, target missed by > 5 mm",
            Class::Failed => "run failed",
            Class::SelfCollision => "self-collision",
        }
    }

    /// The colour of the class in the maps (the command-line tool's SVG and
    /// the page's layer use the same), `#rrggbb`.
    pub fn colour(self) -> &'static str {
        match self {
            Class::Success => "#5fb89a",
            Class::Collision => "#c0392b",
            Class::Limit => "#2f6fb5",
            Class::Missed => "#e9a23b",
            Class::Failed => "#7d4e9e",
            Class::PathBlocked => "#8f9aa6",
            Class::StartOverlap => "#d3d9e0",
            Class::SelfCollision => "#e377c2",
        }
    }

    /// Whether an avoiding method could have succeeded here: the disc is
    /// clear of the start pose and of the path.
    pub fn avoidable(self) -> bool {
        !matches!(self, Class::StartOverlap | Class::PathBlocked)
    }
}

/// The record of one run (one cell, one method), of either kind of arm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// The class.
    pub class: Class,
    /// Smallest obstacle-centre-to-link distance over the run's samples
    /// (to a link's axis in space; `None` when nothing was run).
    pub min_distance: Option<f64>,
    /// Smallest link-to-obstacle clearance over the run's samples, between
    /// their surfaces (`None` when nothing was run; absent from the planar
    /// atlases written before it was kept).
    #[serde(default)]
    pub min_clearance: Option<f64>,
    /// Distance from the end effector to the target at the end (or where
    /// the run failed).
    pub final_error: Option<f64>,
    /// Steps at which a network's input left its trained range.
    pub out_of_range_steps: usize,
    /// Steps with a joint past its position limits; absent when none.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub limit_steps: usize,
    /// Steps whose quadratic program was relaxed; absent when none.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub relaxed_steps: usize,
    /// Why the run stopped, for `failed` (and a `path_blocked` run that failed).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub error: Option<String>,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl Outcome {
    fn not_run() -> Self {
        Self {
            class: Class::StartOverlap,
            min_distance: None,
            min_clearance: None,
            final_error: None,
            out_of_range_steps: 0,
            limit_steps: 0,
            relaxed_steps: 0,
            error: None,
        }
    }
}

/// One grid point and its outcome in each method (in the order of the
/// atlas's methods), of an arm whose obstacles have `M` coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell<const M: usize = 2> {
    /// The obstacle's centre (m).
    pub centre: [f64; M],
    /// One outcome per method.
    pub outcomes: Vec<Outcome>,
    /// Where avoidance is possible (neither `start_overlap` nor
    /// `path_blocked`): whether it matters here, i.e. whether the arm
    /// without avoidance (`none`) collides; `None` elsewhere. Far from the
    /// arm every method succeeds, avoiding or not.
    pub avoidance_needed: Option<bool>,
}

impl Cell {
    /// Obstacle centre x (m).
    pub fn x(&self) -> f64 {
        self.centre[0]
    }

    /// Obstacle centre y (m).
    pub fn y(&self) -> f64 {
        self.centre[1]
    }
}

/// What to map: a scene (whose first obstacle is moved), a grid and methods.
#[derive(Debug, Clone, PartialEq)]
pub struct Spec {
    /// The scene; its first obstacle is centred on each cell in turn (its
    /// radius is kept, any other obstacles stay where they are).
    pub scene: Scene,
    /// The obstacle centres.
    pub grid: Grid,
    /// The methods to run (duplicates are dropped).
    pub methods: Vec<Method>,
    /// The paper task the scene came from, for the report.
    pub task: Option<u32>,
}

impl Spec {
    /// The paper's task `task` on the default grid ([`Grid::around_reach`],
    /// [`DEFAULT_GRID`] points per side) in the paper's five methods.
    pub fn task(task: u32) -> Result<Self> {
        let scene = Scene::task(task)?;
        let grid = Grid::around_reach(&scene.arm, DEFAULT_GRID);
        Ok(Self {
            scene,
            grid,
            methods: methods::PAPER.to_vec(),
            task: Some(task),
        })
    }
}

/// A finished atlas.
#[derive(Debug, Clone, PartialEq)]
pub struct Atlas {
    /// The paper task, if the scene is one.
    pub task: Option<u32>,
    /// The grid.
    pub grid: Grid,
    /// Radius of the moved obstacle (m).
    pub radius: f64,
    /// Gain `lambda` of the obstacle vector.
    pub lambda: f64,
    /// The methods, in the order of each cell's outcomes.
    pub methods: Vec<Method>,
    /// Row by row from `y0`, each row from `x0`: cell `(i, j)` is `cells[j * n + i]`.
    pub cells: Vec<Cell>,
    /// Where the `v` network saw obstacle centres in training,
    /// `[x0, x1, y0, y1]` (when networks were given).
    pub trained_region: Option<[f64; 4]>,
    /// One summary per method.
    pub summary: Vec<MethodSummary>,
}

impl Atlas {
    /// Runs a whole atlas on this thread. `networks` are needed for the
    /// network methods (and give the trained obstacle region of the summary).
    pub fn run(spec: Spec, networks: Option<Arc<Networks>>) -> Result<Self> {
        let mut job = Job::new(spec, networks)?;
        while !job.is_done() {
            job.advance(usize::MAX);
        }
        job.finish()
    }

    /// The outcome of cell `index` in `method`, if the atlas ran that method.
    pub fn outcome(&self, index: usize, method: Method) -> Option<&Outcome> {
        let m = self.methods.iter().position(|&x| x == method)?;
        self.cells.get(index)?.outcomes.get(m)
    }

    /// The summary of `method`.
    pub fn summary_of(&self, method: Method) -> Option<&MethodSummary> {
        self.summary.iter().find(|s| s.method == method)
    }
}

/// A planar atlas being computed, a chunk of cells at a time: the one
/// [`Sweep`] over the arm's plane ([`Chunked`]), and what its summaries
/// need.
pub type Job = Chunked<Arm, 2, 2, PlaneHead>;

/// What a planar atlas records beside its cells: the request, the moved
/// obstacle's radius and the networks (their trained region).
#[derive(Debug, Clone)]
pub struct PlaneHead {
    spec: Spec,
    radius: f64,
    networks: Option<Arc<Networks>>,
}

impl Job {
    /// Checks the spec and builds one planner per method. Network methods
    /// without networks, or networks for another arm, are refused here.
    pub fn new(mut spec: Spec, networks: Option<Arc<Networks>>) -> Result<Self> {
        spec.scene.validate()?;
        spec.grid.validate()?;
        let mut methods = Vec::new();
        for m in spec.methods.iter().copied() {
            if !methods.contains(&m) {
                methods.push(m);
            }
        }
        spec.methods = methods;
        let radius = spec
            .scene
            .obstacles
            .first()
            .ok_or(Error::NoObstacle)?
            .radius;
        let surrogate = networks.clone().map(|n| n as Arc<dyn Surrogate>);
        let sweep = Sweep::new(&spec.scene, (), spec.grid, &spec.methods, surrogate, radius)?;
        let head = PlaneHead {
            spec,
            radius,
            networks,
        };
        Ok(Chunked::of_sweep(sweep, head))
    }
}

impl Head<2> for PlaneHead {
    type Atlas = Atlas;
    const CELLS: &'static str = "atlas cells computed";
    fn finish(self, _grid: Grid, cells: Vec<Cell>) -> Result<Atlas> {
        let trained_region = self.networks.as_ref().map(|n| {
            let r = n.trained_range();
            [
                r.obstacle_min[0],
                r.obstacle_max[0],
                r.obstacle_min[1],
                r.obstacle_max[1],
            ]
        });
        let summary = summary::summarise(&self.spec.methods, &cells, trained_region, self.radius);
        Ok(Atlas {
            task: self.spec.task,
            grid: self.spec.grid,
            radius: self.radius,
            lambda: self.spec.scene.param(&crate::planner::methods::LAMBDA),
            methods: self.spec.methods,
            cells,
            trained_region,
            summary,
        })
    }
}

/// The planar atlas lies in the arm's plane.
impl Mapped<2> for Arm {
    type Surface = ();
    type Geometry = PlaneGeometry;
    fn point((): (), x: f64, y: f64) -> [f64; 2] {
        [x, y]
    }
    fn geometry(scene: &Scene, radius: f64) -> Result<PlaneGeometry> {
        PlaneGeometry::new(scene, radius)
    }
    fn classify(geometry: &PlaneGeometry, centre: [f64; 2]) -> Option<Class> {
        geometry.classify(centre)
    }
    fn place(p: &mut Planner, centre: [f64; 2]) -> Result<()> {
        p.move_obstacle(0, centre)
    }
}
