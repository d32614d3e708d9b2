//! `redundant-ik figure`: the paper's stroboscopic figures (Figs. 2-11) as SVG,
//! drawn with plotters: the arm every few steps, the obstacle disc, the
//! straight-line path, start and end poses highlighted, axes in metres.

use std::path::{Path, PathBuf};

use clap::Args;
use plotters::prelude::*;
use redundant_ik::planner::methods;
use redundant_ik::{Method, Planner, Scene, Trajectory};

use super::simulate::{MethodArg, SceneArgs};

/// Options of `redundant-ik figure`.
#[derive(Args, Debug)]
pub struct FigureArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub method: MethodArg,
    /// Output SVG file, or with --all a directory.
    #[arg(long)]
    pub out: PathBuf,
    /// Write the whole set: both tasks in every available mode, plus the
    /// comparison figure of each task.
    #[arg(long)]
    pub all: bool,
    /// Instead of the arm: clearance and tracking error over time for every
    /// method on one figure.
    #[arg(long, conflicts_with = "all")]
    pub compare: bool,
    /// Draw the arm every this many steps.
    #[arg(long, default_value_t = 5)]
    pub every: usize,
}

/// Runs `redundant-ik figure`.
pub fn run(args: &FigureArgs) -> Result<(), String> {
    if args.every == 0 {
        return Err("--every must be at least 1".into());
    }
    if args.compare {
        let scene = args.scene.scene()?;
        let runs = run_all_modes(&args.scene, &scene)?;
        draw_compare(&args.out, args.scene.task, &scene, &runs)?;
        println!("wrote {}", args.out.display());
        return Ok(());
    }
    if !args.all {
        let (scene, traj) = args.scene.run(args.method.method)?;
        draw(&args.out, args.scene.task, &scene, &traj, args.every)?;
        println!("wrote {}", args.out.display());
        return Ok(());
    }
    std::fs::create_dir_all(&args.out)
        .map_err(|e| format!("cannot create directory {}: {e}", args.out.display()))?;
    for task in [1, 2] {
        let mut sa = args.scene.clone();
        sa.task = task;
        let scene = sa.scene()?;
        let runs = run_all_modes(&sa, &scene)?;
        for traj in &runs {
            let path = args.out.join(format!("task{task}_{}.svg", traj.method));
            draw(&path, task, &scene, traj, args.every)?;
            println!("wrote {}", path.display());
        }
        let path = args.out.join(format!("task{task}_compare.svg"));
        draw_compare(&path, task, &scene, &runs)?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// Runs `scene` with every method whose networks are available (the others
/// are skipped with a note on stderr).
fn run_all_modes(sa: &SceneArgs, scene: &Scene) -> Result<Vec<Trajectory>, String> {
    let mut runs = Vec::new();
    for &mode in methods::ALL {
        let nets = match sa.networks.for_method(mode) {
            Ok(n) => n,
            Err(e) => {
                eprintln!("skipping {mode}: {e}");
                continue;
            }
        };
        runs.push(Planner::run(scene.clone(), mode, nets).map_err(|e| e.to_string())?);
    }
    Ok(runs)
}

/// A legend swatch: a short line drawn in `style`.
fn swatch(style: ShapeStyle) -> impl Fn((i32, i32)) -> PathElement<(i32, i32)> {
    move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style)
}

/// Draws the series legend of `chart` at `position`, on a light box.
fn draw_legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    position: SeriesLabelPosition,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    chart
        .configure_series_labels()
        .position(position)
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(200, 200, 200))
        .draw()
}

/// Colour of a method in the comparison figure ([`Method::info`]'s).
fn mode_colour(method: Method) -> RGBColor {
    let hex = method.info().colour;
    let channel = |i: usize| u8::from_str_radix(hex.get(i..i + 2).unwrap_or("00"), 16).unwrap_or(0);
    RGBColor(channel(1), channel(3), channel(5))
}

