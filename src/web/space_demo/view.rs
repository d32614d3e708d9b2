//! `SpaceDemo`'s 3-D view: what the page's three.js renderer
//! (`www/view/`) draws, read from the core each frame it changed.

use wasm_bindgen::prelude::*;

use super::super::space_stage;
use super::super::{to_js, JsResult};
use super::SpaceDemo;

#[wasm_bindgen]
impl SpaceDemo {
    /// What the 3-D view draws now (`docs/web.md`, "The 3-D view"): the
    /// camera for the stage's size, the links' segments and radius, the
    /// joints, the spheres, the path, the trail, the ghost, the ellipsoids
    /// switched on, the target, the floor, the selected item and the slice
    /// atlas's revision ([`SpaceDemo::layer_view`] gives its cells).
    pub fn view(&self) -> JsResult<JsValue> {
        let d = self.drawn.get();
        to_js(&space_stage::view(
            &d.session,
            d.stage.width,
            d.stage.height,
            d.layer_revision,
            d.shown,
        ))
    }

    /// Switches a legend entry's drawing: `ellipse`, the velocity ellipsoid
    /// `{J theta_dot : |theta_dot| <= 1}` at the hand (its three principal
    /// ellipses at 1/4 scale), or `force`, the force ellipsoid (half-axes
    /// `1 / sigma_i` at 1/10 scale, at most 0.6 m): the plane's
    /// `setShown`. Returns whether the key names one.
    #[wasm_bindgen(js_name = setShown)]
    pub fn set_shown(&mut self, key: &str, on: bool) -> bool {
        let shown = &mut self.drawn.edit().shown;
        match key {
            "ellipse" => shown.velocity = on,
            "force" => shown.force = on,
            _ => return false,
        }
        true
    }

    /// Whether the drawing has the keyboard (the selected item is ringed).
    #[wasm_bindgen(js_name = setKeyboardFocus)]
    pub fn set_keyboard_focus(&mut self, on: bool) {
        self.drawn.edit().keyboard = on;
    }
}
