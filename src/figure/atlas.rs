//! The atlas as SVG: one heat map per method, side by side, the cells
//! coloured by class; on top the arm's start pose, the path (the straight
//! line, a circle or a polyline) and its end, the canonical obstacle and the v network's trained region;
//! below, the legend of the classes. Each panel's title gives its success
//! rate, over the cells where avoidance is possible and over those where it
//! mattered (the arm without avoidance collides there).
//!
//! One drawing for every arm ([`Maps`]): the planar atlas over the arm's
//! plane ([`atlas_svg`]), and the slice atlas of an arm in space over its
//! plane ([`slice_svg`]), whose marks are the arm, the path and the task's
//! sphere seen square to the slice.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::colour::MUTED;
use super::{hex, svg, text_size, why};
use crate::atlas::space::SliceAtlas;
use crate::atlas::{summarise, Atlas, Class, Grid, MethodSummary};
use crate::error::{Result, Short};
use crate::kinematics::Pose;
use crate::scene::{Scene, SpaceScene};

const INK: RGBColor = RGBColor(31, 41, 51);
const ARM: RGBColor = RGBColor(29, 78, 137);
const ACCENT: RGBColor = RGBColor(217, 115, 26);
const REGION: RGBColor = RGBColor(255, 255, 255);

/// Plot width of one panel in pixels (the height follows the region's aspect).
const PANEL_W: f64 = 330.0;

type Pt = (f64, f64);

/// The part of segment `a`-`b` inside the box `[x0, x1] x [y0, y1]`
/// (Liang-Barsky), if any: plotters does not clip what lies outside a
/// chart's range, it pins it to the edge.
fn clip(a: Pt, b: Pt, [x0, x1, y0, y1]: [f64; 4]) -> Option<(Pt, Pt)> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - x0),
        (dx, x1 - a.0),
        (-dy, a.1 - y0),
        (dy, y1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then_some((
        (a.0 + t0 * dx, a.1 + t0 * dy),
        (a.0 + t1 * dx, a.1 + t1 * dy),
    ))
}

/// The pieces of a polyline inside the box, each as long as it can be.
fn clip_polyline(points: &[Pt], bounds: [f64; 4]) -> Vec<Vec<Pt>> {
    let mut pieces: Vec<Vec<Pt>> = Vec::new();
    for (a, b) in points.windows(2).filter_map(|w| clip(w[0], w[1], bounds)) {
        match pieces.last_mut() {
            Some(piece) if piece.last() == Some(&a) => piece.push(b),
            _ => pieces.push(vec![a, b]),
        }
    }
    pieces
}

fn inside(p: Pt, [x0, x1, y0, y1]: [f64; 4]) -> bool {
    (x0..=x1).contains(&p.0) && (y0..=y1).contains(&p.1)
}

/// What the maps of an atlas draw, whatever the arm: the grid, each
/// method's cells and summary, and the scene's marks in the grid's
/// coordinates.
struct Maps<'a> {
    title: String,
    grid: &'a Grid,
    summary: &'a [MethodSummary],
    /// Cell `index`'s class in method `m`: `class(index, m)`.
    class: &'a dyn Fn(usize, usize) -> Class,
    /// The axes' names, `[x, y]`.
    axes: [&'a str; 2],
    /// The classes the legend lists.
    classes: Vec<Class>,
    trained_region: Option<[f64; 4]>,
    /// The path from the hand's start, and its end.
    path: Vec<Pt>,
    end: Pt,
    /// The planar arm's post: the top of the line from the origin.
    post: Option<f64>,
    /// The arm's points at t = 0, from its base.
    arm: Vec<Pt>,
    /// The task's own obstacle: its centre and radius.
    ring: Option<(Pt, f64)>,
    /// The two lines under the legend that say what the marks are.
    marks: [String; 2],
}

/// The classes a legend lists: the limit class only for an arm with
/// limits, self-collision only for one that checks it (no other can have
/// either).
fn legend_classes(limited: bool, checks_self: bool) -> Vec<Class> {
    Class::ALL
        .into_iter()
        .filter(|&c| c != Class::Limit || limited)
        .filter(|&c| c != Class::SelfCollision || checks_self)
        .collect()
}

