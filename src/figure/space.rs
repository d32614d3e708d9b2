//! The stroboscopic figure of a run of an arm in space: two orthographic
//! views side by side, an oblique one (azimuth -55 degrees, elevation 20: from the front left, the arm across the view)
//! and the view from above, each with the floor's grid, the fixed base,
//! the chain every few steps, the start and final poses, the hand's line
//! and trace, and the spheres (an orthographic view draws a sphere as a
//! circle of its radius, so the drawn gap between a capsule's outline and a
//! sphere is true where both lie across the line of sight).

use plotters::prelude::*;

use super::{colour, draw_legend, draw_title, svg, why, Area, Swatch, TITLE_HEIGHT};
use crate::error::Result;
use crate::planner::Method;
use crate::planner::Trajectory;
use crate::scene::SpaceScene;
use crate::space::manipulability::velocity_ellipsoid;
use crate::space::{SpacePose, Vec3};

/// An orthographic view: `(right, up)` screen axes in the world.
#[derive(Clone, Copy)]
struct View {
    right: Vec3,
    up: Vec3,
    name: &'static str,
}

impl View {
    /// The camera at azimuth `az` (from `+x` toward `+y`) and elevation
    /// `el` (degrees), looking at the origin.
    fn oblique(az: f64, el: f64) -> Self {
        let (a, e) = (az.to_radians(), el.to_radians());
        // Toward the camera: (cos e cos a, cos e sin a, sin e).
        let right = [-a.sin(), a.cos(), 0.0];
        let up = [-e.sin() * a.cos(), -e.sin() * a.sin(), e.cos()];
        Self {
            right,
            up,
            name: "oblique view",
        }
    }

    fn top() -> Self {
        Self {
            right: [1.0, 0.0, 0.0],
            up: [0.0, 1.0, 0.0],
            name: "from above (x right, y up)",
        }
    }

    fn project(&self, p: Vec3) -> (f64, f64) {
        let d = |a: Vec3| a[0] * p[0] + a[1] * p[1] + a[2] * p[2];
        (d(self.right), d(self.up))
    }
}

/// The chain's points at `theta` (base, each distinct origin, the flange).
pub(super) fn points(scene: &SpaceScene, theta: &[f64]) -> Result<Vec<Vec3>> {
    let pose = SpacePose::new(&scene.arm, theta)?;
    let mut out = vec![pose.points()[0]];
    for s in scene.arm.segments() {
        out.push(pose.segment(s).1);
    }
    Ok(out)
}

/// The caption line under a figure of a run of an arm in space (the arm
/// called `arm`), as [`super::caption`] writes a planar run's: the method,
/// the arm, the path, the joint weighting, the floor, the gains, the
/// spheres, the loop, the networks' settings, `dt` and `tf`.
pub fn space_caption(arm: &str, scene: &SpaceScene, method: Method) -> String {
    let mut parts = vec![method.label().to_string(), arm.to_string()];
    if !scene.path.is_line() {
        parts.push(super::shortened_path(scene.path.to_string()));
    }
    if !scene.weighting.is_none() {
        parts.push(format!("joint weighting {}", scene.weighting));
    }
    if scene.floor {
        parts.push("the floor is an obstacle".into());
    }
    parts.extend(super::gains(&scene.params, scene.damping.is_some()));
    match &scene.obstacles[..] {
        [] => parts.push("no sphere".into()),
        [one] => parts.push(format!("a sphere of radius {} m", one.radius)),
        all => {
            let radii: Vec<String> = all.iter().map(|o| o.radius.to_string()).collect();
            parts.push(format!(
                "{} spheres, radii {} m",
                all.len(),
                radii.join(", ")
            ));
        }
    }
    parts.extend(super::settings(&scene.params, method, scene.feedback_gain));
    parts.push(format!("dt = {} s, tf = {} s", scene.dt, scene.tf));
    parts.join(" · ")
}

/// The figure of `run` (of `scene`, the arm called `arm`) as SVG, the chain
/// drawn every `every` steps.
pub fn space_svg(
    arm: &str,
    scene: &SpaceScene,
    run: &Trajectory<3>,
    every: usize,
) -> Result<String> {
    space_svg_with(arm, scene, run, every, false)
}

