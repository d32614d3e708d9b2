//! Weights files: exact round trips, refusals with a reason, bad input,
//! rotation equivariance and the trained range.

use super::*;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

#[test]
fn shipped_weights_round_trip_exactly() {
    for json in [
        networks::PHI_PLAIN_JSON,
        networks::PHI_ROWS_JSON,
        networks::PHI_EQUIVARIANT_JSON,
        networks::V_PLAIN_JSON,
    ] {
        let file = <WeightsFile>::from_json(json).unwrap();
        let text = file.to_json().unwrap();
        // The shipped text is exactly what the writer produces (`train` adds a newline).
        assert_eq!(text.trim_end(), json.trim_end());
        let again = <WeightsFile>::from_json(&text).unwrap();
        assert_eq!(file, again);
        // Bit-for-bit, not just approximately.
        for (a, b) in file.nets.iter().zip(&again.nets) {
            for (x, y) in a.mlp.params().iter().zip(b.mlp.params()) {
                assert_eq!(x.to_bits(), y.to_bits());
            }
        }
    }
}

#[test]
fn weights_files_that_name_their_sampling_methods_modes_still_load() {
    // Files written before "method" was the word listed `sampling.modes`.
    let json = networks::V_PLAIN_JSON;
    assert!(json.contains("\"methods\": [") && !json.contains("\"modes\""));
    let old = json.replacen("\"methods\": [", "\"modes\": [", 1);
    let (new, old) = (
        <WeightsFile>::from_json(json).unwrap(),
        <WeightsFile>::from_json(&old).unwrap(),
    );
    assert_eq!(old, new);
    assert_eq!(old.to_json().unwrap().trim_end(), json.trim_end());
}

#[test]
fn bad_weights_files_are_rejected_with_a_clear_error() {
    let v = embedded_v();
    // Wrong shape: a weight missing.
    let mut f = embedded_phi();
    f.nets[0].mlp.layers[1].weights.pop();
    assert!(rejected(&f, &v).contains("weights"), "{}", rejected(&f, &v));
    // Wrong bias count.
    let mut f = embedded_phi();
    f.nets[0].mlp.layers[0].biases.push(0.0);
    assert!(rejected(&f, &v).contains("biases"));
    // Not finite (NaN cannot be written in JSON; it is caught by validation).
    let mut f = embedded_phi();
    f.nets[0].mlp.layers[0].weights[3] = f64::NAN;
    assert!(matches!(Networks::new(f, v.clone()), Err(Error::Weights(m)) if m.contains("finite")));
    // Wrong input count for the variant: a plain Phi net over 2 inputs.
    let eq = <WeightsFile>::from_json(networks::PHI_EQUIVARIANT_JSON).unwrap();
    let mut f = eq.clone();
    f.variant = Variant::Plain;
    assert!(rejected(&f, &v).contains("inputs"));
    // The files swapped.
    let p = serde_json::to_string(&embedded_phi()).unwrap();
    let q = serde_json::to_string(&v).unwrap();
    assert!(matches!(
        Networks::from_json(&q, &p),
        Err(Error::Weights(_))
    ));
    // Truncated, empty, not JSON, unknown format or variant.
    let half = &networks::PHI_PLAIN_JSON[..networks::PHI_PLAIN_JSON.len() / 2];
    for bad in [half, "", "hello", "{}", "[1, 2]"] {
        assert!(matches!(
            Networks::from_json(bad, &q),
            Err(Error::Weights(_))
        ));
    }
    let other_format = networks::V_PLAIN_JSON.replacen("redundant-ik-weights/1", "x/9", 1);
    assert!(
        matches!(Networks::from_json(&p, &other_format), Err(Error::Weights(m)) if m.contains("format"))
    );
    let other_variant = networks::V_PLAIN_JSON.replacen("\"plain\"", "\"sideways\"", 1);
    assert!(matches!(
        Networks::from_json(&p, &other_variant),
        Err(Error::Weights(_))
    ));
    // Out-of-range numbers in the JSON text.
    let huge = networks::V_PLAIN_JSON.replacen("\"post\": 0.5", "\"post\": 1e999", 1);
    assert!(matches!(
        Networks::from_json(&p, &huge),
        Err(Error::Weights(_))
    ));
}