/// What the orange mark is: the line to the target, or the path to its end.
fn path_mark(label: Option<String>) -> String {
    match label {
        None => "orange: the straight line to the target (+)".to_string(),
        Some(label) => format!("orange: the {label} to its end (+)"),
    }
}

/// The maps of `atlas` (computed on `scene`) as SVG, one panel per method.
pub fn atlas_svg(atlas: &Atlas, scene: &Scene) -> Result<String> {
    let start = Pose::new(&scene.arm, &scene.theta0)?;
    let ee = start.end_effector();
    let end = scene.path_end();
    let task = atlas.task.map_or(String::new(), |t| format!("Task {t}: "));
    let n = atlas.grid.n;
    let class = |index: usize, m: usize| atlas.cells[index].outcomes[m].class;
    draw(&Maps {
        title: format!(
            "{task}where the arm stays clear, obstacle (r = {} m) centred on each of {n} x {n} cells, λ = {}",
            atlas.radius, atlas.lambda
        ),
        grid: &atlas.grid,
        summary: &atlas.summary,
        class: &class,
        axes: ["obstacle X1 (m)", "X2 (m)"],
        classes: legend_classes(scene.arm.joint_limits().is_some(), false),
        trained_region: atlas.trained_region,
        path: scene
            .path
            .outline(ee, scene.target, 128)
            .into_iter()
            .map(|p| (p[0], p[1]))
            .collect(),
        end: (end[0], end[1]),
        post: Some(scene.arm.post()),
        arm: start.joints().iter().map(|p| (p[0], p[1])).collect(),
        ring: scene
            .obstacles
            .first()
            .map(|o| ((o.centre[0], o.centre[1]), o.radius)),
        marks: [
            format!(
                "blue: the arm at t = 0 · {}",
                path_mark((!scene.path.is_line()).then(|| super::path_label(&scene.path)))
            ),
            "black ring: the task's own obstacle · white dashes: where the v network saw obstacles in training".to_string(),
        ],
    })
}

/// The maps of a slice atlas of the arm in space `arm` (its name), computed
/// on `scene` (the hand's position, or `pose`: the scene of the position
/// the pose task extends), as SVG, one panel per method: the sphere centred
/// on each cell of the slice; the arm at t = 0, the path and the task's own
/// sphere drawn as seen square to the slice (a sphere's outline is a
/// circle of its radius there).
pub fn slice_svg(atlas: &SliceAtlas, scene: &SpaceScene, arm: &str, pose: bool) -> Result<String> {
    let plane = atlas.plane;
    let on = |p: [f64; 3]| plane.coordinates(p);
    let joints = super::space::points(scene, &scene.theta0)?;
    let summary = summarise(&atlas.methods, &atlas.cells, None, atlas.radius);
    let n = atlas.grid.n;
    let class = |index: usize, m: usize| atlas.cells[index].outcomes[m].class;
    let [u, v] = plane.axes();
    let (x_axis, y_axis) = (format!("sphere {u} (m)"), format!("{v} (m)"));
    let path = (!scene.path.is_line()).then(|| {
        let text = scene.path.to_string();
        super::shortened_path(text)
    });
    draw(&Maps {
        title: format!(
            "{arm}{}: where the arm stays clear, sphere (r = {} m) centred on each of {n} x {n} cells of the slice {plane}",
            if pose { ", the hand's pose" } else { "" },
            Short(atlas.radius)
        ),
        grid: &atlas.grid,
        summary: &summary,
        class: &class,
        axes: [&x_axis, &y_axis],
        classes: legend_classes(
            scene.arm.joint_limits().is_some(),
            !scene.arm.self_pairs().is_empty(),
        ),
        trained_region: None,
        path: scene
            .path
            .outline(scene.start(), scene.target, 128)
            .into_iter()
            .map(on)
            .collect(),
        end: on(scene.path_end()),
        post: None,
        arm: joints.into_iter().map(on).collect(),
        ring: scene.obstacles.first().map(|o| (on(o.centre), o.radius)),
        marks: [
            format!("blue: the arm at t = 0, seen square to the slice · {}", path_mark(path)),
            "black ring: the task's own sphere, seen square to the slice".to_string(),
        ],
    })
}

