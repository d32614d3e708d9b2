//! The browser shell (wasm32 only): JavaScript bindings over the core and
//! a canvas renderer. No mathematics and no simulation logic live here: a
//! [`Demo`] binds a [`Session`](crate::session::Session) (the planner, its
//! ghost, the clock, the histories, dragging) and draws it through
//! `web-sys`. Every core error reaches JavaScript as an exception carrying
//! the core's message; numbers from JavaScript are checked by the core
//! (NaN included), so nothing the user does can panic the module.
//!
//! Two modules are built from this layer (features `page` and `worker`),
//! each holding every arm, planar and in space: the page's, which draws
//! (`Demo` for a planar arm, `SpaceDemo` for an arm in space), and the Web
//! Workers', which computes (the atlas, the benchmark, the trainer, the
//! figures), so the page loads only what it draws with.
//!
//! One file per concern: [`demo`] (the `Demo` binding), [`scene`] (its
//! bindings for the arm, obstacles and networks), [`script`] (a run off
//! screen, every binding's), [`style`] (colours and the legend, the one
//! source the page's CSS reads), [`surface`] (canvas, view, helpers),
//! [`stage`] (the arm's drawing), [`layer`] (an atlas), [`plots`] (the
//! time series), [`input`] (hit-testing and keys) make the page's module;
//! [`worker`] is the workers'. This file holds what both export: the facts
//! the page reads (the methods, the limits, the arm and obstacle syntax).

#[cfg(feature = "page")]
mod demo;
#[cfg(feature = "page")]
mod input;
#[cfg(feature = "page")]
mod keys;
#[cfg(feature = "page")]
mod lab;
#[cfg(feature = "page")]
mod layer;
#[cfg(feature = "page")]
mod plots;
#[cfg(feature = "worker")]
mod robot;
#[cfg(feature = "page")]
mod scene;
#[cfg(feature = "page")]
mod script;
#[cfg(feature = "worker")]
mod space_atlas;
#[cfg(feature = "worker")]
mod space_bench;
#[cfg(feature = "page")]
mod space_demo;
#[cfg(feature = "page")]
mod space_stage;
#[cfg(feature = "worker")]
mod space_takeaway;
#[cfg(feature = "worker")]
mod space_training;
#[cfg(feature = "page")]
mod stage;
#[cfg(feature = "page")]
mod style;
#[cfg(feature = "page")]
mod surface;
#[cfg(feature = "worker")]
mod takeaway;
#[cfg(feature = "page")]
mod tracked;
#[cfg(feature = "worker")]
mod worker;

use std::cell::RefCell;

use serde::Serialize;
use wasm_bindgen::prelude::*;

use crate::error::Error;
use crate::networks::{self, NetworkSet};

#[cfg(feature = "page")]
pub use demo::Demo;
#[cfg(feature = "worker")]
pub use robot::read_robot;
#[cfg(feature = "worker")]
pub use space_atlas::SpaceAtlasJob;
#[cfg(feature = "worker")]
pub use space_bench::*;
#[cfg(feature = "page")]
pub use space_demo::SpaceDemo;
#[cfg(feature = "worker")]
pub use space_takeaway::{slice_atlas_files, space_figure, space_plots};
#[cfg(feature = "worker")]
pub use space_training::{train_space_network, MAX_SPACE_EPOCHS, MAX_SPACE_SAMPLES};
#[cfg(feature = "page")]
pub use style::{atlas_classes, legend_js as legend, palette};
#[cfg(feature = "worker")]
pub use takeaway::*;
#[cfg(feature = "worker")]
pub use worker::*;

