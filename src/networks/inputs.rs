//! What the networks see: the input vector of the `Phi` and `v` networks
//! for a pose (and obstacle point), by variant and by encoding of the angles.
//!
//! The paper feeds raw joint angles ([`Encoding::Raw`]). Joints turn
//! through whole revolutions, so a raw angle leaves any trained interval
//! while the pose it names is one the network has seen (`docs/learning.md`).
//! [`Encoding::Angles`] feeds `(sin theta_i, cos theta_i)` instead: every
//! pose of the joint torus is one point, and no input ever leaves
//! `[-1, 1]`. The training set and the run time build their inputs here, so
//! they cannot disagree.

use super::file::{Encoding, NetKind, Variant};
use crate::arm::MAX_LINKS;

/// Most inputs a network of an arm with [`MAX_LINKS`] links takes: the
/// `v` network's `2n + 2` with encoded angles.
pub const MAX_INPUTS: usize = 2 * MAX_LINKS + 2;

/// The joint angles a network of `kind` and `variant` reads: `theta_2..`
/// for the rotation-equivariant variant (its output is turned by
/// `theta_1` afterwards), all of them otherwise.
fn angles(variant: Variant, theta: &[f64]) -> &[f64] {
    match variant {
        Variant::Equivariant => &theta[1.min(theta.len())..],
        _ => theta,
    }
}

/// Writes the encoded `angles` into `buf` and returns how many entries.
#[inline]
fn encode(encoding: Encoding, angles: &[f64], buf: &mut [f64]) -> usize {
    match encoding {
        Encoding::Raw => {
            buf[..angles.len()].copy_from_slice(angles);
            angles.len()
        }
        Encoding::Angles => {
            for (pair, a) in buf.chunks_exact_mut(2).zip(angles) {
                let (s, c) = crate::kinematics::sin_cos(*a);
                pair[0] = s;
                pair[1] = c;
            }
            2 * angles.len()
        }
    }
}

/// The `Phi` networks' inputs for a pose, written into `buf`.
#[inline]
pub fn phi_inputs<'a>(
    variant: Variant,
    encoding: Encoding,
    theta: &[f64],
    buf: &'a mut [f64; MAX_INPUTS],
) -> &'a [f64] {
    let theta = &theta[..theta.len().min(MAX_LINKS)];
    let k = encode(encoding, angles(variant, theta), buf);
    &buf[..k]
}

/// The `v` network's inputs for a pose and obstacle point `o`, written
/// into `buf` (`(s, c)` = sine and cosine of `theta_1`, `post` the arm's
/// post height). The rotation-equivariant variant sees `O' = R(theta_1)^T
/// (O - P(0)) + P(0)`: the arm at `theta_1` is the arm at `theta_1 = 0`
/// turned by `R(theta_1)` about `P(0)`, and the area gradient is invariant
/// under that turn.
#[inline]
pub fn v_inputs<'a>(
    variant: Variant,
    encoding: Encoding,
    post: f64,
    theta: &[f64],
    (s, c): (f64, f64),
    o: [f64; 2],
    buf: &'a mut [f64; MAX_INPUTS],
) -> &'a [f64] {
    let theta = &theta[..theta.len().min(MAX_LINKS)];
    let k = encode(encoding, angles(variant, theta), buf);
    match variant {
        Variant::Equivariant => {
            let (dx, dy) = (o[0], o[1] - post);
            buf[k] = c * dx - s * dy;
            buf[k + 1] = s * dx + c * dy + post;
        }
        _ => {
            buf[k] = o[0];
            buf[k + 1] = o[1];
        }
    }
    &buf[..k + 2]
}

/// The inputs' names, as the weights file's range lists them (`theta2`,
/// `sin theta2`, `cos theta2`, `o1_rotated`, ...).
pub fn input_names(net: NetKind, variant: Variant, encoding: Encoding, n: usize) -> Vec<String> {
    let first = if variant == Variant::Equivariant {
        2
    } else {
        1
    };
    let mut names: Vec<String> = (first..=n)
        .flat_map(|i| match encoding {
            Encoding::Raw => vec![format!("theta{i}")],
            Encoding::Angles => vec![format!("sin theta{i}"), format!("cos theta{i}")],
        })
        .collect();
    if net == NetKind::V {
        let suffix = if variant == Variant::Equivariant {
            "_rotated"
        } else {
            ""
        };
        names.push(format!("o1{suffix}"));
        names.push(format!("o2{suffix}"));
    }
    names
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn raw_inputs_are_the_paper_ones() {
        let mut buf = [0.0; MAX_INPUTS];
        let theta = [0.1, 0.2, 0.3];
        assert_eq!(
            phi_inputs(Variant::Plain, Encoding::Raw, &theta, &mut buf),
            &theta
        );
        assert_eq!(
            phi_inputs(Variant::Equivariant, Encoding::Raw, &theta, &mut buf),
            &theta[1..]
        );
        let x = v_inputs(
            Variant::Plain,
            Encoding::Raw,
            0.3,
            &theta,
            (0.0, 1.0),
            [0.5, 0.6],
            &mut buf,
        );
        assert_eq!(x, &[0.1, 0.2, 0.3, 0.5, 0.6]);
    }

    #[test]
    fn encoded_angles_are_periodic_and_bounded() {
        let tau = std::f64::consts::TAU;
        let mut a = [0.0; MAX_INPUTS];
        let mut b = [0.0; MAX_INPUTS];
        let x = phi_inputs(
            Variant::Equivariant,
            Encoding::Angles,
            &[9.0, 1.0, -2.0],
            &mut a,
        );
        let y = phi_inputs(
            Variant::Equivariant,
            Encoding::Angles,
            &[0.0, 1.0 + 3.0 * tau, -2.0 - tau],
            &mut b,
        );
        assert_eq!(x.len(), 4);
        for (p, q) in x.iter().zip(y) {
            assert!((p - q).abs() < 1e-12 && p.abs() <= 1.0);
        }
        assert_eq!(
            input_names(NetKind::V, Variant::Equivariant, Encoding::Angles, 3),
            [
                "sin theta2",
                "cos theta2",
                "sin theta3",
                "cos theta3",
                "o1_rotated",
                "o2_rotated"
            ]
        );
    }

    #[test]
    fn the_longest_arm_fits_the_buffer() {
        let theta = vec![0.5; MAX_LINKS];
        let mut buf = [0.0; MAX_INPUTS];
        let x = v_inputs(
            Variant::Plain,
            Encoding::Angles,
            0.3,
            &theta,
            (0.0, 1.0),
            [0.5, 0.6],
            &mut buf,
        );
        assert_eq!(x.len(), MAX_INPUTS);
    }
}
