//! Runs and atlases as comma-separated values, one header line and one
//! line per step (or cell). Numbers are written in full (Rust's shortest
//! form that reads back to the same `f64`), so a spreadsheet and a
//! script see what the program computed.

use std::fmt::Write as _;

use crate::atlas::space::SliceAtlas;
use crate::atlas::Atlas;
use crate::planner::Sample;

/// The columns of a run's CSV after the hand's and the reference's
/// coordinates: the tracking error, the smallest link-to-obstacle
/// clearance (distance from a link to the nearest obstacle's surface,
/// negative inside it; empty without obstacles) and whether a link is
/// inside an obstacle (0 or 1).
pub const RUN_CSV_FIXED: [&str; 3] = ["tracking_error", "clearance", "collision"];

/// The coordinates' names, `x, y` in the plane, `x, y, z` in space and,
/// for the hand's pose, the rotation vector's `rx, ry, rz` after them.
const AXES: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];

/// A run of an arm whose hand has `M` coordinates as CSV: `t,
/// theta1..thetaN, x, y[, z], ref_x, ref_y[, ref_z], tracking_error,
/// clearance, collision`, one line per sample (`steps`, the start first);
/// for the hand's pose, its six coordinates, and the orientation error
/// (rad) after the tracking error.
pub fn run_csv<const M: usize, P>(steps: &[Sample<M, P>]) -> String {
    // A task with an orientation (the pose's) reports its error.
    let pose = steps.first().is_some_and(|s| s.orientation_error.is_some());
    let n = steps.first().map_or(0, |s| s.theta.len());
    let mut out = String::from("t");
    for i in 1..=n {
        let _ = write!(out, ",theta{i}");
    }
    for a in &AXES[..M] {
        let _ = write!(out, ",{a}");
    }
    for a in &AXES[..M] {
        let _ = write!(out, ",ref_{a}");
    }
    for c in RUN_CSV_FIXED {
        let _ = write!(out, ",{c}");
        if pose && c == "tracking_error" {
            out.push_str(",orientation_error");
        }
    }
    out.push('\n');
    for s in steps {
        let _ = write!(out, "{:?}", s.t);
        for v in s.theta.iter().chain(&s.ee).chain(&s.reference) {
            let _ = write!(out, ",{v:?}");
        }
        let _ = write!(out, ",{:?}", s.tracking_error);
        if pose {
            let _ = write!(out, ",{:?}", s.orientation_error.unwrap_or(f64::NAN));
        }
        let _ = write!(
            out,
            ",{},{}",
            s.clearance.map_or(String::new(), |c| format!("{c:?}")),
            u8::from(s.collision)
        );
        out.push('\n');
    }
    out
}

/// An atlas's cells as CSV: `x, y, avoidance_needed`, then for each method
/// its class, the run's smallest link-to-obstacle clearance (m) and its
/// final distance to the target (m); empty where nothing was run.
pub fn atlas_csv(atlas: &Atlas) -> String {
    let mut out = String::from("x,y,avoidance_needed");
    for m in &atlas.methods {
        let _ = write!(out, ",{m}_class,{m}_clearance,{m}_final_error");
    }
    out.push('\n');
    let num = |v: Option<f64>| v.map_or(String::new(), |v| format!("{v:?}"));
    for c in &atlas.cells {
        let needed = c.avoidance_needed.map_or("", |b| if b { "1" } else { "0" });
        let _ = write!(out, "{:?},{:?},{needed}", c.centre[0], c.centre[1]);
        for o in &c.outcomes {
            let clearance = o.min_distance.map(|d| d - atlas.radius);
            let _ = write!(
                out,
                ",{},{},{}",
                o.class.name(),
                num(clearance),
                num(o.final_error)
            );
        }
        out.push('\n');
    }
    out
}

/// A slice atlas as CSV (`redundant-ik atlas --arm A --csv`): the sphere's
/// centre `x, y, z`, then each method's class, smallest clearance (from a
/// capsule to the sphere's surface) and final error; empty where nothing
/// was measured.
pub fn slice_atlas_csv(atlas: &SliceAtlas) -> String {
    let mut out = String::from("x,y,z");
    for m in &atlas.methods {
        let _ = write!(out, ",{m},{m}_clearance,{m}_final_error");
    }
    out.push('\n');
    let num = |x: Option<f64>| x.map_or(String::new(), |v| v.to_string());
    for c in &atlas.cells {
        let _ = write!(out, "{},{},{}", c.centre[0], c.centre[1], c.centre[2]);
        for o in &c.outcomes {
            let _ = write!(
                out,
                ",{},{},{}",
                o.class.name(),
                num(o.min_clearance),
                num(o.final_error)
            );
        }
        out.push('\n');
    }
    out
}
