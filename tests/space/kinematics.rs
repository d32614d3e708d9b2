//! The spatial kinematics as a specification: Jacobians against finite
//! differences, the planar arm as a chain whose axes are parallel, the
//! capsule distances and the generalised criterion.

use redundant_ik::nn::Rng;
use redundant_ik::space::criterion::{area_gradient_add, triangle_areas};
use redundant_ik::space::*;
use redundant_ik::{Arm, Pose};

use super::planar_as_chain;

fn panda() -> Chain {
    SpacePreset::by_key("panda").unwrap().chain()
}

/// A pose within the chain's limits (or within +-pi), from `rng`.
fn random_theta(chain: &Chain, rng: &mut Rng) -> Vec<f64> {
    (0..chain.dof())
        .map(|i| {
            let [lo, hi] = chain.joint_limits().map_or([-3.0, 3.0], |l| l.ranges()[i]);
            lo + (hi - lo) * rng.uniform()
        })
        .collect()
}

/// Central differences of `f` (a vector function of theta) at `theta`,
/// column-major `m x n`.
fn numeric_jacobian(theta: &[f64], m: usize, f: impl Fn(&[f64]) -> Vec<f64>) -> Vec<f64> {
    let h = 1e-6;
    let mut out = vec![0.0; m * theta.len()];
    for i in 0..theta.len() {
        let (mut up, mut down) = (theta.to_vec(), theta.to_vec());
        up[i] += h;
        down[i] -= h;
        let (a, b) = (f(&up), f(&down));
        for r in 0..m {
            out[m * i + r] = (a[r] - b[r]) / (2.0 * h);
        }
    }
    out
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn the_hand_jacobian_is_the_derivative_of_the_hand() {
    let chain = panda();
    let mut rng = Rng::new(7);
    for _ in 0..20 {
        let theta = random_theta(&chain, &mut rng);
        let pose = SpacePose::new(&chain, &theta).unwrap();
        let numeric = numeric_jacobian(&theta, 3, |t| {
            SpacePose::new(&chain, t).unwrap().hand().to_vec()
        });
        let d = largest_difference(pose.jacobian(), &numeric);
        assert!(d < 1e-8, "J against central differences: {d:e}");
    }
}

#[test]
fn a_point_jacobian_is_the_derivative_of_a_point_carried_by_its_segment() {
    let chain = panda();
    let mut rng = Rng::new(11);
    let theta = random_theta(&chain, &mut rng);
    let pose = SpacePose::new(&chain, &theta).unwrap();
    for s in chain.segments() {
        // The point 30% along the segment, carried rigidly by it.
        let at = |t: &[f64]| {
            let p = SpacePose::new(&chain, t).unwrap();
            let (a, b) = p.segment(s);
            (0..3)
                .map(|k| a[k] + 0.3 * (b[k] - a[k]))
                .collect::<Vec<_>>()
        };
        let p = at(&theta);
        let mut jp = vec![0.0; 3 * chain.dof()];
        pose.point_jacobian_into([p[0], p[1], p[2]], s.moved_by, &mut jp);
        let d = largest_difference(&jp, &numeric_jacobian(&theta, 3, at));
        assert!(d < 1e-8, "segment {s:?}: {d:e}");
        let rates: Vec<f64> = (0..chain.dof()).map(|i| 0.1 * i as f64 - 0.2).collect();
        let v = pose.point_velocity([p[0], p[1], p[2]], s.moved_by, &rates);
        for r in 0..3 {
            let want: f64 = (0..chain.dof()).map(|i| jp[3 * i + r] * rates[i]).sum();
            assert!((v[r] - want).abs() < 1e-14);
        }
    }
}

#[test]
fn a_chain_whose_axes_are_parallel_is_the_planar_arm() {
    let mut rng = Rng::new(3);
    for arm in [
        Arm::paper(),
        Arm::new(0.5, vec![0.6, 0.85, 0.6, 0.4]).unwrap(),
    ] {
        let chain = planar_as_chain(&arm);
        for _ in 0..10 {
            let theta: Vec<f64> = (0..arm.dof()).map(|_| rng.uniform() * 6.0 - 3.0).collect();
            let (plane, space) = (
                Pose::new(&arm, &theta).unwrap(),
                SpacePose::new(&chain, &theta).unwrap(),
            );
            // The hand and the Jacobian: planar (x, y) is (x, z), nothing along y.
            let hand = space.hand();
            let want = plane.end_effector();
            assert!(
                (hand[0] - want[0]).abs() < 1e-12
                    && hand[1].abs() < 1e-12
                    && (hand[2] - want[1]).abs() < 1e-12
            );
            for i in 0..arm.dof() {
                let (j2, j3) = (
                    &plane.jacobian()[2 * i..2 * i + 2],
                    &space.jacobian()[3 * i..3 * i + 3],
                );
                assert!(
                    (j3[0] - j2[0]).abs() < 1e-12
                        && j3[1].abs() < 1e-12
                        && (j3[2] - j2[1]).abs() < 1e-12
                );
            }
            // The criterion and its gradient: V_k = |D_k|, dV = sign(D) dD.
            let o = [rng.uniform() * 2.0 - 0.5, rng.uniform() * 2.0];
            let planar_d = redundant_ik::obstacle::triangle_determinants(
                &arm.joints(&redundant_ik::nalgebra::DVector::from_vec(theta.clone())),
                &redundant_ik::nalgebra::Vector2::new(o[0], o[1]),
            );
            let areas: Vec<f64> = triangle_areas(&chain, &space, [o[0], 0.0, o[1]]).collect();
            assert_eq!(areas.len(), arm.dof());
            for (v, d) in areas.iter().zip(&planar_d) {
                assert!(
                    (v - d.abs()).abs() < 1e-12,
                    "V_k {v} against |D_k| {}",
                    d.abs()
                );
            }
            for eps in [0.0, 0.05] {
                let mut planar = vec![0.0; arm.dof()];
                redundant_ik::obstacle::area_gradient_into(&arm, &plane, o, eps, &mut planar);
                let mut spatial = vec![0.0; arm.dof()];
                area_gradient_add(&chain, &space, [o[0], 0.0, o[1]], eps, &mut spatial);
                let d = largest_difference(&planar, &spatial);
                assert!(d < 1e-12, "eps {eps}: the gradients differ by {d:e}");
            }
        }
    }
}

#[test]
fn the_criterions_gradient_is_the_derivative_of_the_summed_areas() {
    let chain = panda();
    let mut rng = Rng::new(5);
    for _ in 0..10 {
        let theta = random_theta(&chain, &mut rng);
        let o = [rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform()];
        let eps = 0.01;
        let total = |t: &[f64]| {
            let p = SpacePose::new(&chain, t).unwrap();
            vec![triangle_areas(&chain, &p, o)
                .map(|v| (v * v + eps * eps).sqrt())
                .sum::<f64>()]
        };
        let pose = SpacePose::new(&chain, &theta).unwrap();
        let mut g = vec![0.0; 7];
        area_gradient_add(&chain, &pose, o, eps, &mut g);
        let d = largest_difference(&g, &numeric_jacobian(&theta, 1, total));
        assert!(d < 1e-7, "dV/dtheta against central differences: {d:e}");
    }
}

#[test]
fn the_capsule_distance_and_its_gradient() {
    let chain = panda();
    let mut rng = Rng::new(9);
    let sphere = Sphere::new([0.4, 0.1, 0.5], 0.05);
    for _ in 0..10 {
        let theta = random_theta(&chain, &mut rng);
        let pose = SpacePose::new(&chain, &theta).unwrap();
        for k in (0..chain.segments().len()).filter(|&k| chain.segments()[k].moved_by > 0) {
            let pair = CapsulePair::at(&chain, &pose, k, 0, &sphere);
            // The distance: the centre to the segment, less both radii.
            let (a, b) = pose.segment(&chain.segments()[k]);
            let brute = (0..=2000)
                .map(|s| {
                    let t = s as f64 / 2000.0;
                    let q: Vec<f64> = (0..3).map(|r| a[r] + t * (b[r] - a[r])).collect();
                    ((q[0] - 0.4).powi(2) + (q[1] - 0.1).powi(2) + (q[2] - 0.5).powi(2)).sqrt()
                })
                .fold(f64::INFINITY, f64::min);
            assert!((pair.distance - (brute - 0.06 - 0.05)).abs() < 1e-6);
            let f = |t: &[f64]| {
                vec![
                    CapsulePair::at(&chain, &SpacePose::new(&chain, t).unwrap(), k, 0, &sphere)
                        .distance,
                ]
            };
            let mut g = vec![0.0; 7];
            pair.gradient_into(&pose, &mut g);
            let d = largest_difference(&g, &numeric_jacobian(&theta, 1, f));
            assert!(
                d < 1e-6,
                "segment {k}: the gradient against central differences: {d:e}"
            );
        }
    }
}

#[test]
fn a_sphere_on_the_fixed_base_is_refused_one_beside_it_is_not() {
    let chain = panda();
    let on = Sphere::new([0.05, 0.0, 0.2], 0.05);
    assert!(matches!(
        on.validate(&chain),
        Err(redundant_ik::Error::SphereOnBase { .. })
    ));
    assert!(Sphere::new([0.5, 0.0, 0.2], 0.05).validate(&chain).is_ok());
    assert!(Sphere::new([f64::NAN, 0.0, 0.2], 0.05)
        .validate(&chain)
        .is_err());
    assert!(Sphere::new([0.5, 0.0, 0.2], 0.0).validate(&chain).is_err());
}

#[test]
fn spheres_read_as_people_write_them_and_a_disc_is_refused() {
    let p: SpherePlacement = "0.4,0.1,0.5".parse().unwrap();
    assert_eq!(p.ball(0.07), Sphere::new([0.4, 0.1, 0.5], 0.07));
    let p: SpherePlacement = "0.4, 0.1, 0.5, 0.1".parse().unwrap();
    assert_eq!(p.radius, Some(0.1));
    let e = "0.4,0.1"
        .parse::<SpherePlacement>()
        .unwrap_err()
        .to_string();
    assert!(e.contains("planar arm"), "{e}");
    assert!("0.4,x,0.5".parse::<SpherePlacement>().is_err());
}

#[test]
fn every_preset_passes_the_chains_checks_and_starts_within_its_limits() {
    for p in PRESETS {
        let c = p.chain();
        c.joint_limits()
            .unwrap()
            .check("the start", p.task.theta0)
            .unwrap();
        let [x, y, z, r] = p.task.sphere;
        Sphere::new([x, y, z], r).validate(&c).unwrap();
    }
}

/// The reference poses Robotics Toolbox for Python computed
/// (scripts/space-reference.py: `models.DH.Panda`, and Drake's iiwa14 URDF
/// as an ETS robot): every frame's origin, the flange, each joint's axis
/// and the hand's Jacobian agree to 1e-9 (they do to about 1e-15).
#[test]
fn the_presets_agree_with_robotics_toolbox() {
    use serde_json::Value as Json;
    for key in ["panda", "iiwa14"] {
        let text = std::fs::read_to_string(format!(
            "{}/tests/data/space/{key}.json",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap();
        let data: Json = serde_json::from_str(&text).unwrap();
        let preset = SpacePreset::by_key(key).unwrap();
        let chain = preset.chain();
        let numbers = |v: &Json| -> Vec<f64> {
            v.as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        let mdh = data.get("mdh").unwrap();
        for (i, row) in chain.rows().iter().enumerate() {
            assert_eq!(
                row.a,
                numbers(mdh.get("a").unwrap())[i],
                "{key} a of joint {}",
                i + 1
            );
            assert!((row.alpha - numbers(mdh.get("alpha").unwrap())[i]).abs() < 1e-15);
            assert_eq!(row.d, numbers(mdh.get("d").unwrap())[i]);
        }
        assert_eq!(
            chain.flange()[2],
            mdh.get("flange").unwrap().as_f64().unwrap()
        );
        let limits: Vec<Vec<f64>> = data
            .get("limits")
            .unwrap()
            .as_array()
            .unwrap()
            .iter()
            .map(numbers)
            .collect();
        for (l, r) in limits.iter().zip(chain.joint_limits().unwrap().ranges()) {
            assert!(
                (l[0] - r[0]).abs() < 1e-9 && (l[1] - r[1]).abs() < 1e-9,
                "{key} limits {l:?} {r:?}"
            );
        }
        let rates = numbers(data.get("rate_limits").unwrap());
        assert_eq!(rates, chain.rate_limits().unwrap().rates());
        assert_eq!(numbers(data.get("ready").unwrap()), preset.task.theta0);
        let mut worst: f64 = 0.0;
        for p in data.get("poses").unwrap().as_array().unwrap() {
            let q = numbers(p.get("q").unwrap());
            let pose = SpacePose::new(&chain, &q).unwrap();
            for (k, o) in p
                .get("origins")
                .unwrap()
                .as_array()
                .unwrap()
                .iter()
                .enumerate()
            {
                worst = worst.max(largest_difference(&numbers(o), &pose.points()[k + 1]));
            }
            for (i, z) in p
                .get("z_axes")
                .unwrap()
                .as_array()
                .unwrap()
                .iter()
                .enumerate()
            {
                worst = worst.max(largest_difference(&numbers(z), &pose.axis(i)));
            }
            let rows: Vec<Vec<f64>> = p
                .get("jacobian")
                .unwrap()
                .as_array()
                .unwrap()
                .iter()
                .map(numbers)
                .collect();
            for (r, row) in rows.iter().enumerate() {
                for (i, want) in row.iter().enumerate() {
                    worst = worst.max((want - pose.jacobian()[3 * i + r]).abs());
                }
            }
        }
        assert!(worst < 1e-9, "{key}: {worst:e} from Robotics Toolbox");
    }
}

/// The velocity ellipsoid's axes and half-lengths rebuild `J J^T`
/// (`sum sigma_i^2 a_i a_i^T`), in a right-handed orthonormal frame, the
/// longest first; its volume is the manipulability's; a chain whose axes
/// are parallel has a flat one.
#[test]
fn the_velocity_ellipsoid_rebuilds_j_j_transpose() {
    use redundant_ik::space::manipulability::{manipulability, velocity_ellipsoid};
    for key in ["panda", "iiwa14"] {
        let scene = redundant_ik::scene::SpaceScene::by_key(key).unwrap();
        for shift in [0.0, 0.3, -0.7] {
            let theta: Vec<f64> = scene.theta0.iter().map(|t| t + shift).collect();
            let pose = SpacePose::new(&scene.arm, &theta).unwrap();
            let a = pose.jjt();
            let (axes, half) = velocity_ellipsoid(a);
            assert!(half[0] >= half[1] && half[1] >= half[2]);
            for r in 0..3 {
                for c in 0..3 {
                    let back: f64 = (0..3)
                        .map(|k| half[k] * half[k] * axes[k][r] * axes[k][c])
                        .sum();
                    assert!(
                        (back - a[r][c]).abs() < 1e-12,
                        "{key}: {back} vs {}",
                        a[r][c]
                    );
                    let d: f64 = (0..3).map(|k| axes[r][k] * axes[c][k]).sum();
                    assert!((d - f64::from(u8::from(r == c))).abs() < 1e-12);
                }
            }
            let w = manipulability(&pose);
            assert!((half[0] * half[1] * half[2] - w).abs() < 1e-12 * (1.0 + w));
        }
    }
    // Flat: rank 2, the third half-length 0, the axes still a frame.
    let (axes, half) = velocity_ellipsoid([[2.0, 0.5, 0.0], [0.5, 1.0, 0.0], [0.0, 0.0, 0.0]]);
    assert_eq!(half[2], 0.0);
    assert!(
        (axes[2][2].abs() - 1.0).abs() < 1e-12,
        "the flat axis is z: {axes:?}"
    );
    // Round: every axis of the sphere will do.
    let (axes, half) = velocity_ellipsoid([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    assert_eq!(half, [1.0; 3]);
    let det = axes[0][0] * (axes[1][1] * axes[2][2] - axes[1][2] * axes[2][1])
        - axes[0][1] * (axes[1][0] * axes[2][2] - axes[1][2] * axes[2][0])
        + axes[0][2] * (axes[1][0] * axes[2][1] - axes[1][1] * axes[2][0]);
    assert!((det - 1.0).abs() < 1e-12);
}