/// The three principal ellipses of the velocity ellipsoid `{J theta_dot :
/// |theta_dot| <= 1}` of `scene`'s chain at `theta`, at the hand, drawn at
/// [`super::ELLIPSE_SCALE`] (the plane's [`super::ellipse_outline`] in
/// space; [`crate::space::manipulability::velocity_ellipsoid`]).
pub fn ellipsoid_rings(scene: &SpaceScene, theta: &[f64]) -> Result<[Vec<Vec3>; 3]> {
    let pose = SpacePose::new(&scene.arm, theta)?;
    let (axes, half) = velocity_ellipsoid(pose.jjt());
    let hand = pose.hand();
    Ok([(0, 1), (0, 2), (1, 2)].map(|(a, b)| {
        (0..=96)
            .map(|k| {
                let t = k as f64 / 96.0 * std::f64::consts::TAU;
                let (u, w) = (
                    super::ELLIPSE_SCALE * half[a] * t.cos(),
                    super::ELLIPSE_SCALE * half[b] * t.sin(),
                );
                std::array::from_fn(|i| hand[i] + u * axes[a][i] + w * axes[b][i])
            })
            .collect()
    }))
}

/// [`space_svg`], with the velocity ellipsoid's principal ellipses at the
/// final pose when `ellipsoid` is set (`figure --ellipse`).
pub fn space_svg_with(
    arm: &str,
    scene: &SpaceScene,
    run: &Trajectory<3>,
    every: usize,
    ellipsoid: bool,
) -> Result<String> {
    let every = every.max(1);
    let rings = match (ellipsoid, run.steps.last()) {
        (true, Some(last)) => Some(ellipsoid_rings(scene, &last.theta)?),
        _ => None,
    };
    let poses: Vec<Vec<Vec3>> = run
        .steps
        .iter()
        .map(|s| points(scene, &s.theta))
        .collect::<Result<_>>()?;
    let s = &run.summary;
    let verdict = match s.min_clearance {
        Some(c) if s.collision_steps > 0 => format!("collides, min clearance {c:.4} m"),
        Some(c) => format!("min clearance {c:.4} m"),
        None => "no sphere".into(),
    };
    let limits = if s.limit_steps > 0 {
        format!(", past a joint limit in {} steps", s.limit_steps)
    } else {
        String::new()
    };
    // A run of the hand's pose ([`super::pose`]) says so, with the
    // orientation's final error.
    let (task, turn) = match s.final_orientation_error {
        Some(r) => (", the hand's pose", format!(", {r:.1e} rad")),
        None => ("", String::new()),
    };
    let head = format!(
        "{arm}, {}{task}: {verdict}{limits}, final error {:.1e} m{turn}",
        run.method.label(),
        s.final_error
    );
    let size = (1100u32, 620u32);
    svg(size, |root| {
        let (head_area, body) = root.split_vertically(TITLE_HEIGHT);
        draw_title(&head_area, &head, run.method.description())?;
        let (left, right) = body.split_horizontally(size.0 / 2);
        let drawn = Drawn {
            scene,
            run,
            poses: &poses,
            every,
            rings: rings.as_ref(),
        };
        panel(&left, View::oblique(-55.0, 20.0), &drawn)?;
        panel(&right, View::top(), &drawn)?;
        let mut legend = vec![
            (
                Swatch::Dashed(colour::MUTED, 1),
                "the hand's line".to_string(),
            ),
            (Swatch::Line(RGBColor(255, 127, 14), 2), "hand".into()),
            (Swatch::Line(RGBColor(31, 119, 180), 3), "start pose".into()),
            (Swatch::Line(BLACK, 3), "final pose".into()),
            (
                Swatch::Line(RGBColor(90, 110, 160), 1),
                format!("every {every}th pose"),
            ),
        ];
        if rings.is_some() {
            legend.push((
                Swatch::Line(VELOCITY, 2),
                "manipulability ellipsoid at 1/4 scale".into(),
            ));
        }
        let (w, h) = body.dim_in_pixel();
        draw_legend(
            &body,
            &legend,
            (w as i32 - 10, h as i32 - 17 * legend.len() as i32 - 20),
            true,
        )
    })
}

/// What both views draw: the scene, the run, its poses' points, every
/// how many steps a pose is drawn, the ellipsoid's rings if asked for.
struct Drawn<'a> {
    scene: &'a SpaceScene,
    run: &'a Trajectory<3>,
    poses: &'a [Vec<Vec3>],
    every: usize,
    rings: Option<&'a [Vec<Vec3>; 3]>,
}

/// The colour of the manipulability ellipsoid (the plane's ellipse's).
const VELOCITY: RGBColor = RGBColor(46, 125, 50);

