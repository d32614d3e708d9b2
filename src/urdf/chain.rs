//! The serial chain of a URDF from a base link to a tip link: the moving
//! joints in order, each with its frame in the previous moving joint's
//! (the fixed joints between folded into it), its axis, kind and limits,
//! and the links the chain carries, each in the frame of the moving joint
//! that moves it. The tree is checked on the way: every joint's links
//! exist, no link has two parents, the joints make no loop, one root.

use std::collections::HashMap;

use serde::Serialize;

use super::{Frame, JointType, Urdf, Vec3, MAX_CHAIN_JOINTS};
use crate::error::{Error, Result};

/// How a chain's joint moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum JointKind {
    /// Turns about its axis (a `revolute` or `continuous` URDF joint).
    Revolute,
    /// Slides along its axis.
    Prismatic,
}

/// A moving joint of the chain.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChainJoint {
    /// The URDF joint's name.
    pub name: String,
    /// How it moves.
    pub kind: JointKind,
    /// Its frame at zero motion in the previous moving joint's frame (the
    /// base link's for the first), the fixed joints between folded in.
    pub origin: Frame,
    /// The axis in its own frame, of unit length.
    pub axis: Vec3,
    /// Its range `[lower, upper]` (rad, or m), where the file gives one
    /// (a `continuous` joint has none).
    pub limits: Option<[f64; 2]>,
    /// Its largest rate (rad/s or m/s), where the file gives one.
    pub velocity: Option<f64>,
    /// Whether the URDF calls it `continuous` (it turns without limits).
    pub continuous: bool,
}

/// A link the chain carries, and where.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChainLink {
    /// The link's name.
    pub name: String,
    /// The moving joint that moves it, counted from 1 (0: the base, which
    /// no joint moves).
    pub moved_by: usize,
    /// Its frame in that joint's frame (the base link's frame for 0).
    pub frame: Frame,
}

/// The serial chain of a URDF from `base` to `tip`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UrdfChain {
    /// The robot's name.
    pub robot: String,
    /// The base link.
    pub base: String,
    /// The tip link.
    pub tip: String,
    /// The moving joints, base first.
    pub joints: Vec<ChainJoint>,
    /// The tip link's frame in the last moving joint's frame.
    pub tip_frame: Frame,
    /// The links from the base to the tip, base first.
    pub links: Vec<ChainLink>,
}

fn refuse(what: impl Into<String>) -> Error {
    Error::Urdf(what.into())
}

fn clip(text: &str) -> String {
    crate::error::clip(text)
}

