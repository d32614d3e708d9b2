//! The page's reader of the spatial weights files by hand, as
//! [`super::by_hand`] reads the planar ones: serde's derived reader of
//! [`SpaceWeightsFile`] put 31 KB raw on the page's module with the arms
//! in space (serde_json's deserializer monomorphised for its structs,
//! `make web`, docs/web.md); this one takes the fields from the plain JSON
//! tree the planar reader already parses, with the derived reader's checks
//! (missing, unknown and repeated fields, types, the kind's name): the one
//! weights file's layout with a chain for its arm, and the files of
//! version 1 ([`SPACE_FORMAT_1`], the shipped Panda set's). What the page
//! does not use, the optimiser's options, takes the default.

use super::by_hand::{
    count, float, floats, limits, list, net_entry, net_kind, nullable, range, read_with, string,
    unsigned, Fields, Read,
};
use crate::json::Json;
use crate::networks::space::{
    SpaceSampling, SpaceTraining, SpaceWeightsFile, SpaceWeightsFile1, SPACE_FORMAT_1,
};
use crate::nn::adam::AdamOptions;
use crate::space::{Chain, JointFrame, LinkVolume, Row, Vec3};

fn triple(v: Json) -> Read<Vec3> {
    let xs = floats(v)?;
    <[f64; 3]>::try_from(xs.as_slice())
        .map_err(|_| format!("invalid length {}, expected 3 numbers", xs.len()))
}

fn row(v: Json) -> Read<Row> {
    let mut f = Fields::of("Row", v)?;
    let r = Row {
        a: f.required("a", float)?,
        alpha: f.required("alpha", float)?,
        d: f.required("d", float)?,
        offset: f.required("offset", float)?,
    };
    f.done()?;
    Ok(r)
}

fn sampling(v: Json) -> Read<SpaceSampling> {
    let mut f = Fields::of("SpaceSampling", v)?;
    let s = SpaceSampling {
        sigma_floor: f.required("sigma_floor", float)?,
        tasks: f.required("tasks", count)?,
        obstacles_per_task: f.required("obstacles_per_task", count)?,
        line_length: f.required("line_length", float)?,
        obstacle_min: f.required("obstacle_min", triple)?,
        obstacle_max: f.required("obstacle_max", triple)?,
        theta_noise: f.required("theta_noise", float)?,
        obstacle_noise: f.required("obstacle_noise", float)?,
        sign_smoothing: f.required("sign_smoothing", float)?,
    };
    f.done()?;
    Ok(s)
}

fn training(v: Json) -> Read<SpaceTraining> {
    let mut f = Fields::of("SpaceTraining", v)?;
    let seed = f.required("seed", unsigned)?;
    let samples = f.required("samples", count)?;
    let hidden = f.required("hidden", |v| list(v, count))?;
    f.present("adam")?;
    let sampling = f.required("sampling", sampling)?;
    let seconds = f.optional("seconds", |v| nullable(v, float))?.flatten();
    f.done()?;
    Ok(SpaceTraining {
        seed,
        samples,
        hidden,
        adam: AdamOptions::default(),
        sampling,
        seconds,
    })
}

