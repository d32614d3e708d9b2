//! The colours of the drawing and its legend: the one place they are
//! written. The renderer draws with these constants; the page sets them as
//! CSS custom properties ([`super::palette`]) and builds its legend from
//! [`legend`], so a swatch is the colour of what it names (the e2e test
//! compares them with the canvas's pixels).
//!
//! The build for the arms in space (`canvas,space`) draws with some of
//! them: the planar stage's own (its mask's bits, the ellipses' scales) go
//! unused there.
#![cfg_attr(not(feature = "page"), allow(dead_code))]

use serde::Serialize;

use crate::session::STROBE_EVERY;

pub use crate::palette::{ACCENT, ARM, DANGER, INK, MUTED, TEAL};
pub const GRID: &str = "#eef1f5";
pub const AXIS: &str = "#c4ccd6";
pub const GHOST: &str = "#c2185b";
pub const REGION: &str = "#b9c7d6";
pub const POST: &str = "#4a5560";
pub const GROUND: &str = "#dfe4ea";
pub const DAMPER: &str = "#17becf";
/// The joints' position limits (their ranges drawn at the joints).
pub const LIMIT: &str = "#8e6bbf";
/// The manipulability (velocity) ellipse and the force ellipse at the hand.
pub const VELOCITY: &str = "#2e7d32";
pub const FORCE: &str = "#6d4c41";
/// The drawn scale of the velocity ellipse (its half-lengths `sigma_i` are
/// m per rad/s), of the force ellipse (`1 / sigma_i`), and the force
/// ellipse's largest drawn half-length (m): the legend says them.
pub const VELOCITY_SCALE: f64 = 0.25;
pub const FORCE_SCALE: f64 = 0.1;
pub const MAX_FORCE: f64 = 0.6;
pub const PAPER: &str = "#ffffff";
pub const FONT: &str = "system-ui, -apple-system, 'Segoe UI', Roboto, sans-serif";

/// Opacity of the stroboscopic trace, of the ghost arm and of the obstacle
/// disc (when a link is inside it, [`HIT_ALPHA`]).
pub const STROBE_ALPHA: f64 = 0.16;
pub const GHOST_ALPHA: f64 = 0.95;
pub const OBSTACLE_ALPHA: f64 = 0.16;
pub const HIT_ALPHA: f64 = 0.55;
/// Opacity of the influence-distance circles.
pub const INFLUENCE_ALPHA: f64 = 0.6;
/// Opacity of an atlas layer's cells.
pub const LAYER_ALPHA: f64 = 0.42;

/// Every named colour, for the page's CSS custom properties.
pub const PALETTE: [(&str, &str); 16] = [
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
    ("limit", LIMIT),
    ("velocity", VELOCITY),
    ("force", FORCE),
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
    /// How the swatch looks: `thick`, `line`, `thin`, `dashed`, `disc`,
    /// `region`, `dot`, `target` or `square`.
    pub kind: &'static str,
    /// Whether the page offers a switch for it (`Demo.setShown`): always
    /// listed, drawn only while on.
    pub toggle: bool,
}