impl UrdfChain {
    /// The chain of `urdf` from `base` (the tree's root when `None`) to
    /// `tip` (when `None`, the one leaf below the base; refused, naming
    /// the leaves, where there are several).
    pub fn new(urdf: &Urdf, base: Option<&str>, tip: Option<&str>) -> Result<Self> {
        // The joint that makes each link a child.
        let mut parent_joint: HashMap<&str, usize> = HashMap::new();
        for (k, j) in urdf.joints.iter().enumerate() {
            for end in [&j.parent, &j.child] {
                if urdf.link(end).is_none() {
                    return Err(refuse(format!(
                        "joint '{}' names the link '{}', which the file does not have",
                        clip(&j.name),
                        clip(end)
                    )));
                }
            }
            if j.parent == j.child {
                return Err(refuse(format!(
                    "joint '{}' joins the link '{}' to itself",
                    clip(&j.name),
                    clip(&j.child)
                )));
            }
            if let Some(&other) = parent_joint.get(j.child.as_str()) {
                return Err(refuse(format!(
                    "the link '{}' has two parents (joints '{}' and '{}'): a URDF is a tree",
                    clip(&j.child),
                    clip(&urdf.joints[other].name),
                    clip(&j.name)
                )));
            }
            parent_joint.insert(&j.child, k);
        }
        let roots: Vec<&str> = urdf
            .links
            .iter()
            .map(|l| l.name.as_str())
            .filter(|l| !parent_joint.contains_key(l))
            .collect();
        let root = match roots[..] {
            [one] => one,
            [] => return Err(refuse("every link has a parent: the joints make a loop")),
            _ => {
                return Err(refuse(format!(
                    "the links {} have no parent: a URDF has one root",
                    names(&roots)
                )))
            }
        };
        let base = match base {
            Some(b) if urdf.link(b).is_none() => {
                return Err(refuse(format!("there is no link '{}' (--base)", clip(b))))
            }
            Some(b) => b,
            None => root,
        };
        let tip = match tip {
            Some(t) if urdf.link(t).is_none() => {
                return Err(refuse(format!("there is no link '{}' (--tip)", clip(t))))
            }
            Some(t) => t.to_string(),
            None => only_leaf(urdf, base)?,
        };
        // From the tip up to the base; a loop stops the walk.
        let mut path = Vec::new();
        let mut at = tip.as_str();
        while at != base {
            let Some(&k) = parent_joint.get(at) else {
                return Err(refuse(format!(
                    "the link '{}' is not below the base '{}'",
                    clip(&tip),
                    clip(base)
                )));
            };
            path.push(k);
            if path.len() > urdf.joints.len() {
                return Err(refuse("the joints make a loop"));
            }
            at = &urdf.joints[k].parent;
        }
        path.reverse();
        let mut joints = Vec::new();
        let mut links = vec![ChainLink {
            name: base.to_string(),
            moved_by: 0,
            frame: Frame::IDENTITY,
        }];
        // The fixed joints since the last moving one.
        let mut folded = Frame::IDENTITY;
        for &k in &path {
            let j = &urdf.joints[k];
            let frame = folded.then(&j.origin);
            let kind = match j.kind {
                JointType::Fixed => {
                    folded = frame;
                    links.push(ChainLink {
                        name: j.child.clone(),
                        moved_by: joints.len(),
                        frame,
                    });
                    continue;
                }
                JointType::Revolute | JointType::Continuous => JointKind::Revolute,
                JointType::Prismatic => JointKind::Prismatic,
            };
            let limit = j.limit.unwrap_or(super::Limit {
                lower: None,
                upper: None,
                velocity: None,
            });
            let limits = match (j.kind, limit.lower, limit.upper) {
                (JointType::Continuous, _, _) => None,
                (_, Some(lo), Some(hi)) => Some([lo, hi]),
                _ => None,
            };
            joints.push(ChainJoint {
                name: j.name.clone(),
                kind,
                origin: frame,
                axis: j.axis,
                limits,
                velocity: limit.velocity.filter(|&v| v > 0.0),
                continuous: j.kind == JointType::Continuous,
            });
            if joints.len() > MAX_CHAIN_JOINTS {
                return Err(refuse(format!(
                    "the chain from '{}' to '{}' has more than {MAX_CHAIN_JOINTS} moving joints",
                    clip(base),
                    clip(&tip)
                )));
            }
            folded = Frame::IDENTITY;
            links.push(ChainLink {
                name: j.child.clone(),
                moved_by: joints.len(),
                frame: Frame::IDENTITY,
            });
        }
        if joints.is_empty() {
            return Err(refuse(format!(
                "no joint moves between '{}' and '{}'",
                clip(base),
                clip(&tip)
            )));
        }
        Ok(Self {
            robot: urdf.name.clone(),
            base: base.to_string(),
            tip,
            joints,
            tip_frame: folded,
            links,
        })
    }

    /// The number of moving joints.
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// Each moving joint's frame in the base link's at the joint values
    /// `q` (rad, or m for a prismatic joint; one per moving joint), after
    /// its motion, and last the tip link's frame; refused where `q` has
    /// another length.
    pub fn frames(&self, q: &[f64]) -> Result<Vec<Frame>> {
        if q.len() != self.dof() {
            return Err(Error::DimensionMismatch {
                what: "joint values of the URDF chain".into(),
                expected: self.dof(),
                found: q.len(),
            });
        }
        let mut at = Frame::IDENTITY;
        let mut out = Vec::with_capacity(self.dof() + 1);
        for (j, &v) in self.joints.iter().zip(q) {
            let motion = match j.kind {
                JointKind::Revolute => Frame::about(j.axis, v),
                JointKind::Prismatic => Frame::translation(j.axis.map(|a| a * v)),
            };
            at = at.then(&j.origin).then(&motion);
            out.push(at);
        }
        out.push(at.then(&self.tip_frame));
        Ok(out)
    }
}

/// The one leaf of the tree below `base`; refused, naming them, where
/// there are several (or none).
fn only_leaf(urdf: &Urdf, base: &str) -> Result<String> {
    let mut leaves = Vec::new();
    let mut stack = vec![base];
    let mut seen = 0;
    while let Some(l) = stack.pop() {
        seen += 1;
        if seen > urdf.links.len() {
            return Err(refuse("the joints make a loop"));
        }
        let children: Vec<&str> = urdf
            .joints
            .iter()
            .filter(|j| j.parent == l)
            .map(|j| j.child.as_str())
            .collect();
        if children.is_empty() {
            leaves.push(l);
        }
        stack.extend(children);
    }
    match leaves[..] {
        [one] => Ok(one.to_string()),
        _ => Err(refuse(format!(
            "the tree below '{}' has the leaves {}: name the tip link (--tip LINK; the page's Tip link)",
            clip(base),
            names(&leaves)
        ))),
    }
}

/// Names in quotes, at most 8 of them.
fn names(list: &[&str]) -> String {
    let mut out: Vec<String> = list
        .iter()
        .take(8)
        .map(|n| format!("'{}'", clip(n)))
        .collect();
    if list.len() > 8 {
        out.push(format!("and {} more", list.len() - 8));
    }
    out.join(", ")
}
