//! Training the networks of an arm in space in a worker (the workers'
//! module): one network of a recipe ([`crate::training::space`], quick or
//! whole-reach) for a shipped arm or for the robot of a run file (a robot
//! the user opened in the page), each epoch reported,
//! its weights file returned as text for the page to install
//! (`SpaceDemo.installNetworks`) and to save. The page trains `Phi` and `v`
//! in two workers at once and cancels by ending them.

use serde::Deserialize;
use wasm_bindgen::prelude::*;

use super::worker::{from_js, read_space_run};
use super::{js_err, to_js};
use crate::networks::NetKind;
use crate::space::SpacePreset;
use crate::training::space::{train_space, SpaceTrainSpec, TrainArm, SPACE_RECIPES};
use crate::training_job::Progress;

/// Most samples a page may ask for (the whole-reach `v` draws 100 000).
pub const MAX_SPACE_SAMPLES: usize = 200_000;
/// Most epochs a page may ask for.
pub const MAX_SPACE_EPOCHS: usize = 5_000;
/// The longest name a page may give its robot (for the messages).
pub const MAX_NAME_CHARS: usize = 200;

/// What the page asks for.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Request {
    /// The preset's key (`panda`, `iiwa14`); or
    #[serde(default)]
    arm: Option<String>,
    /// a spatial run file's JSON text (of the hand's position or its pose),
    /// whose chain and scene are trained for (its first sphere sets the
    /// spheres' radius; the networks serve the position task either way);
    #[serde(default)]
    run: Option<String>,
    /// what the messages call the run's robot (the preset's key where the
    /// chain is a preset's, else `robot`, where absent).
    #[serde(default)]
    name: Option<String>,
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
/// | "v", preset?: "quick" | "reach", samples?, epochs?, seed? }`, or
/// `{ run, name?, net, ... }` with a spatial run file's text (position or
/// pose) in place of
/// the preset's key (a robot of the user's: its chain, start pose and
/// sphere; [`TrainArm::new`] refuses a chain whose first joint slides);
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
    let arm = train_arm(&r)?;
    let recipe = r.preset.as_deref().unwrap_or(SPACE_RECIPES[0].name);
    let mut spec = SpaceTrainSpec::recipe(recipe, arm, r.net, r.seed).map_err(js_err)?;
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

/// The arm a request trains for: the preset it names, or its run file's
/// robot; refused where it gives both or neither.
fn train_arm(r: &Request) -> Result<TrainArm, JsError> {
    match (&r.arm, &r.run) {
        (Some(key), None) => SpacePreset::named(key).map(TrainArm::from).map_err(js_err),
        (None, Some(text)) => {
            let scene = read_space_run(text)?.scene;
            if r.name.as_ref().is_some_and(|n| n.chars().count() > MAX_NAME_CHARS) {
                return Err(JsError::new(&format!(
                    "the robot's name is longer than {MAX_NAME_CHARS} characters"
                )));
            }
            let name = match (&r.name, SpacePreset::of(&scene.arm)) {
                (Some(name), _) => name.clone(),
                (None, Some(p)) => p.key.to_string(),
                (None, None) => "robot".to_string(),
            };
            TrainArm::new(&name, scene).map_err(js_err)
        }
        _ => Err(JsError::new(
            "a training request names its arm by 'arm' (a shipped arm's key) or by 'run' (a run file of the robot), not both",
        )),
    }
}
