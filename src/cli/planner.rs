//! The planner a `simulate` command line describes, built at the scene's
//! start but not run: what the Python package's `Controller` evaluates in
//! the user's own loop. The same options, checks and networks as
//! `simulate`, so a controller and a run of the same keywords are the same
//! arithmetic.

use clap::Parser;
use redundant_ik::planner::{Networks, Planner};
use redundant_ik::scene::PoseScene;
use redundant_ik::space::{Chain, PoseChain};
use redundant_ik::Arm;

use super::simulate::SimulateArgs;

/// A planner of any arm: the hand in the plane (`M = 2`), the hand's
/// position in space (`M = 3`) or its pose (`M = 6`).
#[derive(Clone)]
pub enum AnyPlanner {
    /// A planar arm.
    Plane(Box<Planner<Arm, 2>>),
    /// An arm in space, its hand's position the task.
    Space(Box<Planner<Chain, 3>>),
    /// An arm in space, its hand's pose the task.
    Pose(Box<Planner<PoseChain, 6>>),
}

/// `simulate`'s options alone, as a parser.
#[derive(Parser, Debug)]
#[command(name = "simulate")]
struct Simulate {
    #[command(flatten)]
    args: SimulateArgs,
}

/// The planner `args` describe (the program's name first, then
/// `simulate`'s options), at its scene's start.
pub fn planner<I, T>(args: I) -> Result<AnyPlanner, String>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let a = Simulate::try_parse_from(args)
        .map_err(super::embed::clap_message)?
        .args;
    let e = |e: redundant_ik::Error| e.to_string();
    if let Some(job) = super::space::job(&a.scene, a.method.method, super::space_arm(&a.scene.arm))?
    {
        return Ok(match job.pose {
            None => AnyPlanner::Space(Box::new(
                Planner::new(
                    job.scene,
                    job.method,
                    job.nets.map(|n| n as Networks<Chain, 3>),
                )
                .map_err(e)?,
            )),
            Some(spec) => {
                let scene =
                    PoseScene::from_space(job.scene, spec.orientation, spec.weight).map_err(e)?;
                AnyPlanner::Pose(Box::new(
                    Planner::new(
                        scene,
                        job.method,
                        job.nets.map(|n| n as Networks<PoseChain, 6>),
                    )
                    .map_err(e)?,
                ))
            }
        });
    }
    let method = a.scene.method(&a.method)?;
    let run = a.scene.spec(method)?;
    let nets = run.surrogate_for(method).map_err(e)?;
    Ok(AnyPlanner::Plane(Box::new(
        Planner::new(run.scene, method, nets).map_err(e)?,
    )))
}
