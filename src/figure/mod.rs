//! The figures as SVG, drawn with plotters, one code for the command-line
//! tool (`redundant-ik figure`, `redundant-ik atlas --out`) and the page
//! (its workers' module draws the very same figure for "Save figure"):
//! the paper's stroboscopic drawing of a run (`arm`), a run's time series
//! (`series`: the page's plots, and every method over time) and the
//! atlas's maps (`atlas`). Feature `figure` (on with the tool and the
//! workers' module; the page's own module carries none of it).
//!
//! Text is laid out here, not by plotters' fonts: in WebAssembly plotters
//! measures text through the document, which a Web Worker does not have
//! (it would panic), and natively it guesses from the byte count. The
//! `Measured` backend measures with one table of glyph widths on both,
//! so the command line and the page write the same bytes, and the legends
//! are drawn here too (plotters' own legend measures through the fonts).

mod arm;
mod atlas;
mod pose;
mod series;
mod space;

use plotters::prelude::*;
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind,
};

use crate::error::{Error, Result, Short};
use crate::planner::Method;
use crate::scene::{Params, Scene};

pub use arm::{arm_svg, arm_svg_with, ellipse_outline, ELLIPSE_SCALE};
pub use atlas::{atlas_svg, slice_svg};
pub use pose::{pose_compare_svg, pose_series_svg, pose_svg, PoseRun};
pub use series::{compare_svg, series_svg, space_compare_svg, space_series_svg};
pub use space::{ellipsoid_rings, space_caption, space_svg, space_svg_with};

/// Colours of the figures.
pub(crate) mod colour {
    use crate::palette::{self, rgb};
    use plotters::style::RGBColor;
    const fn of(hex: &str) -> RGBColor {
        let (r, g, b) = rgb(hex);
        RGBColor(r, g, b)
    }
    pub const INK: RGBColor = of(palette::INK);
    pub const MUTED: RGBColor = of(palette::MUTED);
    pub const ARM: RGBColor = of(palette::ARM);
    pub const ACCENT: RGBColor = of(palette::ACCENT);
    pub const DANGER: RGBColor = of(palette::DANGER);
    pub const LIGHT: RGBColor = RGBColor(246, 246, 246);
    pub const BOLD: RGBColor = RGBColor(215, 215, 215);
    pub const FRAME: RGBColor = RGBColor(200, 200, 200);
    /// Joint `i`'s series ([`palette::joint_series`]).
    pub fn joint(i: usize) -> RGBColor {
        of(palette::joint_series(i))
    }
}

/// Width of a glyph of the sans-serif fonts, in ems (Helvetica's metrics,
/// rounded): enough to lay out labels and legends the same everywhere.
fn glyph_width(c: char) -> f64 {
    match c {
        'i' | 'j' | 'l' | '.' | ',' | ':' | ';' | '\'' | '|' | '!' | ' ' | 'I' => 0.28,
        'f' | 't' | 'r' | '(' | ')' | '[' | ']' | '-' | '/' => 0.34,
        'm' | 'w' | 'M' | 'W' | '@' => 0.84,
        '0'..='9' | 'a'..='z' | '+' | '=' | '<' | '>' | '_' | '~' => 0.56,
        'A'..='Z' | '%' | '&' => 0.68,
        _ => 0.62,
    }
}

/// The size in pixels of `text` at a plotters font size `size` (the SVG
/// backend writes `font-size: size / 1.24`).
pub(crate) fn text_size(text: &str, size: f64) -> (u32, u32) {
    let em = size / 1.24;
    let width: f64 = text.chars().map(glyph_width).sum::<f64>() * em;
    (width.ceil() as u32, (em * 1.2).ceil() as u32)
}

/// The SVG backend with text measured by [`text_size`] (see the module
/// documentation); everything else is the SVG backend's.
pub(crate) struct Measured<'a>(SVGBackend<'a>);

type Failure = DrawingErrorKind<std::io::Error>;

