//! The slice atlas of an arm in space in a Web Worker (feature `worker`):
//! [`SpaceAtlasJob`], the core's [`SliceJob`] a row at a time, so that the
//! worker can post progress between rows and the page can cancel (by
//! terminating the worker). Its result is the JSON text `redundant-ik
//! atlas --arm A --json` prints, written by the same serializer.

use serde::Deserialize;
use wasm_bindgen::prelude::*;

use super::js_err;
use super::worker::{read_space_run, SpaceRun};
use crate::atlas::space::{default_region, Plane, SliceJob, DEFAULT_SLICE_GRID};
use crate::atlas::Grid;
use crate::networks::space::{SpaceNetworkSet, SpaceNetworks};
use crate::planner::{methods, Method};
use crate::run::NetworkChoice;
use crate::scene::{PoseScene, SpaceScene};
use crate::space::{PoseChain, SpacePreset};

/// The options of a slice atlas as the page passes them.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Options {
    /// Method names (`"all"` and `"paper"` too); every method that runs in
    /// space when absent, the learned ones only with `networks`.
    methods: Option<Vec<String>>,
    /// `xy:Z0`, `xz:Y0` or `yz:X0`; the vertical plane through the line
    /// when absent.
    plane: Option<String>,
    /// Points per side; 21 when absent.
    n: Option<f64>,
    /// `[u0, u1, v0, v1]` in the plane's axes; the default region when
    /// absent.
    region: Option<Vec<f64>>,
    /// The weights files' text, for the learned methods.
    networks: Option<Texts>,
}

/// The JSON text of a `Phi` and a `v` weights file.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Texts {
    phi: String,
    v: String,
}

/// The slice atlas of an arm in space being computed in a worker.
///
/// ```js
/// const job = new SpaceAtlasJob(runText, {
///   methods: ['numerical', 'case3'], // names, or ['all']; absent: every method in space
///                                    // (the learned ones only with networks)
///   plane: 'xz:0.0',                 // xy:Z0 | xz:Y0 | yz:X0; absent: the vertical plane through the line
///   n: 21,                           // points per side, 2 to 201; absent: 21
///   region: [u0, u1, v0, v1],        // in the plane's axes (m); absent: the default square
///   networks: { phi, v },            // the weights files' text (the Panda's: weights/phi-panda-reach.json
///                                    // and weights/v-panda-reach.json); needed by case1-3 only
/// });
/// while (job.done < job.total) job.advance(job.row); // post progress between chunks
/// const json = job.finish();                          // the text of `atlas --arm A --json`
/// job.free();
/// ```
///
/// `runText` is a run file of an arm in space (what `simulate --arm A
/// --json` writes, with `--task pose` too, or a file of the versions
/// before it): its scene is mapped (the hand's pose task where the file
/// is of the pose: Cases 1 and 3 are left out, as `atlas --task pose`
/// leaves them), its own sphere
/// moved over the grid, the networks computing in its `precision`; its
/// method is not used. `options` is an object or
/// its JSON text; an unknown field is refused by name. The constructor
/// throws with the core's message on bad input (a method that does not
/// run in space, a learned one without networks, networks of another arm,
/// a plane that misses the arm). Cancel by no longer calling `advance`
/// (the page terminates the worker).
#[wasm_bindgen]
pub struct SpaceAtlasJob {
    job: Slice,
    /// The preset the run's chain is, if it is one.
    arm: Option<&'static str>,
}

/// The job of the hand's position task or of its pose task.
#[derive(Clone)]
enum Slice {
    Position(SliceJob),
    Pose(SliceJob<PoseChain, 6>),
}

/// Calls `$f` on the job whichever task it maps.
macro_rules! on_job {
    ($job:expr, $j:ident => $f:expr) => {
        match $job {
            Slice::Position($j) => $f,
            Slice::Pose($j) => $f,
        }
    };
}

