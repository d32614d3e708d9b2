//! What a run of an arm in space writes, whatever its task: its run
//! file, CSV or summary as asked (`run_and_write`), and the lines the
//! summaries share: where it starts and ends, the spheres, the smallest
//! clearances (from the spheres and between the chain's own capsules),
//! the steps past a limit and the relaxed programs.

use std::fmt::Write as _;
use std::sync::Arc;

use redundant_ik::export::{Recorded, RunFile};
use redundant_ik::networks::space::{SpaceNetworkSet, SpaceNetworks};
use redundant_ik::planner::{Networks, Planner, Sample, SceneOf, Summary, Surrogate, Trajectory};
use redundant_ik::space::{Chain, Sphere};
use redundant_ik::urdf::RobotSource;
use redundant_ik::Method;

use super::emit;
use super::simulate::{fmt_list, SimulateArgs};

/// Runs a chain's task (the hand's position or its pose) with `method`
/// (and `nets`, for a learned one) and writes the run as `args` ask: its
/// run file (`--json`: the networks it used and the robot's source in it,
/// what `--from` replays), its CSV (`--csv`) or its summary for people
/// (`readable`).
pub(super) fn run_and_write<A, const M: usize>(
    args: &SimulateArgs,
    scene: A::Scene,
    method: Method,
    nets: Option<Arc<SpaceNetworks>>,
    source: Option<RobotSource>,
    readable: impl FnOnce(&A::Scene, &Trajectory<M, A::Point>) -> String,
) -> Result<(), String>
where
    A: Recorded<M, Set = SpaceNetworkSet>,
    A::Scene: SceneOf<A, M> + redundant_ik::model::Scene<A>,
    A::Scene: serde::Serialize + serde::de::DeserializeOwned,
    [f64; M]: serde::Serialize + serde::de::DeserializeOwned,
    SpaceNetworks: Surrogate<A, M>,
{
    let used = nets.clone();
    let traj = Planner::new(scene.clone(), method, nets.map(|n| n as Networks<A, M>))
        .and_then(Planner::run_to_end)
        .map_err(|e| e.to_string())?;
    if args.json {
        let (networks, precision) = super::space_networks::recorded(used.as_deref());
        let text = RunFile::<A, M>::of(None, scene, traj, networks, precision)
            .with_robot(source)
            .to_json();
        return emit(&format!("{text}\n"));
    }
    if args.csv {
        return emit(&redundant_ik::export::run_csv(&traj.steps));
    }
    emit(&readable(&scene, &traj))
}

/// The run's first and last samples, a line each: the joint angles and
/// the hand (`hand` writes it: a point, or a pose), and after the last,
/// `goal` (the target, or where the path ends).
pub fn ends<const M: usize, P>(
    out: &mut String,
    steps: &[Sample<M, P>],
    hand: impl Fn([f64; M]) -> String,
    goal: &str,
) {
    let (Some(first), Some(last)) = (steps.first(), steps.last()) else {
        return;
    };
    let (start, end) = (fmt_list(&first.theta), fmt_list(&last.theta));
    let _ = writeln!(out, "start  theta = [{start}]  hand {}", hand(first.ee));
    let _ = writeln!(
        out,
        "end    theta = [{end}]  hand {}  {goal}",
        hand(last.ee)
    );
}

/// The spheres and the smallest clearances of a run of `chain` past
/// `spheres`, one line each.
pub fn contact(out: &mut String, s: &Summary, chain: &Chain, spheres: &[Sphere]) {
    for sp in spheres {
        let c = sp.centre;
        let _ = writeln!(
            out,
            "sphere at ({:.4}, {:.4}, {:.4}), radius {} m (the links' capsules: radius {} m)",
            c[0],
            c[1],
            c[2],
            sp.radius,
            chain.radius()
        );
    }
    match s.min_clearance {
        Some(c) => {
            let _ = writeln!(
                out,
                "smallest capsule-to-sphere clearance  {c:.4} m  -> {}",
                if s.collision_steps > 0 {
                    format!("COLLISION in {} steps", s.collision_steps)
                } else {
                    "no collision".into()
                }
            );
        }
        None => {
            let _ = writeln!(out, "no spheres");
        }
    }
    if let Some(c) = s.min_self_clearance {
        let _ = writeln!(
            out,
            "smallest self clearance ({} pairs)     {c:.4} m  -> {}",
            chain.self_pairs().len(),
            if s.self_collision_steps > 0 {
                format!("SELF-COLLISION in {} steps", s.self_collision_steps)
            } else {
                "no self-collision".into()
            }
        );
    }
}

/// The steps past a joint's limit and the relaxed programs, where any.
pub fn limits(out: &mut String, s: &Summary) {
    if s.limit_steps > 0 {
        let _ = writeln!(out, "a joint past its limit in {} steps", s.limit_steps);
    }
    if s.relaxed_steps > 0 {
        let _ = writeln!(
            out,
            "the program's constraints were relaxed in {} steps",
            s.relaxed_steps
        );
    }
}
