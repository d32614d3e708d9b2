//! The spatial planner's step, timed and its allocations counted, for the
//! arms in space (`redundant-ik bench --arm panda`): each preset's own
//! task, restarted at its end.

use super::{time_ns, Options, Probes};
use crate::error::Result;
use crate::planner::space::SpacePlanner;
use crate::planner::Method;
use crate::scene::SpaceScene;

/// One RK4 step of the preset `key`'s task in `method`, sample included
/// (ns); the run restarts at `tf`.
pub fn step_ns(key: &str, method: Method, opts: &Options, probes: &Probes) -> Result<f64> {
    let scene = SpaceScene::by_key(key)?;
    let fresh = || SpacePlanner::new(scene.clone(), method);
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
pub fn allocs_per_step(key: &str, method: Method, count: &dyn Fn() -> u64) -> Result<f64> {
    let mut p = SpacePlanner::new(SpaceScene::by_key(key)?, method)?;
    let n = p.scene().steps();
    let before = count();
    for _ in 0..n {
        std::hint::black_box(p.step()?);
    }
    Ok((count() - before) as f64 / n as f64)
}
