//! The manipulability ellipse (`kinematics::velocity_ellipse`): its axes are
//! the eigenvectors of `J J^T`, its half-lengths the square roots of their
//! eigenvalues (the singular values of `J`), on random arms and poses.

use nalgebra::{Matrix2, SymmetricEigen};
use redundant_ik::kinematics::{velocity_ellipse, Pose};
use redundant_ik::Arm;

/// A small deterministic generator (xorshift), so the test needs no crate.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn axes_are_the_eigenvectors_of_j_jt_scaled_by_the_roots_of_its_eigenvalues() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    for _ in 0..500 {
        let n = 2 + (rng.next() * 5.0) as usize;
        let links: Vec<f64> = (0..n).map(|_| 0.1 + rng.next()).collect();
        let arm = Arm::new(0.5, links).expect("a valid arm");
        let theta: Vec<f64> = (0..n).map(|_| (rng.next() - 0.5) * 6.0).collect();
        let pose = Pose::new(&arm, &theta).expect("a valid pose");
        let [a, b, c] = pose.jjt();
        let m = Matrix2::new(a, b, b, c);
        let (axes, half) = velocity_ellipse([a, b, c]);
        let scale = a + c;
        let eig = SymmetricEigen::new(m);
        let (mut l1, mut l2) = (eig.eigenvalues[0], eig.eigenvalues[1]);
        if l1 < l2 {
            std::mem::swap(&mut l1, &mut l2);
        }
        assert!(half[0] >= half[1]);
        assert!((half[0] - l1.max(0.0).sqrt()).abs() < 1e-9 * scale.sqrt().max(1.0));
        assert!((half[1] - l2.max(0.0).sqrt()).abs() < 1e-6 * scale.sqrt().max(1.0));
        // The product of the half-lengths is the manipulability.
        assert!((half[0] * half[1] - pose.manipulability()).abs() < 1e-6 * scale.max(1.0));
        for (axis, h) in axes.iter().zip(half) {
            let v = nalgebra::Vector2::new(axis[0], axis[1]);
            assert!((v.norm() - 1.0).abs() < 1e-12, "unit axis");
            // J J^T v = sigma^2 v.
            let err = (m * v - v * (h * h)).norm();
            assert!(err < 1e-9 * scale.max(1.0), "eigenvector: {err}");
        }
        let dot = axes[0][0] * axes[1][0] + axes[0][1] * axes[1][1];
        assert!(dot.abs() < 1e-12, "orthogonal axes");
    }
}

#[test]
fn a_stretched_arm_has_a_flat_ellipse() {
    let arm = Arm::paper();
    let pose = Pose::new(&arm, &[0.0, 0.0, 0.0]).expect("pose");
    let (axes, half) = velocity_ellipse(pose.jjt());
    assert!(half[1] < 1e-9, "singular: no velocity along the arm");
    // Along the stretched arm nothing moves: the major axis is across it.
    let j = pose.joints();
    let along = [j[3][0] - j[0][0], j[3][1] - j[0][1]];
    assert!((axes[0][0] * along[0] + axes[0][1] * along[1]).abs() < 1e-9);
}