/// The legend's entries: key, label, colour, alpha, kind. Their order is
/// that of the bits of [`super::stage::draw`]'s mask of what it drew.
const LEGEND: [(&str, &str, &str, f64, &str); 15] = [
    ("arm", "arm", ARM, 1.0, "thick"),
    ("strobe", "", ARM, STROBE_ALPHA, "thin"),
    (
        "ghost",
        "numerical route (the same scene solved exactly)",
        GHOST,
        GHOST_ALPHA,
        "dashed",
    ),
    ("path", "path to follow", MUTED, 1.0, "dashed"),
    ("trail", "end-effector trail", ACCENT, 1.0, "line"),
    (
        "reference",
        "where the hand should be now",
        MUTED,
        1.0,
        "dot",
    ),
    ("target", "target (drag it)", ACCENT, 1.0, "target"),
    (
        "obstacle",
        "obstacle (drag it)",
        DANGER,
        OBSTACLE_ALPHA,
        "disc",
    ),
    (
        "region",
        "obstacle region the v network was trained on",
        REGION,
        1.0,
        "region",
    ),
    (
        "dampers",
        "influence distance, and the link-obstacle pairs within it",
        DAMPER,
        1.0,
        "line",
    ),
    (
        "floor",
        "link below the floor (y < 0)",
        DANGER,
        1.0,
        "thick",
    ),
    (
        "atlas",
        "atlas map under the arm (its colours: the Atlas panel)",
        "",
        0.0,
        "square",
    ),
    (
        "limits",
        "each joint's range (its position limits), a dot at its angle",
        LIMIT,
        1.0,
        "line",
    ),
    (
        "ellipse",
        "manipulability ellipse {Jθ̇ : |θ̇| ≤ 1} at 1/4 scale (half-axes σ₁, σ₂)",
        VELOCITY,
        1.0,
        "line",
    ),
    (
        "force",
        "force ellipse (half-axes 1/σᵢ) at 1/10 scale, at most 0.6 m",
        FORCE,
        1.0,
        "line",
    ),
];

/// The entries the page may switch ([`Entry::toggle`]).
pub const TOGGLES: u32 = bit::ELLIPSE | bit::FORCE;

/// The legend entry whose key is `key`, if the page may switch it: its bit.
pub fn toggle_bit(key: &str) -> Option<u32> {
    let i = LEGEND.iter().position(|e| e.0 == key)?;
    Some(1u32 << i).filter(|b| TOGGLES & b != 0)
}

pub mod bit {
    pub const ARM: u32 = 1;
    pub const STROBE: u32 = 1 << 1;
    pub const GHOST: u32 = 1 << 2;
    pub const PATH: u32 = 1 << 3;
    pub const TRAIL: u32 = 1 << 4;
    pub const REFERENCE: u32 = 1 << 5;
    pub const TARGET: u32 = 1 << 6;
    pub const OBSTACLE: u32 = 1 << 7;
    pub const REGION: u32 = 1 << 8;
    pub const DAMPERS: u32 = 1 << 9;
    pub const FLOOR: u32 = 1 << 10;
    pub const ATLAS: u32 = 1 << 11;
    pub const LIMITS: u32 = 1 << 12;
    pub const ELLIPSE: u32 = 1 << 13;
    pub const FORCE: u32 = 1 << 14;
}

/// The legend of the stage, in the order of the bits of
/// [`super::stage::draw`]'s mask of what it drew (the page shows only
/// those).
pub fn legend() -> Vec<Entry> {
    LEGEND
        .iter()
        .enumerate()
        .map(|(i, &(key, label, colour, alpha, kind))| Entry {
            key,
            label: if label.is_empty() {
                format!("every {STROBE_EVERY}th pose")
            } else {
                label.into()
            },
            // The atlas layer's swatch: a cell where the method succeeds.
            swatch: if colour.is_empty() {
                rgba(crate::atlas::Class::Success.colour(), LAYER_ALPHA)
            } else {
                rgba(colour, alpha)
            },
            kind,
            toggle: TOGGLES & (1 << i) != 0,
        })
        .collect()
}

