//! The workers' `readRobot`: a robot's URDF (and the mesh files it names,
//! for its collision volumes) read into the chain the page's `SpaceDemo`
//! runs (`SpaceDemo.ofChain`), and what the reader made of it for the page
//! to show before it runs: the chain's links and joints, their limits, the
//! volumes and the reader's warnings. The URDF reader (roxmltree, 31 KB
//! gzipped) lives in the workers' module, which the page loads when a
//! robot is opened, not in the page's own.

use serde::Serialize;
use wasm_bindgen::prelude::*;

use super::{js_err, to_js};
use crate::urdf::{volume, JointKind, Urdf, UrdfChain};

/// A segment's radius for a link without collision geometry (m): the
/// command line's.
const DEFAULT_RADIUS: f64 = 0.05;

/// What `readRobot` returns.
#[derive(Serialize)]
struct RobotRead {
    /// The robot's name (its `<robot name>`, or `robot`).
    name: String,
    /// The chain's base and tip links.
    base: String,
    tip: String,
    /// The chain's JSON, for `SpaceDemo.ofChain`.
    chain: String,
    /// The moving joints, base first.
    joints: Vec<JointRead>,
    /// Each link volume: its link, how it was made, its radius (m).
    volumes: Vec<VolumeRead>,
    /// Each link the chain carries, where its visuals go: the moving joint
    /// that moves it (from 1; 0: the base) and its frame in that joint's
    /// frame of the chain model (`UrdfChain::link_frames`).
    links: Vec<LinkRead>,
    /// What the reader warns of (a mesh not at hand, a link without geometry).
    warnings: Vec<String>,
}

#[derive(Serialize)]
struct JointRead {
    name: String,
    /// `revolute`, `continuous` or `prismatic`.
    kind: &'static str,
    /// `[lower, upper]` (rad or m), where the file gives them.
    limits: Option<[f64; 2]>,
    /// The largest rate, where the file gives it.
    velocity: Option<f64>,
}

#[derive(Serialize)]
struct LinkRead {
    name: String,
    moved_by: usize,
    /// The rotation, by rows.
    rotation: [[f64; 3]; 3],
    translation: [f64; 3],
}

#[derive(Serialize)]
struct VolumeRead {
    link: String,
    source: String,
    radius: f64,
}

/// Reads a URDF's `text` into the chain from `base` to `tip` (each
/// optional: the tree's root and its one leaf); `meshes` maps a mesh's
/// name, as the URDF gives it or as its last part, to its bytes (STL),
/// for the links' volumes. Throws with the reader's message where the file is not
/// a URDF it reads or the chain is not one it runs.
#[wasm_bindgen(js_name = readRobot)]
pub fn read_robot(
    text: &str,
    base: Option<String>,
    tip: Option<String>,
    meshes: JsValue,
) -> Result<JsValue, JsError> {
    let files = js_sys::Map::new();
    if !meshes.is_undefined() && !meshes.is_null() {
        let entries = js_sys::Object::entries(
            meshes
                .dyn_ref::<js_sys::Object>()
                .ok_or_else(|| JsError::new("meshes: expected { name: bytes }"))?,
        );
        for e in entries.iter() {
            let pair: js_sys::Array = e.unchecked_into();
            files.set(&pair.get(0), &pair.get(1));
        }
    }
    // A mesh by its name as the URDF gives it (the page resolved each to
    // a file it was given), else by its name's last part.
    let mesh = |name: &str| -> Option<Vec<u8>> {
        let file = name.rsplit(['/', '\\']).next()?;
        let exact = files.get(&JsValue::from_str(name));
        let bytes = if exact.is_undefined() {
            files.get(&JsValue::from_str(file))
        } else {
            exact
        };
        let array = bytes.dyn_ref::<js_sys::Uint8Array>()?;
        (array.length() as usize <= crate::urdf::stl::MAX_STL_BYTES).then(|| array.to_vec())
    };
    let urdf = Urdf::parse(text).map_err(js_err)?;
    let uc = UrdfChain::new(&urdf, base.as_deref(), tip.as_deref()).map_err(js_err)?;
    let (volumes, warnings) = volume::volumes(&urdf, &uc, &mesh, DEFAULT_RADIUS);
    let chain = uc.to_chain(&volumes, None).map_err(js_err)?;
    let read = RobotRead {
        name: if urdf.name.is_empty() {
            "robot".into()
        } else {
            urdf.name.clone()
        },
        base: uc.base.clone(),
        tip: uc.tip.clone(),
        chain: serde_json::to_string(&chain).map_err(|e| JsError::new(&e.to_string()))?,
        joints: uc
            .joints
            .iter()
            .map(|j| JointRead {
                name: j.name.clone(),
                kind: match j.kind {
                    JointKind::Prismatic => "prismatic",
                    _ if j.continuous => "continuous",
                    _ => "revolute",
                },
                limits: j.limits,
                velocity: j.velocity,
            })
            .collect(),
        volumes: volumes
            .iter()
            .map(|v| VolumeRead {
                link: v.link.clone(),
                source: match &v.source {
                    volume::Source::Sphere => "sphere".into(),
                    volume::Source::Cylinder => "cylinder".into(),
                    volume::Source::Box => "box".into(),
                    volume::Source::Mesh(m) => format!("mesh {m}"),
                    volume::Source::Segment => "segment".into(),
                },
                radius: v.radius,
            })
            .collect(),
        links: uc
            .link_frames()
            .into_iter()
            .map(|(name, moved_by, f)| LinkRead {
                name: name.into(),
                moved_by,
                rotation: f.rotation,
                translation: f.translation,
            })
            .collect(),
        warnings,
    };
    to_js(&read)
}