/// One view: its bounds from everything drawn, equal scales, then the
/// floor grid, the spheres, the poses and the line.
fn panel(area: &Area<'_>, view: View, d: &Drawn<'_>) -> std::result::Result<(), String> {
    let Drawn {
        scene,
        run,
        poses,
        every,
        rings,
    } = *d;
    let mut pts: Vec<(f64, f64)> = poses.iter().flatten().map(|p| view.project(*p)).collect();
    for sp in &scene.obstacles {
        let (u, v) = view.project(sp.centre);
        pts.extend([
            (u - sp.radius, v - sp.radius),
            (u + sp.radius, v + sp.radius),
        ]);
    }
    for ring in rings.into_iter().flatten() {
        pts.extend(ring.iter().map(|p| view.project(*p)));
    }
    let g = 0.6;
    for corner in [[-g, -g, 0.0], [g, -g, 0.0], [-g, g, 0.0], [g, g, 0.0]] {
        pts.push(view.project(corner));
    }
    let (mut u0, mut u1, mut v0, mut v1) = pts.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), &(u, v)| (a.min(u), b.max(u), c.min(v), d.max(v)),
    );
    // Equal scales: widen the shorter side.
    let (w, h) = area.dim_in_pixel();
    let (pw, ph) = (w as f64 - 40.0, h as f64 - 60.0);
    let scale = (pw / (u1 - u0)).min(ph / (v1 - v0));
    let (cu, cv) = (0.5 * (u0 + u1), 0.5 * (v0 + v1));
    (u0, u1) = (cu - 0.5 * pw / scale, cu + 0.5 * pw / scale);
    (v0, v1) = (cv - 0.5 * ph / scale, cv + 0.5 * ph / scale);
    let mut chart = ChartBuilder::on(area)
        .margin(20)
        .caption(
            view.name,
            ("sans-serif", 13).into_font().color(&colour::MUTED),
        )
        .build_cartesian_2d(u0..u1, v0..v1)
        .map_err(why)?;
    // The floor's grid, 0.1 m apart, over +-0.6 m.
    let steps = 12;
    for k in 0..=steps {
        let t = -g + 2.0 * g * k as f64 / steps as f64;
        for line in [[[t, -g, 0.0], [t, g, 0.0]], [[-g, t, 0.0], [g, t, 0.0]]] {
            chart
                .draw_series(LineSeries::new(
                    line.iter().map(|p| view.project(*p)),
                    colour::LIGHT.stroke_width(1),
                ))
                .map_err(why)?;
        }
    }
    // The spheres, filled.
    for sp in &scene.obstacles {
        let (u, v) = view.project(sp.centre);
        let outline: Vec<(f64, f64)> = (0..=72)
            .map(|i| {
                let a = i as f64 / 72.0 * std::f64::consts::TAU;
                (u + sp.radius * a.cos(), v + sp.radius * a.sin())
            })
            .collect();
        chart
            .draw_series(std::iter::once(Polygon::new(
                outline,
                colour::DANGER.mix(0.35).filled(),
            )))
            .map_err(why)?;
    }
    // Intermediate poses, faint; the base, thick.
    let n = poses.len();
    let faint = RGBColor(90, 110, 160).mix(0.45);
    for (i, p) in poses.iter().enumerate() {
        if i == 0 || i + 1 == n || i % every != 0 {
            continue;
        }
        chart
            .draw_series(LineSeries::new(
                p.iter().map(|q| view.project(*q)),
                faint.stroke_width(1),
            ))
            .map_err(why)?;
    }
    if let Some(first) = poses.first() {
        chart
            .draw_series(LineSeries::new(
                first[..2].iter().map(|q| view.project(*q)),
                BLACK.stroke_width(6),
            ))
            .map_err(why)?;
    }
    // The path (a circle through 96 chords) and the hand's trace.
    let outline = scene.path.outline(scene.start(), scene.target, 96);
    chart
        .draw_series(DashedLineSeries::new(
            outline.iter().map(|q| view.project(*q)),
            5,
            4,
            colour::MUTED.stroke_width(1),
        ))
        .map_err(why)?;
    chart
        .draw_series(LineSeries::new(
            run.steps.iter().map(|s| view.project(s.ee)),
            RGBColor(255, 127, 14).stroke_width(2),
        ))
        .map_err(why)?;
    for (p, c) in [(&poses[0], RGBColor(31, 119, 180)), (&poses[n - 1], BLACK)] {
        let q: Vec<(f64, f64)> = p.iter().map(|x| view.project(*x)).collect();
        chart
            .draw_series(LineSeries::new(q.clone(), c.stroke_width(3)))
            .map_err(why)?;
        chart
            .draw_series(q.iter().map(|x| Circle::new(*x, 3, c.filled())))
            .map_err(why)?;
    }
    for ring in rings.into_iter().flatten() {
        chart
            .draw_series(LineSeries::new(
                ring.iter().map(|x| view.project(*x)),
                VELOCITY.stroke_width(2),
            ))
            .map_err(why)?;
    }
    Ok(())
}
