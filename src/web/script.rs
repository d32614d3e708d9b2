//! What a script asks of every binding beyond the stage: a whole run off
//! screen with overrides (`window.demo.simulate()`), one definition for
//! the planar [`Demo`] and the [`SpaceDemo`] in space.

use wasm_bindgen::prelude::*;

use super::demo::Demo;
use super::scene::point;
use super::space_demo::SpaceDemo;
use super::{js_err, to_js, JsResult};
use crate::geometry::Ball;
use crate::planner::{Method, Summary};
use crate::scene::Scene;

/// The overrides of a run off screen (each absent one the scene's).
struct Overrides {
    target: Option<Vec<f64>>,
    obstacles: Option<Vec<f64>>,
    tf: Option<f64>,
    theta0: Option<Vec<f64>>,
    feedback: Option<f64>,
    refine: Option<f64>,
}

/// `scene` with the overrides, each checked as it is set, run whole by
/// `run` (the session's run off screen, which checks the scene); its
/// summary, or the core's reason.
fn simulate<A, P, const M: usize, const D: usize>(
    mut scene: Scene<A, P, M, D>,
    method: &str,
    o: Overrides,
    run: impl FnOnce(Scene<A, P, M, D>, Method) -> crate::Result<Summary>,
) -> JsResult<JsValue> {
    let method: Method = method.parse().map_err(js_err)?;
    if let Some(flat) = o.obstacles {
        scene.obstacles = Ball::from_flat(&flat).map_err(js_err)?;
    }
    if let Some(t) = o.target {
        scene.target = point("target", &t)?;
    }
    if let Some(tf) = o.tf {
        scene.tf = tf;
    }
    if let Some(t) = o.theta0 {
        scene.theta0 = t;
    }
    if let Some(k) = o.feedback {
        crate::scene::validate_gain(k, scene.dt).map_err(js_err)?;
        scene.feedback_gain = k;
    }
    if let Some(k) = o.refine {
        scene
            .params
            .set(&crate::planner::methods::REFINE, k)
            .map_err(js_err)?;
    }
    to_js(&run(scene, method).map_err(js_err)?)
}

/// `simulate` on the binding `$binding`, whose session `self.$session()`
/// has the scene in use (`scene()`) and runs one off screen
/// (`run_offscreen`).
macro_rules! script_simulate {
    ($binding:ident, $session:ident) => {
        #[wasm_bindgen]
        impl $binding {
            /// Runs a whole task off screen with the scene in use and the
            /// networks installed, and returns its summary (the `summary`
            /// of `redundant-ik simulate --json`). `target` (the hand's
            /// point: `[x, y]` in the plane, `[x, y, z]` in space),
            /// `obstacles` (flat, the centre and the radius of each: `[x,
            /// y, r, ...]` in the plane, `[x, y, z, r, ...]` in space),
            /// `tf`, `theta0`, the closed-loop gain `feedback` and the
            /// `refine` steps on a learned `Phi` default to the scene in
            /// use. The scene on the stage does not change. Throws with the
            /// core's reason on a bad override, a learned method without
            /// networks or a failed step.
            #[allow(clippy::too_many_arguments)] // one optional argument per override, as JavaScript passes them
            pub fn simulate(
                &self,
                method: &str,
                target: Option<Vec<f64>>,
                obstacles: Option<Vec<f64>>,
                tf: Option<f64>,
                theta0: Option<Vec<f64>>,
                feedback: Option<f64>,
                refine: Option<f64>,
            ) -> JsResult<JsValue> {
                let session = self.$session();
                let overrides = Overrides {
                    target,
                    obstacles,
                    tf,
                    theta0,
                    feedback,
                    refine,
                };
                simulate(session.scene().clone(), method, overrides, |s, m| {
                    session.run_offscreen(s, m)
                })
            }
        }
    };
}

script_simulate!(Demo, session);
script_simulate!(SpaceDemo, session);
