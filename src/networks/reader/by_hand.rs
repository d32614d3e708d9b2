//! The page's reader of weights files by hand (see `networks::reader`):
//! serde_json's parser builds a plain JSON tree ([`Json`], `crate::json`), and the fields of [`WeightsFile`] are taken from it
//! with the checks of serde's derived readers (missing, unknown and
//! repeated fields, types, the enums' names, the arm's constructor).

use crate::arm::{Arm, JointLimits, RateLimits};
use crate::json::Json;
use crate::networks::file::{
    Encoding, InputRange, Learned, NetEntry, NetKind, Sampling, Training, WeightsFile,
};
use crate::nn::lm::{LmOptions, StopReason, TrainReport};
use crate::nn::mlp::{Layer, MapMinMax, Mlp};
use crate::planner::Method;

/// Why a value does not read, with the path of fields to it.
pub(super) type Read<T> = Result<T, String>;

/// What a value is, for messages (serde's words).
fn kind(v: &Json) -> &'static str {
    match v {
        Json::Null => "null",
        Json::Bool(_) => "a boolean",
        Json::Uint(_) | Json::Int(_) => "an integer",
        Json::Float(_) => "a floating point number",
        Json::Str(_) => "a string",
        Json::Array(_) => "a sequence",
        Json::Object(_) => "a map",
    }
}

pub(super) fn wrong(value: &Json, expected: &str) -> String {
    format!("invalid type: {}, expected {expected}", kind(value))
}

/// An object's fields, taken one by one; what is left is refused where the
/// struct refuses unknown fields.
pub(super) struct Fields {
    what: &'static str,
    pairs: Vec<(String, Json)>,
}

impl Fields {
    pub(super) fn of(what: &'static str, value: Json) -> Read<Self> {
        let Json::Object(pairs) = value else {
            return Err(wrong(&value, &format!("struct {what}")));
        };
        for (i, (key, _)) in pairs.iter().enumerate() {
            if pairs[..i].iter().any(|(k, _)| k == key) {
                return Err(format!("{what}: duplicate field `{}`", clip(key)));
            }
        }
        Ok(Self { what, pairs })
    }

    /// The field `key` (or its older name `alias`), if present.
    fn take_any(&mut self, key: &str, alias: Option<&str>) -> Option<Json> {
        let i = self
            .pairs
            .iter()
            .position(|(k, _)| k == key || Some(k.as_str()) == alias)?;
        Some(self.pairs.remove(i).1)
    }

    /// An optional field read by `read`, `None` when absent.
    pub(super) fn optional<T>(
        &mut self,
        key: &str,
        read: impl FnOnce(Json) -> Read<T>,
    ) -> Read<Option<T>> {
        match self.take_any(key, None) {
            Some(v) => read(v).map(Some).map_err(|e| format!("{key}: {e}")),
            None => Ok(None),
        }
    }

    /// A field that must be present.
    pub(super) fn required<T>(&mut self, key: &str, read: impl FnOnce(Json) -> Read<T>) -> Read<T> {
        self.required_as(key, None, read)
    }

    fn required_as<T>(
        &mut self,
        key: &str,
        alias: Option<&str>,
        read: impl FnOnce(Json) -> Read<T>,
    ) -> Read<T> {
        match self.take_any(key, alias) {
            Some(v) => read(v).map_err(|e| format!("{key}: {e}")),
            None => Err(format!("{}: missing field `{key}`", self.what)),
        }
    }

    /// A field that must be present and whose value the page does not read.
    pub(super) fn present(&mut self, key: &str) -> Read<()> {
        self.required(key, |_| Ok(()))
    }

    /// Refuses the fields not taken (`deny_unknown_fields`).
    pub(super) fn done(self) -> Read<()> {
        match self.pairs.first() {
            Some((key, _)) => Err(format!("{}: unknown field `{}`", self.what, clip(key))),
            None => Ok(()),
        }
    }
}

/// A key quoted in a message, cut to 40 characters (a file can be hostile).
pub(super) fn clip(text: &str) -> String {
    crate::error::clip(text)
}

pub(super) fn float(v: Json) -> Read<f64> {
    v.number().ok_or_else(|| wrong(&v, "f64"))
}

