//! Time series: a run's plots (the page's three panels: the clearance
//! between the links and the nearest obstacle's edge, tracking error,
//! joint angles), and every method of a scene over time (clearance and
//! tracking error, `redundant-ik figure --compare`). One drawing for every
//! arm: a planar run and a run in space are read into the same samples
//! (`Step`), their titles and captions each arm's own.

use std::ops::Range;

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::space::space_caption;
use super::{
    caption, caption_lines, colour, draw_caption, draw_legend, draw_title, hex, legend_width, svg,
    why, Area, Swatch, TITLE_HEIGHT,
};
use crate::error::Result;
use crate::planner::{Method, Sample, Trajectory};
use crate::scene::{Scene, SpaceScene};

type Chart<'a, 'b> =
    ChartContext<'a, super::Measured<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The vertical range of a clearance panel: from below 0 (contact, or the
/// deepest a link went inside) to above the largest clearance.
fn clearance_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((0.0f64, 1e-3f64), |(lo, hi), c| (lo.min(c), hi.max(c)));
    let pad = 0.08 * (hi - lo);
    (lo - pad, hi + pad)
}

/// One panel over `t` with a light mesh.
fn panel<'a, 'b>(
    area: &'a Area<'b>,
    t: Range<f64>,
    y: Range<f64>,
    y_desc: &str,
) -> std::result::Result<Chart<'a, 'b>, String> {
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(36)
        .y_label_area_size(70)
        .build_cartesian_2d(t, y)
        .map_err(why)?;
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc(y_desc)
        .light_line_style(colour::LIGHT)
        .bold_line_style(colour::BOLD)
        .draw()
        .map_err(why)?;
    Ok(chart)
}

/// The width of the charts of [`series_svg`] and [`compare_svg`]; their
/// legends get a column of their own to the right (issue 27: drawn inside
/// a chart, a legend covered curves: the θ3 curve, and in the comparison
/// of ten methods most of the later half of the run).
const CHARTS_WIDTH: u32 = 820;

/// The width of the legends' column for `legends`, with its margins.
fn legend_column(legends: &[&[(Swatch, String)]]) -> u32 {
    legends
        .iter()
        .map(|l| legend_width(l))
        .max()
        .unwrap_or(0)
        .max(0) as u32
        + 20
}

/// One sample as the plots read it, for any arm: the time, the clearance
/// between the links and the nearest obstacle's edge, the tracking error
/// and the joint angles.
struct Step<'a> {
    t: f64,
    clearance: Option<f64>,
    error: f64,
    /// The orientation's error (rad), for a run of the hand's pose.
    orientation: Option<f64>,
    theta: &'a [f64],
}

/// One run as the comparison reads it, for any arm: the method, its
/// smallest clearance and final error, and its samples.
struct Run<'a> {
    method: Method,
    min_clearance: Option<f64>,
    final_error: f64,
    steps: Vec<Step<'a>>,
}

impl<'a> Run<'a> {
    fn of<const M: usize>(run: &'a Trajectory<M>) -> Self {
        Self {
            method: run.method,
            min_clearance: run.summary.min_clearance,
            final_error: run.summary.final_error,
            steps: steps(&run.steps),
        }
    }
}

/// The samples of any arm's run, as the plots read them.
fn steps<const M: usize>(samples: &[Sample<M>]) -> Vec<Step<'_>> {
    samples
        .iter()
        .map(|s| Step {
            t: s.t,
            clearance: s.clearance,
            error: s.tracking_error,
            orientation: s.orientation_error,
            theta: &s.theta,
        })
        .collect()
}

/// A run's time series as SVG: the clearance between the links and the
/// nearest obstacle's edge (0, contact, dashed), tracking error and joint
/// angles, one panel each with its legend beside it, and the caption line.
pub fn series_svg(task: u32, scene: &Scene, run: &Trajectory) -> Result<String> {
    let head = format!("Task {task}, {} over time", run.method.label());
    let line = caption(task, scene, run.method);
    plots_svg(
        &head,
        &line,
        run.method,
        &steps(&run.steps),
        scene.arm.dof(),
    )
}

/// The time series of a run of an arm in space (the arm called `arm`), as
/// [`series_svg`] draws a planar run's: the page in space's plots and
/// `redundant-ik figure --arm A --plots`.
pub fn space_series_svg(arm: &str, scene: &SpaceScene, run: &Trajectory<3>) -> Result<String> {
    let head = format!("{arm}, {} over time", run.method.label());
    let line = space_caption(arm, scene, run.method);
    plots_svg(
        &head,
        &line,
        run.method,
        &steps(&run.steps),
        scene.arm.dof(),
    )
}

/// The plots of a run of the hand's pose (its samples' hand and reference
/// as points, [`super::pose`]): an arm in space's, the orientation's error
/// beside the position's; `line` the caption.
pub(super) fn pose_plots_svg(
    arm: &str,
    run: &Trajectory<3>,
    joints: usize,
    line: &str,
) -> Result<String> {
    let head = format!("{arm}, {} over time (the hand's pose)", run.method.label());
    plots_svg(&head, line, run.method, &steps(&run.steps), joints)
}

