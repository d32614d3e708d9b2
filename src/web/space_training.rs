//! Training the networks of an arm in space in a worker (the workers'
//! module): one network of the preset's recipe
//! ([`crate::training::space`], quick or whole-reach), each epoch reported,
//! its weights file returned as text for the page to install
//! (`SpaceDemo.installNetworks`) and to save. The page trains `Phi` and `v`
//! in two workers at once and cancels by ending them.

use serde::Deserialize;
use wasm_bindgen::prelude::*;

use super::worker::from_js;
use super::{js_err, to_js};
use crate::networks::NetKind;
use crate::training::space::{train_space, SpaceTrainSpec, SPACE_RECIPES};
use crate::training_job::Progress;

/// Most samples a page may ask for (the whole-reach `v` draws 100 000).
pub const MAX_SPACE_SAMPLES: usize = 200_000;
/// Most epochs a page may ask for.
pub const MAX_SPACE_EPOCHS: usize = 5_000;

/// What the page asks for.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Request {
    /// The preset's key (`panda`, `iiwa14`).
    arm: String,
    /// `phi` or `v`.
    net: NetKind,
    /// A recipe of [`SPACE_RECIPES`] (the first where absent).
    #[serde(default)]
    preset: Option<String>,
    samples: Option<usize>,
    epochs: Option<usize>,
    #[serde(default)]
    seed: u64,
}

/// Trains one network of an arm in space: `request` is `{ arm, net: "phi"
/// | "v", preset?: "quick" | "reach", samples?, epochs?, seed? }`;
/// `on_epoch(progress)` is called after every epoch with `{ net,
/// optimiser, epoch, train_mse, val_mse, mu, gradient, max_epochs }` (the
/// plane's training's progress). Returns the weights file as JSON text (what
/// `redundant-ik train --arm A --net N` writes). Throws with the core's
/// message on bad input.
#[wasm_bindgen(js_name = trainSpaceNetwork)]
pub fn train_space_network(
    request: JsValue,
    on_epoch: &js_sys::Function,
) -> Result<String, JsError> {
    let r: Request = from_js(&request, "a training request", true)?;
    let p = crate::space::SpacePreset::by_key(&r.arm)
        .ok_or_else(|| JsError::new(&format!("no arm in space is called '{}'", r.arm)))?;
    let recipe = r.preset.as_deref().unwrap_or(SPACE_RECIPES[0].name);
    let mut spec = SpaceTrainSpec::recipe(recipe, p, r.net, r.seed).map_err(js_err)?;
    if let Some(n) = r.samples {
        crate::error::within("samples", n as f64, 20.0, MAX_SPACE_SAMPLES as f64)
            .map_err(js_err)?;
        spec.samples = n;
    }
    if let Some(n) = r.epochs {
        crate::error::within("epochs", n as f64, 1.0, MAX_SPACE_EPOCHS as f64).map_err(js_err)?;
        spec.adam.max_epochs = n;
    }
    let (net, max_epochs) = (r.net, spec.adam.max_epochs);
    let file = train_space(&spec, |report| {
        let progress = Progress {
            net: match net {
                NetKind::Phi => "phi",
                NetKind::V => "v",
            },
            optimiser: "adam",
            report: *report,
            max_epochs,
        };
        if let Ok(v) = to_js(&progress) {
            let _ = on_epoch.call1(&JsValue::NULL, &v);
        }
        true
    })
    .map_err(js_err)?;
    file.to_json().map_err(js_err)
}
