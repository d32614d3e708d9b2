//! The browser shell (wasm32 only): JavaScript bindings over the core and
//! a canvas renderer. No mathematics and no simulation logic live here: a
//! [`Demo`] binds a [`Session`](crate::session::Session) (the planner, its
//! ghost, the clock, the histories, dragging) and draws it through
//! `web-sys`. Every core error reaches JavaScript as an exception carrying
//! the core's message; numbers from JavaScript are checked by the core
//! (NaN included), so nothing the user does can panic the module.
//!
//! Two modules are built from this layer (features `page` and `worker`):
//! the page's, which draws, and the Web Workers', which computes (the atlas,
//! the benchmark), so the page loads only what it draws with.
//!
//! One file per concern: [`demo`] (the `Demo` binding), [`style`] (colours
//! and the legend, the one source the page's CSS reads), [`surface`]
//! (canvas, view transform, drawing helpers), [`stage`] (the arm's drawing),
//! [`layer`] (an atlas drawn under it), [`plots`] (the time series) and
//! [`input`] (pointer hit-testing and keys) and [`playground`] (the arm,
//! several obstacles, trained networks, runs off screen) make the page's module;
//! [`worker`] is the workers'. This file holds what both export.

#[cfg(feature = "page")]
mod demo;
#[cfg(feature = "page")]
mod input;
#[cfg(feature = "page")]
mod layer;
#[cfg(feature = "page")]
mod playground;
#[cfg(feature = "page")]
mod plots;
#[cfg(feature = "page")]
mod stage;
#[cfg(feature = "page")]
mod style;
#[cfg(feature = "page")]
mod surface;
#[cfg(feature = "worker")]
mod worker;

use std::cell::RefCell;

use serde::Serialize;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;

use crate::error::Error;
use crate::networks::Networks;
use crate::planner::Method;

#[cfg(feature = "page")]
pub use demo::Demo;
#[cfg(feature = "worker")]
pub use worker::*;

thread_local! {
    /// The trained networks built into the module, loaded once (or why not).
    static NETWORKS: RefCell<Option<Result<Networks, String>>> = const { RefCell::new(None) };
    /// Message of the last panic, for the page to show.
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
    /// The global `performance` object: the window's, or the worker's.
    static PERFORMANCE: Option<web_sys::Performance> =
        js_sys::Reflect::get(&js_sys::global(), &JsValue::from_str("performance"))
            .ok()
            .and_then(|p| p.dyn_into::<web_sys::Performance>().ok());
}

/// The networks shipped with the module, loaded on first use.
fn shared_networks() -> Result<Networks, String> {
    NETWORKS.with(|cell| {
        cell.borrow_mut()
            .get_or_insert_with(|| {
                Networks::embedded().map_err(|e| {
                    Error::NetworksUnavailable(format!(
                        "the built-in weights could not be loaded ({e})"
                    ))
                    .to_string()
                })
            })
            .clone()
    })
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

/// Whether the trained networks (Cases 1-3) are available: `null` when they
/// are, else the reason.
#[wasm_bindgen(js_name = networksError)]
pub fn networks_error() -> Option<String> {
    shared_networks().err()
}

/// The five methods, in the paper's order: `[{ name, label, description }]`
/// (`Method::name`, `Method::label`, `Method::description`), for the page's menus.
#[wasm_bindgen]
pub fn modes() -> Result<JsValue, JsError> {
    #[derive(Serialize)]
    struct Entry {
        name: &'static str,
        label: &'static str,
        description: &'static str,
    }
    let all: Vec<Entry> = methods::PAPER
        .iter()
        .map(|m| Entry {
            name: m.name(),
            label: m.label(),
            description: m.description(),
        })
        .collect();
    to_js(&all)
}

#[cfg(feature = "page")]
/// The colours the drawing uses, `{ name: css colour }`: the page sets them
/// as CSS custom properties (`--arm`, ...), so the stylesheet has no copy.
#[wasm_bindgen]
pub fn palette() -> Result<JsValue, JsError> {
    let map: std::collections::BTreeMap<&str, &str> = style::PALETTE.iter().copied().collect();
    to_js(&map)
}

/// The legend of the drawing: `[{ key, label, swatch, kind }]`, each swatch
/// the colour (with the alpha) that the renderer draws that element with.
#[cfg(feature = "page")]
#[wasm_bindgen]
pub fn legend() -> Result<JsValue, JsError> {
    to_js(&style::legend())
}

/// The classes of an atlas, in the order of `setAtlasLayer`'s indices:
/// `[{ name, label, colour, swatch }]`: `colour` is `#rrggbb` (the command
/// line's SVG draws it), `swatch` the translucent colour the layer is drawn
/// with.
#[cfg(feature = "page")]
#[wasm_bindgen(js_name = atlasClasses)]
pub fn atlas_classes() -> Result<JsValue, JsError> {
    #[derive(Serialize)]
    struct Entry {
        name: &'static str,
        label: &'static str,
        colour: &'static str,
        swatch: String,
    }
    let all: Vec<Entry> = crate::atlas::Class::ALL
        .iter()
        .map(|c| Entry {
            name: c.name(),
            label: c.label(),
            colour: c.colour(),
            swatch: style::rgba(c.colour(), layer::LAYER_ALPHA),
        })
        .collect();
    to_js(&all)
}

/// A serialisable value as a plain JavaScript object (`None` as `null`).
fn to_js<T: Serialize>(value: &T) -> Result<JsValue, JsError> {
    value
        .serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(|e| JsError::new(&e.to_string()))
}

fn js_err(e: Error) -> JsError {
    JsError::new(&e.to_string())
}

/// `performance.now()` in a page or a worker (0 where there is none).
fn now_ms() -> f64 {
    PERFORMANCE.with(|p| p.as_ref().map_or(0.0, |p| p.now()))
}