/// Two stacked panels over time for every run: the clearance between the
/// obstacle centre and the nearest link (with the radius as a dashed line),
/// and the tracking error on a log scale.
fn draw_compare(path: &Path, task: u32, scene: &Scene, runs: &[Trajectory]) -> Result<(), String> {
    let e = |err: &dyn std::fmt::Display| format!("cannot draw {}: {err}", path.display());
    let root = SVGBackend::new(path, (820, 720)).into_drawing_area();
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let root = root
        .titled(
            &format!("Task {task}: the methods over time"),
            ("sans-serif", 18),
        )
        .map_err(|x| e(&x))?;
    let (top, bottom) = root.split_vertically(330);
    let tf = runs
        .iter()
        .filter_map(|r| r.steps.last().map(|s| s.t))
        .fold(0.0, f64::max)
        .max(1e-9);
    let radius = scene.obstacles.iter().map(|o| o.radius).fold(0.0, f64::max);

    // Clearance.
    let dmax = runs
        .iter()
        .flat_map(|r| r.steps.iter().filter_map(|s| s.distance))
        .fold(radius, f64::max)
        * 1.1;
    let mut chart = ChartBuilder::on(&top)
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..tf, 0.0..dmax)
        .map_err(|x| e(&x))?;
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc("clearance to O (m)")
        .light_line_style(RGBColor(246, 246, 246))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()
        .map_err(|x| e(&x))?;
    if radius > 0.0 {
        chart
            .draw_series(DashedLineSeries::new(
                vec![(0.0, radius), (tf, radius)],
                6,
                4,
                ShapeStyle::from(&RGBColor(214, 39, 40)).stroke_width(1),
            ))
            .map_err(|x| e(&x))?
            .label(format!("obstacle radius {radius} m"))
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RGBColor(214, 39, 40)));
    }
    for r in runs {
        let c = mode_colour(r.method);
        let min = r
            .summary
            .min_distance
            .map_or(String::new(), |d| format!(", min {d:.4} m"));
        chart
            .draw_series(LineSeries::new(
                r.steps.iter().filter_map(|s| s.distance.map(|d| (s.t, d))),
                ShapeStyle::from(&c).stroke_width(2),
            ))
            .map_err(|x| e(&x))?
            .label(format!("{}{min}", r.method.label()))
            .legend(swatch(ShapeStyle::from(&c).stroke_width(2)));
    }
    draw_legend(&mut chart, SeriesLabelPosition::UpperRight).map_err(|x| e(&x))?;

    // Tracking error, log scale (exact zeros drawn at the floor).
    const FLOOR: f64 = 1e-12;
    let emax = runs
        .iter()
        .flat_map(|r| r.steps.iter().map(|s| s.tracking_error))
        .fold(1e-6, f64::max)
        * 3.0;
    let mut chart = ChartBuilder::on(&bottom)
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(0.0..tf, (FLOOR..emax).log_scale())
        .map_err(|x| e(&x))?;
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc("tracking error (m)")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .light_line_style(RGBColor(246, 246, 246))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()
        .map_err(|x| e(&x))?;
    for r in runs {
        let c = mode_colour(r.method);
        chart
            .draw_series(LineSeries::new(
                r.steps.iter().map(|s| (s.t, s.tracking_error.max(FLOOR))),
                ShapeStyle::from(&c).stroke_width(2),
            ))
            .map_err(|x| e(&x))?
            .label(format!(
                "{}, final {:.1e} m",
                r.method.label(),
                r.summary.final_error
            ))
            .legend(swatch(ShapeStyle::from(&c).stroke_width(2)));
    }
    draw_legend(&mut chart, SeriesLabelPosition::LowerRight).map_err(|x| e(&x))?;
    root.present().map_err(|x| e(&x))?;
    Ok(())
}