/// The page's modules' allocator (feature `small-alloc`, which `make web`
/// turns on for them): Talc instead of dlmalloc, 2.5 KB smaller gzipped
/// in the planar page's baseline build and 2.8 KB in its SIMD build
/// (docs/web.md, "Module size"), which paid for the networks' `f32`
/// kernels there. It claims wasm memory pages as it needs them, as
/// dlmalloc does, and never returns them.
#[cfg(feature = "small-alloc")]
#[global_allocator]
static ALLOCATOR: talc::wasm::WasmDynamicTalc = talc::wasm::new_wasm_dynamic_allocator();

thread_local! {
    /// Message of the last panic, for the page to show.
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
    /// The global `performance` object: the window's, or the worker's.
    #[cfg(any(feature = "page", feature = "worker"))]
    static PERFORMANCE: Option<web_sys::Performance> =
        js_sys::Reflect::get(&js_sys::global(), &JsValue::from_str("performance"))
            .ok()
            .and_then(|p| wasm_bindgen::JsCast::dyn_into::<web_sys::Performance>(p).ok());
}

/// Installs the panic hook: the message goes to the console and is kept for
/// [`last_panic`], so the page can show it. Runs when the module starts.
#[wasm_bindgen(start)]
pub fn start() {
    install_panic_hook();
}

fn install_panic_hook() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        std::panic::set_hook(Box::new(|info| {
            LAST_PANIC.with(|p| *p.borrow_mut() = Some(info.to_string()));
            console_error_panic_hook::hook(info);
        }));
    });
}

/// The message of the last panic inside the module, if any (a bug: please
/// report it). After a panic the module cannot be used any more.
#[wasm_bindgen(js_name = lastPanic)]
pub fn last_panic() -> Option<String> {
    LAST_PANIC.with(|p| p.borrow().clone())
}

/// The crate's version: the page stamps a robot's kept reading with it.
#[wasm_bindgen(js_name = moduleVersion)]
pub fn module_version() -> String {
    env!("CARGO_PKG_VERSION").into()
}

/// A shipped network set by name (`paper` when absent).
fn network_set(set: Option<String>) -> Result<NetworkSet, JsError> {
    set.as_deref()
        .map_or(Ok(NetworkSet::Paper), |s| s.parse().map_err(js_err))
}

#[cfg(any(feature = "page", feature = "worker"))]
/// Whether a shipped network set (`paper` when absent) loads: `null` when
/// it does, else the reason (an unknown set's name included).
#[wasm_bindgen(js_name = networksError)]
pub fn networks_error(set: Option<String>) -> Option<String> {
    let set = set.as_deref().map_or(Ok(NetworkSet::Paper), str::parse);
    set.and_then(networks::builtin_set)
        .err()
        .map(|e| e.to_string())
}

/// The shipped network sets' names, in the order of the menus
/// (`builtinWeightsFiles(name)` names their files).
#[wasm_bindgen(js_name = networkSets)]
pub fn network_sets() -> Vec<String> {
    NetworkSet::ALL.iter().map(|s| s.name().into()).collect()
}

/// What a menu says of each shipped set, in the order of [`network_sets`].
#[wasm_bindgen(js_name = networkSetLabels)]
pub fn network_set_labels() -> Vec<String> {
    NetworkSet::ALL.iter().map(|s| s.label().into()).collect()
}

/// The networks' arithmetics, `[[name, label], ...]`, the default first:
/// what `setPrecision` takes and the state's `precision` says.
#[cfg(feature = "page")]
#[wasm_bindgen]
pub fn precisions() -> JsResult<JsValue> {
    let all: Vec<[&str; 2]> = crate::nn::Precision::ALL
        .iter()
        .map(|p| [p.name(), p.label()])
        .collect();
    to_js(&all)
}

/// The weights files of a shipped set (`paper` when absent), `[phi, v]`. A
/// module built without them (the page's) fetches these (the paper's at
/// start-up, the others when first chosen) and hands them to
/// [`provide_builtin_networks`].
/// An unknown set has none.
#[wasm_bindgen(js_name = builtinWeightsFiles)]
pub fn builtin_weights_files(set: Option<String>) -> Vec<String> {
    network_set(set)
        .map(|s| s.files().iter().map(|f| f.to_string()).collect())
        .unwrap_or_default()
}

