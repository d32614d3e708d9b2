//! The redundancy-resolution methods, one file each (as mink keeps one file
//! per task and per limit): what each computes for a pose, and what the
//! planner, the command line, the page, the atlas, the benchmark and the
//! tests need to know of it.
//!
//! A method is a [`Method`]: a handle on its [`MethodInfo`] (name, label,
//! description, paper figures, the networks it needs, its colour, the
//! parameters it reads) and on its [`Rule`], which writes the joint rates of
//! a pose into a slice the planner owns. A planner builds the method's rule
//! once ([`Method::rule`]) and calls it at every RK4 stage; the rule owns
//! its scratch space, so a step allocates nothing.
//!
//! **Adding a method** is one new file here that defines its `Method`
//! constant, and its line in [`register!`](self) below. Everything that
//! lists methods reads [`ALL`] (every method) or [`PAPER`] (the five of the
//! paper's section VI, which the published tables default to, so they do
//! not change when a method is added).

mod influence;
mod paper;
mod projection;
mod weighting;

pub use distance::DISTANCE_GAIN;
pub use influence::{INFLUENCE, STOP_DISTANCE};
pub use jointrange::JOINT_RANGE_GAIN;
pub use manipulability::MANIPULABILITY_GAIN;
pub use paper::{DELTA, LAMBDA, REFINE, SIGN_SMOOTHING};
pub use priority::ESCAPE_SPEED;
pub use qp::constraints::{
    DAMPER_GAIN, LIMIT_GAIN, LIMIT_INFLUENCE, LIMIT_STOP, RATE_LIMIT, SELF_DAMPER_GAIN,
    SELF_INFLUENCE, SELF_STOP_DISTANCE,
};
pub use qp::SLACK_WEIGHT;

use std::fmt;
use std::hash::{Hash, Hasher};
use std::str::FromStr;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::Surrogate;
use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::model::{Model, Scene as _};
use crate::scene::Param;
use crate::space::{Chain, PoseChain};

/// One line per method, in the order of the menus: declares the method's
/// module and puts its constant into [`ALL`].
macro_rules! register {
    ($($module:ident :: $method:ident),+ $(,)?) => {
        $(mod $module; pub use $module::$method;)+
        /// Every method, in the order of the menus.
        pub const ALL: &[Method] = &[$($method),+];
    };
}

register! {
    none::NO_AVOIDANCE,
    numerical::NUMERICAL,
    case1::CASE1,
    case2::CASE2,
    case3::CASE3,
    distance::DISTANCE,
    priority::PRIORITY,
    qp::QP,
    manipulability::MANIPULABILITY,
    jointrange::JOINT_RANGE,
}

/// The constraints of the `qp` method's program, one file each
/// (`qp/constraints/`): the velocity dampers and the joint-rate limit.
pub use qp::constraints;

/// The names of the methods that run an arm in space, for messages.
pub fn space_names() -> String {
    crate::error::choices(
        &ALL.iter()
            .filter(|m| m.in_space())
            .map(|m| m.name())
            .collect::<Vec<_>>(),
    )
}

/// The five methods of the paper's section VI, in its order (Figs. 2-6 and
/// 7-11). The atlas, `bench` and `eval` default to these.
pub const PAPER: [Method; 5] = [NO_AVOIDANCE, NUMERICAL, CASE1, CASE2, CASE3];

/// Where a method comes from, for the grouped menus.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Group {
    /// The five methods of the paper's section VI.
    Paper,
    /// Methods the field uses today, on the same scenes.
    Beyond,
}

impl Group {
    /// Every group, in the order of the menus.
    pub const ALL: [Group; 2] = [Group::Paper, Group::Beyond];

    /// The name in `methods()` and JSON (`paper`, `beyond`).
    pub fn name(self) -> &'static str {
        match self {
            Group::Paper => "paper",
            Group::Beyond => "beyond",
        }
    }

    /// What a menu heads it with.
    pub fn label(self) -> &'static str {
        match self {
            Group::Paper => "The paper",
            Group::Beyond => "Beyond the paper",
        }
    }
}

/// Which of the paper's networks a method runs (section V).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Needs {
    /// The `Phi` network (eq. 19).
    pub phi: bool,
    /// The `v` network (eqs. 14-15).
    pub v: bool,
}

impl Needs {
    /// No network: the method is computed exactly.
    pub const NOTHING: Needs = Needs {
        phi: false,
        v: false,
    };

    /// Whether any network is needed.
    pub fn any(self) -> bool {
        self.phi || self.v
    }
}