#[test]
fn networks_reject_bad_input_without_panicking() {
    let nets = Networks::embedded().unwrap();
    let (mut phi, mut g) = ([0.0; 6], [0.0; 3]);
    // The slice API checks theta and the obstacle point.
    assert!(nets.phi_into(&[0.1, 0.2], &mut phi).is_err());
    assert!(nets
        .area_gradient_into(&[0.1, 0.2], [0.5, 0.5], &mut g)
        .is_err());
    let nan = [0.1, f64::NAN, 0.2];
    assert!(nets.phi_into(&nan, &mut phi).is_err());
    assert!(!nets.phi_in_range_slice(&nan));
    let ok = [0.3, 2.0, -0.5];
    assert!(nets
        .area_gradient_into(&ok, [f64::INFINITY, 0.5], &mut g)
        .is_err());
    assert!(!nets.v_in_range_slice(&ok, [f64::INFINITY, 0.5]));
    assert!(nets.phi_into(&ok, &mut phi[..4]).is_err());
    // The planner's interface takes a pose: one of another arm, or a wrong
    // output buffer, is an error too.
    let two_links = Arm::new(0.5, vec![1.0, 1.0]).unwrap();
    let alien = Pose::new(&two_links, &[0.1, 0.2]).unwrap();
    assert!(Surrogate::phi(&nets, &alien, &mut phi[..4]).is_err());
    assert!(Surrogate::area_gradient(&nets, &alien, [0.5, 0.5], &mut g[..2]).is_err());
    assert!(!Surrogate::phi_in_range(&nets, &alien));
    let pose = Pose::new(&Arm::paper(), &ok).unwrap();
    assert!(Surrogate::phi(&nets, &pose, &mut phi[..5]).is_err());
    assert!(Surrogate::area_gradient(&nets, &pose, [0.5, 0.5], &mut g).is_ok());
    assert!(!Surrogate::v_in_range(&nets, &pose, [f64::NAN, 0.5]));
}

#[test]
fn phi_is_rotation_equivariant_which_the_equivariant_variant_uses() {
    // J(theta) = R(theta_1) J(0, theta_2, theta_3), so Phi(theta) = Phi(0, ..) R(theta_1)^T.
    let arm = Arm::paper();
    let th = DVector::from_vec(vec![0.7, 1.9, -0.8]);
    let mut th0 = th.clone();
    th0[0] = 0.0;
    let p = ik::phi(&arm.jacobian(&th), 0.0).unwrap();
    let p0 = ik::phi(&arm.jacobian(&th0), 0.0).unwrap();
    let (s, c) = th[0].sin_cos();
    let rt = redundant_ik::nalgebra::Matrix2::new(c, -s, s, c);
    assert!((p - p0 * rt).amax() < 1e-12);
}

#[test]
fn trained_range_is_reported_and_leaving_it_is_flagged() {
    let nets = Networks::embedded().unwrap();
    let r = nets.trained_range();
    let json = serde_json::to_string(&r).unwrap();
    assert!(json.contains("obstacle_min"));
    assert_eq!(r.obstacle_min, [0.3, 0.3]);
    // The tasks' start poses are inside; a stretched arm (singular) is not.
    let start = Scene::task1().theta0;
    assert!(nets.phi_in_range_slice(&start));
    assert!(nets.v_in_range_slice(&start, [0.5, 0.5]));
    assert!(!nets.phi_in_range_slice(&[0.3, 0.0, 0.0]));
    assert!(!nets.v_in_range_slice(&start, [1.5, -0.4]));
}