#[cfg(any(feature = "page", feature = "worker"))]
/// Hands the module a shipped set (`paper` when absent): the JSON text of
/// the two files of [`builtin_weights_files`]. Throws if they do not load
/// (the reason then stays what [`networks_error`] says). Only the first
/// call per set counts.
#[wasm_bindgen(js_name = provideBuiltinNetworks)]
pub fn provide_builtin_networks(
    phi_json: &str,
    v_json: &str,
    set: Option<String>,
) -> Result<(), JsError> {
    networks::provide_builtin(network_set(set)?, Ok((phi_json, v_json))).map_err(js_err)
}

#[cfg(any(feature = "page", feature = "worker"))]
/// Tells the module why a shipped set (`paper` when absent) could not be
/// fetched; the methods that need it then say so.
#[wasm_bindgen(js_name = builtinNetworksFailed)]
pub fn builtin_networks_failed(why: &str, set: Option<String>) {
    if let Ok(set) = network_set(set) {
        let _ = networks::provide_builtin(set, Err(why.to_string()));
    }
}

/// Every method, in the order of the menus: `[{ name, label, description,
/// group, paper_figures, networks: { phi, v }, avoids, colour, params }]`
/// ([`crate::planner::MethodInfo`]).
#[wasm_bindgen]
pub fn methods() -> Result<JsValue, JsError> {
    let all: Vec<_> = crate::planner::methods::ALL
        .iter()
        .map(|m| m.info())
        .collect();
    to_js(&all)
}

/// Every parameter of the methods: `[{ name, flag, label, unit, bounds,
/// default, slider: [min, max, step], scale: 'linear' | 'log', count }]`
/// ([`crate::scene::Param`], declared by the methods), for the page's
/// controls and address.
#[wasm_bindgen]
pub fn params() -> Result<JsValue, JsError> {
    to_js(&crate::planner::params::all())
}

/// The groups of the method menu, in order: `[{ name, label }]`
/// ([`crate::planner::Group`]).
#[wasm_bindgen(js_name = methodGroupLabels)]
pub fn method_group_labels() -> Result<JsValue, JsError> {
    let all: Vec<[&str; 2]> = crate::planner::Group::ALL
        .iter()
        .map(|g| [g.name(), g.label()])
        .collect();
    to_js(&all)
}

/// The paper's five methods in its order (Figs. 2-6): what the atlas, the
/// benchmark and `eval` default to.
#[wasm_bindgen(js_name = paperMethods)]
pub fn paper_methods() -> Vec<String> {
    crate::planner::methods::PAPER
        .iter()
        .map(|m| m.name().to_string())
        .collect()
}

/// The Training panel's presets, in menu order (the first is the
/// default): `[{ name, label }]`, the label made from the preset's sizes
/// ([`crate::training::Preset`]).
#[wasm_bindgen(js_name = trainingPresets)]
pub fn training_presets() -> Result<JsValue, JsError> {
    #[derive(Serialize)]
    struct Entry {
        name: &'static str,
        label: &'static str,
    }
    let all: Vec<Entry> = crate::training::Preset::ALL
        .iter()
        .map(|p| Entry {
            name: p.name(),
            label: p.label(),
        })
        .collect();
    to_js(&all)
}

/// The method a page starts with where its address names none
/// ([`crate::session::default_method`]).
#[wasm_bindgen(js_name = defaultMethod)]
pub fn default_method() -> String {
    crate::session::default_method().name().into()
}

