//! `SpaceDemo`: an arm in space on one canvas, bound to JavaScript (the
//! page's 3-D stage). Each method forwards to the
//! [`SpaceSession`] and maps the core's errors to exceptions; drawing goes
//! to [`super::space_stage`] and the plane's [`super::plots`].

use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

use super::space_stage::{self, SliceLayer};

mod layer;
mod networks;
mod pose;
mod robot;
mod self_collision;
mod view;
use super::surface::Surface;
use super::tracked::Tracked;
use super::{finite, js_err, plots, to_js, JsResult};
use crate::export::{PoseRunFile, SpaceRunFile};
use crate::networks::space::SpaceNetworkSet;
use crate::planner::Method;
use crate::session::space::{SpaceSession, KEY_ORBIT};

/// How the page names elbow `k` (a joint, from 0): `elbow 4`.
fn elbow(k: usize) -> String {
    format!("elbow {}", k + 1)
}

/// How far a pixel of pointer travel turns the view (rad).
const ORBIT_PER_PX: f64 = 0.008;

/// One arm in space drawn on one canvas. Several can live on a page.
#[wasm_bindgen]
pub struct SpaceDemo {
    /// What is drawn, and whether the drawing is out of date: a binding
    /// changes it only through [`Tracked::edit`], which marks it stale, and
    /// [`SpaceDemo::frame`] draws only then or while the clock runs. An idle
    /// page in space then costs no drawing (it painted the arm, the floor
    /// and the plots 60 times a second, which slowed its workers' benchmark
    /// on 2 cores; docs/web.md).
    drawn: Tracked<Drawn>,
}

/// The session and the surfaces it is drawn on.
struct Drawn {
    session: SpaceSession,
    stage: Surface,
    plots: Option<Surface>,
    layer: Option<SliceLayer>,
    /// Counts the layers set or cleared, so the 3-D view redraws its
    /// cells only when they change.
    layer_revision: u32,
    keyboard: bool,
    /// The ellipsoids drawn at the hand (`setShown`, the legend's switches,
    /// as the plane's ellipses).
    shown: space_stage::Shown,
}

impl SpaceDemo {
    pub(super) fn session(&self) -> &SpaceSession {
        &self.drawn.get().session
    }

    /// The session, to change (the drawing is stale from now on).
    fn session_mut(&mut self) -> &mut SpaceSession {
        &mut self.drawn.edit().session
    }

    fn projection(&self) -> crate::session::space::Projection {
        let d = self.drawn.get();
        d.session.projection(d.stage.width, d.stage.height)
    }

    /// `session` drawn on `stage`, its plots on `plots` if given.
    fn with_session(
        stage: HtmlCanvasElement,
        plots: Option<HtmlCanvasElement>,
        session: SpaceSession,
    ) -> JsResult<SpaceDemo> {
        Ok(Self {
            drawn: Tracked::new(Drawn {
                session,
                stage: Surface::new(stage)?,
                plots: plots.map(Surface::new).transpose()?,
                layer: None,
                layer_revision: 0,
                keyboard: false,
                shown: space_stage::Shown::default(),
            }),
        })
    }
}

#[wasm_bindgen]
impl SpaceDemo {
    /// The preset `arm`'s task (`panda`, `iiwa14`) in `method` (default
    /// `numerical`), drawn on `stage`, its plots on `plots` if given;
    /// paused at `t = 0`.
    #[wasm_bindgen(constructor)]
    pub fn new(
        stage: HtmlCanvasElement,
        plots: Option<HtmlCanvasElement>,
        arm: &str,
        method: Option<String>,
    ) -> JsResult<SpaceDemo> {
        let method = match method {
            Some(m) => m.parse::<Method>().map_err(js_err)?,
            None => Method::NUMERICAL,
        };
        let session = SpaceSession::new(arm, method).map_err(js_err)?;
        Self::with_session(stage, plots, session)
    }

    /// The networks' arithmetic from now on: `f64` (the default) or `f32`
    /// (a run file keeps it as `precision`). Throws on another name,
    /// changing nothing.
    #[wasm_bindgen(js_name = setPrecision)]
    pub fn set_precision(&mut self, name: &str) -> JsResult {
        let p: crate::nn::Precision = name.parse().map_err(js_err)?;
        self.session_mut().set_precision(p);
        Ok(())
    }

    /// Switches method (by name).
    #[wasm_bindgen(js_name = setMethod)]
    pub fn set_method(&mut self, method: &str) -> JsResult {
        let m = method.parse::<Method>().map_err(js_err)?;
        self.session_mut().set_method(m).map_err(js_err)
    }

    /// Sets a method's parameter by name (`lambda`, `influence`, ...).
    #[wasm_bindgen(js_name = setParam)]
    pub fn set_param(&mut self, name: &str, value: f64) -> JsResult {
        self.session_mut().set_param(name, value).map_err(js_err)
    }

