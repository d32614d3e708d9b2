//! The browser shell: a thin `wasm-bindgen` layer over [`Planner`].
//!
//! No mathematics lives here. A [`Demo`] owns a planner (and, in the network
//! cases, a second planner in `numerical` mode: the "ghost" arm), forwards the
//! page's requests to it, keeps the histories the page draws (trail,
//! stroboscopic trace, time series) and draws everything on a canvas through
//! `web-sys`. Every core error reaches JavaScript as an exception carrying the
//! core's message; every value that comes from JavaScript is checked first
//! (NaN included), so nothing the user does can panic the module.

use std::cell::RefCell;
use std::f64::consts::PI;
use std::sync::Arc;

use serde::Serialize;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{CanvasRenderingContext2d, HtmlCanvasElement};

use crate::bench;
use crate::error::{Error, Result};
use crate::{
    DampingSchedule, Line, Mode, Networks, Obstacle, Planner, Scene, Surrogate, TrainedRange,
};

/// Speed (m/s) of the straight line planned when the user drops the target.
const DRAG_LINE_SPEED: f64 = 0.25;
/// Shortest line the page plans after a drag (s).
const MIN_LINE_DURATION: f64 = 1.0;
/// Every how many steps a pose joins the stroboscopic trace (the paper's figures).
const STROBE_EVERY: usize = 5;
/// Most steps one animation frame may take (keeps a slow device responsive).
const MAX_STEPS_PER_FRAME: usize = 40;
/// Caps on the stored histories.
const MAX_TRAIL: usize = 4000;
const MAX_STROBE: usize = 200;
const MAX_HISTORY: usize = 600;
/// Largest canvas side accepted from the page (device pixels).
const MAX_CANVAS_PX: f64 = 8192.0;
/// World rectangle (metres) the stage always shows: x range, then y range.
const VIEW_X: [f64; 2] = [-0.6, 2.2];
const VIEW_Y: [f64; 2] = [-0.25, 1.95];

const FONT: &str = "system-ui, -apple-system, 'Segoe UI', Roboto, sans-serif";
const INK: &str = "#1f2933";
const MUTED: &str = "#6b7785";
const GRID: &str = "#eef1f5";
const AXIS: &str = "#c4ccd6";
const ARM: &str = "#1d4e89";
const ACCENT: &str = "#d9731a";
const DANGER: &str = "#c0392b";
const TEAL: &str = "#2a9d8f";
const GHOST: &str = "#5f6b78";

