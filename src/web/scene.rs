//! [`Demo`]'s bindings for the scene: the arm, several obstacles, the
//! path (typed or drawn), the networks (loaded, trained in the page or
//! shipped, and their arithmetic), and whole runs off screen. Each forwards to
//! the [`Session`](crate::session::Session) and maps the core's errors to
//! exceptions; values from JavaScript are checked by the core.

use wasm_bindgen::prelude::*;

use super::demo::Demo;
use super::{finite, input, js_err, JsResult};
use crate::arm::Arm;
use crate::obstacle::Obstacle;
use crate::scene::PAPER_RADIUS;

/// A point of `D` coordinates a script passed as `what` (`[x, y]` in the
/// plane, `[x, y, z]` in space), or why it is not one.
pub(super) fn point<const D: usize>(what: &str, v: &[f64]) -> JsResult<[f64; D]> {
    v.try_into().map_err(|_| {
        let names = ["x", "y", "z"];
        JsError::new(&format!(
            "{what}: expected [{}], got {} numbers",
            names[..D.min(3)].join(", "),
            v.len()
        ))
    })
}

#[wasm_bindgen]
impl Demo {
    /// Replaces the arm: a post of height `post` and 2 to 6 links of the
    /// given lengths (m; `limits()` has the bounds). Throws, keeping the
    /// arm, on bad numbers. The scene restarts at `t = 0` from a start pose
    /// for the new arm; networks trained for another arm are set aside (see
    /// `Session::set_arm`).
    #[wasm_bindgen(js_name = setArm)]
    pub fn set_arm(&mut self, post: f64, links: Vec<f64>) -> JsResult {
        let arm = Arm::new(post, links).map_err(js_err)?;
        self.session.set_arm(arm).map_err(js_err)
    }

    /// Replaces the arm as [`Demo::set_arm`] does, with its joints'
    /// position limits flat as `[lo1, hi1, lo2, hi2, ...]` (rad) and rate
    /// limits (rad/s), each `undefined` for none. Throws, keeping the arm,
    /// when a limit is bad, their count does not match the links, or the
    /// new start pose lies outside them.
    #[wasm_bindgen(js_name = setLimitedArm)]
    pub fn set_limited_arm(
        &mut self,
        post: f64,
        links: Vec<f64>,
        limits: Option<Vec<f64>>,
        rates: Option<Vec<f64>>,
    ) -> JsResult {
        let (limits, rates) = super::limits_from(limits, rates)?;
        let arm = Arm::new(post, links)
            .and_then(|a| a.with_limits(limits, rates))
            .map_err(js_err)?;
        self.session.set_arm(arm).map_err(js_err)
    }

    /// Gives the arm joint position limits, flat as `[lo1, hi1, lo2, hi2,
    /// ...]` (rad), and rate limits (rad/s), each `undefined` for none,
    /// keeping the scene. Throws, changing nothing, when a limit is bad,
    /// their count does not match the links, or the start pose lies
    /// outside them.
    #[wasm_bindgen(js_name = setArmLimits)]
    pub fn set_arm_limits(
        &mut self,
        limits: Option<Vec<f64>>,
        rates: Option<Vec<f64>>,
    ) -> JsResult {
        let (limits, rates) = super::limits_from(limits, rates)?;
        self.session.set_arm_limits(limits, rates).map_err(js_err)
    }

    /// Adds an obstacle at `(x, y)` with radius `r` (default 0.05 m);
    /// returns its index. Throws beyond 8 obstacles, on the post, or with a
    /// bad radius; nothing changes then.
    #[wasm_bindgen(js_name = addObstacle)]
    pub fn add_obstacle(&mut self, x: f64, y: f64, r: Option<f64>) -> JsResult<usize> {
        let ob = Obstacle::new(x, y, r.unwrap_or(PAPER_RADIUS));
        self.session.add_obstacle(ob).map_err(js_err)
    }

    /// Adds an obstacle of the default radius at canvas CSS pixel `(x, y)`
    /// (a click on the drawing); returns its index. Throws as
    /// [`Demo::add_obstacle`].
    #[wasm_bindgen(js_name = addObstacleAt)]
    pub fn add_obstacle_at(&mut self, x: f64, y: f64) -> JsResult<usize> {
        let [wx, wy] = self.view().to_world(finite("x", x)?, finite("y", y)?);
        self.add_obstacle(wx, wy, None)
    }

    /// Removes the obstacle under canvas CSS pixel `(x, y)` (`slop` extra
    /// pixels of tolerance), if any: its index, or `undefined`.
    #[wasm_bindgen(js_name = removeObstacleAt)]
    pub fn remove_obstacle_at(&mut self, x: f64, y: f64, slop: f64) -> JsResult<Option<usize>> {
        let Some(i) = input::obstacle_at(&self.session, self.view(), x, y, slop) else {
            return Ok(None);
        };
        self.session.remove_obstacle(i).map_err(js_err)?;
        Ok(Some(i))
    }

    /// Sets the radius of obstacle `i` (m), keeping its centre; throws,
    /// changing nothing, on a bad radius or index.
    #[wasm_bindgen(js_name = setObstacleRadius)]
    pub fn set_obstacle_radius(&mut self, i: f64, r: f64) -> JsResult {
        self.session
            .set_obstacle_radius(index(i)?, r)
            .map_err(js_err)
    }

