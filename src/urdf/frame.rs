//! A rigid transform of a URDF: a rotation (by rows) and a translation,
//! as an `<origin xyz="..." rpy="..."/>` writes one. URDF's `rpy` is
//! roll, pitch and yaw about the fixed axes `x`, `y` and `z` in that
//! order, so `R = Rz(yaw) Ry(pitch) Rx(roll)` (the URDF specification,
//! `<origin>`; the same as ROS's `tf` and Pinocchio's `rpyToMatrix`).

use serde::Serialize;

use crate::space::rotation::{self, IDENTITY};

/// A 3-vector.
pub type Vec3 = [f64; 3];

/// A rotation and a translation: `p -> R p + t`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Frame {
    /// The rotation, by rows.
    pub rotation: [[f64; 3]; 3],
    /// The translation (m).
    pub translation: Vec3,
}

impl Default for Frame {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Frame {
    /// No rotation, no translation.
    pub const IDENTITY: Frame = Frame {
        rotation: IDENTITY,
        translation: [0.0; 3],
    };

    /// The frame of an `<origin>`: `xyz` and the fixed-axis `rpy`.
    pub fn from_xyz_rpy(xyz: Vec3, rpy: Vec3) -> Self {
        Self {
            rotation: rotation::rpy_matrix(rpy),
            translation: xyz,
        }
    }

    /// The translation alone.
    pub fn translation(t: Vec3) -> Self {
        Self {
            rotation: IDENTITY,
            translation: t,
        }
    }

    /// `self * other`: `other` expressed in this frame's parent.
    pub fn then(&self, other: &Frame) -> Frame {
        let mut rotation = [[0.0; 3]; 3];
        for (r, row) in rotation.iter_mut().enumerate() {
            for (c, x) in row.iter_mut().enumerate() {
                *x = (0..3)
                    .map(|k| self.rotation[r][k] * other.rotation[k][c])
                    .sum();
            }
        }
        Frame {
            rotation,
            translation: self.apply(other.translation),
        }
    }

    /// The point `p` of this frame in its parent: `R p + t`.
    pub fn apply(&self, p: Vec3) -> Vec3 {
        let mut out = self.translation;
        for (r, o) in out.iter_mut().enumerate() {
            *o += (0..3).map(|k| self.rotation[r][k] * p[k]).sum::<f64>();
        }
        out
    }

    /// The direction `v` of this frame in its parent: `R v`.
    pub fn rotate(&self, v: Vec3) -> Vec3 {
        std::array::from_fn(|r| (0..3).map(|k| self.rotation[r][k] * v[k]).sum())
    }

    /// The rotation by `angle` about the unit `axis` (Rodrigues).
    pub fn about(axis: Vec3, angle: f64) -> Frame {
        Frame {
            rotation: rotation::about(axis, angle),
            translation: [0.0; 3],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12)
    }

    #[test]
    fn rpy_turns_about_the_fixed_axes_roll_first() {
        let h = std::f64::consts::FRAC_PI_2;
        // Roll about x takes y to z.
        let roll = Frame::from_xyz_rpy([0.0; 3], [h, 0.0, 0.0]);
        assert!(close(roll.rotate([0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]));
        // Yaw about z takes x to y.
        let yaw = Frame::from_xyz_rpy([0.0; 3], [0.0, 0.0, h]);
        assert!(close(yaw.rotate([1.0, 0.0, 0.0]), [0.0, 1.0, 0.0]));
        // Roll then yaw about the fixed axes: y -> z (roll) -> z (yaw).
        let both = Frame::from_xyz_rpy([0.0; 3], [h, 0.0, h]);
        assert!(close(both.rotate([0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]));
        assert!(close(both.rotate([1.0, 0.0, 0.0]), [0.0, 1.0, 0.0]));
        // Rodrigues agrees with the rpy of one axis.
        let about = Frame::about([1.0, 0.0, 0.0], h);
        assert!(close(about.rotate([0.0, 1.0, 0.0]), [0.0, 0.0, 1.0]));
    }

    #[test]
    fn frames_compose_child_after_parent() {
        let a = Frame::from_xyz_rpy([1.0, 0.0, 0.0], [0.0, 0.0, std::f64::consts::FRAC_PI_2]);
        let b = Frame::translation([1.0, 0.0, 0.0]);
        // b's origin, one metre along a's x (the world's y), from a's origin.
        assert!(close(a.then(&b).translation, [1.0, 1.0, 0.0]));
    }
}
