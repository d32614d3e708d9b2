//! The slice atlas a cell at a time ([`SliceJob`]): one planner per
//! method, built once, whose sphere is moved to each cell's centre and
//! which is reset to `t = 0` for each run, keeping only the run's summary
//! (nothing is allocated per run but the cell's record). A caller advances
//! it in chunks to report progress and to cancel between them: the
//! command-line tool all at once (across its cores), a Web Worker a row at
//! a time. The atlas equals that of a new planner on a copy of the scene
//! for every cell and method (`tests/space/atlas_job.rs`).

use std::sync::Arc;

use super::{Plane, SliceAtlas, SliceCell, SliceOutcome};
use crate::atlas::{Class, Grid};
use crate::error::{Error, Result};
use crate::networks::space::SpaceNetworks;
use crate::planner::{Method, REACH_TOLERANCE};
use crate::planner::{Networks, Planner};
use crate::scene::SpaceScene;
use crate::space::Chain;
use crate::space::{clearance, SpacePose, Sphere, Vec3};

/// A slice atlas being computed, a chunk of cells at a time: what
/// [`super::slice`] runs, and what the page's worker runs a row at
/// a time (`SpaceAtlasJob`, src/web/space_atlas.rs).
#[derive(Clone)]
pub struct SliceJob {
    scene: SpaceScene,
    plane: Plane,
    grid: Grid,
    radius: f64,
    methods: Vec<Method>,
    /// The start pose, for what the sphere does before any run.
    pose: SpacePose,
    /// One planner per method (in the order of `methods`), reused for
    /// every cell.
    planners: Vec<Planner<Chain, 3>>,
    cells: Vec<SliceCell>,
}