pub(super) fn unsigned(v: Json) -> Read<u64> {
    match v {
        Json::Uint(x) => Ok(x),
        other => Err(wrong(&other, "an unsigned integer")),
    }
}

pub(super) fn count(v: Json) -> Read<usize> {
    let x = unsigned(v)?;
    usize::try_from(x).map_err(|_| format!("{x} is out of range for usize"))
}

fn task(v: Json) -> Read<u32> {
    let x = unsigned(v)?;
    u32::try_from(x).map_err(|_| format!("{x} is out of range for u32"))
}

pub(super) fn boolean(v: Json) -> Read<bool> {
    match v {
        Json::Bool(b) => Ok(b),
        other => Err(wrong(&other, "a boolean")),
    }
}

pub(super) fn string(v: Json) -> Read<String> {
    match v {
        Json::Str(s) => Ok(s),
        other => Err(wrong(&other, "a string")),
    }
}

pub(super) fn list<T>(v: Json, read: impl Fn(Json) -> Read<T>) -> Read<Vec<T>> {
    match v {
        Json::Array(items) => items
            .into_iter()
            .enumerate()
            .map(|(i, x)| read(x).map_err(|e| format!("[{i}]: {e}")))
            .collect(),
        other => Err(wrong(&other, "a sequence")),
    }
}

pub(super) fn floats(v: Json) -> Read<Vec<f64>> {
    list(v, float)
}

pub(super) fn pair(v: Json) -> Read<[f64; 2]> {
    let xs = floats(v)?;
    match xs[..] {
        [a, b] => Ok([a, b]),
        _ => Err(format!(
            "invalid length {}, expected an array of length 2",
            xs.len()
        )),
    }
}

pub(super) fn nullable<T>(v: Json, read: impl FnOnce(Json) -> Read<T>) -> Read<Option<T>> {
    match v {
        Json::Null => Ok(None),
        v => read(v).map(Some),
    }
}

/// A name read by a type's own reader of names (`FromStr`).
fn named<T: std::str::FromStr<Err = crate::error::Error>>(v: Json) -> Read<T> {
    string(v)?
        .parse()
        .map_err(|e: crate::error::Error| e.to_string())
}

pub(super) fn net_kind(v: Json) -> Read<NetKind> {
    match string(v)?.as_str() {
        "phi" => Ok(NetKind::Phi),
        "v" => Ok(NetKind::V),
        other => Err(format!(
            "unknown variant `{}`, expected `phi` or `v`",
            clip(other)
        )),
    }
}

fn arm(v: Json) -> Read<Arm> {
    let mut f = Fields::of("Arm", v)?;
    let post = f.required("post", float)?;
    let links = f.required("links", floats)?;
    let (joint_limits, rate_limits) = limits(&mut f)?;
    f.done()?;
    Arm::new(post, links)
        .and_then(|a| a.with_limits(joint_limits, rate_limits))
        .map_err(|e| e.to_string())
}

/// An arm's optional `joint_limits` and `rate_limits` (the planar arm's
/// and a chain's), checked as their constructors check them.
pub(super) fn limits(f: &mut Fields) -> Read<(Option<JointLimits>, Option<RateLimits>)> {
    let joint_limits = f
        .optional("joint_limits", |v| nullable(v, |v| list(v, pair)))?
        .flatten()
        .map(JointLimits::new)
        .transpose()
        .map_err(|e| e.to_string())?;
    let rate_limits = f
        .optional("rate_limits", |v| nullable(v, floats))?
        .flatten()
        .map(RateLimits::new)
        .transpose()
        .map_err(|e| e.to_string())?;
    Ok((joint_limits, rate_limits))
}

fn map_min_max(v: Json) -> Read<MapMinMax> {
    let mut f = Fields::of("MapMinMax", v)?;
    Ok(MapMinMax {
        min: f.required("min", floats)?,
        max: f.required("max", floats)?,
    })
}

fn layer(v: Json) -> Read<Layer> {
    let mut f = Fields::of("Layer", v)?;
    Ok(Layer {
        weights: f.required("weights", floats)?,
        biases: f.required("biases", floats)?,
    })
}

fn mlp(v: Json) -> Read<Mlp> {
    let mut f = Fields::of("Mlp", v)?;
    Ok(Mlp {
        sizes: f.required("sizes", |v| list(v, count))?,
        layers: f.required("layers", |v| list(v, layer))?,
        input_map: f.required("input_map", map_min_max)?,
        output_map: f.required("output_map", map_min_max)?,
    })
}

