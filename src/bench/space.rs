//! The planner's step on an arm in space, timed and its allocations counted, for the
//! arms in space (`redundant-ik bench --arm panda`): each preset's own
//! task, restarted at its end.

use std::sync::Arc;

use super::{time_ns, Forward, Options, Probes};
use crate::error::{Error, Result};
use crate::networks::space::{SpaceNetworkSet, SpaceNetworks};
use crate::planner::Method;
use crate::planner::{Networks, Planned, Planner, SceneOf};
use crate::scene::{PoseScene, SpaceScene};

/// One RK4 step of the preset `key`'s task in `method`, sample included
/// (ns); the run restarts at `tf`.
pub fn step_ns(key: &str, method: Method, opts: &Options, probes: &Probes) -> Result<f64> {
    let nets = shipped_networks(key, method)?;
    step_ns_with(key, method, nets, opts, probes)
}

/// [`step_ns`] with the networks given (the workers' module, which is
/// handed the weights files' text): `None` for the methods without. They
/// run in the options' precision.
pub fn step_ns_with(
    key: &str,
    method: Method,
    nets: Option<Arc<SpaceNetworks>>,
    opts: &Options,
    probes: &Probes,
) -> Result<f64> {
    step_ns_of(SpaceScene::by_key(key)?, key, method, nets, opts, probes)
}

/// [`step_ns_with`] on `scene` (a robot's own, read from its run file),
/// which messages call `name`; the options' refinement steps replace the
/// scene's.
pub fn step_ns_of(
    mut scene: SpaceScene,
    name: &str,
    method: Method,
    nets: Option<Arc<SpaceNetworks>>,
    opts: &Options,
    probes: &Probes,
) -> Result<f64> {
    if method.uses_networks() && nets.is_none() {
        return Err(Error::NetworksUnavailable(format!(
            "{} needs the networks of the arm '{name}'",
            method.name()
        )));
    }
    let nets = nets.map(|n| n.in_precision(opts.precision) as Networks<_, 3>);
    refined(&mut scene, opts.refine)?;
    scene_step_ns(scene, method, nets, opts, probes)
}

/// One RK4 step of `scene` in `method` with `nets`, sample included (ns);
/// the run restarts at `tf`. For every arm.
pub fn scene_step_ns<S, A, const M: usize>(
    scene: S,
    method: Method,
    nets: Option<Networks<A, M>>,
    opts: &Options,
    probes: &Probes,
) -> Result<f64>
where
    S: SceneOf<A, M> + crate::model::Scene<A> + Clone,
    A: Planned<M, Scene = S>,
{
    let fresh = || Planner::new(scene.clone(), method, nets.clone());
    let mut p = fresh()?;
    time_ns(opts, probes, || {
        if p.done() {
            p = fresh()?;
        }
        std::hint::black_box(p.step()?);
        Ok(())
    })
}

/// Heap allocations per RK4 step over one whole run of `scene` in
/// `method`, once the planner exists. For every arm.
pub fn scene_allocs_per_step<S, A, const M: usize>(
    scene: S,
    method: Method,
    nets: Option<Networks<A, M>>,
    count: &dyn Fn() -> u64,
) -> Result<f64>
where
    S: SceneOf<A, M> + crate::model::Scene<A> + Clone,
    A: Planned<M, Scene = S>,
{
    let mut p = Planner::new(scene, method, nets)?;
    let n = p.scene().steps();
    let before = count();
    for _ in 0..n {
        std::hint::black_box(p.step()?);
    }
    Ok((count() - before) as f64 / n as f64)
}

/// A second sphere for the pose task's benchmark, below and beside the
/// presets' line (m): `(x, y, z, radius)`.
pub const SECOND_SPHERE: [f64; 4] = [0.3, -0.25, 0.35, 0.05];

/// The preset `key`'s pose task as `bench --task pose` times it: its line
/// and sphere, the hand's start orientation kept, a second sphere
/// ([`SECOND_SPHERE`]) and self-collision checked (issue 40's goal scene).
pub fn pose_task(key: &str) -> Result<PoseScene> {
    let mut space = SpaceScene::by_key(key)?;
    let [x, y, z, r] = SECOND_SPHERE;
    space
        .obstacles
        .push(crate::space::Sphere::new([x, y, z], r));
    let zero = vec![0.0; space.arm.dof()];
    space.arm = space
        .arm
        .clone()
        .with_self_collision(&[], &[&zero, &space.theta0])?;
    PoseScene::from_space(space, None, crate::space::ORIENTATION_WEIGHT)
}

/// Heap allocations per RK4 step over one whole run of the preset `key`'s
/// task in `method`, once the planner exists.
pub fn allocs_per_step(
    key: &str,
    method: Method,
    opts: &Options,
    count: &dyn Fn() -> u64,
) -> Result<f64> {
    let nets =
        shipped_networks(key, method)?.map(|n| n.in_precision(opts.precision) as Networks<_, 3>);
    let mut scene = SpaceScene::by_key(key)?;
    refined(&mut scene, opts.refine)?;
    scene_allocs_per_step(scene, method, nets, count)
}

/// Forward passes of the spatial `Phi` and `v` networks at the preset
/// `key`'s start pose, `v` for its first sphere (ns), in the options'
/// precision.
pub fn forward_ns(
    key: &str,
    nets: Arc<SpaceNetworks>,
    opts: &Options,
    probes: &Probes,
) -> Result<Forward> {
    forward_ns_of(&SpaceScene::by_key(key)?, nets, opts, probes)
}

/// [`forward_ns`] at `scene`'s start pose and first sphere (a robot's own
/// scene, read from its run file).
pub fn forward_ns_of(
    scene: &SpaceScene,
    nets: Arc<SpaceNetworks>,
    opts: &Options,
    probes: &Probes,
) -> Result<Forward> {
    let nets = nets.in_precision(opts.precision);
    nets.check_chain(&scene.arm)?;
    let pose = crate::space::SpacePose::new(&scene.arm, &scene.theta0)?;
    let n = pose.dof();
    let o = scene
        .obstacles
        .first()
        .map_or([0.5, 0.0, 0.5], |s| s.centre);
    let mut out = vec![0.0; 3 * n];
    let phi = time_ns(opts, probes, || {
        nets.phi(std::hint::black_box(&pose), &mut out)
    })?;
    let mut g = vec![0.0; n];
    let v = time_ns(opts, probes, || {
        nets.area_gradient(std::hint::black_box(&pose), o, &mut g)
    })?;
    Ok(Forward {
        phi,
        v,
        phi_plain: None,
        phi_rows: None,
    })
}

/// The networks shipped for the preset `key` when `method` learns (none
/// otherwise); a learned method on a preset with none is refused.
pub fn shipped_networks(key: &str, method: Method) -> Result<Option<Arc<SpaceNetworks>>> {
    if !method.uses_networks() {
        return Ok(None);
    }
    let set = SpaceNetworkSet::for_arm(key).ok_or_else(|| {
        Error::NetworksUnavailable(format!("no networks are shipped for the arm '{key}'"))
    })?;
    #[cfg(feature = "embedded-weights")]
    return set.load().map(Some);
    #[cfg(not(feature = "embedded-weights"))]
    Err(Error::NetworksUnavailable(format!(
        "this build has no weights built in: the set '{}' must be handed to it",
        set.name()
    )))
}

/// Gives `scene` `refine` refinement steps (Cases 1 and 3).
fn refined(scene: &mut SpaceScene, refine: u32) -> Result<()> {
    scene
        .params
        .set(&crate::planner::methods::REFINE, f64::from(refine))
}
