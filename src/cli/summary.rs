//! The lines a run's summary shares for every arm in space, whatever its
//! task: the spheres, the smallest clearances (from the spheres and
//! between the chain's own capsules), the steps past a limit and the
//! relaxed programs.

use std::fmt::Write as _;

use redundant_ik::planner::Summary;
use redundant_ik::space::{Chain, Sphere};

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
