//! What runs in the page's Web Workers (feature `worker`): the atlas, a
//! chunk of cells at a time so that the worker can report progress between
//! chunks; the trainer, which reports every epoch; and the in-browser
//! benchmark, one figure per call. The page's own module carries none of
//! them.

use serde::{Deserialize, Serialize};
use wasm_bindgen::prelude::*;

use super::{js_err, now_ms};
use crate::atlas::{Grid, Job, Spec, DEFAULT_GRID};
use crate::bench;
use crate::error::Error;
use crate::networks;
use crate::planner::{methods, Method};
use crate::run::{NetworkChoice, Run};

/// Refuses a field of `value` not in `names`: the derived readers read only
/// the fields they know, so a misspelt one would quietly become a default.
fn known_fields(value: &JsValue, names: &[&str], what: &str) -> Result<(), JsError> {
    for key in js_sys::Object::keys(&js_sys::Object::from(value.clone())).iter() {
        let key = key.as_string().unwrap_or_default();
        if !names.contains(&key.as_str()) {
            return Err(JsError::new(&format!(
                "{what}: unknown field '{key}', expected one of {}",
                names.join(", ")
            )));
        }
    }
    Ok(())
}

/// Whether `value` holds a number that is not finite (NaN, an infinity),
/// at any depth up to 32 (JSON would make it `null`, which an optional
/// field reads as absent).
fn holds_non_finite(value: &JsValue, depth: u32) -> bool {
    if let Some(x) = value.as_f64() {
        return !x.is_finite();
    }
    if depth == 0 || !value.is_object() {
        return false;
    }
    if js_sys::Array::is_array(value) {
        return js_sys::Array::from(value)
            .iter()
            .any(|v| holds_non_finite(&v, depth - 1));
    }
    js_sys::Object::values(&js_sys::Object::from(value.clone()))
        .iter()
        .any(|v| holds_non_finite(&v, depth - 1))
}

/// A value the page passes, read through its JSON text by serde_json (the
/// reader the module has anyway: serde-wasm-bindgen's own deserializer
/// cost the workers' module 37 KB of code), `what` naming it in errors.
/// With `finite`, a number that is not finite is refused, as
/// serde-wasm-bindgen's reader refused it where a field was checked.
pub(super) fn from_js<T: serde::de::DeserializeOwned>(
    value: &JsValue,
    what: &str,
    finite: bool,
) -> Result<T, JsError> {
    if finite && holds_non_finite(value, 32) {
        return Err(JsError::new(&format!(
            "{what}: a number is not finite (NaN or an infinity)"
        )));
    }
    let text: String = js_sys::JSON::stringify(value)
        .ok()
        .and_then(|t| t.as_string())
        .ok_or_else(|| JsError::new(&format!("{what}: not an object")))?;
    serde_json::from_str(&text).map_err(|e| JsError::new(&format!("{what}: {e}")))
}

/// A run as the page passes it (`Demo.run()`), checked.
pub(super) fn read_run(run: JsValue) -> Result<Run, JsError> {
    let run: Run = from_js(&run, "not a run", true)?;
    run.validate().map_err(js_err)?;
    Ok(run)
}

/// A run file of an arm in space as the workers' jobs read it (the slice
/// atlas, the training, the benchmark): of the hand's position, or of its
/// pose, with the position scene that pose scene extends.
pub(super) struct SpaceRun {
    /// The pose task's scene, for a run of the hand's pose.
    pub pose: Option<crate::scene::PoseScene>,
    /// The position scene (the pose scene's where the run is of the pose).
    pub scene: crate::scene::SpaceScene,
    /// The networks the run names.
    pub networks: Option<NetworkChoice<crate::networks::space::SpaceNetworkSet>>,
    /// The networks' arithmetic.
    pub precision: crate::nn::Precision,
    /// What the outputs call its arm ([`crate::space::SpacePreset::label_of`]).
    pub label: String,
}

/// What the outputs call a run file's arm: its preset's label, else the
/// robot's name the file records with its joints.
pub(super) fn label_of(
    chain: &crate::space::Chain,
    robot: Option<&crate::urdf::RobotSource>,
) -> String {
    crate::space::SpacePreset::label_of(chain, crate::urdf::RobotSource::name_of(robot))
}