fn draw(
    path: &Path,
    task: u32,
    scene: &Scene,
    traj: &Trajectory,
    every: usize,
) -> Result<(), String> {
    // World bounds: every joint of every drawn pose, the obstacles and the post.
    let (mut x0, mut x1, mut y0, mut y1) = (-0.2f64, 0.2f64, 0.0f64, 0.6f64);
    for s in &traj.steps {
        for p in &s.joints {
            x0 = x0.min(p[0]);
            x1 = x1.max(p[0]);
            y0 = y0.min(p[1]);
            y1 = y1.max(p[1]);
        }
    }
    for o in &scene.obstacles {
        x0 = x0.min(o.centre[0] - o.radius);
        x1 = x1.max(o.centre[0] + o.radius);
        y0 = y0.min(o.centre[1] - o.radius);
        y1 = y1.max(o.centre[1] + o.radius);
    }
    let pad = 0.1;
    let (x0, x1, y0, y1) = (x0 - pad, x1 + pad, y0 - pad, y1 + pad);
    // Equal scale on both axes: size the plot area in proportion.
    let plot_w = 720.0;
    let plot_h = plot_w * (y1 - y0) / (x1 - x0);
    let (ml, mr, mt, mb) = (70u32, 20u32, 50u32, 60u32);
    let w = plot_w as u32 + ml + mr;
    let h = plot_h as u32 + mt + mb;

    let root = SVGBackend::new(path, (w, h)).into_drawing_area();
    let e = |err: &dyn std::fmt::Display| format!("cannot draw {}: {err}", path.display());
    root.fill(&WHITE).map_err(|x| e(&x))?;
    let s = &traj.summary;
    let fig = traj
        .method
        .paper_figure(task)
        .map(|n| format!(" (paper Fig. {n})"))
        .unwrap_or_default();
    let verdict = match s.min_distance {
        Some(d) if s.collided => format!("collides, min distance {d:.4} m"),
        Some(d) => format!("min distance {d:.4} m"),
        None => "no obstacle".into(),
    };
    let title = format!(
        "Task {task}, {}{fig}: {verdict}, final error {:.1e} m",
        traj.method.title(),
        s.final_error
    );
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 17))
        .margin_top(10)
        .margin_right(mr)
        .x_label_area_size(mb - 10)
        .y_label_area_size(ml - 10)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|x| e(&x))?;
    chart
        .configure_mesh()
        .x_desc("X1 (m)")
        .y_desc("X2 (m)")
        .light_line_style(RGBColor(246, 246, 246))
        .bold_line_style(RGBColor(215, 215, 215))
        .draw()
        .map_err(|x| e(&x))?;

    // Obstacle discs, filled, with the centre point O.
    for o in &scene.obstacles {
        let c = (o.centre[0], o.centre[1]);
        let pts: Vec<(f64, f64)> = (0..=72)
            .map(|i| {
                let a = i as f64 / 72.0 * std::f64::consts::TAU;
                (c.0 + o.radius * a.cos(), c.1 + o.radius * a.sin())
            })
            .collect();
        chart
            .draw_series(std::iter::once(Polygon::new(
                pts,
                RGBColor(214, 39, 40).mix(0.35).filled(),
            )))
            .map_err(|x| e(&x))?;
        chart
            .draw_series(std::iter::once(Circle::new(
                c,
                2,
                RGBColor(214, 39, 40).filled(),
            )))
            .map_err(|x| e(&x))?;
    }
    // The post.
    chart
        .draw_series(LineSeries::new(
            vec![(0.0, 0.0), (0.0, scene.arm.post())],
            ShapeStyle::from(&BLACK).stroke_width(5),
        ))
        .map_err(|x| e(&x))?;
    // Intermediate poses, faint.
    let n = traj.steps.len();
    let grey = RGBColor(90, 110, 160);
    for (i, st) in traj.steps.iter().enumerate() {
        if i == 0 || i + 1 == n || i % every != 0 {
            continue;
        }
        let pts: Vec<(f64, f64)> = st.joints.iter().map(|p| (p[0], p[1])).collect();
        chart
            .draw_series(LineSeries::new(
                pts,
                ShapeStyle::from(&grey.mix(0.45)).stroke_width(1),
            ))
            .map_err(|x| e(&x))?;
    }
    // Straight-line path and the end-effector trace.
    let first = &traj.steps[0];
    chart
        .draw_series(LineSeries::new(
            vec![
                (first.ee[0], first.ee[1]),
                (scene.target[0], scene.target[1]),
            ],
            ShapeStyle::from(&RGBColor(44, 160, 44)).stroke_width(1),
        ))
        .map_err(|x| e(&x))?
        .label("straight-line task")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RGBColor(44, 160, 44)));
    chart
        .draw_series(LineSeries::new(
            traj.steps.iter().map(|s| (s.ee[0], s.ee[1])),
            ShapeStyle::from(&RGBColor(255, 127, 14)).stroke_width(2),
        ))
        .map_err(|x| e(&x))?
        .label("end effector")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], RGBColor(255, 127, 14)));
    // Start and end poses, highlighted, with joints.
    for (st, color, label) in [
        (first, RGBColor(31, 119, 180), "start pose"),
        (&traj.steps[n - 1], RGBColor(0, 0, 0), "final pose"),
    ] {
        let pts: Vec<(f64, f64)> = st.joints.iter().map(|p| (p[0], p[1])).collect();
        chart
            .draw_series(LineSeries::new(
                pts.clone(),
                ShapeStyle::from(&color).stroke_width(3),
            ))
            .map_err(|x| e(&x))?
            .label(label)
            .legend(swatch(ShapeStyle::from(&color).stroke_width(3)));
        chart
            .draw_series(pts.iter().map(|p| Circle::new(*p, 4, color.filled())))
            .map_err(|x| e(&x))?;
    }
    draw_legend(&mut chart, SeriesLabelPosition::LowerRight).map_err(|x| e(&x))?;
    root.present().map_err(|x| e(&x))?;
    Ok(())
}
