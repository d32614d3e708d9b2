//! `SpaceDemo`'s slice atlas on the stage: a layer on its plane, the cell
//! under the pointer and a sphere placed on a cell (the page's Atlas
//! panel in space, `www/space-atlas.js`).

use wasm_bindgen::prelude::*;

use super::super::space_stage::SliceLayer;
use super::super::{finite, js_err, to_js, JsResult};
use super::SpaceDemo;
use crate::atlas::space::Plane;
use crate::atlas::Grid;

#[wasm_bindgen]
impl SpaceDemo {
    /// Shows a slice atlas on its plane, `axes` (`xy`, `xz` or `yz`) at
    /// `at` (m) along the third: `region` `[u0, u1, v0, v1]`, `n` points per
    /// side, one class per cell. (Not the plane's text `xz:0.2`: its number
    /// parser would add 4 KB to the page's module.)
    #[wasm_bindgen(js_name = setAtlasLayer)]
    pub fn set_atlas_layer(
        &mut self,
        axes: &str,
        at: f64,
        region: Vec<f64>,
        n: usize,
        classes: Vec<u8>,
    ) -> JsResult {
        let at = finite("plane offset", at)?;
        let plane = match axes {
            "xy" => Plane::Xy(at),
            "xz" => Plane::Xz(at),
            "yz" => Plane::Yz(at),
            _ => return Err(JsError::new("a slice's plane is xy, xz or yz")),
        };
        let region: [f64; 4] = region
            .try_into()
            .map_err(|_| JsError::new("an atlas region is [u0, u1, v0, v1]"))?;
        let grid = Grid::new(region, n).map_err(js_err)?;
        let layer = SliceLayer::new(plane, grid, classes).map_err(js_err)?;
        let d = self.drawn.edit();
        d.layer = Some(layer);
        d.layer_revision = d.layer_revision.wrapping_add(1).max(1);
        Ok(())
    }

    /// The shown slice atlas's cell under canvas pixel `(x, y)`, if any.
    #[wasm_bindgen(js_name = atlasCellAt)]
    pub fn atlas_cell_at(&self, x: f64, y: f64) -> Option<usize> {
        let proj = self.projection();
        let d = self.drawn.get();
        let layer = d.layer.as_ref()?;
        (x.is_finite() && y.is_finite())
            .then(|| layer.cell_at(&proj, x, y))
            .flatten()
    }

    /// Moves the first sphere to the centre of the shown atlas's cell `k`
    /// (the run follows, as for a drag); refused without such a cell.
    #[wasm_bindgen(js_name = placeSphereAtCell)]
    pub fn place_sphere_at_cell(&mut self, k: usize) -> JsResult {
        let point = self
            .drawn
            .get()
            .layer
            .as_ref()
            .and_then(|l| l.cell_point(k))
            .ok_or_else(|| JsError::new("no shown slice atlas has that cell"))?;
        self.session_mut().move_sphere(0, point).map_err(js_err)
    }

    /// Hides the atlas.
    #[wasm_bindgen(js_name = clearAtlasLayer)]
    pub fn clear_atlas_layer(&mut self) {
        let d = self.drawn.edit();
        if d.layer.take().is_some() {
            d.layer_revision = d.layer_revision.wrapping_add(1).max(1);
        }
    }

    /// The shown slice atlas as the 3-D view draws it: `{ corners, colours }`
    /// (four corners `x, y, z` a cell, one colour a cell), or `null`.
    #[wasm_bindgen(js_name = layerView)]
    pub fn layer_view(&self) -> JsResult<JsValue> {
        match &self.drawn.get().layer {
            Some(l) => to_js(&l.view()),
            None => Ok(JsValue::NULL),
        }
    }
}