/// The three panels of [`series_svg`] for any arm: `head` the title,
/// `line` the caption, `joints` the number of joint curves.
fn plots_svg(
    head: &str,
    line: &str,
    method: Method,
    steps: &[Step<'_>],
    joints: usize,
) -> Result<String> {
    let t1 = steps.last().map_or(0.0, |s| s.t).max(1e-9);
    // Clearance to the nearest obstacle's edge (0: contact), as the
    // page's plots and readouts give it.
    let clearance: Vec<(f64, f64)> = steps
        .iter()
        .filter_map(|s| s.clearance.map(|c| (s.t, c)))
        .collect();
    let clearance_legend = if clearance.is_empty() {
        Vec::new()
    } else {
        vec![
            (Swatch::Line(colour::ARM, 2), "nearest link".to_string()),
            (Swatch::Dashed(colour::DANGER, 1), "contact".to_string()),
        ]
    };
    let joint_legend: Vec<(Swatch, String)> = (0..joints)
        .map(|i| (Swatch::Line(colour::joint(i), 2), format!("θ{}", i + 1)))
        .collect();
    // The hand's pose: its orientation's error beside its position's.
    let turn: Vec<(f64, f64)> = steps
        .iter()
        .filter_map(|s| s.orientation.map(|r| (s.t, r)))
        .collect();
    let error_legend = if turn.is_empty() {
        Vec::new()
    } else {
        vec![
            (Swatch::Line(colour::ACCENT, 2), "position (m)".to_string()),
            (
                Swatch::Line(colour::ARM, 2),
                "orientation (rad)".to_string(),
            ),
        ]
    };
    let column = legend_column(&[&clearance_legend, &joint_legend, &error_legend]);
    let size = (CHARTS_WIDTH + column, 760u32);
    let (lines, foot_height) = caption_lines(line, size.0);
    let size = (size.0, size.1 - 30 + foot_height);
    svg(size, |root| {
        let (head_area, root) = root.split_vertically(TITLE_HEIGHT);
        draw_title(&head_area, head, method.description())?;
        let h = root.dim_in_pixel().1;
        let (panels, foot) = root.split_vertically(h - foot_height);
        draw_caption(&foot, &lines)?;
        let (panels, legends) = panels.split_horizontally(CHARTS_WIDTH);
        let areas = panels.split_evenly((3, 1));
        let keys = legends.split_evenly((3, 1));

        let (lo, hi) = clearance_range(clearance.iter().map(|p| p.1));
        let mut chart = panel(&areas[0], 0.0..t1, lo..hi, "clearance to obstacle (m)")?;
        if !clearance.is_empty() {
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(0.0, 0.0), (t1, 0.0)],
                    6,
                    4,
                    colour::DANGER.stroke_width(1),
                ))
                .map_err(why)?;
            chart
                .draw_series(LineSeries::new(clearance, colour::ARM.stroke_width(2)))
                .map_err(why)?;
            draw_legend(&keys[0], &clearance_legend, LEGEND_AT, false)?;
        }

        let error: Vec<(f64, f64)> = steps.iter().map(|s| (s.t, s.error)).collect();
        let emax = error.iter().chain(&turn).map(|p| p.1).fold(1e-3, f64::max) * 1.1;
        let label = match turn.is_empty() {
            true => "tracking error (m)",
            false => "tracking error (m, rad)",
        };
        let mut chart = panel(&areas[1], 0.0..t1, 0.0..emax, label)?;
        chart
            .draw_series(LineSeries::new(error, colour::ACCENT.stroke_width(2)))
            .map_err(why)?;
        if !turn.is_empty() {
            chart
                .draw_series(LineSeries::new(turn, colour::ARM.stroke_width(2)))
                .map_err(why)?;
            draw_legend(&keys[1], &error_legend, LEGEND_AT, false)?;
        }

        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in steps.iter().flat_map(|s| s.theta) {
            lo = lo.min(*v);
            hi = hi.max(*v);
        }
        if !(lo.is_finite() && hi.is_finite()) {
            (lo, hi) = (-std::f64::consts::PI, std::f64::consts::PI);
        }
        let pad = ((hi - lo) * 0.1).max(0.1);
        let mut chart = panel(&areas[2], 0.0..t1, lo - pad..hi + pad, "joint angles (rad)")?;
        for i in 0..joints {
            chart
                .draw_series(LineSeries::new(
                    steps
                        .iter()
                        .filter_map(|s| s.theta.get(i).map(|v| (s.t, *v))),
                    colour::joint(i).stroke_width(2),
                ))
                .map_err(why)?;
        }
        draw_legend(&keys[2], &joint_legend, LEGEND_AT, false)
    })
}

/// Where a legend's box starts in its column: level with the chart's top
/// (the charts' margin is 12 px).
const LEGEND_AT: (i32, i32) = (4, 12);