thread_local! {
    /// The trained networks built into the module, loaded once (or why not).
    static NETWORKS: RefCell<Option<std::result::Result<Loaded, String>>> =
        const { RefCell::new(None) };
    /// Message of the last panic, for the page to show.
    static LAST_PANIC: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Trained networks as the planner uses them, with what they were trained on.
#[derive(Clone)]
struct Loaded {
    surrogate: Arc<dyn Surrogate>,
    range: TrainedRange,
}

impl Loaded {
    fn new(nets: Networks) -> Self {
        Self {
            range: nets.trained_range(),
            surrogate: Arc::new(nets),
        }
    }
}

/// The one place the network modes are wired in: the trained networks
/// shipped with the module.
fn embedded_networks() -> Result<Loaded> {
    let nets = Networks::embedded().map_err(|e| {
        Error::NetworksUnavailable(format!("the built-in weights could not be loaded ({e})"))
    })?;
    Ok(Loaded::new(nets))
}

/// The shared networks, loading them on first use.
fn shared_networks() -> std::result::Result<Loaded, String> {
    NETWORKS.with(|cell| {
        cell.borrow_mut()
            .get_or_insert_with(|| embedded_networks().map_err(|e| e.to_string()))
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

/// Whether the trained networks (Cases 1-3) are available, and if not, why.
/// Returns `null` when they are, else the reason.
#[wasm_bindgen(js_name = networksError)]
pub fn networks_error() -> Option<String> {
    shared_networks().err()
}

/// The in-browser benchmark, one figure per call so that a Web Worker can
/// report progress between them (`www/bench-worker.js`); the same code as
/// `redundant-ik bench` ([`crate::bench`]), timed with `performance.now()`.
/// `batch_ms` is the shortest timed batch (1 to 1000 ms); each figure is the
/// median of seven batches after a warm-up.
fn bench_options(batch_ms: f64) -> std::result::Result<bench::Options, JsError> {
    finite("batch length", batch_ms)?;
    if !(1.0..=1000.0).contains(&batch_ms) {
        return Err(JsError::new(&format!(
            "the batch length must lie between 1 and 1000 ms (got {batch_ms})"
        )));
    }
    Ok(bench::Options {
        batch_ms,
        ..bench::Options::default()
    })
}

fn bench_probes(clock: &dyn Fn() -> f64) -> bench::Probes<'_> {
    bench::Probes {
        now_ms: clock,
        allocations: None,
    }
}

/// One `theta_dot` of `mode` at Task 1's start pose, in nanoseconds.
#[wasm_bindgen(js_name = benchThetaDot)]
pub fn bench_theta_dot(mode: &str, batch_ms: f64) -> std::result::Result<f64, JsError> {
    let mode: Mode = mode.parse().map_err(js_err)?;
    let opts = bench_options(batch_ms)?;
    bench::theta_dot_ns(mode, &opts, &bench_probes(&now_ms)).map_err(js_err)
}

/// One RK4 step of Task 1 in `mode`, sample included, in nanoseconds.
#[wasm_bindgen(js_name = benchStep)]
pub fn bench_step(mode: &str, batch_ms: f64) -> std::result::Result<f64, JsError> {
    let mode: Mode = mode.parse().map_err(js_err)?;
    let opts = bench_options(batch_ms)?;
    bench::step_ns(mode, &opts, &bench_probes(&now_ms)).map_err(js_err)
}

/// Forward passes of the shipped networks in nanoseconds:
/// `{ phi, v, phi_plain, phi_rows }`.
#[wasm_bindgen(js_name = benchForward)]
pub fn bench_forward(batch_ms: f64) -> std::result::Result<JsValue, JsError> {
    let opts = bench_options(batch_ms)?;
    let f = bench::forward_ns(&opts, &bench_probes(&now_ms)).map_err(js_err)?;
    to_js(&f)
}

/// A serialisable value as a plain JavaScript object.
fn to_js<T: Serialize>(value: &T) -> std::result::Result<JsValue, JsError> {
    let json = serde_json::to_string(value).map_err(|e| JsError::new(&e.to_string()))?;
    js_sys::JSON::parse(&json).map_err(|_| JsError::new("could not build the result object"))
}

fn js_err(e: Error) -> JsError {
    JsError::new(&e.to_string())
}

fn finite(what: &str, value: f64) -> std::result::Result<f64, JsError> {
    crate::error::finite(what, value).map_err(js_err)
}

thread_local! {
    /// The global `performance` object: the window's, or the worker's.
    static PERFORMANCE: Option<web_sys::Performance> =
        js_sys::Reflect::get(&js_sys::global(), &JsValue::from_str("performance"))
            .ok()
            .and_then(|p| p.dyn_into::<web_sys::Performance>().ok());
}

/// `performance.now()` in a page or a worker (0 where there is none).
fn now_ms() -> f64 {
    PERFORMANCE.with(|p| p.as_ref().map_or(0.0, |p| p.now()))
}

/// A canvas and its 2-D context, with its size in CSS pixels.
struct Surface {
    canvas: HtmlCanvasElement,
    ctx: CanvasRenderingContext2d,
    width: f64,
    height: f64,
    dpr: f64,
}

impl Surface {
    fn new(canvas: HtmlCanvasElement) -> std::result::Result<Self, JsError> {
        let ctx = canvas
            .get_context("2d")
            .ok()
            .flatten()
            .and_then(|c| c.dyn_into::<CanvasRenderingContext2d>().ok())
            .ok_or_else(|| JsError::new("this browser gives no 2-D canvas context"))?;
        let width = f64::from(canvas.client_width().max(1));
        let height = f64::from(canvas.client_height().max(1));
        let mut s = Self {
            canvas,
            ctx,
            width,
            height,
            dpr: 1.0,
        };
        s.resize(width, height, 1.0)?;
        Ok(s)
    }

    /// Sets the size in CSS pixels and the device-pixel ratio; the backing store
    /// gets `size * dpr` pixels, so lines stay sharp on high-DPI screens.
    fn resize(&mut self, width: f64, height: f64, dpr: f64) -> std::result::Result<(), JsError> {
        for (what, v) in [
            ("width", width),
            ("height", height),
            ("device pixel ratio", dpr),
        ] {
            finite(what, v)?;
            if v <= 0.0 {
                return Err(JsError::new(&format!(
                    "canvas {what} must be positive (got {v})"
                )));
            }
        }
        let dpr = dpr.min(4.0);
        let w = (width * dpr).round().clamp(1.0, MAX_CANVAS_PX);
        let h = (height * dpr).round().clamp(1.0, MAX_CANVAS_PX);
        self.canvas.set_width(w as u32);
        self.canvas.set_height(h as u32);
        self.width = w / dpr;
        self.height = h / dpr;
        self.dpr = dpr;
        Ok(())
    }

    /// Clears to white and sets the CSS-pixel transform.
    fn begin(&self) {
        let c = &self.ctx;
        let _ = c.set_transform(self.dpr, 0.0, 0.0, self.dpr, 0.0, 0.0);
        c.set_global_alpha(1.0);
        c.set_fill_style_str("#ffffff");
        c.fill_rect(0.0, 0.0, self.width, self.height);
        c.set_line_cap("round");
        c.set_line_join("round");
    }
}

/// The world-to-canvas map of the stage (CSS pixels, y up in the world).
#[derive(Clone, Copy)]
struct View {
    scale: f64,
    ox: f64,
    oy: f64,
}

impl View {
    fn fit(width: f64, height: f64) -> Self {
        let (wx, wy) = (VIEW_X[1] - VIEW_X[0], VIEW_Y[1] - VIEW_Y[0]);
        let scale = (width / wx).min(height / wy);
        let cx = 0.5 * (VIEW_X[0] + VIEW_X[1]);
        let cy = 0.5 * (VIEW_Y[0] + VIEW_Y[1]);
        Self {
            scale,
            ox: 0.5 * width - scale * cx,
            oy: 0.5 * height + scale * cy,
        }
    }
    fn to_px(self, p: [f64; 2]) -> (f64, f64) {
        (self.ox + self.scale * p[0], self.oy - self.scale * p[1])
    }
    fn to_world(self, x: f64, y: f64) -> [f64; 2] {
        [(x - self.ox) / self.scale, (self.oy - y) / self.scale]
    }
}

/// Which handle the pointer holds.
#[derive(Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
enum Handle {
    Target,
    Obstacle,
}

impl Handle {
    fn name(self) -> &'static str {
        match self {
            Handle::Target => "target",
            Handle::Obstacle => "obstacle",
        }
    }
}

/// One point of the time-series plots.
#[derive(Clone, Copy)]
struct Point {
    t: f64,
    distance: Option<f64>,
    error: f64,
    theta: [f64; 3],
}

/// The ghost arm: the same scene and changes, solved numerically.
struct Ghost {
    planner: Planner,
    prev: Vec<f64>,
}

/// The snapshot [`Demo::state`] returns.
#[derive(Serialize)]
struct State<'a> {
    t: f64,
    task: u32,
    mode: &'a str,
    running: bool,
    speed: f64,
    lambda: f64,
    damping: bool,
    auto_damping: bool,
    feedback: f64,
    theta: &'a [f64],
    joints: &'a [[f64; 2]],
    ee: [f64; 2],
    reference: [f64; 2],
    target: [f64; 2],
    line: Line,
    obstacle: Option<[f64; 2]>,
    radius: Option<f64>,
    distance: Option<f64>,
    min_distance: Option<f64>,
    collision: bool,
    collided: bool,
    tracking_error: f64,
    final_error: f64,
    manipulability: f64,
    delta: f64,
    in_range: bool,
    phi_handover: bool,
    handover_steps: usize,
    networks: bool,
    trained_range: Option<&'a TrainedRange>,
    ghost: Option<GhostState>,
    steps: usize,
    frame_steps: usize,
    solver_ms: f64,
    solver_ms_per_step: f64,
    dragging: Option<&'static str>,
    error: Option<&'a str>,
}

#[derive(Serialize)]
struct GhostState {
    theta: Vec<f64>,
    ee: [f64; 2],
}

/// One interactive simulation drawn on one canvas. Several can live on a page.
#[wasm_bindgen]
pub struct Demo {
    planner: Planner,
    networks: Option<Loaded>,
    ghost: Option<Ghost>,
    task: u32,
    damping: bool,
    stage: Surface,
    plots: Option<Surface>,
    running: bool,
    stop_at: Option<f64>,
    speed: f64,
    backlog: f64,
    prev_theta: Vec<f64>,
    trail: Vec<[f64; 2]>,
    strobe: Vec<Vec<[f64; 2]>>,
    strobe_count: usize,
    history: Vec<Point>,
    drag: Option<Handle>,
    drag_point: Option<[f64; 2]>,
    frame_steps: usize,
    solver_ms: f64,
    solver_ms_per_step: f64,
    error: Option<String>,
}

#[wasm_bindgen]
impl Demo {
    /// A demo of the paper's task `task` (1 or 2) in mode `numerical`, drawn on
    /// `stage`, with the time-series plots on `plots` if given. Paused at `t = 0`.
    #[wasm_bindgen(constructor)]
    pub fn new(
        stage: HtmlCanvasElement,
        plots: Option<HtmlCanvasElement>,
        task: u32,
    ) -> std::result::Result<Demo, JsError> {
        install_panic_hook();
        let planner =
            Planner::new(Self::scene(task, true, 0.0)?, Mode::Numerical, None).map_err(js_err)?;
        let mut demo = Demo {
            prev_theta: planner.sample().theta.clone(),
            planner,
            networks: None,
            ghost: None,
            task,
            damping: true,
            stage: Surface::new(stage)?,
            plots: plots.map(Surface::new).transpose()?,
            running: false,
            stop_at: None,
            speed: 2.0,
            backlog: 0.0,
            trail: Vec::new(),
            strobe: Vec::new(),
            strobe_count: 0,
            history: Vec::new(),
            drag: None,
            drag_point: None,
            frame_steps: 0,
            solver_ms: 0.0,
            solver_ms_per_step: 0.0,
            error: None,
        };
        demo.clear_histories();
        Ok(demo)
    }

    fn scene(task: u32, damping: bool, feedback: f64) -> std::result::Result<Scene, JsError> {
        let mut scene = Scene::task(task).map_err(js_err)?;
        scene.damping = damping.then(DampingSchedule::default);
        scene.feedback_gain = feedback;
        Ok(scene)
    }

    /// Loads the paper's scene `task` (1 or 2; obstacle, start pose, target and
    /// `lambda = 4`), keeping the mode, the damping switch and the feedback
    /// gain, and runs it from
    /// `t = 0` to `tf = 10 s`.
    #[wasm_bindgen(js_name = loadTask)]
    pub fn load_task(&mut self, task: u32) -> std::result::Result<(), JsError> {
        let scene = Self::scene(task, self.damping, self.planner.scene().feedback_gain)?;
        let networks = self.networks.as_ref().map(|n| n.surrogate.clone());
        let planner = Planner::new(scene, self.planner.mode(), networks).map_err(js_err)?;
        self.planner = planner;
        self.task = task;
        self.restart();
        self.run_to_end();
        Ok(())
    }

    /// Back to `t = 0` of the current scene (with the current target and
    /// obstacle), paused, histories cleared.
    pub fn reset(&mut self) {
        self.planner.reset();
        self.restart();
    }

    /// Resets and runs the current scene from `t = 0` to its final time.
    #[wasm_bindgen(js_name = runTask)]
    pub fn run_task(&mut self) {
        self.reset();
        self.run_to_end();
    }

    fn run_to_end(&mut self) {
        self.running = true;
        self.stop_at = Some(self.planner.scene().tf);
    }

    fn restart(&mut self) {
        self.running = false;
        self.stop_at = None;
        self.backlog = 0.0;
        self.error = None;
        self.drag = None;
        self.drag_point = None;
        self.sync_ghost(true);
        self.clear_histories();
    }

    fn clear_histories(&mut self) {
        self.prev_theta.clone_from(&self.planner.sample().theta);
        self.trail.clear();
        self.strobe.clear();
        self.history.clear();
        self.strobe_count = 0;
        self.record();
    }

    /// Keeps the ghost planner in step with the mode: present in the network
    /// cases (a copy of the planner, solved numerically), absent otherwise.
    fn sync_ghost(&mut self, fresh: bool) {
        let mode = self.planner.mode();
        if !(mode.learned_phi() || mode.learned_v()) {
            self.ghost = None;
            return;
        }
        if self.ghost.is_some() && !fresh {
            return;
        }
        let mut planner = self.planner.clone();
        if planner.set_mode(Mode::Numerical).is_ok() {
            let prev = planner.theta().iter().cloned().collect();
            self.ghost = Some(Ghost { planner, prev });
        }
    }

    /// Sets the mode: `none`, `numerical`, `case1`, `case2` or `case3`. The
    /// network cases need the trained networks; without them this throws
    /// "networks not available: ..." and the mode stays as it was.
    #[wasm_bindgen(js_name = setMode)]
    pub fn set_mode(&mut self, mode: &str) -> std::result::Result<(), JsError> {
        let mode: Mode = mode.parse().map_err(js_err)?;
        if (mode.learned_phi() || mode.learned_v()) && self.networks.is_none() {
            let nets = shared_networks().map_err(|e| JsError::new(&e))?;
            self.planner
                .set_networks(Some(nets.surrogate.clone()))
                .map_err(js_err)?;
            self.networks = Some(nets);
        }
        self.planner.set_mode(mode).map_err(js_err)?;
        self.sync_ghost(false);
        Ok(())
    }

    /// Loads user-trained networks for this demo from the JSON text of a `Phi`
    /// weights file and a `v` weights file (the format `redundant-ik train`
    /// writes). Throws with the reason if they are corrupt or do not fit the
    /// arm; the networks in use stay then.
    #[wasm_bindgen(js_name = loadNetworks)]
    pub fn load_networks(
        &mut self,
        phi_json: &str,
        v_json: &str,
    ) -> std::result::Result<(), JsError> {
        let nets = Networks::from_json(phi_json, v_json).map_err(js_err)?;
        let loaded = Loaded::new(nets);
        self.planner
            .set_networks(Some(loaded.surrogate.clone()))
            .map_err(js_err)?;
        if let Some(g) = &mut self.ghost {
            g.planner
                .set_networks(Some(loaded.surrogate.clone()))
                .map_err(js_err)?;
        }
        self.networks = Some(loaded);
        Ok(())
    }

    /// Sets `lambda`, the gain of the obstacle vector (eq. 14); at least 0.
    #[wasm_bindgen(js_name = setLambda)]
    pub fn set_lambda(&mut self, lambda: f64) -> std::result::Result<(), JsError> {
        self.planner.set_lambda(lambda).map_err(js_err)?;
        if let Some(g) = &mut self.ghost {
            g.planner.set_lambda(lambda).map_err(js_err)?;
        }
        Ok(())
    }

    /// Switches the damping schedule (damped least squares near singular
    /// poses) on or off.
    #[wasm_bindgen(js_name = setDamping)]
    pub fn set_damping(&mut self, on: bool) -> std::result::Result<(), JsError> {
        let d = on.then(DampingSchedule::default);
        self.planner.set_damping(d).map_err(js_err)?;
        if let Some(g) = &mut self.ghost {
            g.planner.set_damping(d).map_err(js_err)?;
        }
        self.damping = on;
        Ok(())
    }

    /// Closed-loop gain `K` (1/s): the planner then commands
    /// `Xdot + K (X_ref - X)`, which pulls the end effector back onto the line
    /// and keeps the networks' small errors from accumulating. `0` is the
    /// paper's open loop (the default). The ghost arm gets the same gain.
    #[wasm_bindgen(js_name = setFeedback)]
    pub fn set_feedback(&mut self, gain: f64) -> std::result::Result<(), JsError> {
        self.planner.set_feedback_gain(gain).map_err(js_err)?;
        if let Some(g) = &mut self.ghost {
            g.planner.set_feedback_gain(gain).map_err(js_err)?;
        }
        Ok(())
    }

    /// Simulated seconds per real second (0.05 to 50).
    #[wasm_bindgen(js_name = setSpeed)]
    pub fn set_speed(&mut self, speed: f64) -> std::result::Result<(), JsError> {
        finite("speed", speed)?;
        if !(0.05..=50.0).contains(&speed) {
            return Err(JsError::new(&format!(
                "speed must lie between 0.05 and 50 (got {speed})"
            )));
        }
        self.speed = speed;
        Ok(())
    }

    /// Plans a new straight line from the current end effector to `(x, y)`,
    /// lasting `duration` seconds (default: at 0.25 m/s, at least 1 s).
    #[wasm_bindgen(js_name = setTarget)]
    pub fn set_target(
        &mut self,
        x: f64,
        y: f64,
        duration: Option<f64>,
    ) -> std::result::Result<(), JsError> {
        let target = [finite("target x", x)?, finite("target y", y)?];
        let duration = match duration {
            Some(d) => finite("line duration", d)?,
            None => {
                let ee = self.planner.sample().ee;
                let dist = (target[0] - ee[0]).hypot(target[1] - ee[1]);
                (dist / DRAG_LINE_SPEED).max(MIN_LINE_DURATION)
            }
        };
        self.planner.set_target(target, duration).map_err(js_err)?;
        if let Some(g) = &mut self.ghost {
            g.planner.set_target(target, duration).map_err(js_err)?;
        }
        self.strobe.clear();
        self.strobe_count = 0;
        Ok(())
    }

    /// Moves the obstacle centre to `(x, y)` (takes effect at the next step).
    /// Throws, leaving it where it was, if the disc would overlap the base post.
    #[wasm_bindgen(js_name = setObstacle)]
    pub fn set_obstacle(&mut self, x: f64, y: f64) -> std::result::Result<(), JsError> {
        let (x, y) = (finite("obstacle x", x)?, finite("obstacle y", y)?);
        let radius = self
            .planner
            .scene()
            .obstacles
            .first()
            .map_or(crate::scene::PAPER_RADIUS, |o| o.radius);
        let obstacles = vec![Obstacle::new(x, y, radius)];
        self.planner
            .set_obstacles(obstacles.clone())
            .map_err(js_err)?;
        if let Some(g) = &mut self.ghost {
            g.planner.set_obstacles(obstacles).map_err(js_err)?;
        }
        Ok(())
    }

    /// Starts or pauses the clock. Starting after a task run continues
    /// without a stop time.
    #[wasm_bindgen(js_name = setRunning)]
    pub fn set_running(&mut self, running: bool) {
        if running && !self.running {
            self.backlog = 0.0;
            if self
                .stop_at
                .is_some_and(|s| self.planner.time() >= s - 1e-9)
            {
                self.stop_at = None;
            }
        }
        self.running = running;
    }

    /// Whether the clock runs.
    #[wasm_bindgen(getter)]
    pub fn running(&self) -> bool {
        self.running
    }

    /// One RK4 step (the page's "step" button); pauses the clock.
    pub fn step(&mut self) -> std::result::Result<(), JsError> {
        self.running = false;
        self.backlog = 0.0;
        self.advance(1).map_err(js_err)?;
        self.prev_theta.clone_from(&self.planner.sample().theta);
        Ok(())
    }

    /// Steps without drawing until `t >= time` (a fast path for tests and
    /// scripts), honouring a task's stop time. At most 100 000 steps.
    #[wasm_bindgen(js_name = runUntil)]
    pub fn run_until(&mut self, time: f64) -> std::result::Result<(), JsError> {
        finite("time", time)?;
        let dt = self.planner.scene().dt;
        let end = self.stop_at.map_or(time, |s| s.min(time));
        let n = ((end - self.planner.time()) / dt - 1e-9)
            .ceil()
            .clamp(0.0, 100_000.0) as usize;
        self.advance(n).map_err(js_err)?;
        self.prev_theta.clone_from(&self.planner.sample().theta);
        self.check_stop();
        Ok(())
    }

    /// Advances the clock by `elapsed_ms` of real time (scaled by the speed;
    /// nothing happens while paused) and draws the frame. Throws if a step
    /// fails; the clock is then paused and the state is the last good one.
    pub fn frame(&mut self, elapsed_ms: f64) -> std::result::Result<(), JsError> {
        let mut result = Ok(());
        if self.running && elapsed_ms.is_finite() && elapsed_ms > 0.0 {
            let dt = self.planner.scene().dt;
            self.backlog += elapsed_ms.min(250.0) / 1000.0 * self.speed / dt;
            let mut n = (self.backlog.floor() as usize).min(MAX_STEPS_PER_FRAME);
            if let Some(stop) = self.stop_at {
                let left = ((stop - self.planner.time()) / dt - 1e-9).ceil().max(0.0) as usize;
                n = n.min(left);
            }
            self.backlog = (self.backlog - n as f64).clamp(0.0, 1.0);
            result = self.advance(n);
            self.check_stop();
        }
        self.draw();
        result.map_err(js_err)
    }

    fn check_stop(&mut self) {
        if let Some(stop) = self.stop_at {
            if self.planner.time() >= stop - 1e-9 {
                self.running = false;
                self.backlog = 0.0;
            }
        }
    }

    /// Takes `n` steps, timing the planner's step calls.
    fn advance(&mut self, n: usize) -> Result<()> {
        if n == 0 {
            return Ok(());
        }
        let mut solver = 0.0;
        let mut taken = 0;
        for _ in 0..n {
            // The pose before the step, for smooth drawing (after a failed
            // step, the unchanged pose itself).
            self.prev_theta.clear();
            self.prev_theta
                .extend_from_slice(self.planner.theta().as_slice());
            let t0 = now_ms();
            let stepped = self.planner.step().map(|_| ());
            solver += now_ms() - t0;
            if let Err(e) = stepped {
                self.running = false;
                self.backlog = 0.0;
                self.error = Some(e.to_string());
                self.frame_steps = taken;
                return Err(e);
            }
            taken += 1;
            if let Some(g) = &mut self.ghost {
                g.prev.clear();
                g.prev.extend_from_slice(g.planner.theta().as_slice());
                if g.planner.step().is_err() {
                    // The numerical comparison failed where the networks did not;
                    // the ghost is only an illustration, so it bows out.
                    self.ghost = None;
                }
            }
            self.record();
        }
        self.error = None;
        self.frame_steps = taken;
        self.solver_ms = solver;
        self.solver_ms_per_step = solver / taken as f64;
        Ok(())
    }

    /// Appends the planner's current sample to the histories the page draws.
    fn record(&mut self) {
        let s = self.planner.sample();
        if self.trail.len() >= MAX_TRAIL {
            self.trail.drain(..MAX_TRAIL / 4);
        }
        self.trail.push(s.ee);
        if self.strobe_count.is_multiple_of(STROBE_EVERY) {
            if self.strobe.len() >= MAX_STROBE {
                self.strobe.remove(0);
            }
            self.strobe.push(s.joints.clone());
        }
        self.strobe_count += 1;
        if self.history.len() >= MAX_HISTORY {
            self.history.remove(0);
        }
        let th = |i: usize| s.theta.get(i).copied().unwrap_or(0.0);
        self.history.push(Point {
            t: s.t,
            distance: s.distance,
            error: s.tracking_error,
            theta: [th(0), th(1), th(2)],
        });
    }

    /// Runs the current scene (start pose, target, obstacle, `lambda`,
    /// damping and feedback as they are now) from `t = 0` to `tf` in each of
    /// the five modes, without touching the simulation on screen. Returns an
    /// array of `{ mode, summary, error }`: `summary` as the CLI's JSON
    /// (`min_distance`, `collided`, `final_error`, `reached`,
    /// `out_of_range_steps`, ...) or `null` with `error` saying why the mode
    /// could not run (e.g. no networks, or a singular pose without damping).
    #[wasm_bindgen(js_name = compareModes)]
    pub fn compare_modes(&self) -> std::result::Result<JsValue, JsError> {
        #[derive(Serialize)]
        struct Row {
            mode: &'static str,
            summary: Option<crate::Summary>,
            error: Option<String>,
        }
        let scene = self.planner.scene().clone();
        let networks = match &self.networks {
            Some(n) => Some(n.surrogate.clone()),
            None => shared_networks().ok().map(|n| n.surrogate),
        };
        let rows: Vec<Row> = Mode::ALL
            .iter()
            .map(
                |&mode| match Planner::run(scene.clone(), mode, networks.clone()) {
                    Ok(run) => Row {
                        mode: mode.name(),
                        summary: Some(run.summary),
                        error: None,
                    },
                    Err(e) => Row {
                        mode: mode.name(),
                        summary: None,
                        error: Some(e.to_string()),
                    },
                },
            )
            .collect();
        let json = serde_json::to_string(&rows).map_err(|e| JsError::new(&e.to_string()))?;
        js_sys::JSON::parse(&json).map_err(|_| JsError::new("could not build the comparison"))
    }

    /// A snapshot of the state as a plain object: `t`, `mode`, `theta`,
    /// `joints`, `ee`, `target`, `obstacle`, `radius`, `distance`,
    /// `min_distance` and `collided` (since the last reset or task load),
    /// `running`, `solver_ms` (planner step time in the last frame that
    /// stepped) and more.
    pub fn state(&self) -> std::result::Result<JsValue, JsError> {
        let s = self.planner.sample();
        let summary = self.planner.summary();
        let scene = self.planner.scene();
        let obstacle = scene.obstacles.first();
        let state = State {
            t: s.t,
            task: self.task,
            mode: self.planner.mode().name(),
            running: self.running,
            speed: self.speed,
            lambda: scene.lambda,
            damping: scene.damping.is_some(),
            auto_damping: summary.auto_damping,
            feedback: scene.feedback_gain,
            theta: &s.theta,
            joints: &s.joints,
            ee: s.ee,
            reference: s.reference,
            target: scene.target,
            line: self.planner.line(),
            obstacle: obstacle.map(|o| o.centre),
            radius: obstacle.map(|o| o.radius),
            distance: s.distance,
            min_distance: summary.min_distance,
            collision: s.collision,
            collided: summary.collided,
            tracking_error: s.tracking_error,
            final_error: summary.final_error,
            manipulability: s.manipulability,
            delta: s.delta,
            in_range: s.in_range,
            phi_handover: s.phi_handover,
            handover_steps: summary.handover_steps,
            networks: self.networks.is_some() || shared_networks().is_ok(),
            trained_range: self.networks.as_ref().map(|n| &n.range),
            ghost: self.ghost.as_ref().map(|g| GhostState {
                theta: g.planner.theta().iter().cloned().collect(),
                ee: {
                    let x = scene.arm.forward(g.planner.theta());
                    [x[0], x[1]]
                },
            }),
            steps: summary.steps,
            frame_steps: self.frame_steps,
            solver_ms: self.solver_ms,
            solver_ms_per_step: self.solver_ms_per_step,
            dragging: self.drag.map(Handle::name),
            error: self.error.as_deref(),
        };
        let json = serde_json::to_string(&state).map_err(|e| JsError::new(&e.to_string()))?;
        js_sys::JSON::parse(&json).map_err(|_| JsError::new("could not build the state object"))
    }

    /// Sets the stage size in CSS pixels and the device-pixel ratio, then redraws.
    pub fn resize(
        &mut self,
        width: f64,
        height: f64,
        dpr: f64,
    ) -> std::result::Result<(), JsError> {
        self.stage.resize(width, height, dpr)?;
        self.draw();
        Ok(())
    }

    /// Sets the plot canvas size in CSS pixels and the device-pixel ratio.
    #[wasm_bindgen(js_name = resizePlots)]
    pub fn resize_plots(
        &mut self,
        width: f64,
        height: f64,
        dpr: f64,
    ) -> std::result::Result<(), JsError> {
        if let Some(p) = &mut self.plots {
            p.resize(width, height, dpr)?;
        }
        self.draw();
        Ok(())
    }

    fn view(&self) -> View {
        View::fit(self.stage.width, self.stage.height)
    }

    /// Canvas CSS-pixel position `[x, y]` of the world point `(x, y)` (metres).
    #[wasm_bindgen(js_name = worldToCanvas)]
    pub fn world_to_canvas(&self, x: f64, y: f64) -> std::result::Result<Vec<f64>, JsError> {
        let p = self.view().to_px([finite("x", x)?, finite("y", y)?]);
        Ok(vec![p.0, p.1])
    }

    /// World position `[x, y]` (metres) of the canvas CSS-pixel point `(x, y)`.
    #[wasm_bindgen(js_name = canvasToWorld)]
    pub fn canvas_to_world(&self, x: f64, y: f64) -> std::result::Result<Vec<f64>, JsError> {
        Ok(self
            .view()
            .to_world(finite("x", x)?, finite("y", y)?)
            .to_vec())
    }

    fn hit(&self, x: f64, y: f64, slop: f64) -> Option<Handle> {
        let view = self.view();
        let near = |p: [f64; 2], r: f64| {
            let (px, py) = view.to_px(p);
            (px - x).hypot(py - y) <= r
        };
        let scene = self.planner.scene();
        let target = self
            .drag_point
            .filter(|_| self.drag == Some(Handle::Target));
        if near(target.unwrap_or(scene.target), 10.0 + slop) {
            return Some(Handle::Target);
        }
        let ob = scene.obstacles.first()?;
        near(ob.centre, ob.radius * view.scale + slop).then_some(Handle::Obstacle)
    }

    /// What a pointer at canvas CSS pixel `(x, y)` would grab, with `slop`
    /// extra pixels of tolerance: `"target"`, `"obstacle"` or `""`.
    pub fn hover(&self, x: f64, y: f64, slop: f64) -> String {
        if !(x.is_finite() && y.is_finite() && slop.is_finite()) {
            return String::new();
        }
        self.hit(x, y, slop.clamp(0.0, 64.0))
            .map_or("", Handle::name)
            .to_string()
    }

    /// Starts a drag at canvas CSS pixel `(x, y)`; returns what was grabbed
    /// (`"target"`, `"obstacle"` or `""`).
    #[wasm_bindgen(js_name = pointerDown)]
    pub fn pointer_down(&mut self, x: f64, y: f64, slop: f64) -> String {
        let grabbed = self.hover(x, y, slop);
        self.drag = match grabbed.as_str() {
            "target" => Some(Handle::Target),
            "obstacle" => Some(Handle::Obstacle),
            _ => None,
        };
        self.drag_point = None;
        grabbed
    }

    /// Moves the held handle. The obstacle moves at once; throws (and stays
    /// put) if it would overlap the base post. The target only moves its
    /// marker until [`Demo::pointer_up`].
    #[wasm_bindgen(js_name = pointerMove)]
    pub fn pointer_move(&mut self, x: f64, y: f64) -> std::result::Result<(), JsError> {
        let Some(handle) = self.drag else {
            return Ok(());
        };
        // Keep handles on the canvas, so they can always be picked up again.
        let (x, y) = (finite("pointer x", x)?, finite("pointer y", y)?);
        let (w, h) = (self.stage.width, self.stage.height);
        let p = self
            .view()
            .to_world(x.clamp(8.0, w - 8.0), y.clamp(8.0, h - 8.0));
        match handle {
            Handle::Target => {
                self.drag_point = Some(p);
                Ok(())
            }
            Handle::Obstacle => self.set_obstacle(p[0], p[1]),
        }
    }

    /// Ends a drag at `(x, y)`. Releasing the target plans a new straight line
    /// from the current end effector and starts the clock.
    #[wasm_bindgen(js_name = pointerUp)]
    pub fn pointer_up(&mut self, x: f64, y: f64) -> std::result::Result<(), JsError> {
        let moved = self.pointer_move(x, y);
        let handle = self.drag.take();
        let point = self.drag_point.take();
        moved?;
        if let (Some(Handle::Target), Some(p)) = (handle, point) {
            self.set_target(p[0], p[1], None)?;
            self.stop_at = None;
            self.set_running(true);
        }
        Ok(())
    }

    /// Abandons a drag (pointer cancelled): the target stays where it was.
    #[wasm_bindgen(js_name = pointerCancel)]
    pub fn pointer_cancel(&mut self) {
        self.drag = None;
        self.drag_point = None;
    }

    /// Redraws the stage and the plots.
    pub fn draw(&self) {
        self.draw_stage();
        if let Some(p) = &self.plots {
            self.draw_plots(p);
        }
    }
}

// ---------------------------------------------------------------------------
// Drawing
// ---------------------------------------------------------------------------

fn dash(ctx: &CanvasRenderingContext2d, pattern: &[f64]) {
    let arr = js_sys::Array::new();
    for v in pattern {
        arr.push(&JsValue::from_f64(*v));
    }
    let _ = ctx.set_line_dash(&arr);
}

fn polyline(ctx: &CanvasRenderingContext2d, view: View, pts: &[[f64; 2]]) {
    ctx.begin_path();
    for (i, p) in pts.iter().enumerate() {
        let (x, y) = view.to_px(*p);
        if i == 0 {
            ctx.move_to(x, y);
        } else {
            ctx.line_to(x, y);
        }
    }
    ctx.stroke();
}

fn disc(ctx: &CanvasRenderingContext2d, x: f64, y: f64, r: f64) {
    ctx.begin_path();
    let _ = ctx.arc(x, y, r.max(0.0), 0.0, 2.0 * PI);
}

/// Tick spacing giving about `target` ticks over `span`.
fn nice_step(span: f64, target: f64) -> f64 {
    let raw = (span / target).max(1e-12);
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let nice = if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

fn fmt_tick(v: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).clamp(0.0, 6.0) as usize;
    let v = if v.abs() < step * 1e-6 { 0.0 } else { v };
    format!("{v:.decimals$}")
}

impl Demo {
    /// The pose to draw: between the last two steps while the clock runs, so
    /// motion looks smooth at any speed.
    fn display_theta(&self, prev: &[f64], now: &[f64]) -> nalgebra::DVector<f64> {
        let a = if self.running {
            self.backlog.clamp(0.0, 1.0)
        } else {
            1.0
        };
        nalgebra::DVector::from_iterator(
            now.len(),
            now.iter()
                .zip(prev.iter().chain(std::iter::repeat(&0.0)))
                .map(|(n, p)| p + a * (n - p)),
        )
    }

    fn draw_stage(&self) {
        let s = &self.stage;
        let ctx = &s.ctx;
        let view = self.view();
        s.begin();
        self.draw_grid(ctx, view, s.width, s.height);

        let scene = self.planner.scene();
        let arm = &scene.arm;
        let base = arm.base();

        // Workspace boundary: what the end effector can reach.
        ctx.set_stroke_style_str(AXIS);
        ctx.set_line_width(1.0);
        dash(ctx, &[2.0, 5.0]);
        let (bx, by) = view.to_px([base[0], base[1]]);
        disc(ctx, bx, by, arm.max_reach() * view.scale);
        ctx.stroke();
        dash(ctx, &[]);

        // Where the v network saw obstacles in training (network v modes).
        if let (true, Some(n)) = (self.planner.mode().learned_v(), &self.networks) {
            let (x0, y0) = view.to_px(n.range.obstacle_min);
            let (x1, y1) = view.to_px(n.range.obstacle_max);
            ctx.set_stroke_style_str("#b9c7d6");
            ctx.set_line_width(1.0);
            dash(ctx, &[3.0, 4.0]);
            ctx.stroke_rect(x0.min(x1), y0.min(y1), (x1 - x0).abs(), (y1 - y0).abs());
            dash(ctx, &[]);
            ctx.set_font(&format!("10px {FONT}"));
            ctx.set_fill_style_str(MUTED);
            ctx.set_text_align("left");
            ctx.set_text_baseline("bottom");
            let _ = ctx.fill_text(
                "v net: trained obstacle region",
                x0.min(x1) + 3.0,
                y0.min(y1) - 3.0,
            );
        }

        // Stroboscopic trace: every fifth pose, faint (as in Figs. 2-11).
        ctx.set_stroke_style_str(ARM);
        ctx.set_global_alpha(0.16);
        ctx.set_line_width(1.5);
        for pose in &self.strobe {
            polyline(ctx, view, pose);
        }
        ctx.set_global_alpha(1.0);

        // The straight line being tracked.
        let line = self.planner.line();
        ctx.set_stroke_style_str(MUTED);
        ctx.set_line_width(1.25);
        dash(ctx, &[6.0, 5.0]);
        polyline(ctx, view, &[line.start, line.end]);
        dash(ctx, &[]);

        // End-effector trail.
        ctx.set_stroke_style_str(ACCENT);
        ctx.set_line_width(2.0);
        polyline(ctx, view, &self.trail);

        // Obstacle disc, with its point O.
        for ob in &scene.obstacles {
            let (ox, oy) = view.to_px(ob.centre);
            let hit = self.planner.sample().collision;
            disc(ctx, ox, oy, ob.radius * view.scale);
            ctx.set_fill_style_str(if hit {
                "rgba(192,57,43,0.55)"
            } else {
                "rgba(192,57,43,0.16)"
            });
            ctx.fill();
            ctx.set_stroke_style_str(DANGER);
            ctx.set_line_width(if self.drag == Some(Handle::Obstacle) {
                2.5
            } else {
                1.5
            });
            ctx.stroke();
            disc(ctx, ox, oy, 2.0);
            ctx.set_fill_style_str(DANGER);
            ctx.fill();
        }

        // Base post and ground.
        let (gx, gy) = view.to_px([0.0, 0.0]);
        ctx.set_fill_style_str("#dfe4ea");
        ctx.fill_rect(gx - 18.0, gy, 36.0, 6.0);
        ctx.set_stroke_style_str("#4a5560");
        ctx.set_line_width(8.0);
        ctx.set_line_cap("butt");
        polyline(ctx, view, &[[0.0, 0.0], [base[0], base[1]]]);
        ctx.set_line_cap("round");

        // The arm.
        let pose = arm.joints(&self.display_theta(&self.prev_theta, &self.planner.sample().theta));
        let pts: Vec<[f64; 2]> = pose.iter().map(|p| [p[0], p[1]]).collect();
        ctx.set_stroke_style_str(ARM);
        ctx.set_line_width(7.0);
        polyline(ctx, view, &pts);
        for (i, p) in pts.iter().enumerate() {
            let (x, y) = view.to_px(*p);
            let last = i + 1 == pts.len();
            disc(ctx, x, y, if last { 3.5 } else { 5.0 });
            ctx.set_fill_style_str(if last { ARM } else { "#ffffff" });
            ctx.fill();
            ctx.set_line_width(2.0);
            ctx.stroke();
        }

        // Ghost, on top: where the numerical route would have the arm.
        if let Some(g) = &self.ghost {
            let th: Vec<f64> = g.planner.theta().iter().cloned().collect();
            let pose = arm.joints(&self.display_theta(&g.prev, &th));
            let pts: Vec<[f64; 2]> = pose.iter().map(|p| [p[0], p[1]]).collect();
            ctx.set_global_alpha(0.8);
            ctx.set_stroke_style_str(GHOST);
            ctx.set_line_width(2.0);
            dash(ctx, &[7.0, 5.0]);
            polyline(ctx, view, &pts);
            dash(ctx, &[]);
            for p in &pts[1..] {
                let (x, y) = view.to_px(*p);
                disc(ctx, x, y, 3.0);
                ctx.stroke();
            }
            ctx.set_global_alpha(1.0);
        }

        // Reference point on the line.
        let (rx, ry) = view.to_px(self.planner.sample().reference);
        disc(ctx, rx, ry, 3.0);
        ctx.set_fill_style_str(MUTED);
        ctx.fill();

        // Target marker (at the pointer while dragging).
        let target = match (self.drag, self.drag_point) {
            (Some(Handle::Target), Some(p)) => p,
            _ => scene.target,
        };
        let (tx, ty) = view.to_px(target);
        ctx.set_stroke_style_str(ACCENT);
        ctx.set_line_width(if self.drag == Some(Handle::Target) {
            2.5
        } else {
            2.0
        });
        disc(ctx, tx, ty, 9.0);
        ctx.stroke();
        ctx.begin_path();
        ctx.move_to(tx - 14.0, ty);
        ctx.line_to(tx - 4.0, ty);
        ctx.move_to(tx + 4.0, ty);
        ctx.line_to(tx + 14.0, ty);
        ctx.move_to(tx, ty - 14.0);
        ctx.line_to(tx, ty - 4.0);
        ctx.move_to(tx, ty + 4.0);
        ctx.line_to(tx, ty + 14.0);
        ctx.stroke();

        // Caption.
        ctx.set_font(&format!("600 12px {FONT}"));
        ctx.set_fill_style_str(INK);
        ctx.set_text_align("left");
        ctx.set_text_baseline("top");
        let _ = ctx.fill_text(
            &format!(
                "t = {:.1} s   ·   {}",
                self.planner.sample().t,
                mode_label(self.planner.mode())
            ),
            12.0,
            10.0,
        );
    }

    fn draw_grid(&self, ctx: &CanvasRenderingContext2d, view: View, w: f64, h: f64) {
        let lo = view.to_world(0.0, h);
        let hi = view.to_world(w, 0.0);
        let step = nice_step((hi[0] - lo[0]).min(hi[1] - lo[1]), 6.0);
        ctx.set_line_width(1.0);
        ctx.set_font(&format!("11px {FONT}"));
        ctx.set_fill_style_str(MUTED);
        let (ax, ay) = view.to_px([0.0, 0.0]);
        let mut x = (lo[0] / step).ceil() * step;
        ctx.set_text_align("center");
        ctx.set_text_baseline("top");
        while x <= hi[0] {
            let (px, _) = view.to_px([x, 0.0]);
            ctx.set_stroke_style_str(if x.abs() < 1e-9 { AXIS } else { GRID });
            ctx.begin_path();
            ctx.move_to(px.round() + 0.5, 0.0);
            ctx.line_to(px.round() + 0.5, h);
            ctx.stroke();
            if x.abs() > 1e-9 {
                let _ = ctx.fill_text(&fmt_tick(x, step), px, (ay + 8.0).min(h - 14.0));
            }
            x += step;
        }
        let mut y = (lo[1] / step).ceil() * step;
        ctx.set_text_align("right");
        ctx.set_text_baseline("middle");
        while y <= hi[1] {
            let (_, py) = view.to_px([0.0, y]);
            ctx.set_stroke_style_str(if y.abs() < 1e-9 { AXIS } else { GRID });
            ctx.begin_path();
            ctx.move_to(0.0, py.round() + 0.5);
            ctx.line_to(w, py.round() + 0.5);
            ctx.stroke();
            if y.abs() > 1e-9 {
                let _ = ctx.fill_text(&fmt_tick(y, step), (ax - 6.0).max(28.0), py);
            }
            y += step;
        }
        ctx.set_text_align("right");
        ctx.set_text_baseline("bottom");
        let _ = ctx.fill_text("X₁ (m)", w - 8.0, ay - 4.0);
        ctx.set_text_align("left");
        ctx.set_text_baseline("top");
        let _ = ctx.fill_text("X₂ (m)", ax + 6.0, 30.0);
    }

    fn draw_plots(&self, s: &Surface) {
        s.begin();
        let ctx = &s.ctx;
        let (t0, t1) = match (self.history.first(), self.history.last()) {
            (Some(a), Some(b)) => (a.t, b.t.max(a.t + 10.0)),
            _ => (0.0, 10.0),
        };
        let panel_h = s.height / 3.0;
        let radius = self.planner.scene().obstacles.first().map(|o| o.radius);

        let distance: Vec<(f64, f64)> = self
            .history
            .iter()
            .filter_map(|p| p.distance.map(|d| (p.t, d)))
            .collect();
        let dmax = distance
            .iter()
            .map(|p| p.1)
            .fold(radius.unwrap_or(0.0) * 2.0, f64::max);
        let frame = PlotFrame::new(s.width, 0.0, panel_h, (t0, t1), (0.0, dmax * 1.1));
        frame.axes(ctx, "distance to obstacle (m)");
        if let Some(r) = radius {
            ctx.set_stroke_style_str(DANGER);
            ctx.set_line_width(1.0);
            dash(ctx, &[4.0, 3.0]);
            frame.line(ctx, &[(t0, r), (t1, r)]);
            dash(ctx, &[]);
            frame.label_right(ctx, "radius", r, DANGER);
        }
        ctx.set_stroke_style_str(ARM);
        ctx.set_line_width(1.75);
        frame.line(ctx, &distance);

        let error: Vec<(f64, f64)> = self.history.iter().map(|p| (p.t, p.error)).collect();
        let emax = error.iter().map(|p| p.1).fold(1e-3, f64::max);
        let frame = PlotFrame::new(s.width, panel_h, panel_h, (t0, t1), (0.0, emax * 1.1));
        frame.axes(ctx, "tracking error (m)");
        ctx.set_stroke_style_str(ACCENT);
        ctx.set_line_width(1.75);
        frame.line(ctx, &error);

        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for p in &self.history {
            for v in p.theta {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        if !(lo.is_finite() && hi.is_finite()) {
            (lo, hi) = (-PI, PI);
        }
        let pad = ((hi - lo) * 0.1).max(0.1);
        let frame = PlotFrame::new(
            s.width,
            2.0 * panel_h,
            panel_h,
            (t0, t1),
            (lo - pad, hi + pad),
        );
        frame.axes(ctx, "joint angles (rad)");
        for (i, (colour, name)) in [(ARM, "θ₁"), (TEAL, "θ₂"), (ACCENT, "θ₃")]
            .into_iter()
            .enumerate()
        {
            frame.key(ctx, i, name, colour);
            let series: Vec<(f64, f64)> = self.history.iter().map(|p| (p.t, p.theta[i])).collect();
            ctx.set_stroke_style_str(colour);
            ctx.set_line_width(1.5);
            frame.line(ctx, &series);
        }
    }
}

fn mode_label(mode: Mode) -> &'static str {
    match mode {
        Mode::None => "no avoidance (v = 0)",
        Mode::Numerical => "numerical Φ and v",
        Mode::Case1 => "Case 1: Φ by network, v numerical",
        Mode::Case2 => "Case 2: Φ numerical, v by network",
        Mode::Case3 => "Case 3: Φ and v by networks",
    }
}

/// One small time-series panel.
struct PlotFrame {
    left: f64,
    right: f64,
    top: f64,
    bottom: f64,
    tx: (f64, f64),
    vy: (f64, f64),
}

impl PlotFrame {
    fn new(width: f64, y0: f64, height: f64, tx: (f64, f64), vy: (f64, f64)) -> Self {
        let span = (vy.1 - vy.0).abs().max(1e-12);
        Self {
            left: 44.0,
            right: width - 10.0,
            top: y0 + 22.0,
            bottom: y0 + height - 18.0,
            tx,
            vy: (vy.0, vy.0 + span),
        }
    }

    fn px(&self, t: f64, v: f64) -> (f64, f64) {
        let fx = (t - self.tx.0) / (self.tx.1 - self.tx.0).max(1e-12);
        let fy = (v - self.vy.0) / (self.vy.1 - self.vy.0);
        (
            self.left + fx * (self.right - self.left),
            self.bottom - fy.clamp(-0.05, 1.05) * (self.bottom - self.top),
        )
    }

    fn axes(&self, ctx: &CanvasRenderingContext2d, title: &str) {
        ctx.set_font(&format!("600 11px {FONT}"));
        ctx.set_fill_style_str(INK);
        ctx.set_text_align("left");
        ctx.set_text_baseline("bottom");
        let _ = ctx.fill_text(title, self.left, self.top - 6.0);
        ctx.set_font(&format!("10px {FONT}"));
        ctx.set_fill_style_str(MUTED);
        ctx.set_line_width(1.0);
        // Value ticks.
        let step = nice_step(self.vy.1 - self.vy.0, 3.0);
        let mut v = (self.vy.0 / step).ceil() * step;
        ctx.set_text_align("right");
        ctx.set_text_baseline("middle");
        while v <= self.vy.1 + 1e-12 {
            let (_, y) = self.px(self.tx.0, v);
            ctx.set_stroke_style_str(GRID);
            ctx.begin_path();
            ctx.move_to(self.left, y.round() + 0.5);
            ctx.line_to(self.right, y.round() + 0.5);
            ctx.stroke();
            let _ = ctx.fill_text(&fmt_tick(v, step), self.left - 5.0, y);
            v += step;
        }
        // Time ticks.
        let step = nice_step(self.tx.1 - self.tx.0, 5.0);
        let mut t = (self.tx.0 / step).ceil() * step;
        ctx.set_text_align("center");
        ctx.set_text_baseline("top");
        while t <= self.tx.1 + 1e-9 {
            let (x, _) = self.px(t, self.vy.0);
            if x < self.right - 34.0 {
                let _ = ctx.fill_text(&fmt_tick(t, step), x, self.bottom + 3.0);
            }
            t += step;
        }
        ctx.set_text_align("right");
        let _ = ctx.fill_text("t (s)", self.right, self.bottom + 3.0);
        ctx.set_stroke_style_str(AXIS);
        ctx.begin_path();
        ctx.move_to(self.left + 0.5, self.top);
        ctx.line_to(self.left + 0.5, self.bottom + 0.5);
        ctx.line_to(self.right, self.bottom + 0.5);
        ctx.stroke();
    }

    fn line(&self, ctx: &CanvasRenderingContext2d, pts: &[(f64, f64)]) {
        ctx.begin_path();
        for (i, (t, v)) in pts.iter().enumerate() {
            let (x, y) = self.px(*t, *v);
            if i == 0 {
                ctx.move_to(x, y);
            } else {
                ctx.line_to(x, y);
            }
        }
        ctx.stroke();
    }

    /// A coloured entry of the panel's legend, right-aligned in the title row.
    fn key(&self, ctx: &CanvasRenderingContext2d, index: usize, text: &str, colour: &str) {
        let x = self.right - 40.0 * (2 - index.min(2)) as f64 - 18.0;
        let y = self.top - 12.0;
        ctx.set_stroke_style_str(colour);
        ctx.set_line_width(2.0);
        ctx.begin_path();
        ctx.move_to(x - 16.0, y);
        ctx.line_to(x - 4.0, y);
        ctx.stroke();
        ctx.set_font(&format!("11px {FONT}"));
        ctx.set_fill_style_str(INK);
        ctx.set_text_align("left");
        ctx.set_text_baseline("middle");
        let _ = ctx.fill_text(text, x, y);
    }

    fn label_right(&self, ctx: &CanvasRenderingContext2d, text: &str, v: f64, colour: &str) {
        let (_, y) = self.px(self.tx.1, v);
        ctx.set_fill_style_str(colour);
        ctx.set_text_align("right");
        ctx.set_text_baseline("bottom");
        let _ = ctx.fill_text(text, self.right, y - 2.0);
    }
}
