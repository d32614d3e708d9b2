//! Every declared parameter, in the order of the methods' menus (each
//! method's list, first appearance first), found by name; and the scene's
//! JSON form, whose parameters go by those names
//! ([`crate::scene::SceneFile`]).

use std::sync::OnceLock;

use super::methods::ALL;
use crate::error::{Error, Result};
use crate::scene::{Param, ParamMap, Params, Scene, SceneFile};

/// Every parameter some method reads, each once, in menu order.
pub fn all() -> &'static [&'static Param] {
    static ALL_PARAMS: OnceLock<Vec<&'static Param>> = OnceLock::new();
    ALL_PARAMS.get_or_init(|| {
        let mut out: Vec<&'static Param> = Vec::new();
        for m in ALL {
            for &p in m.params() {
                if !out.iter().any(|q| std::ptr::eq(*q, p)) {
                    out.push(p);
                }
            }
        }
        out
    })
}

/// The parameter named `name` (its URL and JSON name).
pub fn by_name(name: &str) -> Result<&'static Param> {
    all()
        .iter()
        .copied()
        .find(|p| p.name == name)
        .ok_or_else(|| Error::UnknownName {
            kind: "parameter",
            name: crate::error::clip(name),
            choices: crate::error::join(&all().iter().map(|p| p.name).collect::<Vec<_>>(), ", "),
        })
}

/// The parameter whose flag is `flag` (`--influence`).
pub fn by_flag(flag: &str) -> Option<&'static Param> {
    all().iter().copied().find(|p| p.flag == flag)
}

impl<A, P, const M: usize, const D: usize> From<Scene<A, P, M, D>> for SceneFile<A, P, M, D> {
    /// Every declared parameter is written, at its value in the scene, so
    /// a file says what ran even after a default changes.
    fn from(s: Scene<A, P, M, D>) -> Self {
        let params = ParamMap(
            all()
                .iter()
                .map(|p| (p.name.to_string(), s.param(p)))
                .collect(),
        );
        SceneFile {
            arm: s.arm,
            theta0: s.theta0,
            target: s.target,
            path: s.path,
            obstacles: s.obstacles,
            damping: s.damping,
            dt: s.dt,
            tf: s.tf,
            feedback_gain: s.feedback_gain,
            params,
            joint_weighting: s.weighting,
            floor: s.floor,
            lambda: None,
            delta: None,
            avoidance: None,
            sign_smoothing: None,
            refine: None,
        }
    }
}

impl<A, P, const M: usize, const D: usize> TryFrom<SceneFile<A, P, M, D>> for Scene<A, P, M, D> {
    type Error = Error;

    /// The older fields first, then `params` (a file has one or the
    /// other); each name must be a declared parameter and each value
    /// within its bounds. The whole scene is checked by
    /// [`Scene::validate`] where a file is read.
    fn try_from(f: SceneFile<A, P, M, D>) -> Result<Self> {
        let mut values: Vec<(&'static Param, f64)> = Vec::new();
        let legacy = [
            ("lambda", f.lambda),
            ("delta", f.delta),
            ("sign_smoothing", f.sign_smoothing),
            ("refine", f.refine),
        ];
        let named = legacy
            .into_iter()
            .filter_map(|(k, v)| v.map(|v| (k.to_string(), v)))
            .chain(f.avoidance.into_iter().flat_map(|m| m.0))
            .chain(f.params.0);
        for (name, v) in named {
            let p = by_name(&name)?;
            values.retain(|(q, _)| !std::ptr::eq(*q, p));
            values.push((p, v));
        }
        let mut params = Params::default();
        params.set_all(&values)?;
        Ok(Scene {
            arm: f.arm,
            theta0: f.theta0,
            target: f.target,
            path: f.path,
            obstacles: f.obstacles,
            damping: f.damping,
            dt: f.dt,
            tf: f.tf,
            feedback_gain: f.feedback_gain,
            params,
            weighting: f.joint_weighting,
            floor: f.floor,
        })
    }
}
