//! `redundant-ik atlas`: the task run with its obstacle on every cell of a
//! grid, in every method ([`redundant_ik::atlas`]); a table of success rates,
//! the whole map as JSON, and the heat maps as SVG.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};
use redundant_ik::atlas::{Atlas, Chunked, Class, Grid, Head, Job, Mapped, Spec, DEFAULT_GRID};
use redundant_ik::Method;

use super::simulate::SceneArgs;
use super::{emit, parse_list};

/// Options of `redundant-ik atlas`.
#[derive(Args, Debug)]
pub struct AtlasArgs {
    /// The scene (its first obstacle is moved over the grid; --obstacle
    /// places the canonical one that the map marks).
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Grid points per side (2 to 201).
    #[arg(long, default_value_t = DEFAULT_GRID)]
    pub grid: usize,
    /// Region x0,x1,y0,y1 in metres (default: the box of the arm's reach
    /// above the floor).
    #[arg(long, allow_hyphen_values = true)]
    pub region: Option<String>,
    /// Methods to map, comma-separated; `paper` (the default) for the
    /// paper's five, `all` for every method (for an arm in space the
    /// default is every method that runs in space).
    #[arg(long = "methods", alias = "modes")]
    pub methods: Option<String>,
    /// For an arm in space: the plane of the sphere's centres, xy:Z0, xz:Y0
    /// or yz:X0 (default: the vertical plane through the task's line).
    #[arg(long, allow_hyphen_values = true)]
    pub slice: Option<String>,
    /// Print the whole atlas as one JSON object instead of the table.
    #[arg(long, conflicts_with = "csv")]
    pub json: bool,
    /// Print the cells as CSV instead of the table: x, y, whether
    /// avoidance matters there, then each method's class, clearance and
    /// final error.
    #[arg(long)]
    pub csv: bool,
    /// Write the heat maps, one per method, as SVG.
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Threads to use (default: every core; 1 runs on this thread only).
    #[arg(long)]
    pub threads: Option<usize>,
}

/// Parses `--methods`: `paper`, `all` or a comma-separated list of method
/// names.
pub fn parse_methods(s: &str) -> Result<Vec<Method>, String> {
    Method::parse_list(s).map_err(|e| e.to_string())
}

/// Runs `redundant-ik atlas`.
pub fn run(args: &AtlasArgs) -> Result<(), String> {
    if args.slice.is_some() {
        return Err(
            "--slice chooses the plane of an atlas of an arm in space (--arm panda or iiwa14)"
                .into(),
        );
    }
    let scene = args.scene.scene()?;
    let methods = parse_methods(args.methods.as_deref().unwrap_or("paper"))?;
    let grid = match &args.region {
        Some(r) => match parse_list(r).map_err(|e| format!("--region: {e}"))?[..] {
            [x0, x1, y0, y1] => Grid::new([x0, x1, y0, y1], args.grid),
            _ => {
                return Err(format!(
                    "--region needs four numbers x0,x1,y0,y1, got '{r}'"
                ))
            }
        },
        None => Grid::new(Grid::around_reach(&scene.arm, args.grid).region, args.grid),
    }
    .map_err(|e| e.to_string())?;
    let networks = if methods.iter().any(|m| m.uses_networks()) {
        let run = args.scene.spec(Method::NUMERICAL)?;
        Some(run.load_networks().map_err(|e| e.to_string())?)
    } else {
        None
    };
    let spec = Spec {
        scene: scene.clone(),
        grid,
        methods,
        task: Some(args.scene.task()?),
    };
    let threads = threads(args)?;

    #[allow(clippy::disallowed_methods)] // the native CLI has a clock
    let start = Instant::now();
    let job = Job::new(spec, networks).map_err(|e| e.to_string())?;
    let atlas = compute(job, threads)?;
    let seconds = start.elapsed().as_secs_f64();

    if let Some(path) = &args.out {
        write_maps(path, redundant_ik::figure::atlas_svg(&atlas, &scene))?;
    }
    if args.csv {
        return emit(&redundant_ik::export::atlas_csv(&atlas));
    }
    if args.json {
        let json = serde_json::to_string(&atlas).map_err(|e| e.to_string())?;
        return emit(&format!("{json}\n"));
    }
    emit(&report(&atlas, seconds, threads))
}

/// Writes an atlas's maps (`--out`), or says why not.
pub(super) fn write_maps(
    path: &std::path::Path,
    svg: redundant_ik::Result<String>,
) -> Result<(), String> {
    let svg = svg.map_err(|e| e.to_string())?;
    std::fs::write(path, svg).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
    eprintln!("wrote {}", path.display());
    Ok(())
}