    /// `none` or `wln`.
    #[wasm_bindgen(js_name = setWeighting)]
    pub fn set_weighting(&mut self, name: &str) -> JsResult {
        let w = name.parse().map_err(js_err)?;
        self.session_mut().set_weighting(w).map_err(js_err)
    }

    /// Whether the damping schedule near singular poses is on.
    #[wasm_bindgen(js_name = setDamping)]
    pub fn set_damping(&mut self, on: bool) -> JsResult {
        self.session_mut().set_damping(on).map_err(js_err)
    }

    /// Makes the path the hand follows the one written `text` (`line`,
    /// `circle:CX,CY,CZ,NX,NY,NZ[,LAPS]`, `points:X,Y,Z;...`: the core's
    /// syntax, the address's `path=`) or, given `stroke` (canvas CSS
    /// pixels flat, `[x0, y0, x1, y1, ...]`), the polyline drawn on the
    /// plane through the hand's start that faces the camera, thinned by
    /// the core to points at least 5 cm apart; runs it and returns the
    /// path's text. Throws, changing nothing, on bad text or a path the
    /// scene refuses. (The plane's `Demo.setPath`, in space.)
    #[wasm_bindgen(js_name = setPath)]
    pub fn set_path(&mut self, text: &str, stroke: Option<Vec<f64>>) -> JsResult<String> {
        let path = match stroke {
            Some(flat) => {
                let proj = self.projection();
                self.session().drawn_path(&proj, &flat).map_err(js_err)?
            }
            None => text.parse().map_err(js_err)?,
        };
        let text = path.to_string();
        self.session_mut().set_path(path).map_err(js_err)?;
        Ok(text)
    }

    /// The run's start pose (rad, one angle a joint; the address's
    /// `theta0`). Throws, changing nothing, on the wrong count, a
    /// non-finite angle or one past its limit.
    #[wasm_bindgen(js_name = setStart)]
    pub fn set_start(&mut self, theta0: Vec<f64>) -> JsResult {
        self.session_mut().set_start(&theta0).map_err(js_err)
    }

    /// Whether the floor is an obstacle.
    #[wasm_bindgen(js_name = setFloor)]
    pub fn set_floor(&mut self, on: bool) -> JsResult {
        self.session_mut().set_floor(on).map_err(js_err)
    }

    /// Closed-loop gain `K` (1/s).
    #[wasm_bindgen(js_name = setFeedback)]
    pub fn set_feedback(&mut self, gain: f64) -> JsResult {
        self.session_mut().set_feedback(gain).map_err(js_err)
    }

    /// Playback speed (times real time).
    #[wasm_bindgen(js_name = setSpeed)]
    pub fn set_speed(&mut self, speed: f64) -> JsResult {
        self.session_mut().set_speed(speed).map_err(js_err)
    }

    /// The end of the hand's line (m).
    #[wasm_bindgen(js_name = setTarget)]
    pub fn set_target(&mut self, x: f64, y: f64, z: f64) -> JsResult {
        self.session_mut().set_target([x, y, z]).map_err(js_err)
    }

    /// The spheres, `[x, y, z, r, ...]` (m).
    #[wasm_bindgen(js_name = setSpheres)]
    pub fn set_spheres(&mut self, flat: Vec<f64>) -> JsResult {
        self.session_mut().set_spheres(&flat).map_err(js_err)
    }

    /// Adds a sphere; returns its index.
    #[wasm_bindgen(js_name = addSphere)]
    pub fn add_sphere(&mut self, x: f64, y: f64, z: f64, r: f64) -> JsResult<usize> {
        self.session_mut().add_sphere([x, y, z], r).map_err(js_err)
    }

    /// Removes sphere `i` (from 0).
    #[wasm_bindgen(js_name = removeSphere)]
    pub fn remove_sphere(&mut self, i: usize) -> JsResult {
        self.session_mut().remove_sphere(i).map_err(js_err)
    }

    /// The preset's own task again.
    #[wasm_bindgen(js_name = loadTask)]
    pub fn load_task(&mut self) -> JsResult {
        self.session_mut().load_task().map_err(js_err)
    }

    /// Back to `t = 0`, paused.
    pub fn reset(&mut self) {
        self.session_mut().reset();
    }

    /// One step, paused.
    pub fn step(&mut self) {
        self.session_mut().step();
    }

    /// Starts (replaying an ended run) or pauses the clock.
    #[wasm_bindgen(js_name = setRunning)]
    pub fn set_running(&mut self, running: bool) {
        self.session_mut().set_running(running);
    }

    /// Whether the clock runs.
    #[wasm_bindgen(getter)]
    pub fn running(&self) -> bool {
        self.session().running()
    }