/// Every run of one scene over time, as SVG: the clearance between the
/// links and the nearest obstacle's edge (0, contact, dashed), and the
/// tracking error on a log scale, each with its legend beside it.
pub fn compare_svg(task: u32, scene: &Scene, runs: &[Trajectory]) -> Result<String> {
    let title = format!("Task {task}: the methods over time");
    let line = caption(
        task,
        scene,
        runs.first().map_or(Method::NUMERICAL, |r| r.method),
    );
    let runs: Vec<Run<'_>> = runs.iter().map(Run::of).collect();
    compare_of(&title, &line, !scene.obstacles.is_empty(), &runs)
}

/// Every run of one scene of an arm in space (the arm called `arm`) over
/// time, as [`compare_svg`] draws a planar scene's: `redundant-ik figure
/// --arm A --compare`.
pub fn space_compare_svg(arm: &str, scene: &SpaceScene, runs: &[Trajectory<3>]) -> Result<String> {
    let title = format!("{arm}: the methods over time");
    let line = space_caption(
        arm,
        scene,
        runs.first().map_or(Method::NUMERICAL, |r| r.method),
    );
    let runs: Vec<Run<'_>> = runs.iter().map(Run::of).collect();
    compare_of(&title, &line, !scene.obstacles.is_empty(), &runs)
}

/// The two panels of [`compare_svg`] for any arm: `line` the caption of
/// the first run (its method's part left out).
fn compare_of(title: &str, line: &str, has_obstacle: bool, runs: &[Run<'_>]) -> Result<String> {
    let tf = runs
        .iter()
        .filter_map(|r| r.steps.last().map(|s| s.t))
        .fold(0.0, f64::max)
        .max(1e-9);
    let mut clearance_legend = Vec::new();
    if has_obstacle {
        clearance_legend.push((Swatch::Dashed(colour::DANGER, 1), "contact".to_string()));
    }
    for r in runs {
        let min = r
            .min_clearance
            .map_or(String::new(), |d| format!(", min {d:.4} m"));
        clearance_legend.push((
            Swatch::Line(method_colour(r.method), 2),
            format!("{}{min}", r.method.label()),
        ));
    }
    let error_legend: Vec<(Swatch, String)> = runs
        .iter()
        .map(|r| {
            (
                Swatch::Line(method_colour(r.method), 2),
                format!("{}, final {:.1e} m", r.method.label(), r.final_error),
            )
        })
        .collect();
    let width = CHARTS_WIDTH + legend_column(&[&clearance_legend, &error_legend]);
    let line = line
        .split_once(" · ")
        .map_or(line.to_string(), |(_, rest)| rest.to_string());
    let (lines, foot_height) = caption_lines(&line, width);
    svg((width, 720 + foot_height), |root| {
        let root = root.titled(title, ("sans-serif", 18)).map_err(why)?;
        let h = root.dim_in_pixel().1;
        let (charts, foot) = root.split_vertically(h - foot_height);
        draw_caption(&foot, &lines)?;
        let (charts, legends) = charts.split_horizontally(CHARTS_WIDTH);
        let (top, bottom) = charts.split_vertically(330);
        let (top_key, bottom_key) = legends.split_vertically(330);

        // Clearance to the nearest obstacle's edge (0: contact).
        let (lo, hi) = clearance_range(
            runs.iter()
                .flat_map(|r| r.steps.iter().filter_map(|s| s.clearance)),
        );
        let mut chart = panel(&top, 0.0..tf, lo..hi, "clearance to obstacle (m)")?;
        if has_obstacle {
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(0.0, 0.0), (tf, 0.0)],
                    6,
                    4,
                    colour::DANGER.stroke_width(1),
                ))
                .map_err(why)?;
        }
        for r in runs {
            chart
                .draw_series(LineSeries::new(
                    r.steps.iter().filter_map(|s| s.clearance.map(|d| (s.t, d))),
                    method_colour(r.method).stroke_width(2),
                ))
                .map_err(why)?;
        }
        draw_legend(&top_key, &clearance_legend, LEGEND_AT, false)?;

        // Tracking error, log scale (exact zeros drawn at the floor).
        const FLOOR: f64 = 1e-12;
        let emax = runs
            .iter()
            .flat_map(|r| r.steps.iter().map(|s| s.error))
            .fold(1e-6, f64::max)
            * 3.0;
        let mut chart = ChartBuilder::on(&bottom)
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..tf, (FLOOR..emax).log_scale())
            .map_err(why)?;
        chart
            .configure_mesh()
            .x_desc("t (s)")
            .y_desc("tracking error (m)")
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .light_line_style(colour::LIGHT)
            .bold_line_style(colour::BOLD)
            .draw()
            .map_err(why)?;
        for r in runs {
            chart
                .draw_series(LineSeries::new(
                    r.steps.iter().map(|s| (s.t, s.error.max(FLOOR))),
                    method_colour(r.method).stroke_width(2),
                ))
                .map_err(why)?;
        }
        draw_legend(&bottom_key, &error_legend, LEGEND_AT, false)
    })
}

/// Colour of a method ([`Method::info`]'s).
fn method_colour(method: Method) -> RGBColor {
    hex(method.info().colour)
}
