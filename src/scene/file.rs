//! A scene as JSON: what `simulate --json`, the page's "Download run" and
//! the atlas write and what they read back. The parameters go by name in
//! one object, `params`; the fields that files written before parameters
//! were declared by their methods carry (`lambda`, `delta`, `avoidance`,
//! `sign_smoothing`, `refine`) are still read. Turning names into
//! parameters needs the methods' list of them, so the conversions to and
//! from [`super::Scene`] live with that list (`crate::planner::params`).

use std::fmt;

use serde::de::{MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::{JointWeighting, Path};
use crate::arm::Arm;
use crate::geometry::Ball;
use crate::ik::DampingSchedule;

/// Parameter values by name, in the order of the methods' list; written
/// and read as one JSON object (a name given twice is refused).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ParamMap(pub Vec<(String, f64)>);

impl Serialize for ParamMap {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (k, v) in &self.0 {
            map.serialize_entry(k, v)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for ParamMap {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct Entries;
        impl<'de> Visitor<'de> for Entries {
            type Value = ParamMap;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("an object of parameter values by name")
            }
            fn visit_map<A: MapAccess<'de>>(
                self,
                mut m: A,
            ) -> std::result::Result<ParamMap, A::Error> {
                let mut out: Vec<(String, f64)> = Vec::new();
                while let Some((k, v)) = m.next_entry::<String, f64>()? {
                    if out.iter().any(|(q, _)| *q == k) {
                        return Err(serde::de::Error::custom(format!(
                            "parameter '{k}' given twice"
                        )));
                    }
                    out.push((k, v));
                }
                Ok(ParamMap(out))
            }
        }
        d.deserialize_map(Entries)
    }
}

/// The JSON form of a [`super::Scene`], of either kind of arm: the arm
/// as its own JSON (a planar arm's post and links, a chain's rows), the
/// hand's `M` coordinates, the obstacles as balls of `M` coordinates.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(
    deny_unknown_fields,
    bound(
        serialize = "A: Serialize, P: Serialize + Default + PartialEq, [f64; M]: Serialize, [f64; D]: Serialize",
        deserialize = "A: Deserialize<'de>, P: Deserialize<'de> + Default, [f64; M]: Deserialize<'de>, [f64; D]: Deserialize<'de>"
    )
)]
pub struct SceneFile<A = Arm, P = Path, const M: usize = 2, const D: usize = M> {
    /// The manipulator.
    pub arm: A,
    /// Joint angles at `t = 0` (radians).
    pub theta0: Vec<f64>,
    /// End of the straight line, `X(tf)`.
    pub target: [f64; M],
    /// The path, as its text (`circle:1.2,0.8`); absent: the line.
    #[serde(default, skip_serializing_if = "is_default")]
    pub path: P,
    /// The obstacles (discs in the plane, spheres in space).
    pub obstacles: Vec<Ball<D>>,
    /// Optional damping schedule near singular poses.
    pub damping: Option<DampingSchedule>,
    /// Runge-Kutta step (s).
    pub dt: f64,
    /// Final time (s).
    pub tf: f64,
    /// Closed-loop gain `K`.
    pub feedback_gain: f64,
    /// Every declared parameter's value, by name (absent in older files).
    #[serde(default)]
    pub params: ParamMap,
    /// How the methods of eq. (5) use the joint limits (absent: `none`).
    #[serde(default, skip_serializing_if = "JointWeighting::is_none")]
    pub joint_weighting: JointWeighting,
    /// Whether the floor and the post are obstacles (absent: no).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub floor: bool,
    /// Older files: the gain `lambda`.
    #[serde(default, skip_serializing)]
    pub lambda: Option<f64>,
    /// Older files: the damping `delta`.
    #[serde(default, skip_serializing)]
    pub delta: Option<f64>,
    /// Older files: the parameters of the methods beyond the paper, by name.
    #[serde(default, skip_serializing)]
    pub avoidance: Option<ParamMap>,
    /// Older files: the sign smoothing `eps`.
    #[serde(default, skip_serializing)]
    pub sign_smoothing: Option<f64>,
    /// Older files: the Newton-Schulz steps on a learned `Phi`.
    #[serde(default, skip_serializing)]
    pub refine: Option<f64>,
}

/// Whether `p` is its type's default (a path's: the line).
fn is_default<P: Default + PartialEq>(p: &P) -> bool {
    *p == P::default()
}