#[wasm_bindgen]
impl SpaceAtlasJob {
    /// See the type's documentation.
    #[wasm_bindgen(constructor)]
    pub fn new(run: &str, options: JsValue) -> Result<SpaceAtlasJob, JsError> {
        // The run's scene: the hand's position, or its pose (and the
        // position scene it extends, whose line and sphere set the plane).
        let SpaceRun {
            pose,
            scene,
            networks,
            precision,
            ..
        } = read_space_run(run)?;
        let arm = SpacePreset::of(&scene.arm).map(|p| p.key);
        let o = read_options(options)?;
        // The user's own weights files travel in the run file.
        let texts = o.networks.or(match networks {
            Some(NetworkChoice::Files { phi, v }) => Some(Texts { phi, v }),
            _ => None,
        });
        // Cases 1 and 3 need a Phi, which no network has for the pose.
        let runs = |m: &Method| pose.is_none() || !m.info().networks.phi;
        let methods = match o.methods {
            None => methods::ALL
                .iter()
                .copied()
                .filter(|m| m.in_space() && (texts.is_some() || !m.uses_networks()) && runs(m))
                .collect(),
            Some(names) => Method::parse_list(&names.join(",")).map_err(js_err)?,
        };
        let plane = match o.plane.as_deref() {
            None => Plane::through_line(&scene),
            Some(text) => text.parse::<Plane>().map_err(js_err)?,
        };
        let n = match o.n {
            None => DEFAULT_SLICE_GRID,
            Some(n) => Grid::points_per_side(n).map_err(js_err)?,
        };
        let region = match o.region.as_deref() {
            None => default_region(&scene, plane),
            Some(&[a, b, c, d]) => [a, b, c, d],
            Some(other) => {
                return Err(JsError::new(&format!(
                    "region needs four numbers [u0, u1, v0, v1] in the plane's axes, got {}",
                    other.len()
                )))
            }
        };
        let grid = Grid::new(region, n).map_err(js_err)?;
        let learned = methods.iter().find(|m| m.uses_networks());
        let networks = match (learned, texts) {
            (None, _) => None,
            // In the run's arithmetic, as on the page.
            (Some(_), Some(t)) => Some(
                std::sync::Arc::new(SpaceNetworks::read(&t.phi, &t.v).map_err(js_err)?)
                    .in_precision(precision),
            ),
            (Some(m), None) => {
                let files = arm.and_then(SpaceNetworkSet::for_arm).map_or_else(
                    || "no networks are shipped for this arm".to_string(),
                    |s| {
                        let [phi, v] = s.file_names();
                        format!("its set's files are weights/{phi} and weights/{v}")
                    },
                );
                return Err(JsError::new(&format!(
                    "method {m} needs networks: pass options.networks = {{ phi, v }}, the weights files' text ({files})"
                )));
            }
        };
        let job = slice_job(
            &scene,
            pose.as_ref(),
            plane,
            grid,
            &methods,
            networks.as_ref(),
        )
        .map_err(js_err)?;
        Ok(SpaceAtlasJob { job, arm })
    }

    /// Cells in the grid.
    #[wasm_bindgen(getter)]
    pub fn total(&self) -> usize {
        on_job!(&self.job, j => j.total())
    }

    /// Cells computed so far.
    #[wasm_bindgen(getter)]
    pub fn done(&self) -> usize {
        on_job!(&self.job, j => j.done())
    }

    /// Points per side: a sensible chunk is one row.
    #[wasm_bindgen(getter)]
    pub fn row(&self) -> usize {
        on_job!(&self.job, j => j.row())
    }

    /// Computes up to `cells` more cells; returns how many are done in all.
    pub fn advance(&mut self, cells: usize) -> usize {
        on_job!(&mut self.job, j => j.advance(cells))
    }

    /// The finished atlas as the JSON text of `redundant-ik atlas --arm A
    /// --json` (a `SliceAtlas`: `arm`, `plane`, `grid`, `radius`,
    /// `methods`, `cells` of `{ centre, outcomes }`); throws while cells
    /// are missing.
    pub fn finish(&self) -> Result<String, JsError> {
        let mut atlas = on_job!(self.job.clone(), j => j.finish()).map_err(js_err)?;
        atlas.arm = self.arm;
        serde_json::to_string(&atlas).map_err(|e| JsError::new(&e.to_string()))
    }
}

/// The job of `scene`'s position task, or of `pose`'s where the run is of
/// the hand's pose.
fn slice_job(
    scene: &SpaceScene,
    pose: Option<&PoseScene>,
    plane: Plane,
    grid: crate::atlas::Grid,
    methods: &[Method],
    networks: Option<&std::sync::Arc<SpaceNetworks>>,
) -> crate::error::Result<Slice> {
    Ok(match pose {
        Some(p) => Slice::Pose(SliceJob::pose(p, plane, grid, methods, networks)?),
        None => Slice::Position(SliceJob::new(scene, plane, grid, methods, networks)?),
    })
}

/// The options as an object or as JSON text (absent: every default).
fn read_options(options: JsValue) -> Result<Options, JsError> {
    const WHAT: &str = "slice atlas options";
    if !(options.is_undefined() || options.is_null() || options.is_string()) {
        return super::worker::from_js(&options, WHAT, false);
    }
    let text = options.as_string().unwrap_or_else(|| "{}".into());
    serde_json::from_str(&text).map_err(|e| JsError::new(&format!("{WHAT}: {e}")))
}
