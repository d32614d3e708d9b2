//! `Demo`: one interactive simulation on one canvas, bound to JavaScript.
//! Each method forwards to the [`Session`] and maps the core's errors to
//! exceptions; drawing goes to [`super::stage`] and [`super::plots`].

use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

use super::layer::Layer;
use super::surface::Surface;
use super::tracked::Tracked;
use super::{finite, input, js_err, now_ms, plots, stage, to_js, JsResult};
use crate::atlas::Grid;
use crate::planner::Method;
use crate::session::Session;
use crate::view::{Camera, View};

/// One interactive simulation drawn on one canvas. Several can live on a page.
#[wasm_bindgen]
pub struct Demo {
    /// What the stage and the plots draw. The bindings reach its fields
    /// through `Deref` (`self.session`) to read them and through
    /// `DerefMut` to change them, which marks the drawing stale
    /// ([`Tracked::edit`]), so that [`Demo::frame`] draws, and hands the
    /// page a state, only when something changed or the clock ran.
    drawing: Tracked<Drawing>,
    /// What the last frame drew ([`stage::draw`]'s mask).
    drawn: std::cell::Cell<u32>,
}

/// The planar demo's drawn value: the session and how it is shown.
pub struct Drawing {
    pub(super) session: Session,
    pub(super) stage: Surface,
    plots: Option<Surface>,
    layer: Option<Layer>,
    /// The legend's entries switched on (`setShown`: the lab's ellipses).
    shown: u32,
    /// The stage's view: fitted to the scene, or the user's zoom.
    camera: Camera,
    /// Whether the drawing has the keyboard's focus: the selected item is
    /// ringed then (`setKeyboardFocus`).
    pub(super) keyboard: bool,
    /// CSS pixels to the drawing's unit: 1, or [`PROJECTOR`] in projector
    /// mode (`setProjector`).
    pub(super) magnify: f64,
}

impl Demo {
    /// The session (the script's run off screen reads it).
    pub(super) fn session(&self) -> &crate::session::Session {
        &self.drawing.get().session
    }
}

impl std::ops::Deref for Demo {
    type Target = Drawing;
    fn deref(&self) -> &Drawing {
        self.drawing.get()
    }
}

impl std::ops::DerefMut for Demo {
    /// Any change of what is drawn: the drawing is stale from now on. A
    /// change through a field's `&self` method (interior mutability: the
    /// camera's `Cell`) goes through `Deref` instead, so such a binding
    /// takes `&mut **self` itself (`moveView`, `fitView`).
    fn deref_mut(&mut self) -> &mut Drawing {
        self.drawing.edit()
    }
}

/// How much larger projector mode draws the strokes, markers and text of
/// the stage and the plots.
const PROJECTOR: f64 = 1.4;

impl Demo {
    /// The stage's view now (`crate::view::Camera`): what it draws, hit-tests
    /// and maps pointer positions with.
    pub(super) fn view(&self) -> View {
        let size = (self.stage.width, self.stage.height);
        self.camera.view(&self.session, size)
    }
}

#[wasm_bindgen]
impl Demo {
    /// A demo of the paper's task `task` (1 or 2) with method `numerical`, drawn on
    /// `stage`, with the time-series plots on `plots` if given. Paused at `t = 0`.
    #[wasm_bindgen(constructor)]
    pub fn new(
        stage: HtmlCanvasElement,
        plots: Option<HtmlCanvasElement>,
        task: u32,
    ) -> JsResult<Demo> {
        super::install_panic_hook();
        let mut session = Session::new(task).map_err(js_err)?;
        session.set_clock(now_ms);
        Ok(Demo {
            drawing: Tracked::new(Drawing {
                session,
                stage: Surface::new(stage)?,
                plots: plots.map(Surface::new).transpose()?,
                layer: None,
                shown: 0,
                camera: Camera::default(),
                keyboard: false,
                magnify: 1.0,
            }),
            drawn: std::cell::Cell::new(0),
        })
    }