    /// Shows the run at `time` (s).
    #[wasm_bindgen(js_name = runUntil)]
    pub fn run_until(&mut self, time: f64) -> JsResult {
        self.session_mut().run_until(time).map_err(js_err)
    }

    /// Advances the clock by `elapsed_ms` and, if anything changed since
    /// the last frame (a binding changed something, or the clock ran),
    /// draws and returns the state; else draws nothing and returns
    /// `undefined`, so that an idle page repaints nothing.
    pub fn frame(&mut self, elapsed_ms: f64) -> JsResult<JsValue> {
        let ((), changed) = self
            .drawn
            .tick(|d| d.session.running(), |d| d.session.tick(elapsed_ms));
        if changed {
            self.draw();
            self.state()
        } else {
            Ok(JsValue::UNDEFINED)
        }
    }

    /// The snapshot as a plain object (`docs/web.md`, "The page in space").
    pub fn state(&self) -> JsResult<JsValue> {
        to_js(&self.session().state())
    }

    /// Draws the stage's overlay and the plots (the 3-D view draws
    /// [`SpaceDemo::view`]).
    pub fn draw(&self) {
        let d = self.drawn.get();
        space_stage::draw(&d.session, &d.stage, d.keyboard);
        if let Some(p) = &d.plots {
            let limits = d
                .session
                .scene()
                .arm
                .joint_limits()
                .map_or(&[][..], |l| l.ranges());
            plots::draw_points(&d.session.points(), limits, d.session.scene().tf, p);
        }
    }

    /// Sizes the stage (CSS px, device-pixel ratio).
    pub fn resize(&mut self, width: f64, height: f64, dpr: f64) -> JsResult {
        self.drawn.edit().stage.resize(width, height, dpr)
    }

    /// Sizes the plots.
    #[wasm_bindgen(js_name = resizePlots)]
    pub fn resize_plots(&mut self, width: f64, height: f64, dpr: f64) -> JsResult {
        match &mut self.drawn.edit().plots {
            Some(p) => p.resize(width, height, dpr),
            None => Ok(()),
        }
    }

    /// The item under canvas pixel `(x, y)` (`target`, `sphere 1`, ...,
    /// or an elbow, `elbow 4`).
    pub fn hover(&self, x: f64, y: f64, slop: f64) -> Option<String> {
        let proj = self.projection();
        let s = self.session();
        s.handle_at(&proj, x, y, slop)
            .map(|h| h.describe())
            .or_else(|| s.elbow_at(&proj, x, y, slop).map(elbow))
    }

    /// Grabs the item under `(x, y)` (the target or a sphere, else an
    /// elbow, whose drag moves the arm in the null space); `undefined` on
    /// the empty drawing (where a drag orbits).
    #[wasm_bindgen(js_name = pointerDown)]
    pub fn pointer_down(&mut self, x: f64, y: f64, slop: f64) -> Option<String> {
        let proj = self.projection();
        let s = self.session_mut();
        s.pointer_down(&proj, x, y, slop)
            .map(|h| h.describe())
            .or_else(|| s.grab_elbow(&proj, x, y, slop).map(elbow))
    }

    /// Moves the arm along joint `joint`'s self-motion (from 0) by `amount`
    /// rad of joint-space arc, the hand held still (the page's slider);
    /// the pose becomes the run's start. Throws, changing nothing, at a
    /// singular pose or past a joint's limit.
    #[wasm_bindgen(js_name = selfMotion)]
    pub fn self_motion(&mut self, joint: usize, amount: f64) -> JsResult {
        self.session_mut()
            .self_motion(joint, amount)
            .map_err(js_err)
    }

    /// Moves the item held under `(x, y)`.
    #[wasm_bindgen(js_name = pointerMove)]
    pub fn pointer_move(&mut self, x: f64, y: f64) -> JsResult {
        let proj = self.projection();
        self.session_mut().pointer_move(&proj, x, y).map_err(js_err)
    }

    /// Lets go.
    #[wasm_bindgen(js_name = pointerUp)]
    pub fn pointer_up(&mut self) {
        self.session_mut().pointer_up();
    }

    /// Orbits by a pointer's travel of `(dx, dy)` CSS px.
    pub fn orbit(&mut self, dx: f64, dy: f64) -> JsResult {
        finite("orbit", dx)?;
        finite("orbit", dy)?;
        self.session_mut()
            .orbit(-dx * ORBIT_PER_PX, dy * ORBIT_PER_PX)
            .map_err(js_err)
    }

    /// Orbits by `steps` of the orbit key (15 degrees) about the vertical
    /// and `up` steps up.
    #[wasm_bindgen(js_name = orbitSteps)]
    pub fn orbit_steps(&mut self, steps: f64, up: f64) -> JsResult {
        self.session_mut()
            .orbit(steps * KEY_ORBIT, up * KEY_ORBIT)
            .map_err(js_err)
    }

