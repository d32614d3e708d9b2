//! The interactive session the page runs, as a specification, natively and
//! in the browser: the clock, the ghost twin, dragging, the histories and the
//! state the page reads.

#[cfg(target_family = "wasm")]
wasm_bindgen_test::wasm_bindgen_test_configure!(run_in_browser);

use std::sync::Arc;

use redundant_ik::networks::Networks;
use redundant_ik::planner::methods;
use redundant_ik::session::{
    Handle, Session, MAX_OBSTACLES, MAX_STEPS_PER_FRAME, NUDGE, STROBE_EVERY,
};
use redundant_ik::{Arm, Error, Method, Obstacle};

fn with_networks(task: u32) -> Session {
    let mut s = Session::new(task).unwrap();
    s.set_networks(Arc::new(Networks::embedded().unwrap()))
        .unwrap();
    s
}

fn four_links() -> Arm {
    Arm::new(0.5, vec![0.6, 0.85, 0.6, 0.4]).unwrap()
}

mod clock;
mod lab;
mod runs;
mod scene;
mod view;
