//! The chains read from URDF ([`crate::urdf`]): a joint frame per joint,
//! each turning about its own `z`, and the links' capsules fixed in their
//! joints' frames (`Chain::of_joints`), beside the chains of modified-DH
//! rows of the parent module.

use serde::{Deserialize, Serialize};

use super::{check_rotation, Chain, Segment, Vec3, MAX_JOINTS, MIN_JOINTS};
use crate::error::{coordinate, non_negative, Error, Result};

/// A joint of a chain read from URDF: its frame at zero in the previous
/// joint's frame (the base's for the first), its axis that frame's `z`
/// (the reader turns each URDF joint so): frame `i = frame (i-1) F_i
/// Rz(theta_i)` for a revolute joint, `frame (i-1) F_i Tz(q_i)` for a
/// prismatic one (its coordinate `q_i` in metres).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointFrame {
    /// `F_i`'s rotation, by rows.
    pub rotation: [[f64; 3]; 3],
    /// `F_i`'s translation (m).
    pub translation: Vec3,
    /// Whether the joint slides along its `z` instead of turning about it
    /// (absent: it turns).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub prismatic: bool,
}

/// A link's capsule in the frame of the joint that moves it, for a chain
/// read from URDF: a sphere where its ends meet.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LinkVolume {
    /// One end, in joint `moved_by`'s frame (the base's for 0) (m).
    pub a: Vec3,
    /// The other end (m).
    pub b: Vec3,
    /// The radius (m).
    pub radius: f64,
    /// How many joints move it (0: the fixed base).
    pub moved_by: usize,
}

impl Chain {
    /// A chain of joint frames (a URDF's, [`crate::urdf`]): each joint
    /// turns about the `z` of its frame, `frame (i-1) F_i Rz(theta_i)`; the
    /// links' capsules fixed in their joints' frames. Refused for too few
    /// or too many joints, a rotation that is not one, a number that is
    /// not finite, a capsule moved by a joint the chain lacks or of a
    /// negative radius.
    pub fn of_joints(
        rotation: [[f64; 3]; 3],
        origin: [f64; 3],
        joints: Vec<JointFrame>,
        flange: [f64; 3],
        volumes: Vec<LinkVolume>,
    ) -> Result<Self> {
        if !(MIN_JOINTS..=MAX_JOINTS).contains(&joints.len()) {
            return Err(Error::LinkCount {
                found: joints.len(),
                min: MIN_JOINTS,
                max: MAX_JOINTS,
            });
        }
        check_rotation(&rotation)?;
        for (&o, axis) in origin.iter().zip(["x", "y", "z"]) {
            coordinate(&format!("base {axis}"), o)?;
        }
        for (i, j) in joints.iter().enumerate() {
            check_rotation(&j.rotation)?;
            for (&t, axis) in j.translation.iter().zip(["x", "y", "z"]) {
                coordinate(&format!("joint {} origin {axis}", i + 1), t)?;
            }
        }
        for (&f, axis) in flange.iter().zip(["x", "y", "z"]) {
            coordinate(&format!("flange {axis}"), f)?;
        }
        let mut radius: f64 = 0.0;
        let mut segments = Vec::with_capacity(volumes.len());
        let n = joints.len();
        for (k, v) in volumes.iter().enumerate() {
            if v.moved_by > joints.len() {
                return Err(Error::OutOfRange {
                    what: "joint moving a link volume".into(),
                    value: v.moved_by as f64,
                    min: 0.0,
                    max: joints.len() as f64,
                });
            }
            for &x in v.a.iter().chain(&v.b) {
                coordinate("link volume end", x)?;
            }
            non_negative("link volume radius", v.radius)?;
            coordinate("link volume radius", v.radius)?;
            radius = radius.max(v.radius);
            // The pose places its ends after the hand.
            segments.push(Segment {
                from: n + 2 + 2 * k,
                to: n + 3 + 2 * k,
                moved_by: v.moved_by,
                radius: v.radius,
            });
        }
        Ok(Self {
            twists: Vec::new(),
            base: (rotation, origin),
            rows: Vec::new(),
            joints,
            flange,
            flange_rotation: super::IDENTITY,
            radius,
            volumes,
            joint_limits: None,
            rate_limits: None,
            self_pairs: Vec::new(),
            segments,
        })
    }

    /// The joint frames of a chain read from URDF (none for rows).
    pub fn joint_frames(&self) -> &[JointFrame] {
        &self.joints
    }
}