    /// Loads the paper's scene `task` (1 or 2; obstacle, start pose, target and
    /// `lambda = 4`), keeping the method, the damping switch and the feedback
    /// gain, and runs it from `t = 0` to `tf = 10 s`.
    #[wasm_bindgen(js_name = loadTask)]
    pub fn load_task(&mut self, task: u32) -> JsResult {
        self.session.load_task(task).map_err(js_err)
    }

    /// Back to `t = 0` of the current scene (with the current target and
    /// obstacle), paused, histories cleared.
    pub fn reset(&mut self) {
        self.session.reset();
    }

    /// Resets and runs the current scene from `t = 0` to its final time.
    #[wasm_bindgen(js_name = runTask)]
    pub fn run_task(&mut self) {
        self.session.run_task();
    }

    /// Sets the method by name (`methods()` lists them). Methods that use
    /// networks take the loaded ones, else the built-in ones where they fit
    /// the arm; without them this throws "networks not available: ..." and
    /// the method stays as it was.
    #[wasm_bindgen(js_name = setMethod)]
    pub fn set_method(&mut self, method: &str) -> JsResult {
        let method: Method = method.parse().map_err(js_err)?;
        self.session.set_method(method).map_err(js_err)
    }

    /// Sets `lambda`, the gain of the obstacle vector (eq. 14); at least 0.
    #[wasm_bindgen(js_name = setLambda)]
    pub fn set_lambda(&mut self, lambda: f64) -> JsResult {
        self.session.set_lambda(lambda).map_err(js_err)
    }

    /// Sets a parameter of the methods by name (`lambda`, `influence`,
    /// `stop_distance`, ...; `params()` lists them with their bounds).
    /// Throws, changing nothing, on an unknown name or a value out of bounds.
    #[wasm_bindgen(js_name = setParam)]
    pub fn set_param(&mut self, name: &str, value: f64) -> JsResult {
        let param = crate::planner::params::by_name(name).map_err(js_err)?;
        self.session.set_param(param, value).map_err(js_err)
    }

    /// Switches the damping schedule (damped least squares near singular
    /// poses) on or off.
    #[wasm_bindgen(js_name = setDamping)]
    pub fn set_damping(&mut self, on: bool) -> JsResult {
        self.session.set_damping(on).map_err(js_err)
    }

    /// Moves the arm along the self-motion through joint `joint` (0-based)
    /// by `amount` rad of joint-space arc, the hand holding still; the new
    /// pose is the run's start, paused. Throws, changing nothing, where
    /// the joint has no self-motion or the pose would pass a limit.
    #[wasm_bindgen(js_name = selfMotion)]
    pub fn self_motion(&mut self, joint: usize, amount: f64) -> JsResult {
        self.session.self_motion(joint, amount).map_err(js_err)
    }

    /// How the methods of eq. (5) use the arm's joint limits: a name of
    /// `limits().joint_weightings` (`none`, `wln`); refused, changing
    /// nothing, for any other.
    #[wasm_bindgen(js_name = setWeighting)]
    pub fn set_weighting(&mut self, name: &str) -> JsResult {
        let w = name.parse().map_err(js_err)?;
        self.session.set_weighting(w);
        Ok(())
    }

    /// Switches a legend entry the page offers a toggle for (`legend()`'s
    /// `toggle`: `ellipse`, `force`) on or off; false for any other key.
    #[wasm_bindgen(js_name = setShown)]
    pub fn set_shown(&mut self, key: &str, on: bool) -> bool {
        let Some(b) = super::style::toggle_bit(key) else {
            return false;
        };
        self.shown = if on { self.shown | b } else { self.shown & !b };
        self.draw();
        true
    }

    /// Whether the floor `y = 0` and the post are obstacles for the
    /// methods that read link-obstacle pairs (`distance`, `priority`, `qp`).
    #[wasm_bindgen(js_name = setFloor)]
    pub fn set_floor(&mut self, on: bool) {
        self.session.set_floor(on);
    }

    /// Closed-loop gain `K` (1/s): the planner then commands
    /// `Xdot + K (X_ref - X)`; `0` is the paper's open loop (the default).
    #[wasm_bindgen(js_name = setFeedback)]
    pub fn set_feedback(&mut self, gain: f64) -> JsResult {
        self.session.set_feedback(gain).map_err(js_err)
    }