/// The legend of the drawing in perspective (an arm in space,
/// [`super::space_stage::draw`]): the same entries' form as [`legend`]'s,
/// in the order the page lists them; `ghost` is drawn beside a learned
/// method only, `ellipse` and `force` are the page's switches
/// ([`super::SpaceDemo::set_shown`]).
pub fn space_legend() -> Vec<Entry> {
    const ENTRIES: [(&str, &str, &str, f64, &str); 12] = [
        ("arm", "the arm: its links as capsules of the collision radius", ARM, 1.0, "thick"),
        ("sphere", "a sphere (red when a link is inside it)", DANGER, 0.28, "disc"),
        ("target", "the target: the end of the hand's line", TEAL, 1.0, "target"),
        ("path", "the path to follow", MUTED, 1.0, "dashed"),
        ("trail", "where the hand has been", ACCENT, 1.0, "line"),
        ("reference", "where the hand should be now", MUTED, 1.0, "dot"),
        ("shadow", "shadows on the floor (grid: 0.1 m)", INK, 0.13, "thick"),
        (
            "frame",
            "the hand's full pose: the target's frame and the hand's (x, y, z in red, green, blue)",
            DANGER,
            1.0,
            "line",
        ),
        (
            "self",
            "two links near each other (self-collision on): their closest points joined, red where they overlap",
            DAMPER,
            1.0,
            "line",
        ),
        (
            "ghost",
            "numerical route (the same scene solved exactly), beside a learned method",
            GHOST,
            GHOST_ALPHA,
            "dashed",
        ),
        (
            "ellipse",
            "manipulability ellipsoid {Jθ̇ : |θ̇| ≤ 1} at 1/4 scale: its three principal ellipses (half-axes σ₁, σ₂, σ₃)",
            VELOCITY,
            1.0,
            "line",
        ),
        (
            "force",
            "force ellipsoid (half-axes 1/σᵢ) at 1/10 scale, at most 0.6 m",
            FORCE,
            1.0,
            "line",
        ),
    ];
    ENTRIES
        .iter()
        .map(|&(key, label, colour, alpha, kind)| Entry {
            key,
            label: label.into(),
            swatch: rgba(colour, alpha),
            kind,
            toggle: matches!(key, "ellipse" | "force"),
        })
        .collect()
}

/// The colours the drawing uses, `{ name: css colour }`: the page sets them
/// as CSS custom properties (`--arm`, ...), so the stylesheet has no copy.
#[wasm_bindgen::prelude::wasm_bindgen]
pub fn palette() -> Result<wasm_bindgen::JsValue, wasm_bindgen::JsError> {
    super::to_js(&crate::session::ByName(PALETTE.to_vec()))
}

/// The legend of a drawing: `[{ key, label, swatch, kind, toggle }]`, each
/// swatch the colour (with the alpha) that the renderer draws that element
/// with; `space`: the drawing in perspective's ([`space_legend`]), else the
/// plane's ([`legend`]).
#[wasm_bindgen::prelude::wasm_bindgen(js_name = legend)]
pub fn legend_js(space: Option<bool>) -> Result<wasm_bindgen::JsValue, wasm_bindgen::JsError> {
    super::to_js(&if space == Some(true) {
        space_legend()
    } else {
        legend()
    })
}

/// The classes of an atlas, in the order of `setAtlasLayer`'s indices:
/// `[{ name, label, colour, swatch, limits, self_collision, avoidable }]`:
/// `colour` is `#rrggbb` (the command
/// line's SVG draws it), `swatch` the translucent colour the layer is drawn
/// with.
#[wasm_bindgen::prelude::wasm_bindgen(js_name = atlasClasses)]
pub fn atlas_classes() -> Result<wasm_bindgen::JsValue, wasm_bindgen::JsError> {
    #[derive(Serialize)]
    struct Entry {
        name: &'static str,
        label: &'static str,
        colour: &'static str,
        swatch: String,
        /// Only an arm with joint limits has it (the class `limit`).
        limits: bool,
        /// Only a chain that checks self-collision has it.
        self_collision: bool,
        /// Avoidance is possible in a cell of this class (not on the
        /// path, not on the arm at the start): the success rate's cells.
        avoidable: bool,
    }
    let all: Vec<Entry> = crate::atlas::Class::ALL
        .iter()
        .map(|c| Entry {
            name: c.name(),
            label: c.label(),
            colour: c.colour(),
            swatch: rgba(c.colour(), LAYER_ALPHA),
            limits: *c == crate::atlas::Class::Limit,
            self_collision: *c == crate::atlas::Class::SelfCollision,
            avoidable: c.avoidable(),
        })
        .collect();
    super::to_js(&all)
}