    /// Zooms in by `factor` (out below 1); returns the factor applied.
    pub fn zoom(&mut self, factor: f64) -> JsResult<f64> {
        self.session_mut().zoom(factor).map_err(js_err)
    }

    /// Sets the view: yaw and pitch (rad), distance (m).
    #[wasm_bindgen(js_name = setView)]
    pub fn set_view(&mut self, yaw: f64, pitch: f64, distance: f64) -> JsResult {
        self.session_mut()
            .set_view(yaw, pitch, distance)
            .map_err(js_err)
    }

    /// Back to the preset's view.
    #[wasm_bindgen(js_name = resetView)]
    pub fn reset_view(&mut self) {
        self.session_mut().reset_view();
    }

    /// Selects the next item for the keys; returns what it is.
    #[wasm_bindgen(js_name = selectNext)]
    pub fn select_next(&mut self, forward: bool) -> String {
        self.session_mut().select_next(forward).describe()
    }

    /// Moves the selected item by `(dx, dy)` key steps along the view's
    /// right and up.
    pub fn nudge(&mut self, dx: f64, dy: f64, fine: bool) -> JsResult {
        let proj = self.projection();
        self.session_mut()
            .nudge(&proj, dx, dy, fine)
            .map_err(js_err)
    }

    /// The canvas pixel of world point `(x, y, z)`: `[x, y, depth]`.
    #[wasm_bindgen(js_name = worldToCanvas)]
    pub fn world_to_canvas(&self, x: f64, y: f64, z: f64) -> Vec<f64> {
        self.projection().project([x, y, z]).to_vec()
    }

    /// The run as `redundant-ik simulate --arm A --json` writes it (with
    /// `--task pose` for the hand's pose; what
    /// `simulate --from` replays and the workers' jobs read): the one run
    /// file, with the networks a learned method ran with (the shipped
    /// set's name, or the weights files' text of networks of your own),
    /// so that the command line replays it so, and the robot it ran (a
    /// shipped one's key; a URDF of the user's whole, without a SHA-256:
    /// the page's module has none).
    #[wasm_bindgen(js_name = runFile)]
    pub fn run_file(&self) -> String {
        let s = self.session();
        let networks = s.network_choice().cloned();
        let robot = Some(s.source().clone());
        if let (Some(scene), Some(run)) = (s.pose_scene(), s.pose_trajectory()) {
            return PoseRunFile::of(None, scene, run, networks, s.precision())
                .with_robot(robot)
                .to_json();
        }
        SpaceRunFile::of(
            None,
            s.scene().clone(),
            s.trajectory(),
            networks,
            s.precision(),
        )
        .with_robot(robot)
        .to_json()
    }

    /// The run as CSV, as `redundant-ik simulate --arm A --csv` writes it:
    /// one line per sample (the library's one run CSV,
    /// [`crate::export::run_csv`]).
    #[wasm_bindgen(js_name = runCsv)]
    pub fn run_csv(&self) -> String {
        crate::export::run_csv(self.session().samples())
    }

    /// Every method that can run here on this scene, run whole:
    /// `[{ method, summary, failure }]`.
    #[wasm_bindgen(js_name = compareMethods)]
    pub fn compare_methods(&self) -> JsResult<JsValue> {
        to_js(&self.session().compare())
    }
}

/// The arms in space (`arm=panda`): each preset's key, label, source and
/// licence, joints and limits, as the core has them.
#[wasm_bindgen(js_name = spacePresets)]
pub fn space_presets() -> JsResult<JsValue> {
    to_js(&crate::space::PRESETS)
}

/// The training recipes in space, the default first: `[{ name, hidden,
/// phi: [samples, epochs], v: [samples, epochs] }]` (the worker's
/// `trainSpaceNetwork` takes the name;
/// [`crate::training::space::SPACE_RECIPES`]).
#[wasm_bindgen(js_name = spaceTrainingRecipes)]
pub fn space_training_recipes() -> JsResult<JsValue> {
    to_js(&crate::training::space::SPACE_RECIPES)
}

/// The shipped network sets in space: `[{ name, arm, files: [phi, v] }]`,
/// the files under `weights/`.
#[wasm_bindgen(js_name = spaceNetworkSets)]
pub fn space_network_sets() -> JsResult<JsValue> {
    #[derive(serde::Serialize)]
    struct Set {
        name: &'static str,
        arm: &'static str,
        files: [&'static str; 2],
    }
    let sets: Vec<Set> = SpaceNetworkSet::ALL
        .iter()
        .map(|s| Set {
            name: s.name(),
            arm: s.arm(),
            files: s.file_names(),
        })
        .collect();
    to_js(&sets)
}
