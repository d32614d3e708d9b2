//! The paper's stroboscopic figure of a run (Figs. 2-11): the arm every
//! few steps, the obstacle discs, the path (the straight line, a circle or
//! a polyline) and the hand's trace, the start and final poses highlighted,
//! axes in metres; on request the manipulability ellipse at the final pose.

use plotters::prelude::*;

use super::{
    caption, caption_lines, colour, draw_caption, draw_legend, draw_title, svg, why, Swatch,
    TITLE_HEIGHT,
};
use crate::error::Result;
use crate::kinematics::{velocity_ellipse, Pose};
use crate::planner::Trajectory;
use crate::scene::Scene;

/// The drawn scale of the manipulability ellipse (its half-lengths are the
/// singular values of `J`, m per rad/s), as on the page.
pub const ELLIPSE_SCALE: f64 = 0.25;

/// The figure of `run` (of `scene`, from paper task `task`) as SVG, the
/// arm drawn every `every` steps (at least 1).
pub fn arm_svg(task: u32, scene: &Scene, run: &Trajectory, every: usize) -> Result<String> {
    arm_svg_with(task, scene, run, every, false)
}

/// The outline of the manipulability ellipse `{J theta_dot : |theta_dot|
/// <= 1}` at the pose `theta` of `scene`'s arm, centred at its hand and
/// drawn at [`ELLIPSE_SCALE`] ([`velocity_ellipse`]: axes the eigenvectors
/// of `J J^T`, half-lengths the square roots of its eigenvalues).
pub fn ellipse_outline(scene: &Scene, theta: &[f64]) -> Result<Vec<(f64, f64)>> {
    let pose = Pose::new(&scene.arm, theta)?;
    let (axes, half) = velocity_ellipse(pose.jjt());
    let [cx, cy] = pose.end_effector();
    let (a, b) = (ELLIPSE_SCALE * half[0], ELLIPSE_SCALE * half[1]);
    Ok((0..=72)
        .map(|i| {
            let t = i as f64 / 72.0 * std::f64::consts::TAU;
            let (u, v) = (a * t.cos(), b * t.sin());
            (
                cx + u * axes[0][0] + v * axes[1][0],
                cy + u * axes[0][1] + v * axes[1][1],
            )
        })
        .collect())
}

