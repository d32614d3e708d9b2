//! The browser API (src/wasm.rs) in a real browser:
//! `wasm-pack test --headless --chrome`. Native `cargo test` skips this test.
#![cfg(target_family = "wasm")]

use redundant_ik::web::{networks_error, Demo};
use serde_json::Value;
use wasm_bindgen::prelude::*;
use wasm_bindgen_test::*;
use web_sys::HtmlCanvasElement;

wasm_bindgen_test_configure!(run_in_browser);

#[wasm_bindgen(inline_js = "
export function make_canvas(w, h) {
  const c = document.createElement('canvas');
  c.style.width = w + 'px';
  c.style.height = h + 'px';
  c.style.display = 'block';
  document.body.appendChild(c);
  return c;
}
export function mark_canvas(c) {
  const g = c.getContext('2d');
  g.save();
  g.setTransform(1, 0, 0, 1, 0, 0);
  g.fillStyle = 'rgb(255, 0, 255)';
  g.fillRect(0, 0, 1, 1);
  g.restore();
}
export function canvas_marked(c) {
  const [r, g, b] = c.getContext('2d').getImageData(0, 0, 1, 1).data;
  return r === 255 && g === 0 && b === 255;
}")]
extern "C" {
    fn make_canvas(w: u32, h: u32) -> HtmlCanvasElement;
    /// Paints the canvas's top-left pixel magenta, which no drawing uses.
    fn mark_canvas(c: &HtmlCanvasElement);
    /// Whether the top-left pixel is still the mark: nothing drew over it.
    fn canvas_marked(c: &HtmlCanvasElement) -> bool;
}

fn demo(task: u32) -> Demo {
    let mut d = Demo::new(make_canvas(640, 520), Some(make_canvas(640, 300)), task).unwrap();
    d.resize(640.0, 520.0, 1.0).unwrap();
    d
}

fn state(d: &Demo) -> Value {
    json_of(d.state().unwrap())
}

/// A JavaScript value as JSON.
fn json_of(js: JsValue) -> Value {
    let text: String = js_sys::JSON::stringify(&js).unwrap().into();
    serde_json::from_str(&text).unwrap()
}

fn message(e: JsError) -> String {
    let v: JsValue = e.into();
    let err: js_sys::Error = v.unchecked_into();
    err.message().into()
}

fn pair(v: &Value) -> [f64; 2] {
    [v[0].as_f64().unwrap(), v[1].as_f64().unwrap()]
}

mod atlas;
mod panels;
mod scene;
mod space_atlas;
mod space_training;
