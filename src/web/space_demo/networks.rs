//! `SpaceDemo`'s networks: installing a shipped set or networks of your
//! own (trained in the page, or files the user gave), and handing the
//! latter's files to the workers' jobs (the slice atlas, the benchmark),
//! whose module carries no networks of its own.

use wasm_bindgen::prelude::*;

use super::super::{js_err, to_js, JsResult};
use super::SpaceDemo;
use crate::networks::space::SpaceNetworkSet;
use crate::run::NetworkChoice;

#[wasm_bindgen]
impl SpaceDemo {
    /// The weights files' text of the arm's networks; `set` names the
    /// shipped set they are (`panda-reach`), if they are one.
    #[wasm_bindgen(js_name = installNetworks)]
    pub fn install_networks(&mut self, phi: &str, v: &str, set: Option<String>) -> JsResult {
        let set = set
            .map(|s| s.parse::<SpaceNetworkSet>())
            .transpose()
            .map_err(js_err)?;
        self.session_mut()
            .install_networks(phi, v, set)
            .map_err(js_err)
    }

    /// The weights files of the networks installed when they are your own
    /// (`{ phi, v }`, their JSON text); null for a shipped set (the page
    /// fetches its files by name) or none.
    #[wasm_bindgen(js_name = networkFiles)]
    pub fn network_files(&self) -> JsResult<JsValue> {
        match self.session().network_choice() {
            Some(NetworkChoice::Files { phi, v }) => {
                #[derive(serde::Serialize)]
                struct Files<'a> {
                    phi: &'a str,
                    v: &'a str,
                }
                to_js(&Files { phi, v })
            }
            _ => Ok(JsValue::NULL),
        }
    }
}