    /// Simulated seconds per real second (0.05 to 50).
    #[wasm_bindgen(js_name = setSpeed)]
    pub fn set_speed(&mut self, speed: f64) -> JsResult {
        self.session.set_speed(speed).map_err(js_err)
    }

    /// Plans a new straight line from the current end effector to `(x, y)`,
    /// lasting `duration` seconds (default: at 0.25 m/s, at least 1 s).
    #[wasm_bindgen(js_name = setTarget)]
    pub fn set_target(&mut self, x: f64, y: f64, duration: Option<f64>) -> JsResult {
        self.session.set_target([x, y], duration).map_err(js_err)
    }

    /// Starts the run from the joint angles `theta0` (rad) and ends it at
    /// `tf` (s, whole steps): a run shared by its address. Throws, changing
    /// nothing, on a bad pose or time.
    #[wasm_bindgen(js_name = setStart)]
    pub fn set_start(&mut self, theta0: Vec<f64>, tf: f64) -> JsResult {
        self.session.set_start(theta0, tf).map_err(js_err)
    }

    /// Moves the obstacle centre to `(x, y)` (takes effect at the next step).
    /// Throws, leaving it where it was, if the disc would overlap the base post.
    #[wasm_bindgen(js_name = setObstacle)]
    pub fn set_obstacle(&mut self, x: f64, y: f64) -> JsResult {
        self.session.set_obstacle([x, y]).map_err(js_err)
    }

    /// Starts or pauses the clock.
    #[wasm_bindgen(js_name = setRunning)]
    pub fn set_running(&mut self, running: bool) {
        self.session.set_running(running);
    }

    /// Whether the clock runs.
    #[wasm_bindgen(getter)]
    pub fn running(&self) -> bool {
        self.session.running()
    }

    /// One RK4 step (the page's "step" button); pauses the clock.
    pub fn step(&mut self) -> JsResult {
        self.session.step().map_err(js_err)
    }

    /// Steps without drawing until `t >= time` (a fast path for tests and
    /// scripts), honouring a task's stop time. At most 100 000 steps.
    #[wasm_bindgen(js_name = runUntil)]
    pub fn run_until(&mut self, time: f64) -> JsResult {
        self.session.run_until(time).map_err(js_err)
    }

    /// Advances the clock by `elapsed_ms` of real time (scaled by the speed)
    /// and, if anything changed since the last frame (a binding changed
    /// the scene or the view, or the clock ran), draws and returns the
    /// state (as [`Demo::state`]); else draws nothing and returns
    /// `undefined`, so that an idle page repaints nothing. Throws if a step
    /// fails; the clock is then paused and the state is the last good one.
    ///
    /// A frame is one call into the module (and a drag's pointer move the
    /// other).
    pub fn frame(&mut self, elapsed_ms: f64) -> JsResult<JsValue> {
        let (stepped, changed) = self
            .drawing
            .tick(|d| d.session.running(), |d| d.session.tick(elapsed_ms));
        if changed || stepped.is_err() {
            self.draw();
        }
        stepped.map_err(js_err)?;
        if changed {
            self.state()
        } else {
            Ok(JsValue::UNDEFINED)
        }
    }

    /// Runs the current scene from `t = 0` to `tf` with every method, off
    /// screen: `[{ method, label, summary, error }]`, `summary` as the CLI's
    /// JSON or `null` with `error` saying why the method could not run.
    #[wasm_bindgen(js_name = compareMethods)]
    pub fn compare_methods(&self) -> JsResult<JsValue> {
        to_js(&self.session.compare_methods())
    }

    /// A snapshot of the state as a plain object (see `docs/web.md`);
    /// `networks` says whether the methods that use networks can run
    /// (networks loaded, or built-in ones trained for the arm).
    pub fn state(&self) -> JsResult<JsValue> {
        let state = to_js(&self.session.state())?;
        // What the last frame drew (`drawn()`), so the page needs no
        // second call for the legend.
        let _ = js_sys::Reflect::set(&state, &"drawn".into(), &self.drawn.get().into());
        Ok(state)
    }

