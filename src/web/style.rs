//! The colours of the drawing and its legend: the one place they are
//! written. The renderer draws with these constants; the page sets them as
//! CSS custom properties ([`super::palette`]) and builds its legend from
//! [`legend`], so a swatch is the colour of what it names (the e2e test
//! compares them with the canvas's pixels).

use serde::Serialize;

use crate::session::STROBE_EVERY;

pub const INK: &str = "#1f2933";
pub const MUTED: &str = "#5f6b78";
pub const GRID: &str = "#eef1f5";
pub const AXIS: &str = "#c4ccd6";
pub const ARM: &str = "#1d4e89";
pub const ACCENT: &str = "#d9731a";
pub const DANGER: &str = "#c0392b";
pub const TEAL: &str = "#2a9d8f";
pub const GHOST: &str = "#5f6b78";
pub const REGION: &str = "#b9c7d6";
pub const POST: &str = "#4a5560";
pub const GROUND: &str = "#dfe4ea";
pub const DAMPER: &str = "#17becf";
pub const PAPER: &str = "#ffffff";
pub const FONT: &str = "system-ui, -apple-system, 'Segoe UI', Roboto, sans-serif";

/// Opacity of the stroboscopic trace, of the ghost arm and of the obstacle
/// disc (when a link is inside it, [`HIT_ALPHA`]).
pub const STROBE_ALPHA: f64 = 0.16;
pub const GHOST_ALPHA: f64 = 0.8;
pub const OBSTACLE_ALPHA: f64 = 0.16;
pub const HIT_ALPHA: f64 = 0.55;
/// Opacity of the influence-distance circles.
pub const INFLUENCE_ALPHA: f64 = 0.6;

/// Every named colour, for the page's CSS custom properties.
pub const PALETTE: [(&str, &str); 13] = [
    ("ink", INK),
    ("muted", MUTED),
    ("grid", GRID),
    ("axis", AXIS),
    ("arm", ARM),
    ("accent", ACCENT),
    ("danger", DANGER),
    ("teal", TEAL),
    ("ghost", GHOST),
    ("region", REGION),
    ("post", POST),
    ("ground", GROUND),
    ("damper", DAMPER),
];

/// `#rrggbb` with an alpha, as a CSS colour.
pub fn rgba(hex: &str, alpha: f64) -> String {
    let channel = |i: usize| u8::from_str_radix(hex.get(i..i + 2).unwrap_or("00"), 16).unwrap_or(0);
    format!(
        "rgba({}, {}, {}, {alpha})",
        channel(1),
        channel(3),
        channel(5)
    )
}

/// One entry of the legend.
#[derive(Serialize)]
pub struct Entry {
    /// A name for tests and CSS (`key-<key>`).
    pub key: &'static str,
    /// What it shows.
    pub label: String,
    /// The colour, with the alpha it is drawn with.
    pub swatch: String,
    /// How the swatch looks: `thick`, `line`, `thin`, `dashed`, `disc` or `region`.
    pub kind: &'static str,
}

/// The legend of the stage.
pub fn legend() -> Vec<Entry> {
    let entry = |key, label: &str, swatch: String, kind| Entry {
        key,
        label: label.to_string(),
        swatch,
        kind,
    };
    vec![
        entry("arm", "arm", rgba(ARM, 1.0), "thick"),
        entry(
            "strobe",
            &format!("every {STROBE_EVERY}th pose"),
            rgba(ARM, STROBE_ALPHA),
            "thin",
        ),
        entry(
            "ghost",
            "numerical route (network cases)",
            rgba(GHOST, GHOST_ALPHA),
            "dashed",
        ),
        entry("path", "straight-line task", rgba(MUTED, 1.0), "dashed"),
        entry("trail", "end-effector trail", rgba(ACCENT, 1.0), "line"),
        entry("obstacle", "obstacle", rgba(DANGER, OBSTACLE_ALPHA), "disc"),
        entry(
            "region",
            "obstacle region the v network was trained on (Cases 2, 3)",
            rgba(REGION, 1.0),
            "region",
        ),
        entry(
            "dampers",
            "link-obstacle pairs within the influence distance (distance, priority, qp)",
            rgba(DAMPER, 1.0),
            "line",
        ),
    ]
}
