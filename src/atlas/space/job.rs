//! The slice atlas a cell at a time ([`SliceJob`]): the one
//! [`crate::atlas::Sweep`] over an axis-aligned plane, with the task's
//! first sphere moved to each cell's centre. The atlas equals that of a
//! new planner on a copy of the scene for every cell and method
//! (`tests/space/atlas_job.rs`).

use std::sync::Arc;

use super::{Plane, SliceAtlas};
use crate::atlas::{Cell, Chunked, Class, Grid, Head, Mapped, Sweep};
use crate::error::{Error, Result};
use crate::networks::space::SpaceNetworks;
use crate::planner::{Method, Networks, Planner};
use crate::scene::{PoseScene, SpacePath, SpaceScene};
use crate::space::{clearance, Chain, PoseChain, SpacePose, Sphere, Vec3};

/// A slice atlas being computed, a chunk of cells at a time ([`Chunked`]):
/// what [`super::slice`] runs, and what the page's worker runs a row at
/// a time (`SpaceAtlasJob`, src/web/space_atlas.rs).
/// For the hand's position (`SliceJob`) or its pose
/// (`SliceJob<PoseChain, 6>`, [`SliceJob::pose`]).
pub type SliceJob<A = Chain, const M: usize = 3> = Chunked<A, M, 3, SliceHead>;

/// What a slice atlas records beside its cells: its plane, the moved
/// sphere's radius and the methods.
#[derive(Debug, Clone)]
pub struct SliceHead {
    plane: Plane,
    radius: f64,
    methods: Vec<Method>,
}

impl Head<3> for SliceHead {
    type Atlas = SliceAtlas;
    const CELLS: &'static str = "slice atlas cells computed";
    /// `arm` is left `None` (the caller names its preset).
    fn finish(self, grid: Grid, cells: Vec<Cell<3>>) -> Result<SliceAtlas> {
        Ok(SliceAtlas {
            arm: None,
            plane: self.plane,
            grid,
            radius: self.radius,
            methods: self.methods,
            cells,
        })
    }
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
        let n = scene.arm.dof();
        check_methods(methods, networks, &scene.arm, |m| m.space_rule(n).map(drop))?;
        let nets = networks.map(|n| n.clone() as Networks<Chain, 3>);
        Self::of(scene, &scene.obstacles, plane, grid, methods, nets)
    }
}

/// Refused, method by method in order, where `runs` refuses one or a
/// learned one has no networks; then where the networks were trained for
/// another chain than `chain`.
fn check_methods(
    methods: &[Method],
    networks: Option<&Arc<SpaceNetworks>>,
    chain: &Chain,
    runs: impl Fn(Method) -> Result<()>,
) -> Result<()> {
    for &m in methods {
        runs(m)?;
        if m.uses_networks() && networks.is_none() {
            return Err(Error::NetworksUnavailable(format!(
                "method {m} needs networks trained for this arm in space"
            )));
        }
    }
    networks.map_or(Ok(()), |nets| nets.check_chain(chain))
}

impl SliceJob<PoseChain, 6> {
    /// [`SliceJob::new`] for the hand's pose task: Case 2 runs with the
    /// networks' `v`; Cases 1 and 3 are refused (no `Phi` is trained for
    /// the pose).
    pub fn pose(
        scene: &PoseScene,
        plane: Plane,
        grid: Grid,
        methods: &[Method],
        networks: Option<&Arc<SpaceNetworks>>,
    ) -> Result<Self> {
        grid.validate()?;
        scene.validate()?;
        check_methods(methods, networks, &scene.arm.chain, |_| Ok(()))?;
        let nets = networks.map(|n| n.clone() as Networks<PoseChain, 6>);
        Self::of(scene, &scene.obstacles, plane, grid, methods, nets)
    }
}