pub(super) fn net_entry(v: Json) -> Read<NetEntry> {
    let mut f = Fields::of("NetEntry", v)?;
    let mlp = f.required("mlp", mlp)?;
    f.present("report")?;
    f.done()?;
    Ok(NetEntry {
        mlp,
        report: unread_report(),
    })
}

pub(super) fn range(v: Json) -> Read<InputRange> {
    let mut f = Fields::of("InputRange", v)?;
    let range = InputRange {
        names: f.required("names", |v| list(v, string))?,
        min: f.required("min", floats)?,
        max: f.required("max", floats)?,
        sigma_floor: f.required("sigma_floor", float)?,
    };
    f.done()?;
    Ok(range)
}

fn sampling(v: Json) -> Read<Sampling> {
    let mut f = Fields::of("Sampling", v)?;
    let s = Sampling {
        tasks: f.required("tasks", |v| list(v, task))?,
        random_tasks: f.optional("random_tasks", count)?.unwrap_or(0),
        methods: f.required_as("methods", Some("modes"), |v| list(v, named::<Method>))?,
        obstacles_per_task: f.required("obstacles_per_task", count)?,
        obstacle_min: f.required("obstacle_min", pair)?,
        obstacle_max: f.required("obstacle_max", pair)?,
        theta_noise: f.required("theta_noise", float)?,
        sigma_floor: f.required("sigma_floor", float)?,
        paired_obstacle_share: f.required("paired_obstacle_share", float)?,
        obstacle_noise: f.required("obstacle_noise", float)?,
        obstacle_spread: f.optional("obstacle_spread", float)?.unwrap_or(0.0),
        whole_torus: f.optional("whole_torus", boolean)?.unwrap_or(false),
        sign_smoothing: f.optional("sign_smoothing", float)?.unwrap_or(0.0),
    };
    f.done()?;
    Ok(s)
}

fn training(v: Json) -> Read<Training> {
    let mut f = Fields::of("Training", v)?;
    let seed = f.required("seed", unsigned)?;
    let samples = f.required("samples", count)?;
    let hidden = f.required("hidden", |v| list(v, count))?;
    f.present("options")?;
    f.optional("adam", |_| Ok(()))?;
    let sampling = f.required("sampling", sampling)?;
    let seconds = f.optional("seconds", |v| nullable(v, float))?.flatten();
    f.done()?;
    Ok(Training {
        seed,
        samples,
        hidden,
        options: LmOptions::default(),
        adam: None,
        sampling,
        seconds,
    })
}

/// What stands in for a network's training report, which the page does not read.
pub(super) fn unread_report() -> TrainReport {
    TrainReport {
        epochs: 0,
        best_epoch: 0,
        stop: StopReason::MaxEpochs,
        train_mse: 0.0,
        val_mse: 0.0,
        test_mse: 0.0,
        split: [0; 3],
    }
}

/// A weights file's fields from its JSON text (not yet validated), or why not.
pub(crate) fn read(json: &str) -> Read<WeightsFile> {
    let tree: Json = serde_json::from_str(json).map_err(|e| e.to_string())?;
    read_with(tree, arm, training)
}

/// A weights file's fields from its JSON tree, the arm and the training
/// read by `arm` and `training` (the planar arm's, or a chain's in space).
pub(super) fn read_with<A: Learned>(
    tree: Json,
    arm: fn(Json) -> Read<A>,
    training: fn(Json) -> Read<A::Training>,
) -> Read<WeightsFile<A>> {
    let mut f = Fields::of("WeightsFile", tree)?;
    let file = WeightsFile {
        format: f.required("format", string)?,
        net: f.required("net", net_kind)?,
        variant: f.required("variant", named)?,
        encoding: f
            .optional("encoding", named::<Encoding>)?
            .unwrap_or_default(),
        tool_version: f.required("tool_version", string)?,
        arm: f.required("arm", arm)?,
        range: f.required("range", range)?,
        training: f.required("training", training)?,
        nets: f.required("nets", |v| list(v, net_entry))?,
    };
    f.done()?;
    Ok(file)
}