/// [`arm_svg`], with the manipulability ellipse at the final pose when
/// `ellipse` is set (`figure --ellipse`).
pub fn arm_svg_with(
    task: u32,
    scene: &Scene,
    run: &Trajectory,
    every: usize,
    ellipse: bool,
) -> Result<String> {
    let every = every.max(1);
    let outline = match (ellipse, run.steps.last()) {
        (true, Some(last)) => ellipse_outline(scene, &last.theta)?,
        _ => Vec::new(),
    };
    // World bounds: every joint of every drawn pose, the obstacles and the post.
    let (mut x0, mut x1, mut y0, mut y1) = (-0.2f64, 0.2f64, 0.0f64, 0.6f64);
    for s in &run.steps {
        for p in &s.joints {
            x0 = x0.min(p[0]);
            x1 = x1.max(p[0]);
            y0 = y0.min(p[1]);
            y1 = y1.max(p[1]);
        }
    }
    for &(x, y) in &outline {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
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
    let plot_h = (plot_w * (y1 - y0) / (x1 - x0)).clamp(120.0, 2000.0);
    let (ml, mr, mt, mb, foot) = (70u32, 20u32, 50u32, 60u32, 30u32);
    let size = (plot_w as u32 + ml + mr, plot_h as u32 + mt + mb + foot);

    let s = &run.summary;
    // The paper's figure only for the paper's scene (the damping schedule
    // aside, which the page switches on): a moved obstacle or target is
    // another run.
    let paper_scene = crate::scene::Scene::task(task).is_ok_and(|mut paper| {
        paper.damping = scene.damping;
        &paper == scene
    });
    let fig = run
        .method
        .paper_figure(task)
        .filter(|_| paper_scene)
        .map(|n| format!(" (paper Fig. {n})"))
        .unwrap_or_default();
    // The clearance to the obstacles' edges, as the page and the tables give it.
    let verdict = match s.min_clearance {
        Some(c) if s.collided => format!("collides, min clearance {c:.4} m"),
        Some(c) => format!("min clearance {c:.4} m"),
        None => "no obstacle".into(),
    };
    let head = format!(
        "Task {task}, {}{fig}: {verdict}, final error {:.1e} m",
        run.method.label(),
        s.final_error
    );
    let (lines, foot) = caption_lines(&caption(task, scene, run.method), size.0);
    let size = (size.0, size.1 - 30 + foot);
    svg(size, |root| {
        let (plot, foot_area) = root.split_vertically(size.1 - foot);
        draw_caption(&foot_area, &lines)?;
        let (head_area, plot) = plot.split_vertically(TITLE_HEIGHT);
        draw_title(&head_area, &head, run.method.description())?;
        let mut chart = ChartBuilder::on(&plot)
            .margin_top(2)
            .margin_right(mr)
            .x_label_area_size(mb - 10)
            .y_label_area_size(ml - 10)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(why)?;
        chart
            .configure_mesh()
            .x_desc("X1 (m)")
            .y_desc("X2 (m)")
            .light_line_style(colour::LIGHT)
            .bold_line_style(colour::BOLD)
            .draw()
            .map_err(why)?;

        // The floor, where the post stands: a link below it is visible.
        chart
            .draw_series(LineSeries::new(
                vec![(x0, 0.0), (x1, 0.0)],
                colour::MUTED.stroke_width(1),
            ))
            .map_err(why)?;
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
                    colour::DANGER.mix(0.35).filled(),
                )))
                .map_err(why)?;
            chart
                .draw_series(std::iter::once(Circle::new(c, 2, colour::DANGER.filled())))
                .map_err(why)?;
        }
        // The post.
        chart
            .draw_series(LineSeries::new(
                vec![(0.0, 0.0), (0.0, scene.arm.post())],
                BLACK.stroke_width(5),
            ))
            .map_err(why)?;
        // Intermediate poses, faint.
        let n = run.steps.len();
        let faint = RGBColor(90, 110, 160).mix(0.45);
        for (i, st) in run.steps.iter().enumerate() {
            if i == 0 || i + 1 == n || i % every != 0 {
                continue;
            }
            let pts: Vec<(f64, f64)> = st.joints.iter().map(|p| (p[0], p[1])).collect();
            chart
                .draw_series(LineSeries::new(pts, faint.stroke_width(1)))
                .map_err(why)?;
        }
        // The path (the straight line, a circle or a polyline) and the
        // end-effector trace.
        let Some(first) = run.steps.first() else {
            return Err("a run without samples".into());
        };
        let path = RGBColor(44, 160, 44);
        let track = scene.path.outline(first.ee, scene.target, 128);
        chart
            .draw_series(LineSeries::new(
                track.iter().map(|p| (p[0], p[1])),
                path.stroke_width(1),
            ))
            .map_err(why)?;
        let trace = RGBColor(255, 127, 14);
        chart
            .draw_series(LineSeries::new(
                run.steps.iter().map(|s| (s.ee[0], s.ee[1])),
                trace.stroke_width(2),
            ))
            .map_err(why)?;
        // Start and final poses, highlighted, with joints.
        let start = RGBColor(31, 119, 180);
        for (st, c) in [(first, start), (&run.steps[n - 1], BLACK)] {
            let pts: Vec<(f64, f64)> = st.joints.iter().map(|p| (p[0], p[1])).collect();
            chart
                .draw_series(LineSeries::new(pts.clone(), c.stroke_width(3)))
                .map_err(why)?;
            chart
                .draw_series(pts.iter().map(|p| Circle::new(*p, 4, c.filled())))
                .map_err(why)?;
        }
        let velocity = RGBColor(46, 125, 50);
        if !outline.is_empty() {
            chart
                .draw_series(LineSeries::new(outline, velocity.stroke_width(2)))
                .map_err(why)?;
        }
        let mut legend = vec![
            (Swatch::Line(path, 1), super::path_label(&scene.path)),
            (Swatch::Line(trace, 2), "end effector".into()),
            (Swatch::Line(start, 3), "start pose".into()),
            (Swatch::Line(BLACK, 3), "final pose".into()),
            (
                Swatch::Line(RGBColor(90, 110, 160), 1),
                format!("every {every}th pose"),
            ),
        ];
        if ellipse {
            legend.push((
                Swatch::Line(velocity, 2),
                "manipulability ellipse at 1/4 scale".into(),
            ));
        }
        let (w, h) = plot.dim_in_pixel();
        let bottom = h as i32 - mb as i32 - 10 - 17 * legend.len() as i32 - 10;
        draw_legend(&plot, &legend, (w as i32 - mr as i32 - 8, bottom), true)
    })
}