    /// The scene as a plain object (arm, start pose, target, obstacles,
    /// parameters, time step).
    pub fn scene(&self) -> JsResult<JsValue> {
        to_js(self.session.planner().scene())
    }

    /// What runs, as a plain object `{ task, method, scene, networks }`
    /// (`networks`: `{ set }` for a shipped set, `{ phi, v }` with the
    /// weights files' text for the user's, absent when none is installed):
    /// what the workers' jobs take (`AtlasJob`, `runFiles`, the training's
    /// check) and what a run file records.
    pub fn run(&self) -> JsResult<JsValue> {
        to_js(&self.session.run())
    }

    /// Shows an atlas under the arm: `region` `[x0, x1, y0, y1]`, `n` points
    /// per side and one class index per cell (rows from `y0`, each from
    /// `x0`; the order of `atlasClasses()`). Throws, keeping the layer shown
    /// before, if they do not fit together.
    #[wasm_bindgen(js_name = setAtlasLayer)]
    pub fn set_atlas_layer(&mut self, region: Vec<f64>, n: usize, classes: Vec<u8>) -> JsResult {
        let [x0, x1, y0, y1] = region[..] else {
            return Err(JsError::new(&format!(
                "region needs four numbers [x0, x1, y0, y1], got {}",
                region.len()
            )));
        };
        let grid = Grid::new([x0, x1, y0, y1], n).map_err(js_err)?;
        self.layer = Some(Layer::new(grid, classes).map_err(js_err)?);
        Ok(())
    }

    /// Hides the atlas layer.
    #[wasm_bindgen(js_name = clearAtlasLayer)]
    pub fn clear_atlas_layer(&mut self) {
        self.layer = None;
    }

    /// The atlas cell under canvas CSS pixel `(x, y)`, if a layer is shown
    /// and the point lies on it; the cell is outlined until the next call.
    #[wasm_bindgen(js_name = atlasCellAt)]
    pub fn atlas_cell_at(&mut self, x: f64, y: f64) -> Option<usize> {
        let view = self.view();
        let layer = self.layer.as_mut()?;
        let cell = (x.is_finite() && y.is_finite())
            .then(|| layer.grid().nearest(view.to_world(x, y)))
            .flatten();
        layer.hover = cell;
        cell
    }

    /// Sets the stage size in CSS pixels and the device-pixel ratio, then redraws.
    pub fn resize(&mut self, width: f64, height: f64, dpr: f64) -> JsResult {
        self.stage.resize(width, height, dpr)?;
        self.draw();
        Ok(())
    }

    /// Sets the plot canvas size in CSS pixels and the device-pixel ratio.
    #[wasm_bindgen(js_name = resizePlots)]
    pub fn resize_plots(&mut self, width: f64, height: f64, dpr: f64) -> JsResult {
        if let Some(p) = &mut self.plots {
            p.resize(width, height, dpr)?;
        }
        self.draw();
        Ok(())
    }

    /// Moves the stage's view so that the world point at canvas CSS pixel
    /// `(x, y)` comes to `(to_x, to_y)`, zoomed by `factor` (0.5 to 8
    /// times the fitted scale in all): the wheel zooms about the pointer
    /// (`to` = `(x, y)`), a drag on the empty drawing pans (`factor` 1),
    /// two fingers do both. Returns the zoom now (1: fitted). The view is
    /// then the user's until `fitView()`: kept when the scene changes.
    #[wasm_bindgen(js_name = moveView)]
    pub fn move_view(&mut self, x: f64, y: f64, to_x: f64, to_y: f64, factor: f64) -> f64 {
        // `&mut`: the camera keeps its view in a `Cell`, and a move must
        // mark the drawing stale as any other change does.
        let d = &mut **self;
        let size = (d.stage.width, d.stage.height);
        let moved = ((x, y), (to_x, to_y));
        d.camera.move_view(&d.session, size, moved, factor)
    }

    /// Fits the stage's view to the arm's reach, the obstacles, the target
    /// and the path again (the view follows the scene from then on).
    #[wasm_bindgen(js_name = fitView)]
    pub fn fit_view(&mut self) {
        // Through `DerefMut` explicitly: `Camera::fit` takes `&self`.
        let d = &mut **self;
        d.camera.fit();
    }

