//! `SpaceDemo`'s self-collision switch (the page's "Links kept apart",
//! the address's `self_collision=1`, the command line's
//! `--self-collision`); the view draws the pairs near each other
//! (`SceneView::self_near`).

use wasm_bindgen::prelude::*;

use super::super::{js_err, JsResult};
use super::SpaceDemo;

#[wasm_bindgen]
impl SpaceDemo {
    /// Whether the chain's capsules are checked against each other: every
    /// pair but adjacent links and those touching at the zero pose or the
    /// start (a robot's own pairs where its chain came with some).
    /// `distance`, `priority` and `qp` keep them apart; the state's
    /// `self_clearance` and the summary's `self_collision_steps` say how
    /// close they came.
    #[wasm_bindgen(js_name = setSelfCollision)]
    pub fn set_self_collision(&mut self, on: bool) -> JsResult {
        self.session_mut().set_self_collision(on).map_err(js_err)
    }
}
