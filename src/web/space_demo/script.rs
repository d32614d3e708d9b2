//! What a script asks of `SpaceDemo` beyond the stage: a whole run off
//! screen with overrides (`window.demo.simulate()` in the page in space,
//! as the plane's `Demo.simulate`).

use wasm_bindgen::prelude::*;

use super::super::{js_err, to_js, JsResult};
use super::SpaceDemo;
use crate::planner::Method;
use crate::space::Sphere;

#[wasm_bindgen]
impl SpaceDemo {
    /// Runs a whole task off screen with the scene in use and the
    /// networks installed, and returns its summary (the `summary` of
    /// `redundant-ik simulate --arm A --json`). `target` (`[x, y, z]`),
    /// `spheres` (flat `[x, y, z, r, ...]`, as `setSpheres`), `tf`,
    /// `theta0`, the closed-loop gain `feedback` and the `refine` steps on
    /// a learned `Phi` default to the scene in use. The scene on the stage
    /// does not change. Throws with the core's reason on a bad override, a
    /// learned method without networks or a failed step.
    #[allow(clippy::too_many_arguments)] // one optional argument per override, as JavaScript passes them
    pub fn simulate(
        &self,
        method: &str,
        target: Option<Vec<f64>>,
        spheres: Option<Vec<f64>>,
        tf: Option<f64>,
        theta0: Option<Vec<f64>>,
        feedback: Option<f64>,
        refine: Option<f64>,
    ) -> JsResult<JsValue> {
        let method: Method = method.parse().map_err(js_err)?;
        let session = self.session();
        let mut scene = session.scene().clone();
        if let Some(flat) = spheres {
            scene.obstacles = Sphere::from_flat(&flat).map_err(js_err)?;
        }
        super::super::scene::overridden(&mut scene, target, tf, theta0, feedback, refine)?;
        to_js(&session.run_offscreen(scene, method).map_err(js_err)?)
    }
}