/// A chain as its JSON holds it (`Chain`'s serde form), checked as it is
/// built.
fn chain(v: Json) -> Read<Chain> {
    let mut f = Fields::of("Chain", v)?;
    let base = f.required("base", |v| {
        let [rotation, origin]: [Json; 2] = array(v)?;
        let [a, b, c]: [Json; 3] = array(rotation)?;
        Ok(([triple(a)?, triple(b)?, triple(c)?], triple(origin)?))
    })?;
    let rows = f.optional("rows", |v| list(v, row))?.unwrap_or_default();
    let joints = f
        .optional("joints", |v| list(v, joint))?
        .unwrap_or_default();
    let flange = f.required("flange", triple)?;
    let radius = f.required("radius", float)?;
    let volumes = f
        .optional("volumes", |v| list(v, link_volume))?
        .unwrap_or_default();
    let (joint_limits, rate_limits) = limits(&mut f)?;
    let flange_rotation = f.optional("flange_rotation", |v| {
        let [a, b, c]: [Json; 3] = array(v)?;
        Ok([triple(a)?, triple(b)?, triple(c)?])
    })?;
    let self_pairs = f
        .optional("self_pairs", |v| {
            list(v, |p| {
                let [a, b]: [Json; 2] = array(p)?;
                Ok([count(a)?, count(b)?])
            })
        })?
        .unwrap_or_default();
    f.done()?;
    let chain = match (rows.is_empty(), joints.is_empty(), volumes.is_empty()) {
        (false, true, true) => Chain::placed(base.0, base.1, rows, flange, radius),
        (true, false, _) => Chain::of_joints(base.0, base.1, joints, flange, volumes),
        _ => {
            return Err("a chain has either modified-DH rows or joint frames (with volumes)".into())
        }
    };
    chain
        .and_then(|c| c.with_limits(joint_limits, rate_limits))
        .and_then(|c| match flange_rotation {
            Some(r) => c.with_flange_rotation(r),
            None => Ok(c),
        })
        .and_then(|mut c| {
            if !self_pairs.is_empty() {
                c.set_self_pairs(self_pairs)?;
            }
            Ok(c)
        })
        .map_err(|e| e.to_string())
}

/// A joint frame of a chain read from URDF.
fn joint(v: Json) -> Read<JointFrame> {
    let mut f = Fields::of("JointFrame", v)?;
    let rotation = f.required("rotation", |v| {
        let [a, b, c]: [Json; 3] = array(v)?;
        Ok([triple(a)?, triple(b)?, triple(c)?])
    })?;
    let translation = f.required("translation", triple)?;
    let prismatic = f
        .optional("prismatic", super::by_hand::boolean)?
        .unwrap_or(false);
    f.done()?;
    Ok(JointFrame {
        rotation,
        translation,
        prismatic,
    })
}

/// A link's capsule of a chain read from URDF.
fn link_volume(v: Json) -> Read<LinkVolume> {
    let mut f = Fields::of("LinkVolume", v)?;
    let volume = LinkVolume {
        a: f.required("a", triple)?,
        b: f.required("b", triple)?,
        radius: f.required("radius", float)?,
        moved_by: f.required("moved_by", count)?,
    };
    f.done()?;
    Ok(volume)
}

/// A JSON array of exactly `N` values.
fn array<const N: usize>(v: Json) -> Read<[Json; N]> {
    let Json::Array(items) = v else {
        return Err(super::by_hand::wrong(&v, &format!("{N} values")));
    };
    let found = items.len();
    items
        .try_into()
        .map_err(|_| format!("invalid length {found}, expected {N} values"))
}

/// A spatial weights file's fields from its JSON text (not yet
/// validated): this version's layout, or version 1's turned into it; or
/// why not.
pub(crate) fn read(json: &str) -> Read<SpaceWeightsFile> {
    let tree: Json = serde_json::from_str(json).map_err(|e| e.to_string())?;
    let version_1 = matches!(&tree, Json::Object(pairs)
        if pairs.iter().any(|(k, v)| k == "format" && matches!(v, Json::Str(f) if f == SPACE_FORMAT_1)));
    if !version_1 {
        return read_with(tree, chain, training);
    }
    let mut f = Fields::of("SpaceWeightsFile", tree)?;
    let file = SpaceWeightsFile1 {
        format: f.required("format", string)?,
        net: f.required("net", net_kind)?,
        tool_version: f.required("tool_version", string)?,
        arm: f.required("arm", string)?,
        rows: f.required("rows", |v| list(v, row))?,
        flange: f.required("flange", triple)?,
        range: f.required("range", range)?,
        training: f.required("training", training)?,
        nets: f.required("nets", |v| list(v, net_entry))?,
    };
    f.done()?;
    file.into_current().map_err(|e| e.to_string())
}

/// A chain from its JSON text, as a weights file or a run file writes it
/// (serde's layout of [`Chain`]), read by hand: the page's module reads a
/// robot the workers' module made of a URDF so, without serde's derived
/// reader ([`crate::space::Chain::from_json`]).
pub(crate) fn read_chain(json: &str) -> Read<Chain> {
    let tree: Json = serde_json::from_str(json).map_err(|e| e.to_string())?;
    chain(tree)
}