/// Reads `text`, a run file of an arm in space of either task.
pub(super) fn read_space_run(text: &str) -> Result<SpaceRun, JsError> {
    use crate::export::{is_pose_run, PoseRunFile, SpaceRunFile};
    if is_pose_run(text) {
        let file = PoseRunFile::from_json(text).map_err(js_err)?;
        return Ok(SpaceRun {
            label: label_of(&file.scene.arm.chain, file.robot.as_ref()),
            scene: file.scene.position_scene().0,
            pose: Some(file.scene),
            networks: file.networks,
            precision: file.precision,
        });
    }
    let file = SpaceRunFile::from_json(text).map_err(js_err)?;
    Ok(SpaceRun {
        label: label_of(&file.scene.arm, file.robot.as_ref()),
        pose: None,
        scene: file.scene,
        networks: file.networks,
        precision: file.precision,
    })
}

// ---- the atlas -----------------------------------------------------------

/// The options of an atlas as the page passes them.
#[derive(Deserialize)]
struct AtlasOptions {
    /// Method names; the paper's five when absent.
    methods: Option<Vec<String>>,
    /// Points per side; 41 when absent.
    n: Option<f64>,
    /// `[x0, x1, y0, y1]`; the box of the arm's reach when absent.
    region: Option<Vec<f64>>,
    /// The paper task the scene came from, for the report.
    task: Option<u32>,
    /// Closed-loop gain `K`; the scene's when absent.
    feedback: Option<f64>,
    /// Newton-Schulz steps on a learned `Phi`; the scene's when absent.
    refine: Option<f64>,
    /// The shipped network set (`paper`, `reach`) for the methods that use
    /// networks, instead of the weights files given (or the paper's set).
    networks: Option<String>,
}

const OPTION_NAMES: [&str; 7] = [
    "methods", "n", "region", "task", "feedback", "refine", "networks",
];

/// An atlas being computed in a worker: `new AtlasJob(run, options)`, then
/// `advance(cells)` until `done == total`, then `finish()` for the result
/// (the JSON shape of `redundant-ik atlas --json`).
#[wasm_bindgen]
pub struct AtlasJob {
    job: Job,
    row: usize,
}

#[wasm_bindgen]
impl AtlasJob {
    /// `run` is the page's run (`Demo.run()`: its scene and networks);
    /// `options` is `{ methods, n, region, task, feedback, refine, networks
    /// }`, each optional (`feedback` and `refine` override the scene's,
    /// `task` the run's, and `networks` names a shipped set instead of the
    /// run's networks). The methods that use networks take those, or the
    /// built-in ones where none are named and they fit the arm
    /// ([`Run::load_networks`]). Throws with the core's message on bad
    /// input.
    #[wasm_bindgen(constructor)]
    pub fn new(run: JsValue, options: JsValue) -> Result<AtlasJob, JsError> {
        let mut run = read_run(run)?;
        let options: AtlasOptions = if options.is_undefined() || options.is_null() {
            AtlasOptions {
                methods: None,
                n: None,
                region: None,
                task: None,
                feedback: None,
                refine: None,
                networks: None,
            }
        } else {
            known_fields(&options, &OPTION_NAMES, "atlas options")?;
            from_js(&options, "atlas options", true)?
        };
        let n = match options.n {
            None => DEFAULT_GRID,
            Some(n) => Grid::points_per_side(n).map_err(js_err)?,
        };
        let grid = match options.region.as_deref() {
            None => Grid::around_reach(&run.scene.arm, n),
            Some(&[x0, x1, y0, y1]) => Grid::new([x0, x1, y0, y1], n).map_err(js_err)?,
            Some(other) => {
                return Err(JsError::new(&format!(
                    "region needs four numbers [x0, x1, y0, y1], got {}",
                    other.len()
                )))
            }
        };
        let methods = match options.methods {
            None => methods::PAPER.to_vec(),
            Some(names) => names
                .iter()
                .map(|m| m.parse::<Method>())
                .collect::<Result<Vec<_>, Error>>()
                .map_err(js_err)?,
        };
        if let Some(k) = options.feedback {
            crate::scene::validate_gain(k, run.scene.dt).map_err(js_err)?;
            run.scene.feedback_gain = k;
        }
        if let Some(k) = options.refine {
            run.scene
                .set_param(&crate::planner::methods::REFINE, k)
                .map_err(js_err)?;
        }
        if let Some(name) = options.networks.as_deref() {
            let set = name.parse::<networks::NetworkSet>().map_err(js_err)?;
            run.networks = Some(NetworkChoice::Set(set));
        }
        let networks = if methods.iter().any(|m| m.uses_networks()) {
            Some(run.load_networks().map_err(js_err)?)
        } else {
            None
        };
        let spec = Spec {
            scene: run.scene,
            grid,
            methods,
            task: Some(options.task.unwrap_or(run.task)),
        };
        Ok(AtlasJob {
            job: Job::new(spec, networks).map_err(js_err)?,
            row: n,
        })
    }

