//! `atlas` for an arm in space (`--arm A`, `--urdf FILE`, or `--from` a
//! spatial run file): the slice atlas of its job ([`super::space::Job`]),
//! as a table, JSON or CSV, and its maps (`--out`).

use std::fmt::Write as _;

use redundant_ik::networks::space::SpaceNetworkSet;

use super::space::{networks_for, Job};
use super::{emit, parse_list};

/// `atlas` for a spatial job (`--arm A`, or `--from` a spatial run file:
/// its scene): the sphere over a grid on a slice, in every method that
/// runs in space (or those asked for); a table, JSON or CSV, and the maps
/// as SVG (`--out`).
pub fn atlas(args: &super::atlas::AtlasArgs, job: Job) -> Result<(), String> {
    use redundant_ik::atlas::space::{default_region, Plane, SliceJob};
    use redundant_ik::atlas::{Class, Grid};
    use redundant_ik::scene::PoseScene;
    let (robot, scene, pose) = (job.robot, job.scene, job.pose);
    let plane = match &args.slice {
        Some(t) => t.parse::<Plane>().map_err(|e| format!("--slice: {e}"))?,
        None => Plane::through_line(&scene),
    };
    let methods = match &args.methods {
        Some(list) => super::atlas::parse_methods(list)?,
        None => redundant_ik::planner::methods::ALL
            .iter()
            .copied()
            .filter(|m| m.in_space())
            .filter(|m| {
                // The learned methods where networks are shipped, but
                // those that need a Phi on the pose task (none is trained).
                !m.uses_networks()
                    || !(pose.is_some() && m.entry().info.networks.phi)
                        && robot
                            .preset
                            .is_some_and(|p| SpaceNetworkSet::for_arm(p.key).is_some())
            })
            .collect(),
    };
    // A run file's networks where it names them, else those the flags give.
    let nets = match job.nets {
        Some(n) if methods.iter().any(|m| m.uses_networks()) => Some(n),
        _ => networks_for(&args.scene.networks, &robot, &scene.arm, &methods)?,
    };
    let region = match &args.region {
        Some(r) => match parse_list(r).map_err(|e| format!("--region: {e}"))?[..] {
            [a, b, c, d] => [a, b, c, d],
            _ => {
                return Err(format!(
                    "--region needs four numbers u0,u1,v0,v1 in the slice's axes, got '{r}'"
                ))
            }
        },
        None => default_region(&scene, plane),
    };
    let grid = Grid::new(region, args.grid).map_err(|e| e.to_string())?;
    let threads = super::atlas::threads(args)?;
    #[allow(clippy::disallowed_methods)] // the native CLI has a clock
    let start = std::time::Instant::now();
    let is_pose = pose.is_some();
    let e = |e: redundant_ik::Error| e.to_string();
    let mut a = match pose {
        Some(spec) => {
            let scene =
                PoseScene::from_space(scene.clone(), spec.orientation, spec.weight).map_err(e)?;
            let job = SliceJob::pose(&scene, plane, grid, &methods, nets.as_ref()).map_err(e)?;
            super::atlas::compute(job, threads)
        }
        None => {
            let job = SliceJob::new(&scene, plane, grid, &methods, nets.as_ref()).map_err(e)?;
            super::atlas::compute(job, threads)
        }
    }?;
    let seconds = start.elapsed().as_secs_f64();
    a.arm = robot.preset.map(|p| p.key);
    if let Some(path) = &args.out {
        super::atlas::write_maps(
            path,
            redundant_ik::figure::slice_svg(&a, &scene, &robot.label, is_pose),
        )?;
    }
    if args.json {
        let json = serde_json::to_string(&a).map_err(|e| e.to_string())?;
        return emit(&format!("{json}\n"));
    }
    if args.csv {
        return emit(&redundant_ik::export::slice_atlas_csv(&a));
    }
    let [u, v] = plane.axes();
    let [u0, u1, v0, v1] = a.grid.region;
    let mut out = String::new();
    let _ = writeln!(
        out,
        "Atlas of the hand's {} task of the {} on the slice {plane}: {n} x {n} sphere centres over {u} {u0:.3}..{u1:.3} m, {v} {v0:.3}..{v1:.3} m (radius {} m)",
        if is_pose { "pose" } else { "position" },
        robot.label,
        a.radius,
        n = a.grid.n
    );
    let _ = writeln!(
        out,
        "{} runs in {seconds:.2} s; {} cells where avoidance is possible\n",
        a.cells.len() * a.methods.len(),
        a.avoidable()
    );
    // Self-collision is counted for a chain that checks it.
    let checks_self = !scene.arm.self_pairs().is_empty();
    let shown = Class::ALL
        .into_iter()
        .filter(|&c| c != Class::SelfCollision || checks_self);
    let names: Vec<&str> = shown.clone().map(Class::name).collect();
    let _ = writeln!(
        out,
        "{:<22} {:>8}   cells: {}; relaxed steps",
        "method",
        "success",
        names.join(" / ")
    );
    for (k, m) in a.methods.iter().enumerate() {
        let counts: Vec<String> = shown.clone().map(|c| a.count(k, c).to_string()).collect();
        let relaxed: usize = a.cells.iter().map(|c| c.outcomes[k].relaxed_steps).sum();
        let _ = writeln!(
            out,
            "{:<22} {:>8}   {}; {relaxed}",
            m.label(),
            a.success_rate(k)
                .map_or("–".into(), |r| format!("{:.1}%", 100.0 * r)),
            counts.join(" / ")
        );
    }
    let _ = writeln!(out, "\nsuccess: no collision, no joint past a limit and within 5 mm of the target, over the cells where avoidance is possible");
    emit(&out)
}