    /// Moves obstacle `i`'s centre to `(x, y)` (the number fields beside the
    /// drawing: placement without dragging); throws, changing nothing, on
    /// a bad index or point, or one whose disc would overlap the post.
    #[wasm_bindgen(js_name = moveObstacle)]
    pub fn move_obstacle(&mut self, i: f64, x: f64, y: f64) -> JsResult {
        let centre = [finite("x", x)?, finite("y", y)?];
        self.session
            .move_obstacle(index(i)?, centre)
            .map_err(js_err)
    }

    /// Removes obstacle `i`; throws if there is none.
    #[wasm_bindgen(js_name = removeObstacle)]
    pub fn remove_obstacle(&mut self, i: f64) -> JsResult {
        self.session.remove_obstacle(index(i)?).map_err(js_err)
    }

    /// Replaces all obstacles, given flat as `[x0, y0, r0, x1, y1, r1, ...]`
    /// (at most 8); refused as a whole if one is bad.
    #[wasm_bindgen(js_name = setObstacles)]
    pub fn set_obstacles(&mut self, flat: Vec<f64>) -> JsResult {
        let obs = Obstacle::from_flat(&flat).map_err(js_err)?;
        self.session.set_obstacles(obs).map_err(js_err)
    }

    /// The obstacle under canvas CSS pixel `(x, y)` (with `slop` pixels of
    /// tolerance), if any: for double-click and long-press removal.
    #[wasm_bindgen(js_name = obstacleAt)]
    pub fn obstacle_at(&self, x: f64, y: f64, slop: f64) -> Option<usize> {
        input::obstacle_at(&self.session, self.view(), x, y, slop)
    }

    /// Makes the path the hand follows the one written `text` (`line`,
    /// `circle:CX,CY[,LAPS]`, `points:X,Y;X,Y;...`: the core's syntax, the
    /// address's `path=`) or, given `stroke` (canvas CSS pixels flat,
    /// `[x0, y0, x1, y1, ...]`), the polyline drawn, thinned by the core to
    /// points at least 5 cm apart; runs it and returns the path's text.
    /// Throws, changing nothing, on bad text or a path the scene refuses.
    #[wasm_bindgen(js_name = setPath)]
    pub fn set_path(&mut self, text: &str, stroke: Option<Vec<f64>>) -> JsResult<String> {
        let path = match stroke {
            Some(flat) => {
                let view = self.view();
                let world: Vec<[f64; 2]> = flat
                    .chunks_exact(2)
                    .map(|p| view.to_world(p[0], p[1]))
                    .collect();
                crate::scene::Path::drawn(&world)
            }
            None => text.parse().map_err(js_err)?,
        };
        let text = path.to_string();
        self.session.set_path(path).map_err(js_err)?;
        Ok(text)
    }

    /// Loads user-trained networks for this demo from the JSON text of a `Phi`
    /// weights file and a `v` weights file (the format `redundant-ik train`
    /// writes). Throws with the reason if they are corrupt or were trained
    /// for another arm; the networks in use stay then.
    #[wasm_bindgen(js_name = loadNetworks)]
    pub fn load_networks(&mut self, phi_json: &str, v_json: &str) -> JsResult {
        self.session.load_networks(phi_json, v_json).map_err(js_err)
    }

    /// Installs a shipped network set (`paper` or `reach`; `networkSets()`
    /// lists them) for the methods that use networks. The page's module
    /// must have been handed the set's files (`provideBuiltinNetworks`)
    /// first. Throws, the networks in use staying, when the set is unknown,
    /// not loaded, or for another arm.
    #[wasm_bindgen(js_name = useNetworkSet)]
    pub fn use_network_set(&mut self, name: &str) -> JsResult {
        let set: crate::networks::NetworkSet = name.parse().map_err(js_err)?;
        self.session.use_network_set(set).map_err(js_err)
    }

    /// The networks' arithmetic from now on: `f64` (the default) or `f32`
    /// (weights, activations and sums in single precision: four lanes of
    /// wasm SIMD instead of two; a run file keeps it as `precision`).
    /// Throws on another name, changing nothing.
    #[wasm_bindgen(js_name = setPrecision)]
    pub fn set_precision(&mut self, name: &str) -> JsResult {
        let p: crate::nn::Precision = name.parse().map_err(js_err)?;
        self.session.set_precision(p).map_err(js_err)
    }

    /// Whether networks for the arm in use are available: loaded or trained
    /// for it, or the built-in ones for the paper's arm.
    #[wasm_bindgen(js_name = networksFit)]
    pub fn networks_fit(&self) -> bool {
        self.session.networks_fit()
    }

    /// Sets the networks aside; the network cases then fall back to the
    /// built-in ones (paper's arm) or need new ones.
    #[wasm_bindgen(js_name = clearNetworks)]
    pub fn clear_networks(&mut self) -> JsResult {
        self.session.clear_networks().map_err(js_err)
    }
}

/// An obstacle index from JavaScript: a whole number from 0.
fn index(i: f64) -> JsResult<usize> {
    if i.is_finite() && i >= 0.0 && i.fract() == 0.0 && i < 1e6 {
        Ok(i as usize)
    } else {
        Err(JsError::new(&format!(
            "obstacle index must be a whole number from 0 (got {i})"
        )))
    }
}
