//! A URDF chain as the one chain model ([`crate::space::Chain`]), so that
//! it runs in the planner: each joint turned so that it moves about its
//! frame's `z` (the model's rule), its limits and rates, its volumes.
//!
//! A URDF joint `i` moves about its unit axis `a_i` in the frame its origin
//! `O_i` gives. With `A_i` a rotation that takes `z` to `a_i`, the turn about
//! `a_i` is `A_i Rz(theta) A_i^T`, so the frame `C_i = C_(i-1) F_i Rz(theta_i)`
//! with `F_1 = O_1 A_1` and `F_(i+1) = A_i^T O_(i+1) A_(i+1)` has the joint's
//! axis for its `z` and the joint's origin for its own; the URDF's frame is
//! `C_i A_i^T`. The flange and the volumes moved by joint `k` are turned by
//! `A_k^T` into `C_k`.

use super::volume::Volume;
use super::{Frame, JointKind, UrdfChain, Vec3};
use crate::arm::{JointLimits, RateLimits, MAX_ANGLE};
use crate::error::{Error, Result};
use crate::space::{Chain, JointFrame, LinkVolume, IDENTITY};

/// A rotation that takes `z` to the unit `a`.
fn z_to(a: Vec3) -> Frame {
    let c = a[2];
    if c > 1.0 - 1e-15 {
        return Frame::IDENTITY;
    }
    if c < -1.0 + 1e-15 {
        return Frame::about([1.0, 0.0, 0.0], std::f64::consts::PI);
    }
    // About z x a, by the angle between them.
    let axis = [-a[1], a[0], 0.0];
    let s = (axis[0] * axis[0] + axis[1] * axis[1]).sqrt();
    Frame::about(axis.map(|x| x / s), s.atan2(c))
}

/// The inverse of a rotation (its transpose), with no translation.
fn inverse_rotation(f: &Frame) -> Frame {
    Frame {
        rotation: std::array::from_fn(|r| std::array::from_fn(|c| f.rotation[c][r])),
        translation: [0.0; 3],
    }
}

impl UrdfChain {
    /// Each link the chain carries, placed as the chain model places it:
    /// `(name, moved_by, frame)`, the frame in the chain's joint
    /// `moved_by`'s frame (the URDF joint's frame turned so that its axis
    /// is `z`, as [`UrdfChain::to_chain`] turns it; the world for 0). A
    /// drawing puts a link's visuals at the chain's joint frame times this.
    pub fn link_frames(&self) -> Vec<(&str, usize, Frame)> {
        self.links
            .iter()
            .map(|l| {
                let turn = match l.moved_by {
                    0 => Frame::IDENTITY,
                    k => inverse_rotation(&z_to(self.joints[k - 1].axis)),
                };
                (l.name.as_str(), l.moved_by, turn.then(&l.frame))
            })
            .collect()
    }

    /// The chain model of this chain with `volumes` (`urdf::volume`):
    /// each joint revolute or prismatic (its coordinate in metres), its
    /// range from the file or `joint_limits` (a `revolute` or `prismatic`
    /// joint without one is refused unless `joint_limits` gives every
    /// range; a `continuous` one turns within +-[`MAX_ANGLE`]), its rate
    /// limits where the file gives every joint's.
    pub fn to_chain(&self, volumes: &[Volume], joint_limits: Option<JointLimits>) -> Result<Chain> {
        let refuse = |what: String| Error::Urdf(what);
        let align: Vec<Frame> = self.joints.iter().map(|j| z_to(j.axis)).collect();
        let mut joints = Vec::with_capacity(self.dof());
        for (i, j) in self.joints.iter().enumerate() {
            let before = if i == 0 {
                Frame::IDENTITY
            } else {
                inverse_rotation(&align[i - 1])
            };
            let f = before.then(&j.origin).then(&align[i]);
            joints.push(JointFrame {
                rotation: f.rotation,
                translation: f.translation,
                prismatic: j.kind == JointKind::Prismatic,
            });
        }
        let last = align.last().map(inverse_rotation).unwrap_or_default();
        let tip = last.then(&self.tip_frame);
        let flange = tip.translation;
        let links: Vec<LinkVolume> = volumes
            .iter()
            .map(|v| {
                let turn = match v.moved_by {
                    0 => Frame::IDENTITY,
                    k => inverse_rotation(&align[k - 1]),
                };
                LinkVolume {
                    a: turn.rotate(v.a),
                    b: turn.rotate(v.b),
                    radius: v.radius,
                    moved_by: v.moved_by,
                }
            })
            .collect();
        let limits = match joint_limits {
            Some(l) => l,
            None => {
                let mut ranges = Vec::with_capacity(self.dof());
                for j in &self.joints {
                    match j.limits {
                        Some(r) => ranges.push(r),
                        None if j.continuous => ranges.push([-MAX_ANGLE, MAX_ANGLE]),
                        None => {
                            return Err(refuse(format!(
                                "joint '{}' is {} with no limits: give them (--joint-limits)",
                                crate::error::clip(&j.name),
                                if j.kind == JointKind::Prismatic {
                                    "prismatic"
                                } else {
                                    "revolute"
                                }
                            )))
                        }
                    }
                }
                JointLimits::new(ranges)?
            }
        };
        let rates = self
            .joints
            .iter()
            .map(|j| j.velocity)
            .collect::<Option<Vec<f64>>>()
            .map(RateLimits::new)
            .transpose()?;
        Chain::of_joints(IDENTITY, [0.0; 3], joints, flange, links)?
            .with_limits(Some(limits), rates)?
            .with_flange_rotation(tip.rotation)
    }
}