    /// Cells in the grid.
    #[wasm_bindgen(getter)]
    pub fn total(&self) -> usize {
        self.job.total()
    }

    /// Cells computed so far.
    #[wasm_bindgen(getter)]
    pub fn done(&self) -> usize {
        self.job.done()
    }

    /// Points per side: a sensible chunk is one row.
    #[wasm_bindgen(getter)]
    pub fn row(&self) -> usize {
        self.row
    }

    /// Computes up to `cells` more cells; returns how many are done in all.
    pub fn advance(&mut self, cells: usize) -> usize {
        self.job.advance(cells)
    }

    /// The finished atlas as a plain object (the JSON shape of
    /// `redundant-ik atlas --json`); throws while cells are missing.
    pub fn finish(&self) -> Result<JsValue, JsError> {
        let atlas = self.job.clone().finish().map_err(js_err)?;
        to_js(&atlas)
    }
}

/// A serialisable value as a plain JavaScript object (`None` as `null`),
/// built by serde-wasm-bindgen, which keeps NaN and infinity (an atlas
/// cell's distance or error may be either; JSON would make them `null`).
pub(super) fn to_js<T: Serialize>(value: &T) -> Result<JsValue, JsError> {
    value
        .serialize(&serde_wasm_bindgen::Serializer::json_compatible())
        .map_err(|e| JsError::new(&e.to_string()))
}

// ---- training ------------------------------------------------------------

const TRAIN_FIELDS: [&str; 6] = ["arm", "net", "preset", "samples", "epochs", "seed"];

/// The training request as the page passes it, checked.
fn training_request(request: JsValue) -> Result<crate::training_job::Request, JsError> {
    if !request.is_object() {
        return Err(JsError::new("training request: expected an object"));
    }
    known_fields(&request, &TRAIN_FIELDS, "training request")?;
    from_js(&request, "training request", true)
}

/// Forwards each epoch's progress to `on_epoch`; the job never stops early.
fn forward_epochs(
    on_epoch: &js_sys::Function,
) -> impl FnMut(&crate::training_job::Progress) -> bool + '_ {
    move |p| {
        if let Ok(v) = to_js(p) {
            let _ = on_epoch.call1(&JsValue::NULL, &v);
        }
        true
    }
}

/// `{ phi, v, report }` of a finished job.
fn trained_js(trained: &crate::training_job::Trained) -> Result<JsValue, JsError> {
    let out = serde_json::json!({
        "phi": trained.phi.to_json().map_err(js_err)?,
        "v": trained.v.to_json().map_err(js_err)?,
        "report": trained.report,
    });
    to_js(&out)
}

/// Trains networks for an arm (`crate::training_job::train`):
/// `request` is `{ arm: { post, links }, net: "phi" | "v" | "both", preset:
/// "quick" | "thorough", samples?, epochs?, seed? }`; `run` is the page's
/// run (`Demo.run()`), whose networks, where they fit the arm, give the
/// network not trained (else the built-in ones where they fit).
/// `on_epoch(progress)` is called after every epoch with `{ net,
/// optimiser, epoch, train_mse, val_mse, mu, gradient, max_epochs }`
/// (`optimiser` is `"lm"` or `"adam"`; `mu` is LM's damping or Adam's
/// learning rate). Returns `{ phi,
/// v, report }`: both weights files as JSON text and the report. Throws
/// with the core's message on bad input; nothing is installed anywhere.
#[wasm_bindgen(js_name = trainNetworks)]
pub fn train_networks(
    request: JsValue,
    run: JsValue,
    on_epoch: &js_sys::Function,
) -> Result<JsValue, JsError> {
    let request = training_request(request)?;
    let run = read_run(run)?;
    let installed = run
        .networks
        .as_ref()
        .and_then(|c| c.load().ok())
        .filter(|n| n.arm() == &request.arm);
    let current = networks::available(&request.arm, installed.as_ref()).ok();
    let trained =
        crate::training_job::train(&request, current.as_deref(), forward_epochs(on_epoch))
            .map_err(js_err)?;
    trained_js(&trained)
}

