//! `SpaceDemo` for a robot of the user's: its chain as the workers'
//! module made it of a URDF (`readRobot`, `src/web/worker/robot.rs`), read
//! by hand here (the page's module leaves the URDF reader out: 31 KB
//! gzipped), and its own task ([`SpaceScene::own`]).

use wasm_bindgen::prelude::*;
use web_sys::HtmlCanvasElement;

use super::super::{js_err, JsResult};
use super::SpaceDemo;
use crate::planner::Method;
use crate::scene::SpaceScene;
use crate::session::space::SpaceSession;

#[wasm_bindgen]
impl SpaceDemo {
    /// A robot of the user's on `stage` (its plots on `plots`): `chain` is
    /// its chain's JSON (what `readRobot` returns), `key` and `label` name
    /// it; its own task (the middle of its joints' ranges, a line 0.15 m
    /// along `y`, no sphere) in `method` (default `numerical`), paused at
    /// `t = 0`. `urdf`, `base` and `tip` are the file it was read from and
    /// the links its chain runs between, which its run files carry (as
    /// `simulate --urdf FILE --json` writes them). Throws with the reason
    /// where the chain does not read or its task does not run.
    #[wasm_bindgen(js_name = ofChain)]
    #[allow(clippy::too_many_arguments)] // the JS constructor's own list
    pub fn of_chain(
        stage: HtmlCanvasElement,
        plots: Option<HtmlCanvasElement>,
        key: &str,
        label: &str,
        chain: &str,
        method: Option<String>,
        urdf: Option<String>,
        base: Option<String>,
        tip: Option<String>,
    ) -> JsResult<SpaceDemo> {
        let method = match method {
            Some(m) => m.parse::<Method>().map_err(js_err)?,
            None => Method::NUMERICAL,
        };
        let chain = crate::networks::chain_from_json(chain).map_err(js_err)?;
        let task = SpaceScene::own(chain).map_err(js_err)?;
        let mut session = SpaceSession::of_robot(key, label, task, method).map_err(js_err)?;
        session.set_source(crate::urdf::RobotSource {
            name: label.into(),
            urdf,
            sha256: None,
            base,
            tip,
        });
        Self::with_session(stage, plots, session)
    }
}