    /// Canvas CSS-pixel position `[x, y]` of the world point `(x, y)` (metres).
    #[wasm_bindgen(js_name = worldToCanvas)]
    pub fn world_to_canvas(&self, x: f64, y: f64) -> JsResult<Vec<f64>> {
        let (px, py) = self.view().to_px([finite("x", x)?, finite("y", y)?]);
        Ok(vec![px, py])
    }

    /// World position `[x, y]` (metres) of the canvas CSS-pixel point `(x, y)`.
    #[wasm_bindgen(js_name = canvasToWorld)]
    pub fn canvas_to_world(&self, x: f64, y: f64) -> JsResult<Vec<f64>> {
        let view = self.view();
        Ok(view.to_world(finite("x", x)?, finite("y", y)?).to_vec())
    }

    /// What a pointer at canvas CSS pixel `(x, y)` would grab, with `slop`
    /// extra pixels of tolerance: `"target"`, `"obstacle"` or `undefined`.
    pub fn hover(&self, x: f64, y: f64, slop: f64) -> Option<String> {
        input::hit(&self.session, self.view(), x, y, slop).map(|h| h.name().into())
    }

    /// Starts a drag at canvas CSS pixel `(x, y)`; returns what was grabbed
    /// (`"target"`, `"obstacle"` or `undefined`).
    #[wasm_bindgen(js_name = pointerDown)]
    pub fn pointer_down(&mut self, x: f64, y: f64, slop: f64) -> Option<String> {
        let grabbed = input::hit(&self.session, self.view(), x, y, slop);
        self.session.drag_start(grabbed);
        grabbed.map(|h| h.name().into())
    }

    /// Moves the held handle. The obstacle moves at once; throws (and stays
    /// put) if it would overlap the base post. The target only moves its
    /// marker until [`Demo::pointer_up`].
    #[wasm_bindgen(js_name = pointerMove)]
    pub fn pointer_move(&mut self, x: f64, y: f64) -> JsResult {
        let p = input::drag_point(&self.stage, self.view(), x, y);
        self.session.drag_to(p).map_err(js_err)
    }

    /// Ends a drag at `(x, y)`. Releasing the target plans a new straight line
    /// from the current end effector and starts the clock.
    #[wasm_bindgen(js_name = pointerUp)]
    pub fn pointer_up(&mut self, x: f64, y: f64) -> JsResult {
        let p = input::drag_point(&self.stage, self.view(), x, y);
        self.session.drag_end(p).map_err(js_err)
    }

    /// Abandons a drag (pointer cancelled): the target stays where it was.
    #[wasm_bindgen(js_name = pointerCancel)]
    pub fn pointer_cancel(&mut self) {
        self.session.drag_cancel();
    }

    /// Which entries of `legend()` the last frame drew: bit `i` for entry
    /// `i` (the page's legend shows only those).
    pub fn drawn(&self) -> u32 {
        self.drawn.get()
    }

    /// Projector mode: the stage's and the plots' strokes, markers and
    /// text [`PROJECTOR`] times larger, the world where it was.
    #[wasm_bindgen(js_name = setProjector)]
    pub fn set_projector(&mut self, on: bool) {
        self.magnify = if on { PROJECTOR } else { 1.0 };
    }

    /// Redraws the stage and the plots.
    pub fn draw(&self) {
        let k = self.magnify;
        // The surfaces as they are, or magnified for projector mode (a
        // copy of their handles only then: this runs every frame).
        let magnified = |s: &Surface| (k != 1.0).then(|| s.magnified(k));
        let big_stage = magnified(&self.stage);
        let stage = big_stage.as_ref().unwrap_or(&self.stage);
        let view = self.view().magnified(k);
        let drawn = stage::draw(&self.session, stage, view, self.layer.as_ref(), self.shown);
        self.drawn.set(drawn);
        if self.keyboard {
            self.ring_selected(stage, view);
        }
        if let Some(p) = &self.plots {
            let big = magnified(p);
            plots::draw(&self.session, big.as_ref().unwrap_or(p));
        }
    }
}
