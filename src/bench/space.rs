//! The spatial planner's step, timed and its allocations counted, for the
//! arms in space (`redundant-ik bench --arm panda`): each preset's own
//! task, restarted at its end.

use std::sync::Arc;

use super::{time_ns, Options, Probes};
use crate::error::{Error, Result};
use crate::networks::space::{SpaceNetworkSet, SpaceNetworks};
use crate::planner::space::SpacePlanner;
use crate::planner::Method;
use crate::scene::SpaceScene;

/// One RK4 step of the preset `key`'s task in `method`, sample included
/// (ns); the run restarts at `tf`.
pub fn step_ns(key: &str, method: Method, opts: &Options, probes: &Probes) -> Result<f64> {
    let scene = task(key, opts.refine)?;
    let nets = shipped_networks(key, method)?;
    let fresh = || SpacePlanner::with_networks(scene.clone(), method, nets.clone());
    let mut p = fresh()?;
    time_ns(opts, probes, || {
        if p.done() {
            p = fresh()?;
        }
        std::hint::black_box(p.step()?);
        Ok(())
    })
}

/// Heap allocations per RK4 step over one whole run of the preset `key`'s
/// task in `method`, once the planner exists.
pub fn allocs_per_step(
    key: &str,
    method: Method,
    opts: &Options,
    count: &dyn Fn() -> u64,
) -> Result<f64> {
    let nets = shipped_networks(key, method)?;
    let mut p = SpacePlanner::with_networks(task(key, opts.refine)?, method, nets)?;
    let n = p.scene().steps();
    let before = count();
    for _ in 0..n {
        std::hint::black_box(p.step()?);
    }
    Ok((count() - before) as f64 / n as f64)
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

/// The preset `key`'s task with `refine` refinement steps (Cases 1 and 3).
fn task(key: &str, refine: u32) -> Result<SpaceScene> {
    let mut scene = SpaceScene::by_key(key)?;
    scene
        .params
        .set(&crate::planner::methods::REFINE, f64::from(refine))?;
    Ok(scene)
}