/// What a method is, for people and for the code that lists methods.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MethodInfo {
    /// The name on the command line, in URLs, weights files and JSON.
    pub name: &'static str,
    /// The name people read in menus and legends (the paper's terms).
    pub label: &'static str,
    /// What the method computes, in one line.
    pub description: &'static str,
    /// The paper's group, or beyond it.
    pub group: Group,
    /// The paper's figures of Task 1 and Task 2 with this method, if any.
    pub paper_figures: Option<[u32; 2]>,
    /// The networks it needs.
    pub networks: Needs,
    /// Whether it avoids obstacles at all.
    pub avoids: bool,
    /// Whether the scene's joint weighting reaches it (the paper's `W` of
    /// eq. 7, [`crate::scene::JointWeighting`]): the methods built on
    /// eq. (5), whose rates `weighting.rs` weights.
    pub weighting: bool,
    /// Whether its secondary task reads the arm's joint limits: on an arm
    /// without them it has none (`v = 0`) and its rates are `none`'s.
    pub limits: bool,
    /// Its colour in comparison figures and tables, `#rrggbb`.
    pub colour: &'static str,
    /// The scene's parameters it reads, each declared (`static`) in the
    /// file of the method or constraint that reads it.
    #[serde(serialize_with = "param_names")]
    pub params: &'static [&'static Param],
}

/// A method's parameters as the page reads them: their names.
fn param_names<S: Serializer>(
    params: &&'static [&'static Param],
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    s.collect_seq(params.iter().map(|p| p.name))
}

/// What a method's rule reads besides the pose: the scene (arm,
/// obstacles, gains) and the learned replacements, if any; for an arm `A`
/// whose hand has `M` coordinates (the planar arm's by default).
pub struct Context<'a, A: Model<M> = Arm, const M: usize = 2> {
    /// The scene, with its current target, obstacles and gains.
    pub scene: &'a A::Scene,
    /// The trained networks, if loaded.
    pub networks: Option<&'a dyn Surrogate<A, M>>,
}

impl<A: Model<M>, const M: usize> Clone for Context<'_, A, M> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<A: Model<M>, const M: usize> Copy for Context<'_, A, M> {}

impl<'a, A: Model<M>, const M: usize> Context<'a, A, M> {
    /// The networks, or why `method` cannot run without them.
    pub fn networks_for(&self, method: Method) -> Result<&'a dyn Surrogate<A, M>> {
        self.networks.ok_or_else(|| {
            Error::NetworksUnavailable(format!(
                "method {method} needs networks trained for this arm (--networks)"
            ))
        })
    }

    /// The damping `delta` of the schedule at `pose` (zero when it is off):
    /// what is added to the scene's constant `delta` near singular poses.
    #[inline]
    pub fn scheduled_delta(&self, pose: &A::Pose) -> f64 {
        self.scene
            .damping()
            .map_or(0.0, |d| d.delta_at_sigma(A::sigma_min(pose)))
    }
}

/// What a rate evaluation tells the planner besides the rates.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Note {
    /// The exact damped `Phi` (eq. 20) stood in for the `Phi` network: the
    /// damping schedule was active at a near-singular pose, where `Phi` is
    /// unbounded and no network fits it.
    pub handover: bool,
    /// The constraints of a quadratic program were relaxed because no rate
    /// satisfied them all (`qp`: see its documentation).
    pub relaxed: bool,
}

/// A method's computation for one planner of an arm `A` whose hand has
/// `M` coordinates (the planar arm's by default): the joint rates of a
/// pose, written into a slice the planner owns, with no allocation (the
/// rule owns its scratch space, sized for the arm when it is built).
pub trait Rule<A: Model<M> = Arm, const M: usize = 2>: Send + Sync {
    /// Joint rates `theta_dot` at `pose` for the commanded task velocity
    /// `xdot` (the path's, plus the feedback term) into `out` (`n` entries).
    fn theta_dot(
        &mut self,
        cx: &Context<'_, A, M>,
        pose: &A::Pose,
        xdot: [f64; M],
        out: &mut [f64],
    ) -> Result<Note>;

    /// The null-space vector `v` of eq. (5) at `pose` into `v` (`n`
    /// entries); `false` (and `v` untouched) for a method without one.
    fn null_space(
        &mut self,
        cx: &Context<'_, A, M>,
        pose: &A::Pose,
        v: &mut [f64],
    ) -> Result<bool> {
        let _ = (cx, pose, v);
        Ok(false)
    }

    /// A copy with its own scratch space (a cloned planner steps on its own).
    fn boxed_clone(&self) -> Box<dyn Rule<A, M>>;
}

impl<A: Model<M>, const M: usize> Clone for Box<dyn Rule<A, M>> {
    fn clone(&self) -> Self {
        self.boxed_clone()
    }
}

/// How a method's rule is built for an `n`-joint arm `A`.
pub type Builder<A, const M: usize> = fn(n: usize) -> Box<dyn Rule<A, M>>;

/// A method's registration: its description and how to build its rule for
/// an arm of `n` joints.
pub struct Entry {
    /// What the method is.
    pub info: MethodInfo,
    /// Builds the rule for an `n`-joint arm.
    pub rule: fn(n: usize) -> Box<dyn Rule>,
    /// Builds the rule for an `n`-joint chain in space, where the method
    /// has one.
    pub space: Option<Builder<Chain, 3>>,
    /// Builds the rule for an `n`-joint chain whose task is its hand's
    /// pose, where the method has one.
    pub pose: Option<Builder<PoseChain, 6>>,
}