impl SliceJob {
    /// Checks the request as [`super::slice`] does and builds one
    /// planner per method: refused when a method does not run in space,
    /// a learned one has no networks (or networks for another arm), or no
    /// cell of the grid lies within the arm's reach of its first joint.
    pub fn new(
        scene: &SpaceScene,
        plane: Plane,
        grid: Grid,
        methods: &[Method],
        networks: Option<&Arc<SpaceNetworks>>,
    ) -> Result<Self> {
        grid.validate()?;
        scene.validate()?;
        for m in methods {
            m.space_rule(scene.arm.dof())?;
            if m.uses_networks() && networks.is_none() {
                return Err(Error::NetworksUnavailable(format!(
                    "method {m} needs networks trained for this arm in space"
                )));
            }
        }
        if let Some(nets) = networks {
            nets.check_chain(&scene.arm)?;
        }
        let radius = scene.obstacles.first().map_or(0.05, |s| s.radius);
        let pose = SpacePose::new(&scene.arm, &scene.theta0)?;
        let shoulder = pose.joint_origin(0);
        let reach = scene.arm.reach() + radius + scene.arm.radius();
        let near = |c: Vec3| {
            (0..3)
                .map(|k| (c[k] - shoulder[k]).powi(2))
                .sum::<f64>()
                .sqrt()
                <= reach
        };
        if !(0..grid.cells()).any(|i| near(centre(plane, &grid, i))) {
            return Err(Error::SliceMissesReach {
                slice: plane.to_string(),
                reach,
            });
        }
        let planners = methods
            .iter()
            .map(|&m| {
                let nets = networks.filter(|_| m.uses_networks()).cloned();
                Planner::new(scene.clone(), m, nets.map(|n| n as Networks<Chain, 3>))
            })
            .collect::<Result<Vec<_>>>()?;
        Ok(Self {
            scene: scene.clone(),
            plane,
            grid,
            radius,
            methods: methods.to_vec(),
            pose,
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

    /// Computes up to `cells` more cells on this thread, in order; returns
    /// how many are done in all.
    pub fn advance(&mut self, cells: usize) -> usize {
        let end = self.done().saturating_add(cells).min(self.total());
        for index in self.done()..end {
            let c = centre(self.plane, &self.grid, index);
            let cell = run_cell(&self.scene, &self.pose, self.radius, &mut self.planners, c);
            self.cells.push(cell);
        }
        self.done()
    }

    /// [`Self::advance`] across the machine's cores (rayon): each thread
    /// runs its cells with its own copy of the planners; the cells equal
    /// those of the one-thread path (each run is deterministic).
    #[cfg(all(feature = "parallel", not(target_family = "wasm")))]
    pub fn advance_parallel(&mut self, cells: usize) -> usize {
        use rayon::prelude::*;
        let end = self.done().saturating_add(cells).min(self.total());
        let (scene, pose, radius) = (&self.scene, &self.pose, self.radius);
        let (plane, grid, planners) = (self.plane, &self.grid, &self.planners);
        let new: Vec<SliceCell> = (self.done()..end)
            .into_par_iter()
            .map_init(
                || planners.clone(),
                |p, index| run_cell(scene, pose, radius, p, centre(plane, grid, index)),
            )
            .collect();
        self.cells.extend(new);
        self.done()
    }

    /// The atlas; refused while cells are missing. `arm` is left `None`
    /// (the caller names its preset).
    pub fn finish(self) -> Result<SliceAtlas> {
        if !self.is_done() {
            return Err(Error::OutOfRange {
                what: "slice atlas cells computed".into(),
                value: self.done() as f64,
                min: self.total() as f64,
                max: self.total() as f64,
            });
        }
        Ok(SliceAtlas {
            arm: None,
            plane: self.plane,
            grid: self.grid,
            radius: self.radius,
            methods: self.methods,
            cells: self.cells,
        })
    }
}

/// The centre of cell `index` (rows in `v`, each from `u0`).
fn centre(plane: Plane, grid: &Grid, index: usize) -> Vec3 {
    let [u0, u1, v0, v1] = grid.region;
    let step = |a: f64, b: f64, i: usize| a + (b - a) * i as f64 / (grid.n - 1) as f64;
    let (i, j) = (index % grid.n, index / grid.n);
    plane.point(step(u0, u1, i), step(v0, v1, j))
}

/// Classifies what the sphere `s` does before any run: on the arm at the
/// start or on the fixed base (`start_overlap`), within reach of the
/// hand's path (`path_blocked`: the flange's capsule follows the path), or
/// nothing (`None`).
fn before(scene: &SpaceScene, pose: &SpacePose, s: &Sphere) -> Option<Class> {
    if s.validate(&scene.arm).is_err()
        || clearance(&scene.arm, pose, std::slice::from_ref(s)) <= 0.0
    {
        return Some(Class::StartOverlap);
    }
    let d = scene
        .path
        .distance_to(s.centre, scene.start(), scene.target);
    (d <= s.radius + scene.arm.radius()).then_some(Class::PathBlocked)
}

/// Every planner's run with the first sphere at `c`.
fn run_cell(
    scene: &SpaceScene,
    pose: &SpacePose,
    radius: f64,
    planners: &mut [Planner<Chain, 3>],
    c: Vec3,
) -> SliceCell {
    let sphere = Sphere::new(c, radius);
    let pre = before(scene, pose, &sphere);
    SliceCell {
        centre: c,
        outcomes: planners
            .iter_mut()
            .map(|p| outcome(p, sphere, pre))
            .collect(),
    }
}

/// One run of `p` from `t = 0` with its first sphere at `sphere`.
fn outcome(p: &mut Planner<Chain, 3>, sphere: Sphere, pre: Option<Class>) -> SliceOutcome {
    let not_run = |class, error| SliceOutcome {
        class,
        min_clearance: None,
        final_error: None,
        limit_steps: 0,
        relaxed_steps: 0,
        error,
    };
    if pre == Some(Class::StartOverlap) {
        return not_run(Class::StartOverlap, None);
    }
    let run = p.set_sphere(0, sphere).and_then(|()| {
        p.reset();
        p.summary_to_end()
    });
    match run {
        Ok(s) => {
            let class = pre.unwrap_or(if s.collision_steps > 0 {
                Class::Collision
            } else if s.limit_steps > 0 {
                Class::Limit
            } else if s.final_error > REACH_TOLERANCE {
                Class::Missed
            } else {
                Class::Success
            });
            SliceOutcome {
                class,
                min_clearance: s.min_clearance,
                final_error: Some(s.final_error),
                limit_steps: s.limit_steps,
                relaxed_steps: s.relaxed_steps,
                error: None,
            }
        }
        Err(e) => not_run(pre.unwrap_or(Class::Failed), Some(e.to_string())),
    }
}