impl DrawingBackend for Measured<'_> {
    type ErrorType = std::io::Error;
    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }
    fn ensure_prepared(&mut self) -> std::result::Result<(), Failure> {
        self.0.ensure_prepared()
    }
    fn present(&mut self) -> std::result::Result<(), Failure> {
        self.0.present()
    }
    fn draw_pixel(&mut self, p: BackendCoord, c: BackendColor) -> std::result::Result<(), Failure> {
        self.0.draw_pixel(p, c)
    }
    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> std::result::Result<(), Failure> {
        self.0.draw_line(from, to, style)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        a: BackendCoord,
        b: BackendCoord,
        style: &S,
        fill: bool,
    ) -> std::result::Result<(), Failure> {
        self.0.draw_rect(a, b, style, fill)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> std::result::Result<(), Failure> {
        self.0.draw_path(path, style)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        centre: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> std::result::Result<(), Failure> {
        self.0.draw_circle(centre, radius, style, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> std::result::Result<(), Failure> {
        self.0.fill_polygon(vert, style)
    }
    fn draw_text<T: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &T,
        pos: BackendCoord,
    ) -> std::result::Result<(), Failure> {
        self.0.draw_text(text, style, pos)
    }
    fn estimate_text_size<T: BackendTextStyle>(
        &self,
        text: &str,
        style: &T,
    ) -> std::result::Result<(u32, u32), Failure> {
        Ok(text_size(text, style.size()))
    }
}

/// The drawing area figures are drawn on.
pub(crate) type Area<'a> = DrawingArea<Measured<'a>, plotters::coord::Shift>;

/// Draws a figure of `size` pixels with `draw` and returns its SVG text.
pub(crate) fn svg(
    size: (u32, u32),
    draw: impl FnOnce(&Area<'_>) -> std::result::Result<(), String>,
) -> Result<String> {
    let mut out = String::new();
    {
        let root = Measured(SVGBackend::with_string(&mut out, size)).into_drawing_area();
        root.fill(&WHITE).map_err(fail)?;
        draw(&root).map_err(Error::Figure)?;
        root.present().map_err(fail)?;
    }
    Ok(out)
}

/// A plotters error as the crate's.
pub(crate) fn fail(e: impl std::fmt::Display) -> Error {
    Error::Figure(e.to_string())
}

/// A plotters error as text, inside a figure's drawing.
pub(crate) fn why(e: impl std::fmt::Display) -> String {
    e.to_string()
}

/// The caption line under a run's figures: what was run, with which
/// settings, so that a figure in a report says how it was made.
pub fn caption(task: u32, scene: &Scene, method: Method) -> String {
    let mut parts = vec![method.label().to_string(), format!("Task {task}")];
    if !scene.path.is_line() {
        parts.push(path_label(&scene.path));
    }
    if !scene.arm.same_geometry(&crate::arm::Arm::paper()) {
        parts.push(format!("arm {}", scene.arm));
    }
    // Limits in short decimals (a preset's are radians to 17 digits).
    if let Some(l) = scene.arm.joint_limits() {
        let ranges: Vec<String> = l
            .ranges()
            .iter()
            .map(|[lo, hi]| format!("{}:{}", Short(*lo), Short(*hi)))
            .collect();
        parts.push(format!("joint limits {} rad", ranges.join(",")));
    }
    if let Some(r) = scene.arm.rate_limits() {
        let rates: Vec<String> = r.rates().iter().map(|x| Short(*x).to_string()).collect();
        parts.push(format!("rate limits {} rad/s", rates.join(",")));
    }
    if !scene.weighting.is_none() {
        parts.push(format!("joint weighting {}", scene.weighting));
    }
    if scene.floor {
        parts.push("floor and post are obstacles".into());
    }
    parts.extend(gains(&scene.params, scene.damping.is_some()));
    match scene.obstacles.len() {
        0 => parts.push("no obstacle".into()),
        1 => parts.push(format!("radius {} m", scene.obstacles[0].radius)),
        k => {
            let first = scene.obstacles[0].radius;
            if scene.obstacles.iter().all(|o| o.radius == first) {
                parts.push(format!("{k} obstacles, radius {first} m"));
            } else {
                // Each obstacle's radius, in their order.
                let radii: Vec<String> = scene
                    .obstacles
                    .iter()
                    .map(|o| o.radius.to_string())
                    .collect();
                parts.push(format!("{k} obstacles, radii {} m", radii.join(", ")));
            }
        }
    }
    parts.extend(settings(&scene.params, method, scene.feedback_gain));
    parts.push(format!("dt = {} s, tf = {} s", scene.dt, scene.tf));
    parts.join(" · ")
}

/// The caption's gains, for every arm: `λ` and `δ` (with the damping
/// schedule, when it is on).
pub(crate) fn gains(params: &Params, damping: bool) -> [String; 2] {
    use crate::planner::methods::{DELTA, LAMBDA};
    [
        format!("λ = {}", params.get(&LAMBDA)),
        format!(
            "δ = {}{}",
            params.get(&DELTA),
            if damping {
                " + damping near singular poses"
            } else {
                ""
            }
        ),
    ]
}

/// The caption's loop and the networks' settings, for every arm: open or
/// closed loop, and where they change the run, the refinement of `Phi`
/// and the sign smoothing (docs/learning.md).
pub(crate) fn settings(params: &Params, method: Method, feedback_gain: f64) -> Vec<String> {
    use crate::planner::methods::{REFINE, SIGN_SMOOTHING};
    let mut parts = vec![if feedback_gain > 0.0 {
        format!("closed loop K = {feedback_gain} 1/s")
    } else {
        "open loop".into()
    }];
    let refine = params.count(&REFINE);
    if refine > 0 && method.networks().phi {
        parts.push(format!("Φ refined by {refine} Newton-Schulz steps"));
    }
    let eps = params.get(&SIGN_SMOOTHING);
    if eps > 0.0 {
        parts.push(format!("sign smoothing ε = {eps}"));
    }
    parts
}

/// Font size and line height of the caption under a figure.
const CAPTION_SIZE: f64 = 13.0;
const CAPTION_LINE: u32 = 17;

/// `text`'s parts (split at `sep`) joined again into lines no wider than
/// `width` pixels at font `size` ([`text_size`]); a part wider than a line
/// has a line of its own.
pub(crate) fn wrap(text: &str, sep: &str, width: u32, size: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for part in text.split(sep) {
        match lines.last_mut() {
            Some(line) if text_size(&format!("{line}{sep}{part}"), size).0 <= width => {
                line.push_str(sep);
                line.push_str(part);
            }
            _ => lines.push(part.to_string()),
        }
    }
    lines
}

/// The caption's lines for a figure `width` pixels wide (its parts are
/// separated by ` · `, [`caption`]), and the height of the foot they need.
pub(crate) fn caption_lines(text: &str, width: u32) -> (Vec<String>, u32) {
    // 85% of the width: the glyph table is Helvetica's, and the fonts
    // browsers substitute for sans-serif run up to a tenth wider.
    let lines = wrap(
        text,
        " · ",
        width.saturating_sub(24) * 85 / 100,
        CAPTION_SIZE,
    );
    let foot = 13 + CAPTION_LINE * lines.len() as u32;
    (lines, foot)
}

/// Draws the caption's lines ([`caption_lines`]) in the foot `area`.
pub(crate) fn draw_caption(area: &Area<'_>, lines: &[String]) -> std::result::Result<(), String> {
    for (i, line) in lines.iter().enumerate() {
        area.draw(&Text::new(
            line.clone(),
            (12, 4 + (CAPTION_LINE * i as u32) as i32),
            ("sans-serif", CAPTION_SIZE)
                .into_font()
                .color(&colour::MUTED),
        ))
        .map_err(why)?;
    }
    Ok(())
}

/// Height of the title block [`draw_title`] draws.
pub(crate) const TITLE_HEIGHT: u32 = 48;

/// Draws a figure's title, centred at the top of `area`: `head` (what the
/// figure shows and its verdict) at 17 px and `sub` (the method's
/// description) under it at 13 px, each made smaller where it would not
/// fit the width (the longer methods' titles were clipped at both ends).
pub(crate) fn draw_title(
    area: &Area<'_>,
    head: &str,
    sub: &str,
) -> std::result::Result<(), String> {
    let (w, _) = area.dim_in_pixel();
    let fit = |text: &str, size: f64| {
        let wide = text_size(text, size).0.max(1) as f64;
        size.min(size * (w.saturating_sub(20)) as f64 / wide)
    };
    let centre = (w / 2) as i32;
    let style = |size: f64, colour: &RGBColor| {
        ("sans-serif", size)
            .into_font()
            .color(colour)
            .pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Top,
            ))
    };
    area.draw(&Text::new(
        head.to_string(),
        (centre, 8),
        style(fit(head, 17.0), &BLACK),
    ))
    .map_err(why)?;
    area.draw(&Text::new(
        sub.to_string(),
        (centre, 29),
        style(fit(sub, 13.0), &colour::MUTED),
    ))
    .map_err(why)
}

/// How a legend entry's swatch looks.
#[derive(Clone, Copy)]
pub(crate) enum Swatch {
    /// A line of this colour and width.
    Line(RGBColor, u32),
    /// A dashed line.
    Dashed(RGBColor, u32),
}

/// The size of a legend's labels (px).
const LEGEND_TEXT: f64 = 13.0;

/// The width in pixels of the box [`draw_legend`] draws for `entries`.
pub(crate) fn legend_width(entries: &[(Swatch, String)]) -> i32 {
    entries
        .iter()
        .map(|(_, l)| text_size(l, LEGEND_TEXT).0 as i32)
        .max()
        .unwrap_or(0)
        + 44
}

/// Draws a legend (a framed box of swatches and labels) in `area`'s pixel
/// coordinates, its top-left or top-right corner at `at` (`right`: `at`
/// is the top-right corner).
pub(crate) fn draw_legend(
    area: &Area<'_>,
    entries: &[(Swatch, String)],
    at: (i32, i32),
    right: bool,
) -> std::result::Result<(), String> {
    const SIZE: f64 = LEGEND_TEXT;
    let line = 17;
    let width = legend_width(entries);
    let height = line * entries.len() as i32 + 10;
    let x0 = if right { at.0 - width } else { at.0 };
    let y0 = at.1;
    area.draw(&Rectangle::new(
        [(x0, y0), (x0 + width, y0 + height)],
        WHITE.mix(0.9).filled(),
    ))
    .map_err(why)?;
    area.draw(&Rectangle::new(
        [(x0, y0), (x0 + width, y0 + height)],
        colour::FRAME,
    ))
    .map_err(why)?;
    let font = ("sans-serif", SIZE).into_font().color(&colour::INK);
    for (k, (swatch, label)) in entries.iter().enumerate() {
        let y = y0 + 6 + line * k as i32 + line / 2;
        let (a, b) = ((x0 + 8, y), (x0 + 30, y));
        match *swatch {
            Swatch::Line(c, w) => area
                .draw(&PathElement::new(
                    vec![a, b],
                    ShapeStyle::from(&c).stroke_width(w),
                ))
                .map_err(why)?,
            Swatch::Dashed(c, w) => {
                for s in [0, 9, 18] {
                    area.draw(&PathElement::new(
                        vec![(a.0 + s, y), ((a.0 + s + 5).min(b.0), y)],
                        ShapeStyle::from(&c).stroke_width(w),
                    ))
                    .map_err(why)?;
                }
            }
        }
        area.draw(&Text::new(label.clone(), (x0 + 36, y - 8), font.clone()))
            .map_err(why)?;
    }
    Ok(())
}

/// `#rrggbb` as a plotters colour.
pub(crate) fn hex(s: &str) -> RGBColor {
    let channel = |i: usize| u8::from_str_radix(s.get(i..i + 2).unwrap_or("00"), 16).unwrap_or(0);
    RGBColor(channel(1), channel(3), channel(5))
}

/// What a legend calls a run's path: the paper's "straight-line task", or
/// `path` and its text (clipped to 48 characters: a polyline may have 64
/// points).
pub(crate) fn path_label(path: &crate::scene::Path) -> String {
    if path.is_line() {
        return "straight-line task".to_string();
    }
    shortened_path(path.to_string())
}

/// `path TEXT`, cut after 45 characters where it is longer than 48 (a
/// drawn path has up to 64 points).
pub(crate) fn shortened_path(text: String) -> String {
    match text.char_indices().nth(45) {
        Some((at, _)) if text.len() > 48 => format!("path {}...", &text[..at]),
        _ => format!("path {text}"),
    }
}