/// One network of a training request alone (`crate::training_job::train_net`),
/// `net` `"phi"` or `"v"`, so the page can train both at once in two
/// workers: returns its weights file as JSON text. `on_epoch` as for
/// [`train_networks`].
#[wasm_bindgen(js_name = trainNetwork)]
pub fn train_network(
    request: JsValue,
    net: &str,
    on_epoch: &js_sys::Function,
) -> Result<String, JsError> {
    use crate::networks::NetKind;
    let request = training_request(request)?;
    let net = match net {
        "phi" => NetKind::Phi,
        "v" => NetKind::V,
        other => {
            return Err(JsError::new(&format!(
                "network '{other}': expected phi or v"
            )))
        }
    };
    let file =
        crate::training_job::train_net(&request, net, forward_epochs(on_epoch)).map_err(js_err)?;
    file.to_json().map_err(js_err)
}

/// The end of a training request whose networks [`train_network`] trained
/// (`crate::training_job::conclude`): the check and the report, as
/// [`train_networks`] returns them.
#[wasm_bindgen(js_name = concludeTraining)]
pub fn conclude_training(
    request: JsValue,
    phi_json: &str,
    v_json: &str,
) -> Result<JsValue, JsError> {
    use crate::networks::WeightsFile;
    let request = training_request(request)?;
    let phi = WeightsFile::from_json(phi_json).map_err(js_err)?;
    let v = WeightsFile::from_json(v_json).map_err(js_err)?;
    let trained = crate::training_job::conclude(&request, phi, v).map_err(js_err)?;
    trained_js(&trained)
}

// ---- the benchmark -------------------------------------------------------

/// The benchmark's options: `batch_ms` is the shortest timed batch (1 to
/// 1000 ms); each figure is the median of seven batches after a warm-up;
/// the networks compute in `precision` (`f64` when absent, or `f32`).
pub(super) fn bench_options(
    batch_ms: f64,
    precision: Option<String>,
) -> Result<bench::Options, JsError> {
    crate::error::within("batch length (ms)", batch_ms, 1.0, 1000.0).map_err(js_err)?;
    let precision = precision
        .map(|p| p.parse::<crate::nn::Precision>())
        .transpose()
        .map_err(js_err)?
        .unwrap_or_default();
    Ok(bench::Options {
        batch_ms,
        precision,
        ..bench::Options::default()
    })
}

pub(super) fn probes() -> bench::Probes<'static> {
    bench::Probes {
        now_ms: &now_ms,
        allocations: None,
    }
}

/// The names of the methods the benchmark times (`redundant-ik bench`'s
/// default: the paper's five).
#[wasm_bindgen(js_name = benchMethods)]
pub fn bench_methods() -> Vec<String> {
    bench::Options::default()
        .methods
        .iter()
        .map(|m| m.name().to_string())
        .collect()
}

/// The learned route and the exact route it imitates, whose step times the
/// benchmark's verdict compares: `[learned, exact]` method names.
#[wasm_bindgen(js_name = benchVerdict)]
pub fn bench_verdict() -> Vec<String> {
    bench::VERDICT
        .iter()
        .map(|m| m.name().to_string())
        .collect()
}

/// One `theta_dot` of `method` at Task 1's start pose, in nanoseconds (the
/// code behind `redundant-ik bench`; one figure per call, so a Web Worker can
/// report progress between them); the networks in `precision` (`f64` when
/// absent, or `f32`).
#[wasm_bindgen(js_name = benchThetaDot)]
pub fn bench_theta_dot(
    method: &str,
    batch_ms: f64,
    precision: Option<String>,
) -> Result<f64, JsError> {
    let method: Method = method.parse().map_err(js_err)?;
    bench::theta_dot_ns(method, &bench_options(batch_ms, precision)?, &probes()).map_err(js_err)
}

/// One RK4 step of Task 1 in `method`, sample included, in nanoseconds.
#[wasm_bindgen(js_name = benchStep)]
pub fn bench_step(method: &str, batch_ms: f64, precision: Option<String>) -> Result<f64, JsError> {
    let method: Method = method.parse().map_err(js_err)?;
    bench::step_ns(method, &bench_options(batch_ms, precision)?, &probes()).map_err(js_err)
}

/// Forward passes of the shipped networks in nanoseconds: `{ phi, v }`.
#[wasm_bindgen(js_name = benchForward)]
pub fn bench_forward(batch_ms: f64, precision: Option<String>) -> Result<JsValue, JsError> {
    let f = bench::forward_ns(&bench_options(batch_ms, precision)?, &probes()).map_err(js_err)?;
    to_js(&f)
}
