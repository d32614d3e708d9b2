//! The keyboard on the drawing (`Demo.key`, `Demo.setKeyboardFocus`): what
//! a key does (`input::key`), through the session's selection
//! (`session::keys`), and the ring round the item the keys move.

use wasm_bindgen::prelude::*;

use super::demo::Demo;
use super::{input, js_err, JsResult};

#[wasm_bindgen]
impl Demo {
    /// A key pressed on the drawing (`input::key`): `n` selects the next
    /// item (the target, each obstacle, each elbow; Shift: back), the
    /// arrows move it by 5 cm (Shift: 5 mm; the target plans a new line and
    /// starts the clock, an elbow moves the arm in its null space), `a`
    /// adds an obstacle at the middle of the view and selects it, Delete
    /// or Backspace removes the selected obstacle (stage-input.js routes
    /// `+`, `-` and `0` to `moveView` and `fitView`). Returns whether the
    /// key was used; throws, changing nothing, if the move was refused
    /// (an obstacle onto the post, a ninth obstacle).
    pub fn key(&mut self, key: &str, shift: bool) -> JsResult<bool> {
        use crate::session::Handle;
        let Some(k) = input::key(key, shift) else {
            return Ok(false);
        };
        let s = &mut self.session;
        match k {
            input::Key::Move { dx, dy, fine } => s.nudge_selected(dx, dy, fine).map_err(js_err)?,
            input::Key::Next { forward } => {
                s.select_next(forward);
            }
            input::Key::Add => {
                let v = self.view();
                let [x, y] = v.to_world(self.stage.width / 2.0, self.stage.height / 2.0);
                let [x, y] = [(x * 100.0).round() / 100.0, (y * 100.0).round() / 100.0];
                let ob = crate::obstacle::Obstacle::new(x, y, crate::scene::PAPER_RADIUS);
                let i = self.session.add_obstacle(ob).map_err(js_err)?;
                self.session.select(Handle::Obstacle(i));
            }
            input::Key::Remove => match s.selected() {
                Handle::Obstacle(i) => {
                    s.remove_obstacle(i).map_err(js_err)?;
                    s.select(Handle::Target);
                }
                _ => return Ok(false),
            },
        }
        Ok(true)
    }

    /// Whether the drawing has the keyboard's focus (its focus and blur):
    /// the item the keys move is ringed while it has.
    #[wasm_bindgen(js_name = setKeyboardFocus)]
    pub fn set_keyboard_focus(&mut self, on: bool) {
        self.keyboard = on;
    }

    /// A dashed ring round the item the keys move.
    pub(super) fn ring_selected(&self, stage: &super::surface::Surface, view: crate::view::View) {
        use crate::session::Handle;
        let s = &self.session;
        let (at, r) = match s.selected() {
            Handle::Target => (s.target_marker(), 14.0),
            Handle::Obstacle(i) => match s.obstacles().get(i) {
                Some(o) => (o.centre, o.radius * view.scale + 6.0),
                None => return,
            },
            Handle::Joint(k) => match s.planner().pose().joints().get(k) {
                Some(p) => (*p, 11.0),
                None => return,
            },
        };
        let (x, y) = view.to_px(at);
        let ctx = &stage.ctx;
        ctx.set_stroke_style_str(super::style::INK);
        ctx.set_line_width(1.5);
        super::surface::dash(ctx, &[4.0, 3.0]);
        super::surface::disc(ctx, x, y, r);
        ctx.stroke();
        super::surface::dash(ctx, &[]);
    }
}