/// The threads of an atlas: `--threads`, or one per core.
pub(super) fn threads(args: &AtlasArgs) -> Result<usize, String> {
    match args.threads {
        Some(0) => Err("--threads must be at least 1".into()),
        Some(t) => Ok(t),
        None => Ok(std::thread::available_parallelism().map_or(1, |n| n.get())),
    }
}

/// Runs `job` (the planar atlas or a slice in space) to the end a row, or
/// a row per thread, at a time on `threads` threads, with a progress bar
/// on a terminal; stopped between rows where the user asks
/// ([`super::embed::interrupted`]).
pub(super) fn compute<A, const M: usize, const D: usize, H>(
    mut job: Chunked<A, M, D, H>,
    threads: usize,
) -> Result<H::Atlas, String>
where
    A: Mapped<M, D>,
    H: Head<D>,
{
    let row = job.row();
    let bar = ProgressBar::new(job.total() as u64).with_style(
        ProgressStyle::with_template("atlas {bar:40} {pos}/{len} cells, {eta} left")
            .map_err(|e| e.to_string())?,
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| format!("cannot start {threads} threads: {e}"))?;
    while !job.is_done() {
        if super::embed::interrupted() {
            return Err(super::embed::INTERRUPTED.into());
        }
        let done = if threads == 1 {
            job.advance(row)
        } else {
            pool.install(|| job.advance_parallel(row * threads))
        };
        bar.set_position(done as u64);
    }
    bar.finish_and_clear();
    job.finish().map_err(|e| e.to_string())
}

fn percent(rate: Option<f64>) -> String {
    rate.map_or("–".into(), |r| format!("{:.1}%", 100.0 * r))
}

/// The summary table.
fn report(a: &Atlas, seconds: f64, threads: usize) -> String {
    let mut out = String::new();
    macro_rules! w {
        ($($arg:tt)*) => {{
            let _ = writeln!(out, $($arg)*);
        }};
    }
    let [x0, x1, y0, y1] = a.grid.region;
    let runs = a.cells.len() * a.methods.len();
    w!(
        "Atlas of Task {}: {n} x {n} obstacle centres over x {x0}..{x1} m, y {y0}..{y1} m \
         (radius {} m, lambda {})",
        a.task.map_or("?".into(), |t| t.to_string()),
        a.radius,
        a.lambda,
        n = a.grid.n
    );
    w!(
        "{runs} runs in {seconds:.2} s on {threads} thread{}",
        if threads == 1 { "" } else { "s" }
    );
    w!();
    let region = a
        .trained_region
        .map(|r| format!("v net region x {}..{}, y {}..{}", r[0], r[1], r[2], r[3]));
    let width = a
        .summary
        .iter()
        .map(|s| s.method.label().chars().count())
        .fold("method".len(), usize::max);
    w!(
        "{:<width$} {:>8} {:>8} {:>8} {:>15}   {}",
        "method",
        "success",
        "inside",
        "outside",
        "clearance",
        "cells: success / collision / limit / missed / failed / path_blocked / start_overlap"
    );
    for s in &a.summary {
        // A planar arm has no self-collision to count.
        let counts: Vec<String> = Class::ALL
            .iter()
            .filter(|&&c| c != Class::SelfCollision)
            .map(|&c| s.count(c).to_string())
            .collect();
        let clearance = s
            .clearance
            .map_or("–".into(), |c| format!("{:.3} / {:.3}", c.median, c.p5));
        w!(
            "{:<width$} {:>8} {:>8} {:>8} {:>15}   {}",
            s.method.label(),
            percent(s.success_rate()),
            percent(s.inside_trained_region.and_then(|r| r.rate)),
            percent(s.outside_trained_region.and_then(|r| r.rate)),
            clearance,
            counts.join(" / ")
        );
    }
    w!();
    w!(
        "success: no collision and within 5 mm of the target (the path's end), over the {} cells where \
         avoidance is possible (not path_blocked or start_overlap)",
        a.summary.first().map_or(0, |s| s.avoidable.cells)
    );
    if let Some(r) = region {
        w!("inside / outside: the same, for obstacle centres inside / outside the {r}");
    }
    w!("clearance: the smallest link-to-disc clearance of the successful runs (m), median / 5th percentile");
    for s in &a.summary {
        if let Some(g) = s.agreement {
            w!(
                "{} vs numerical: numerical succeeds and {} does not in {} cells; the reverse in {}",
                s.method.label(),
                s.method.label(),
                g.numerical_only,
                g.method_only
            );
        }
    }
    out
}
