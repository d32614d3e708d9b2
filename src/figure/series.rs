//! Time series: a run's plots (the page's three panels: the clearance
//! between the links and the nearest obstacle's edge, tracking error,
//! joint angles), and every method of a scene over time (clearance and
//! tracking error, `redundant-ik figure --compare`).

use std::ops::Range;

use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

use super::{
    caption, caption_lines, colour, draw_caption, draw_legend, draw_title, hex, svg, why, Area,
    Swatch, TITLE_HEIGHT,
};
use crate::error::Result;
use crate::planner::{Method, Trajectory};
use crate::scene::Scene;

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

/// A run's time series as SVG: the clearance between the links and the
/// nearest obstacle's edge (0, contact, dashed), tracking error and joint
/// angles, one panel each, and the caption line.
pub fn series_svg(task: u32, scene: &Scene, run: &Trajectory) -> Result<String> {
    let size = (820u32, 760u32);
    let t1 = run.steps.last().map_or(0.0, |s| s.t).max(1e-9);
    let head = format!("Task {task}, {} over time", run.method.label());
    let (lines, foot_height) = caption_lines(&caption(task, scene, run.method), size.0);
    let size = (size.0, size.1 - 30 + foot_height);
    svg(size, |root| {
        let (head_area, root) = root.split_vertically(TITLE_HEIGHT);
        draw_title(&head_area, &head, run.method.description())?;
        let h = root.dim_in_pixel().1;
        let (panels, foot) = root.split_vertically(h - foot_height);
        draw_caption(&foot, &lines)?;
        let areas = panels.split_evenly((3, 1));

        // Clearance to the nearest obstacle's edge (0: contact), as the
        // page's plots and readouts give it.
        let clearance: Vec<(f64, f64)> = run
            .steps
            .iter()
            .filter_map(|s| s.clearance.map(|c| (s.t, c)))
            .collect();
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
            let legend = [
                (Swatch::Line(colour::ARM, 2), "nearest link".to_string()),
                (Swatch::Dashed(colour::DANGER, 1), "contact".to_string()),
            ];
            let (w, _) = areas[0].dim_in_pixel();
            draw_legend(&areas[0], &legend, (w as i32 - 24, 16), true)?;
        }

        let error: Vec<(f64, f64)> = run.steps.iter().map(|s| (s.t, s.tracking_error)).collect();
        let emax = error.iter().map(|p| p.1).fold(1e-3, f64::max) * 1.1;
        let mut chart = panel(&areas[1], 0.0..t1, 0.0..emax, "tracking error (m)")?;
        chart
            .draw_series(LineSeries::new(error, colour::ACCENT.stroke_width(2)))
            .map_err(why)?;

        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in run.steps.iter().flat_map(|s| &s.theta) {
            lo = lo.min(*v);
            hi = hi.max(*v);
        }
        if !(lo.is_finite() && hi.is_finite()) {
            (lo, hi) = (-std::f64::consts::PI, std::f64::consts::PI);
        }
        let pad = ((hi - lo) * 0.1).max(0.1);
        let mut chart = panel(&areas[2], 0.0..t1, lo - pad..hi + pad, "joint angles (rad)")?;
        let joints = scene.arm.dof();
        let mut legend = Vec::new();
        for i in 0..joints {
            let c = colour::joint(i);
            chart
                .draw_series(LineSeries::new(
                    run.steps
                        .iter()
                        .filter_map(|s| s.theta.get(i).map(|v| (s.t, *v))),
                    c.stroke_width(2),
                ))
                .map_err(why)?;
            legend.push((Swatch::Line(c, 2), format!("θ{}", i + 1)));
        }
        let (w, _) = areas[2].dim_in_pixel();
        draw_legend(&areas[2], &legend, (w as i32 - 24, 16), true)
    })
}

/// Colour of a method ([`Method::info`]'s).
fn method_colour(method: Method) -> RGBColor {
    hex(method.info().colour)
}

/// Every run of one scene over time, as SVG: the clearance between the
/// links and the nearest obstacle's edge (0, contact, dashed), and the
/// tracking error on a log scale.
pub fn compare_svg(task: u32, scene: &Scene, runs: &[Trajectory]) -> Result<String> {
    let tf = runs
        .iter()
        .filter_map(|r| r.steps.last().map(|s| s.t))
        .fold(0.0, f64::max)
        .max(1e-9);
    let has_obstacle = !scene.obstacles.is_empty();
    let title = format!("Task {task}: the methods over time");
    let line = caption(
        task,
        scene,
        runs.first().map_or(Method::NUMERICAL, |r| r.method),
    );
    let line = line
        .split_once(" · ")
        .map_or(line.clone(), |(_, rest)| rest.to_string());
    let (lines, foot_height) = caption_lines(&line, 820);
    svg((820, 720 + foot_height), |root| {
        let root = root.titled(&title, ("sans-serif", 18)).map_err(why)?;
        let h = root.dim_in_pixel().1;
        let (charts, foot) = root.split_vertically(h - foot_height);
        draw_caption(&foot, &lines)?;
        let (top, bottom) = charts.split_vertically(330);

        // Clearance to the nearest obstacle's edge (0: contact).
        let (lo, hi) = clearance_range(
            runs.iter()
                .flat_map(|r| r.steps.iter().filter_map(|s| s.clearance)),
        );
        let mut chart = panel(&top, 0.0..tf, lo..hi, "clearance to obstacle (m)")?;
        let mut legend = Vec::new();
        if has_obstacle {
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(0.0, 0.0), (tf, 0.0)],
                    6,
                    4,
                    colour::DANGER.stroke_width(1),
                ))
                .map_err(why)?;
            legend.push((Swatch::Dashed(colour::DANGER, 1), "contact".to_string()));
        }
        for r in runs {
            let c = method_colour(r.method);
            let min = r
                .summary
                .min_clearance
                .map_or(String::new(), |d| format!(", min {d:.4} m"));
            chart
                .draw_series(LineSeries::new(
                    r.steps.iter().filter_map(|s| s.clearance.map(|d| (s.t, d))),
                    c.stroke_width(2),
                ))
                .map_err(why)?;
            legend.push((Swatch::Line(c, 2), format!("{}{min}", r.method.label())));
        }
        let (w, _) = top.dim_in_pixel();
        draw_legend(&top, &legend, (w as i32 - 24, 16), true)?;

        // Tracking error, log scale (exact zeros drawn at the floor).
        const FLOOR: f64 = 1e-12;
        let emax = runs
            .iter()
            .flat_map(|r| r.steps.iter().map(|s| s.tracking_error))
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
        let mut legend = Vec::new();
        for r in runs {
            let c = method_colour(r.method);
            chart
                .draw_series(LineSeries::new(
                    r.steps.iter().map(|s| (s.t, s.tracking_error.max(FLOOR))),
                    c.stroke_width(2),
                ))
                .map_err(why)?;
            legend.push((
                Swatch::Line(c, 2),
                format!(
                    "{}, final {:.1e} m",
                    r.method.label(),
                    r.summary.final_error
                ),
            ));
        }
        let (w, h) = bottom.dim_in_pixel();
        let top_of_legend = h as i32 - 48 - 17 * legend.len() as i32 - 10;
        draw_legend(&bottom, &legend, (w as i32 - 24, top_of_legend), true)
    })
}