/// A redundancy-resolution method: a handle on its registration.
/// Compared, hashed and serialised by name.
#[derive(Clone, Copy)]
pub struct Method(&'static Entry);

impl Method {
    /// The paper's methods by name: no avoidance (`none`).
    pub const NO_AVOIDANCE: Method = NO_AVOIDANCE;
    /// The numerical route (`numerical`).
    pub const NUMERICAL: Method = NUMERICAL;
    /// Case 1 (`case1`): `Phi` by a network.
    pub const CASE1: Method = CASE1;
    /// Case 2 (`case2`): `v` by a network.
    pub const CASE2: Method = CASE2;
    /// Case 3 (`case3`): both by networks.
    pub const CASE3: Method = CASE3;

    /// The method registered by `entry` (each method file declares its
    /// constant with this).
    pub const fn new(entry: &'static Entry) -> Self {
        Method(entry)
    }

    /// Its description.
    pub fn info(self) -> &'static MethodInfo {
        &self.0.info
    }

    /// Why this method adds nothing to `none` on an arm without joint
    /// limits (`limited`: whether the arm has them), if that is the case:
    /// the command line prints it, the page shows it beside the drawing.
    pub fn without_limits(self, limited: bool) -> Option<String> {
        (self.0.info.limits && !limited).then(|| {
            format!(
                "{} keeps each joint toward the middle of its range, and this arm has no joint limits: its v is zero and it runs as No avoidance; give the arm joint limits, or pick a preset that has them",
                self.0.info.label
            )
        })
    }

    /// The name used on the command line, in JSON and in the page.
    pub fn name(self) -> &'static str {
        self.0.info.name
    }

    /// The name people read in menus and legends.
    pub fn label(self) -> &'static str {
        self.0.info.label
    }

    /// What the method computes, in one line.
    pub fn description(self) -> &'static str {
        self.0.info.description
    }

    /// `label: description`, for titles and captions.
    pub fn title(self) -> String {
        format!("{}: {}", self.label(), self.description())
    }

    /// The networks it needs.
    pub fn networks(self) -> Needs {
        self.0.info.networks
    }

    /// Whether it needs any trained network.
    pub fn uses_networks(self) -> bool {
        self.0.info.networks.any()
    }

    /// Whether it avoids obstacles at all.
    pub fn avoids(self) -> bool {
        self.0.info.avoids
    }

    /// The paper's figure of this method on `task` (1 or 2), if it has one.
    pub fn paper_figure(self, task: u32) -> Option<u32> {
        let figs = self.0.info.paper_figures?;
        match task {
            1 => Some(figs[0]),
            2 => Some(figs[1]),
            _ => None,
        }
    }

    /// The scene's parameters it reads.
    pub fn params(self) -> &'static [&'static Param] {
        self.0.info.params
    }

    /// Whether it reads parameter `p`.
    pub fn reads(self, p: &'static Param) -> bool {
        self.0.info.params.iter().any(|q| std::ptr::eq(*q, p))
    }

    /// Its registration.
    pub fn entry(self) -> &'static Entry {
        self.0
    }

    /// Its rule for an `n`-joint arm, with its scratch space.
    pub fn rule(self, n: usize) -> Box<dyn Rule> {
        (self.0.rule)(n)
    }

    /// Its rule for an `n`-joint chain in space, or why it has none.
    pub fn space_rule(self, n: usize) -> Result<Box<dyn Rule<Chain, 3>>> {
        self.0.space.map(|b| b(n)).ok_or_else(|| Error::NotInSpace {
            method: self.name(),
            choices: space_names(),
        })
    }

    /// Whether it runs an arm in space.
    pub fn in_space(self) -> bool {
        self.0.space.is_some()
    }

    /// The names of [`ALL`], for messages: `"none, numerical, ... or case3"`.
    pub fn names() -> String {
        crate::error::choices(&ALL.iter().map(|m| m.name()).collect::<Vec<_>>())
    }

    /// A list of method names separated by commas, or `all` (every
    /// method) or `paper` (the paper's five).
    pub fn parse_list(text: &str) -> Result<Vec<Method>> {
        match text.trim() {
            "all" => Ok(ALL.to_vec()),
            "paper" => Ok(PAPER.to_vec()),
            list => list.split(',').map(|m| m.trim().parse()).collect(),
        }
    }
}

impl PartialEq for Method {
    fn eq(&self, other: &Self) -> bool {
        self.name() == other.name()
    }
}

impl Eq for Method {}

impl Hash for Method {
    fn hash<H: Hasher>(&self, state: &mut H) {
        self.name().hash(state);
    }
}

impl fmt::Debug for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Method {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        crate::error::by_name("method", s, ALL, Method::name)
    }
}

impl Serialize for Method {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.serialize_str(self.name())
    }
}

impl<'de> Deserialize<'de> for Method {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}