impl<A: Mapped<M, 3, Surface = Plane> + AsRef<Chain>, const M: usize> SliceJob<A, M>
where
    A::Scene: crate::planner::SceneOf<A, M> + crate::model::Scene<A>,
{
    /// One planner per method on `scene`, whose first sphere (or one of
    /// 0.05 m) the cells move; refused where no cell of the grid lies
    /// within the arm's reach of its first joint.
    fn of(
        scene: &A::Scene,
        spheres: &[Sphere],
        plane: Plane,
        grid: Grid,
        methods: &[Method],
        nets: Option<Networks<A, M>>,
    ) -> Result<Self> {
        use crate::model::Scene as _;
        let chain: &Chain = scene.arm().as_ref();
        let radius = spheres.first().map_or(0.05, |s| s.radius);
        let sweep = Sweep::new(scene, plane, grid, methods, nets, radius)?;
        let shoulder = SpacePose::new(chain, scene.theta0())?.joint_origin(0);
        let reach = chain.reach() + radius + chain.radius();
        let near = |c: Vec3| {
            (0..3)
                .map(|k| (c[k] - shoulder[k]).powi(2))
                .sum::<f64>()
                .sqrt()
                <= reach
        };
        if !(0..grid.cells()).any(|i| near(sweep.centre(i))) {
            return Err(Error::SliceMissesReach {
                slice: plane.to_string(),
                reach,
            });
        }
        let head = SliceHead {
            plane,
            radius,
            methods: methods.to_vec(),
        };
        Ok(Chunked::of_sweep(sweep, head))
    }
}

/// What decides a sphere's class before any run in space: the chain at
/// its start pose, the hand's path and the flange's capsule radius.
#[derive(Debug, Clone)]
pub struct SliceGeometry {
    chain: Chain,
    pose: SpacePose,
    path: SpacePath,
    start: Vec3,
    target: Vec3,
    radius: f64,
}

/// A slice atlas lies on an axis-aligned plane.
impl Mapped<3> for Chain {
    type Surface = Plane;
    type Geometry = SliceGeometry;
    fn point(plane: Plane, u: f64, v: f64) -> Vec3 {
        plane.point(u, v)
    }
    fn geometry(scene: &SpaceScene, radius: f64) -> Result<SliceGeometry> {
        Ok(SliceGeometry {
            chain: scene.arm.clone(),
            pose: SpacePose::new(&scene.arm, &scene.theta0)?,
            path: scene.path.clone(),
            start: scene.start(),
            target: scene.target,
            radius,
        })
    }
    /// On the arm at the start or on the fixed base (`start_overlap`),
    /// within reach of the hand's path (`path_blocked`: the flange's
    /// capsule follows the path), or nothing (`None`).
    fn classify(g: &SliceGeometry, centre: Vec3) -> Option<Class> {
        let s = Sphere::new(centre, g.radius);
        if s.validate(&g.chain).is_err() || clearance(&g.chain, &g.pose, &[s]) <= 0.0 {
            return Some(Class::StartOverlap);
        }
        let d = g.path.distance_to(centre, g.start, g.target);
        (d <= g.radius + g.chain.radius()).then_some(Class::PathBlocked)
    }
    fn place(p: &mut Planner<Chain, 3>, centre: Vec3) -> Result<()> {
        let radius = p.scene().obstacles.first().map_or(0.05, |s| s.radius);
        p.set_sphere(0, Sphere::new(centre, radius))
    }
}

/// The pose task's slice atlas: the position task's geometry (the
/// chain at its start, the hand's line).
impl Mapped<6, 3> for PoseChain {
    type Surface = Plane;
    type Geometry = SliceGeometry;
    fn point(plane: Plane, u: f64, v: f64) -> Vec3 {
        plane.point(u, v)
    }
    fn geometry(scene: &PoseScene, radius: f64) -> Result<SliceGeometry> {
        let (space, _, _) = scene.position_scene();
        <Chain as Mapped<3>>::geometry(&space, radius)
    }
    fn classify(g: &SliceGeometry, centre: Vec3) -> Option<Class> {
        <Chain as Mapped<3>>::classify(g, centre)
    }
    fn place(p: &mut Planner<PoseChain, 6>, centre: Vec3) -> Result<()> {
        let radius = p.scene().obstacles.first().map_or(0.05, |s| s.radius);
        p.set_sphere(0, Sphere::new(centre, radius))
    }
}
