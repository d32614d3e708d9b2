//! Rotations of the hand's orientation, as matrices by rows: URDF's
//! fixed-axis roll-pitch-yaw (`R = Rz(yaw) Ry(pitch) Rx(roll)`, the URDF
//! specification's `<origin rpy>`), a turn about an axis (Rodrigues), and
//! the exponential and logarithm between a rotation and its rotation
//! vector (the axis times the angle, `|r| <= pi`): what the pose task's
//! orientation error (the rotation vector of `R_a R_b^T`) and its shortest
//! path (`R(s) = exp(s log(R_b R_a^T)) R_a`) are made of.

use nalgebra::{Matrix3, Rotation3, UnitQuaternion};

use crate::kinematics::sin_cos;

/// A 3-vector.
type Vec3 = [f64; 3];

/// A rotation matrix, by rows.
pub type Mat3 = [[f64; 3]; 3];

/// The identity rotation.
pub const IDENTITY: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// URDF's `rpy`: roll, pitch and yaw about the fixed axes `x`, `y`, `z` in
/// that order, `R = Rz(yaw) Ry(pitch) Rx(roll)`.
pub fn rpy_matrix(rpy: Vec3) -> Mat3 {
    let (sr, cr) = sin_cos(rpy[0]);
    let (sp, cp) = sin_cos(rpy[1]);
    let (sy, cy) = sin_cos(rpy[2]);
    [
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ]
}

/// The roll, pitch and yaw of `r` ([`rpy_matrix`]'s inverse; pitch in
/// `[-pi/2, pi/2]`, at gimbal lock the yaw taken as 0).
pub fn matrix_rpy(r: &Mat3) -> Vec3 {
    let pitch = (-r[2][0]).clamp(-1.0, 1.0).asin();
    if r[2][0].abs() < 1.0 - 1e-12 {
        [r[2][1].atan2(r[2][2]), pitch, r[1][0].atan2(r[0][0])]
    } else {
        [(-r[1][2]).atan2(r[1][1]), pitch, 0.0]
    }
}

/// The turn by `angle` (rad) about the unit `axis` (Rodrigues' formula).
pub fn about(axis: Vec3, angle: f64) -> Mat3 {
    let (s, c) = sin_cos(angle);
    let t = 1.0 - c;
    let [x, y, z] = axis;
    [
        [t * x * x + c, t * x * y - s * z, t * x * z + s * y],
        [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
        [t * x * z - s * y, t * y * z + s * x, t * z * z + c],
    ]
}

/// The rotation of rotation vector `v`: the turn by `|v|` about `v`.
pub fn exp(v: Vec3) -> Mat3 {
    let angle = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if angle == 0.0 {
        return IDENTITY;
    }
    about(v.map(|x| x / angle), angle)
}

/// The rotation vector of `r` (`|v| <= pi`): through its unit quaternion
/// `(w, u)` (nalgebra's, from the matrix by the largest of its diagonal
/// forms, accurate at every angle), `v = 2 atan2(|u|, |w|) u / |u|` with
/// `u`'s sign taken so that `w >= 0`: exact to rounding near the identity
/// (where `acos(w)` would lose half the digits) and near a half turn.
pub fn log(r: &Mat3) -> Vec3 {
    let m = Matrix3::from_fn(|i, j| r[i][j]);
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m));
    let (w, u) = (q.w, [q.i, q.j, q.k]);
    let size = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
    if size == 0.0 {
        return [0.0; 3];
    }
    let k = 2.0 * size.atan2(w.abs()) / size * if w < 0.0 { -1.0 } else { 1.0 };
    u.map(|x| k * x)
}

/// `a b`.
pub fn mul(a: &Mat3, b: &Mat3) -> Mat3 {
    std::array::from_fn(|r| std::array::from_fn(|c| (0..3).map(|k| a[r][k] * b[k][c]).sum()))
}

/// `a b^T`.
pub fn mul_transpose(a: &Mat3, b: &Mat3) -> Mat3 {
    std::array::from_fn(|r| std::array::from_fn(|c| (0..3).map(|k| a[r][k] * b[c][k]).sum()))
}

/// The rotation vector of `R_a R_b^T` for rotation vectors `a` and `b`:
/// the turn that takes orientation `b` to `a`, in the world's axes.
pub fn difference(a: Vec3, b: Vec3) -> Vec3 {
    log(&mul_transpose(&exp(a), &exp(b)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: Vec3, b: Vec3, tol: f64) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
    }

    #[test]
    fn log_inverts_exp_from_tiny_angles_to_nearly_a_half_turn() {
        for angle in [1e-12, 1e-6, 0.3, 2.0, 3.0, std::f64::consts::PI - 1e-9] {
            let axis = [0.48, -0.6, 0.64];
            let v = axis.map(|x| x * angle);
            let back = log(&exp(v));
            assert!(close(back, v, 1e-12 * angle.max(1e-3)), "{angle}: {back:?}");
        }
        assert_eq!(log(&IDENTITY), [0.0; 3]);
    }

    #[test]
    fn rpy_turns_about_the_fixed_axes_roll_first_and_reads_back() {
        let rpy = [0.3, -0.7, 2.1];
        let r = rpy_matrix(rpy);
        let expected = mul(
            &about([0.0, 0.0, 1.0], 2.1),
            &mul(&about([0.0, 1.0, 0.0], -0.7), &about([1.0, 0.0, 0.0], 0.3)),
        );
        for (a, b) in r.iter().zip(&expected) {
            assert!(close(*a, *b, 1e-15));
        }
        assert!(close(matrix_rpy(&r), rpy, 1e-14));
    }

    #[test]
    fn the_difference_of_two_orientations_turns_one_into_the_other() {
        let (a, b) = ([0.2, -1.1, 0.4], [-0.9, 0.3, 1.5]);
        let d = difference(a, b);
        let turned = mul(&exp(d), &exp(b));
        for (x, y) in turned.iter().zip(&exp(a)) {
            assert!(close(*x, *y, 1e-14));
        }
        assert!(close(difference(a, a), [0.0; 3], 1e-15));
    }
}