/// The limits and defaults the page uses, from the core that enforces
/// them, so that no number is written twice: `{ min_links, max_links,
/// max_obstacles, default_radius, max_weights_bytes, reach_tolerance,
/// default_grid, max_grid, drift_gain, max_lambda, arm_presets,
/// joint_weightings: [[name, label]] }`.
#[wasm_bindgen]
pub fn limits() -> Result<JsValue, JsError> {
    #[derive(Serialize)]
    struct Limits {
        min_links: usize,
        max_links: usize,
        max_obstacles: usize,
        default_radius: f64,
        max_weights_bytes: usize,
        reach_tolerance: f64,
        default_grid: usize,
        max_grid: usize,
        drift_gain: f64,
        max_lambda: f64,
        arm_presets: &'static [crate::arm::Preset],
        joint_weightings: Vec<[&'static str; 2]>,
    }
    to_js(&Limits {
        min_links: crate::session::MIN_LINKS,
        max_links: crate::session::MAX_LINKS,
        max_obstacles: crate::session::MAX_OBSTACLES,
        default_radius: crate::scene::PAPER_RADIUS,
        max_weights_bytes: networks::MAX_FILE_BYTES,
        reach_tolerance: crate::planner::REACH_TOLERANCE,
        default_grid: crate::atlas::DEFAULT_GRID,
        max_grid: crate::atlas::MAX_GRID,
        drift_gain: crate::session::DRIFT_GAIN,
        max_lambda: crate::planner::methods::LAMBDA.bounds.1,
        arm_presets: &crate::arm::PRESETS,
        joint_weightings: crate::scene::JointWeighting::ALL
            .iter()
            .map(|w| [w.name(), w.label()])
            .collect(),
    })
}

/// Parses an arm written `POST:L1,L2,...` (the address's `arm=`, the
/// command line's `--arm`): `{ post, links }`, or an exception saying what
/// is wrong (the arm's own checks included).
#[wasm_bindgen(js_name = parseArm)]
pub fn parse_arm(text: &str) -> Result<JsValue, JsError> {
    let arm: crate::arm::Arm = text.parse().map_err(js_err)?;
    to_js(&arm)
}

/// An arm as `POST:L1,L2,...`, what [`parse_arm`] reads back (and the key
/// under which the page keeps an arm's trained networks).
#[wasm_bindgen(js_name = formatArm)]
pub fn format_arm(post: f64, links: Vec<f64>) -> Result<String, JsError> {
    Ok(crate::arm::Arm::new(post, links)
        .map_err(js_err)?
        .to_string())
}

/// Parses joint limits written `LO:HI,LO:HI,...` in radians (the
/// address's `limits=`, the command line's `--joint-limits`): flat as
/// `[lo1, hi1, lo2, hi2, ...]`, as `setLimitedArm` takes them, or an
/// exception saying what is wrong. Their count is checked with the arm.
#[wasm_bindgen(js_name = parseJointLimits)]
pub fn parse_joint_limits(text: &str) -> Result<Vec<f64>, JsError> {
    let limits: crate::arm::JointLimits = text.parse().map_err(js_err)?;
    Ok(limits.ranges().iter().flatten().copied().collect())
}

/// Joint limits given flat `[lo1, hi1, ...]` as `LO:HI,LO:HI,...`, what
/// [`parse_joint_limits`] reads back.
#[wasm_bindgen(js_name = formatJointLimits)]
pub fn format_joint_limits(flat: Vec<f64>) -> Result<String, JsError> {
    Ok(joint_limits_from(&flat)?.to_string())
}

/// Parses rate limits written `R,R,...` in rad/s (the address's `rates=`,
/// the command line's `--rate-limits`), or an exception saying what is
/// wrong.
#[wasm_bindgen(js_name = parseRateLimits)]
pub fn parse_rate_limits(text: &str) -> Result<Vec<f64>, JsError> {
    let rates: crate::arm::RateLimits = text.parse().map_err(js_err)?;
    Ok(rates.rates().to_vec())
}

/// Rate limits as `R,R,...`, what [`parse_rate_limits`] reads back.
#[wasm_bindgen(js_name = formatRateLimits)]
pub fn format_rate_limits(rates: Vec<f64>) -> Result<String, JsError> {
    Ok(crate::arm::RateLimits::new(rates)
        .map_err(js_err)?
        .to_string())
}

/// Joint limits from a flat `[lo1, hi1, lo2, hi2, ...]`, checked.
/// An arm's limits as the page passes them (each `undefined` for none):
/// joint limits flat (see [`joint_limits_from`]) and rate limits.
#[cfg(feature = "page")]
pub(super) fn limits_from(
    limits: Option<Vec<f64>>,
    rates: Option<Vec<f64>>,
) -> Result<
    (
        Option<crate::arm::JointLimits>,
        Option<crate::arm::RateLimits>,
    ),
    JsError,
> {
    let limits = limits.map(|f| joint_limits_from(&f)).transpose()?;
    let rates = rates
        .map(crate::arm::RateLimits::new)
        .transpose()
        .map_err(js_err)?;
    Ok((limits, rates))
}

fn joint_limits_from(flat: &[f64]) -> Result<crate::arm::JointLimits, JsError> {
    if !flat.len().is_multiple_of(2) {
        return Err(JsError::new(&format!(
            "joint limits: expected lo, hi for each joint, got {} numbers",
            flat.len()
        )));
    }
    let ranges = flat.chunks_exact(2).map(|p| [p[0], p[1]]).collect();
    crate::arm::JointLimits::new(ranges).map_err(js_err)
}

/// Parses obstacles written `x,y,r;x,y,r` (each radius optional, the
/// paper's 0.05 m by default), as the address's `obstacles=` and the
/// command line's `--obstacle` write them: `[x0, y0, r0, x1, y1, r1, ...]`,
/// flat as `setObstacles` takes them, or an exception saying what is
/// wrong. Each obstacle's own checks come when it is placed.
#[wasm_bindgen(js_name = parseObstacles)]
pub fn parse_obstacles(text: &str) -> Result<Vec<f64>, JsError> {
    let list = crate::obstacle::parse_placements(text).map_err(js_err)?;
    Ok(list
        .into_iter()
        .flat_map(|p| {
            let o = p.ball(crate::scene::PAPER_RADIUS);
            [o.centre[0], o.centre[1], o.radius]
        })
        .collect())
}

/// A serialisable value as a plain JavaScript object (`None` as `null`):
/// its JSON text, parsed by the browser. serde-wasm-bindgen built the same
/// objects but cost the page's module 2.4 KB gzipped (its serialiser, the
/// `Serialize` code of every type for it, a string cache); serde_json is in
/// the module anyway. JSON has no NaN or infinity (they would arrive as
/// `null`): the page's values are finite (the planner refuses a step to a
/// non-finite pose; the checks refuse non-finite input). The workers'
/// values, whose atlas cells may hold NaN, use [`worker::to_js`].
fn to_js<T: Serialize>(value: &T) -> Result<JsValue, JsError> {
    let text = serde_json::to_string(value).map_err(|e| JsError::new(&e.to_string()))?;
    js_sys::JSON::parse(&text).map_err(|_| JsError::new("JSON.parse refused the module's JSON"))
}

/// What a binding returns: a value, or an exception with the core's message.
#[cfg(feature = "page")]
type JsResult<T = ()> = Result<T, JsError>;

/// A number from JavaScript, refused unless finite (NaN included).
#[cfg(feature = "page")]
fn finite(what: &str, value: f64) -> JsResult<f64> {
    crate::error::finite(what, value).map_err(js_err)
}

fn js_err(e: Error) -> JsError {
    JsError::new(&e.to_string())
}

/// `performance.now()` in a page or a worker (0 where there is none).
#[cfg(any(feature = "page", feature = "worker"))]
fn now_ms() -> f64 {
    PERFORMANCE.with(|p| p.as_ref().map_or(0.0, |p| p.now()))
}