fn draw(maps: &Maps<'_>) -> Result<String> {
    let [x0, x1, y0, y1] = maps.grid.region;
    let n = maps.grid.n;
    let (dx, dy) = ((x1 - x0) / (n - 1) as f64, (y1 - y0) / (n - 1) as f64);
    // The map covers each cell centre's cell.
    let (wx0, wx1, wy0, wy1) = (x0 - dx / 2.0, x1 + dx / 2.0, y0 - dy / 2.0, y1 + dy / 2.0);
    let plot_h = (PANEL_W * (wy1 - wy0) / (wx1 - wx0)).clamp(80.0, 900.0);
    let (ml, mr, mt, mb) = (52u32, 14u32, 44u32, 40u32);
    let panel_w = PANEL_W as u32 + ml + mr;
    let panel_h = plot_h as u32 + mt + mb;
    let k = maps.summary.len() as u32;
    // The legend of the classes, wrapped to the figure's width.
    let width = (panel_w * k).max(560) as i32;
    let mut places = Vec::new();
    let (mut x, mut y) = (14, 10);
    for &class in &maps.classes {
        let w = 36 + text_size(class.label(), 13.0).0 as i32;
        if x > 14 && x + w > width - 14 {
            (x, y) = (14, y + 22);
        }
        places.push((class, x, y));
        x += w;
    }
    let marks_y = y + 26;
    let (title_h, legend_h) = (36u32, marks_y as u32 + 42);
    let size = (width as u32, title_h + panel_h + legend_h);

    svg(size, |root| {
        let (head, rest) = root.split_vertically(title_h);
        head.draw(&Text::new(
            maps.title.as_str(),
            (12, 10),
            ("sans-serif", 17).into_font().color(&INK),
        ))
        .map_err(why)?;
        let (panels_area, legend) = rest.split_vertically(panel_h);
        let panels = panels_area.split_evenly((1, k as usize));

        let bounds = [wx0, wx1, wy0, wy1];

        for (m, (area, summary)) in panels.iter().zip(maps.summary).enumerate() {
            let rate = summary
                .success_rate()
                .map_or("–".into(), |r| format!("{:.0}%", 100.0 * r));
            let caption = format!(
                "{}: {rate} clear and reached ({}/{})",
                summary.method.label(),
                summary.avoidable.successes,
                summary.avoidable.cells
            );
            let mattered = &summary.mattered;
            let needed = format!(
                "where avoidance mattered: {} ({}/{})",
                mattered
                    .rate
                    .map_or("–".into(), |r| format!("{:.0}%", 100.0 * r)),
                mattered.successes,
                mattered.cells
            );
            let (head, area) = area.split_vertically(42);
            let centre = |size: f64, colour: &'static RGBColor| {
                TextStyle::from(("sans-serif", size).into_font())
                    .color(colour)
                    .pos(Pos::new(HPos::Center, VPos::Top))
            };
            let mid = head.dim_in_pixel().0 as i32 / 2;
            head.draw(&Text::new(caption, (mid, 4), centre(14.0, &INK)))
                .map_err(why)?;
            head.draw(&Text::new(needed, (mid, 23), centre(12.0, &MUTED)))
                .map_err(why)?;
            let mut chart = ChartBuilder::on(&area)
                .margin_top(2)
                .margin_right(mr)
                .x_label_area_size(mb - 8)
                .y_label_area_size(ml - 8)
                .build_cartesian_2d(wx0..wx1, wy0..wy1)
                .map_err(why)?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_labels(5)
                .y_labels(5)
                .x_desc(maps.axes[0])
                .y_desc(maps.axes[1])
                .label_style(("sans-serif", 11))
                .draw()
                .map_err(why)?;

            // Cells, as runs of one class along each row (fewer SVG elements).
            let mut rects = Vec::new();
            for j in 0..n {
                let mut i = 0;
                while i < n {
                    let class = (maps.class)(j * n + i, m);
                    let mut end = i + 1;
                    while end < n && (maps.class)(j * n + end, m) == class {
                        end += 1;
                    }
                    let (cx0, cx1) = (maps.grid.x(i) - dx / 2.0, maps.grid.x(end - 1) + dx / 2.0);
                    let cy = maps.grid.y(j);
                    rects.push(Rectangle::new(
                        [(cx0, cy - dy / 2.0), (cx1, cy + dy / 2.0)],
                        hex(class.colour()).filled(),
                    ));
                    i = end;
                }
            }
            chart.draw_series(rects).map_err(why)?;

            // Where the v network saw obstacle centres in training.
            if let Some([rx0, rx1, ry0, ry1]) = maps.trained_region {
                let edges = [(rx0, ry0), (rx1, ry0), (rx1, ry1), (rx0, ry1), (rx0, ry0)];
                for piece in clip_polyline(&edges, bounds) {
                    chart
                        .draw_series(DashedLineSeries::new(
                            piece,
                            4,
                            3,
                            ShapeStyle::from(&REGION).stroke_width(1),
                        ))
                        .map_err(why)?;
                }
            }
            // The path (the straight line, a circle or a polyline) and
            // its end (the target, for the line).
            let target = maps.end;
            for piece in clip_polyline(&maps.path, bounds) {
                chart
                    .draw_series(DashedLineSeries::new(
                        piece,
                        5,
                        4,
                        ShapeStyle::from(&ACCENT).stroke_width(2),
                    ))
                    .map_err(why)?;
            }
            if inside(target, bounds) {
                chart
                    .draw_series(std::iter::once(Cross::new(
                        target,
                        5,
                        ShapeStyle::from(&ACCENT).stroke_width(2),
                    )))
                    .map_err(why)?;
            }
            // The post and the start pose.
            for piece in maps.post.map_or_else(Vec::new, |top| {
                clip_polyline(&[(0.0, 0.0), (0.0, top)], bounds)
            }) {
                chart
                    .draw_series(LineSeries::new(
                        piece,
                        ShapeStyle::from(&INK).stroke_width(4),
                    ))
                    .map_err(why)?;
            }
            for piece in clip_polyline(&maps.arm, bounds) {
                chart
                    .draw_series(LineSeries::new(
                        piece,
                        ShapeStyle::from(&ARM).stroke_width(3),
                    ))
                    .map_err(why)?;
            }
            chart
                .draw_series(
                    maps.arm
                        .iter()
                        .filter(|p| inside(**p, bounds))
                        .map(|p| Circle::new(*p, 2, WHITE.filled())),
                )
                .map_err(why)?;
            // The canonical obstacle, outlined at its true size.
            if let Some((centre, radius)) = maps.ring {
                let ring: Vec<Pt> = (0..=48)
                    .map(|t| {
                        let a = t as f64 / 48.0 * std::f64::consts::TAU;
                        (centre.0 + radius * a.cos(), centre.1 + radius * a.sin())
                    })
                    .collect();
                for piece in clip_polyline(&ring, bounds) {
                    chart
                        .draw_series(LineSeries::new(
                            piece,
                            ShapeStyle::from(&INK).stroke_width(2),
                        ))
                        .map_err(why)?;
                }
            }
        }

        // Legend of the classes, and of the marks.
        let font = ("sans-serif", 13).into_font().color(&INK);
        for (class, x, y) in places {
            legend
                .draw(&Rectangle::new(
                    [(x, y), (x + 16, y + 16)],
                    hex(class.colour()).filled(),
                ))
                .map_err(why)?;
            legend
                .draw(&Text::new(class.label(), (x + 22, y + 2), font.clone()))
                .map_err(why)?;
        }
        for (k, line) in maps.marks.iter().enumerate() {
            legend
                .draw(&Text::new(
                    line.as_str(),
                    (14, marks_y + 18 * k as i32),
                    font.clone(),
                ))
                .map_err(why)?;
        }
        Ok(())
    })
}
