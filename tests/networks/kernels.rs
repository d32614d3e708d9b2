//! The run-time kernels, the damped and handed-over Phi, the trainer's
//! normal equations and Cholesky, networks of another arm.

use super::*;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

/// Matlab's forward pass written out with the C library's `tanh`: the
/// reference the run-time kernel must reproduce.
fn reference_forward(mlp: &Mlp, x: &[f64]) -> Vec<f64> {
    let scale = |m: &MapMinMax, i: usize, v: f64| {
        if m.max[i] > m.min[i] {
            2.0 * (v - m.min[i]) / (m.max[i] - m.min[i]) - 1.0
        } else {
            v - m.min[i]
        }
    };
    let mut a: Vec<f64> = (0..mlp.inputs())
        .map(|i| scale(&mlp.input_map, i, x[i]))
        .collect();
    let last = mlp.layers.len() - 1;
    for (l, layer) in mlp.layers.iter().enumerate() {
        a = layer
            .weights
            .chunks(mlp.sizes[l])
            .zip(&layer.biases)
            .map(|(row, b)| {
                let z = b + row.iter().zip(&a).map(|(w, v)| w * v).sum::<f64>();
                if l < last {
                    z.tanh()
                } else {
                    z
                }
            })
            .collect();
    }
    a.iter()
        .enumerate()
        .map(|(i, y)| {
            let m = &mlp.output_map;
            if m.max[i] > m.min[i] {
                (y + 1.0) * (m.max[i] - m.min[i]) / 2.0 + m.min[i]
            } else {
                y + m.min[i]
            }
        })
        .collect()
}

#[test]
fn the_run_time_kernels_move_the_shipped_networks_outputs_by_less_than_1e_9() {
    // mapminmax folded into the weights, padded blocks, the vectorised
    // tansig (and FMA where the CPU has it) against Matlab's formulas; on
    // x86-64 both the AVX2 + FMA kernels and the portable ones.
    let mut rng = Rng::new(5);
    let mut worst = 0.0f64;
    for (variant, dispatch) in [
        (Variant::Plain, true),
        (Variant::Rows, true),
        (Variant::Equivariant, true),
        (Variant::Equivariant, false),
    ] {
        redundant_ik::nn::kernel::set_runtime_dispatch(dispatch);
        let nets = Networks::embedded_with(variant).unwrap();
        let files = [nets.phi_file(), nets.v_file()];
        for file in files {
            for entry in &file.nets {
                let kernel = Kernel::new(&entry.mlp);
                let (lo, hi) = (&entry.mlp.input_map.min, &entry.mlp.input_map.max);
                let mut y = vec![0.0; kernel.outputs()];
                for _ in 0..2000 {
                    // Inside the trained box and 20% beyond it.
                    let x: Vec<f64> = lo
                        .iter()
                        .zip(hi)
                        .map(|(a, b)| a + (b - a) * rng.range(-0.2, 1.2))
                        .collect();
                    kernel.forward(&x, &mut y);
                    let r = reference_forward(&entry.mlp, &x);
                    for (a, b) in y.iter().zip(&r) {
                        worst = worst.max((a - b).abs() / (1.0 + b.abs()));
                    }
                }
            }
        }
    }
    redundant_ik::nn::kernel::set_runtime_dispatch(true);
    assert!(worst < 1e-9, "largest change {worst:e}");
    assert!(worst > 0.0, "the kernel must be its own computation");
}

#[test]
fn networks_wider_than_the_stack_buffers_run_the_same_kernel_through_the_heap() {
    // The whole-reach networks may be wide (Adam trains 96-96): the kernels
    // take them through a heap buffer (the SIMD build too, which carries no
    // portable kernel), with the same results.
    let mut rng = Rng::new(9);
    for sizes in [vec![4, 96, 96, 6], vec![3, 130, 2], vec![70, 8, 3]] {
        let n_in = sizes[0];
        let n_out = *sizes.last().unwrap();
        let input_map = MapMinMax::fit(&[-1.0, 1.0].repeat(n_in), n_in);
        let output_map = MapMinMax::fit(&[-2.0, 3.0].repeat(n_out), n_out);
        let mlp = Mlp::nguyen_widrow(&sizes, input_map, output_map, &mut rng).unwrap();
        let kernel = Kernel::new(&mlp);
        let mut y = vec![0.0; n_out];
        for _ in 0..200 {
            let x: Vec<f64> = (0..n_in).map(|_| rng.range(-1.2, 1.2)).collect();
            kernel.forward(&x, &mut y);
            for (a, b) in y.iter().zip(&reference_forward(&mlp, &x)) {
                assert!(
                    (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
                    "{sizes:?}: {a} vs {b}"
                );
            }
        }
    }
}

#[test]
fn tansig_is_within_5e_16_of_tanh() {
    let mut worst = 0.0f64;
    let n = 400_000;
    for i in 0..=n {
        for x in [
            -25.0 + 50.0 * i as f64 / n as f64,
            (i as f64 / n as f64 - 0.5) * 1e-3,
        ] {
            worst = worst.max((tansig(x) - x.tanh()).abs());
        }
    }
    assert!(worst < 5e-16, "{worst:e}");
    assert_eq!(tansig(0.0), 0.0);
    assert_eq!(tansig(1e300), 1.0);
    assert_eq!(tansig(f64::NEG_INFINITY), -1.0);
    assert!(tansig(f64::NAN).is_nan());
    assert!(tansig(-1e-300) <= 0.0);
}

/// The exact `Phi` dressed as a network: Case 1 with it must be the
/// numerical route.
struct ExactPhi(Networks);

impl Surrogate for ExactPhi {
    fn check(&self, arm: &Arm) -> redundant_ik::Result<()> {
        Surrogate::check(&self.0, arm)
    }
    fn phi(&self, pose: &Pose, out: &mut [f64]) -> redundant_ik::Result<()> {
        ik::phi_into(pose.jacobian(), 0.0, out)
    }
    fn area_gradient(&self, pose: &Pose, o: [f64; 2], out: &mut [f64]) -> redundant_ik::Result<()> {
        self.0.area_gradient(pose, o, out)
    }
    fn phi_in_range(&self, _: &Pose) -> bool {
        true
    }
    fn v_in_range(&self, _: &Pose, _: [f64; 2]) -> bool {
        true
    }
}

#[test]
fn a_constant_delta_damps_the_network_phi_instead_of_replacing_it() {
    let exact: Arc<dyn Surrogate> = Arc::new(ExactPhi(Networks::embedded().unwrap()));
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    let mut scene = Scene::task1();
    scene.set_param(&methods::DELTA, 0.001).unwrap();
    let numerical = Planner::run(scene.clone(), Method::NUMERICAL, None).unwrap();
    // With an exact Phi, Case 1 with delta is the damped numerical route ...
    let case1_exact = Planner::run(scene.clone(), Method::CASE1, Some(exact)).unwrap();
    for (a, b) in numerical.steps.iter().zip(&case1_exact.steps) {
        for (x, y) in a.theta.iter().zip(&b.theta) {
            assert!((x - y).abs() < 1e-10);
        }
    }
    // ... and with the trained network it is the network's route, damped:
    // not the numerical route's numbers (the old silent swap), and within
    // the network's accuracy of them.
    let case1 = Planner::run(scene.clone(), Method::CASE1, Some(nets.clone())).unwrap();
    let (s, n) = (&case1.summary, &numerical.summary);
    assert_ne!(s.final_error, n.final_error);
    // Damping trades tracking for bounded rates: about 7 mm here on both.
    assert!(
        (s.final_error - n.final_error).abs() < 1e-3,
        "{s:?} vs {n:?}"
    );
    assert!(!s.collided);
    assert_eq!(s.handover_steps, 0, "a constant delta is no hand-over");
    // delta = 0 gives the undamped network route.
    scene.set_param(&methods::DELTA, 0.0).unwrap();
    let undamped = Planner::run(scene, Method::CASE1, Some(nets)).unwrap();
    assert_ne!(undamped.summary.final_error, s.final_error);
}

#[test]
fn near_a_singular_pose_the_damping_schedule_hands_phi_over_and_says_so() {
    // An out-of-reach target stretches the arm; the schedule switches on
    // automatically and, in Cases 1 and 3, the exact damped Phi stands in.
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    let mut scene = Scene::task1();
    scene.target = [2.5, 0.8];
    for &method in methods::ALL {
        let run = Planner::run(scene.clone(), method, Some(nets.clone())).unwrap();
        let s = &run.summary;
        assert!(s.auto_damping, "{method}");
        let flagged = run.steps.iter().filter(|x| x.phi_handover).count();
        assert_eq!(flagged, s.handover_steps, "{method}");
        if method == Method::CASE1 {
            // Phi by the network, v exact: the arm stretches and the exact
            // damped Phi takes over.
            assert!(s.handover_steps > 10, "{}", s.handover_steps);
        } else if !method.networks().phi {
            // No Phi network, nothing to hand over. (Case 3's v network, far
            // outside its trained range here, folds the arm instead: it
            // never comes near the singular pose.)
            assert_eq!(s.handover_steps, 0, "{method}");
        }
    }
    // In the paper's scenes the networks work alone.
    for method in methods::ALL.iter().copied().filter(|m| m.networks().phi) {
        let run = Planner::run(Scene::task2(), method, Some(nets.clone())).unwrap();
        assert_eq!(run.summary.handover_steps, 0);
    }
}

#[test]
fn normal_equations_from_the_layer_structure_equal_those_from_the_jacobian_rows() {
    // J^T J = sum_s D^s (x) (a~ a~'^T) per layer pair (nn::kronecker) must be
    // the sum over J's rows of g g^T, and J^T e the sum of e g.
    let mut rng = Rng::new(9);
    for sizes in [vec![3, 5, 4, 2], vec![2, 7, 3], vec![4, 6, 5, 3, 2]] {
        let (n_in, n_out) = (sizes[0], *sizes.last().unwrap());
        let mlp = Mlp::nguyen_widrow(
            &sizes,
            MapMinMax::fit(&[-1.0, 1.0].repeat(n_in), n_in),
            MapMinMax::fit(&[-1.0, 1.0].repeat(n_out), n_out),
            &mut rng,
        )
        .unwrap();
        let samples = 37;
        let x: Vec<f64> = (0..samples * n_in).map(|_| rng.range(-1.0, 1.0)).collect();
        let t: Vec<f64> = (0..samples * n_out).map(|_| rng.range(-1.0, 1.0)).collect();
        let idx: Vec<usize> = (0..samples).collect();
        let mut acts = Activations::new(&sizes);
        // Blocks of 5 samples, so partial last blocks are exercised.
        let mut normal = redundant_ik::nn::kronecker::Normal::new(&sizes, 5);
        let (jtj, jte) = normal.accumulate(&mlp, &x, &t, &idx, &mut acts);
        let p = mlp.n_params();
        let (mut ref_jtj, mut ref_jte) = (vec![0.0; p * p], vec![0.0; p]);
        let mut jac = vec![0.0; n_out * p];
        for s in 0..samples {
            mlp.forward_scaled(&x[s * n_in..(s + 1) * n_in], &mut acts);
            let y = acts.output().to_vec();
            mlp.output_jacobian(&mut acts, &mut jac);
            for m in 0..n_out {
                let g = &jac[m * p..(m + 1) * p];
                let e = t[s * n_out + m] - y[m];
                for a in 0..p {
                    ref_jte[a] += e * g[a];
                    for b in 0..p {
                        ref_jtj[a * p + b] += g[a] * g[b];
                    }
                }
            }
        }
        let scale = ref_jtj.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for a in 0..p {
            assert!(
                (jte[a] - ref_jte[a]).abs() < 1e-12 * scale,
                "{sizes:?} J^T e [{a}]"
            );
            for b in 0..p {
                let (got, want) = (jtj[(a, b)], ref_jtj[a * p + b]);
                assert!(
                    (got - want).abs() < 1e-12 * scale,
                    "{sizes:?} J^T J [{a}, {b}]: {got} vs {want}"
                );
            }
        }
    }
}

#[test]
fn the_blocked_cholesky_solves_like_nalgebras_and_refuses_what_is_not_positive_definite() {
    use redundant_ik::nalgebra::DMatrix;
    use redundant_ik::nn::cholesky;
    let mut rng = Rng::new(3);
    // Sizes around the block width (64), and the trainer's 699.
    for n in [1, 2, 63, 64, 65, 130, 200, 699] {
        let m = DMatrix::from_fn(n, n / 2 + 1, |_, _| rng.range(-1.0, 1.0));
        let a = &m * m.transpose() + DMatrix::identity(n, n) * 1e-3;
        let b = DVector::from_fn(n, |_, _| rng.range(-1.0, 1.0));
        let x = cholesky::solve_spd(a.clone(), &b).unwrap();
        let reference = a.clone().cholesky().unwrap().solve(&b);
        let rel = (&x - &reference).norm() / reference.norm();
        assert!(rel < 1e-8, "n = {n}: {rel:e}");
        assert!(
            (&a * &x - &b).norm() < 1e-8 * b.norm() * a.norm(),
            "n = {n}"
        );
    }
    let mut indefinite = DMatrix::identity(70, 70);
    indefinite[(66, 66)] = -1.0;
    assert!(cholesky::solve_spd(indefinite, &DVector::zeros(70)).is_none());
    let mut nan = DMatrix::identity(3, 3);
    nan[(2, 2)] = f64::NAN;
    assert!(cholesky::solve_spd(nan, &DVector::zeros(3)).is_none());
}

#[test]
fn the_planner_refuses_networks_trained_for_another_arm() {
    let nets: Arc<dyn Surrogate> = Arc::new(Networks::embedded().unwrap());
    assert!(nets.check(&Arm::paper()).is_ok());
    for arm in [
        Arm::new(0.5, vec![0.6, 0.85, 0.7]).unwrap(),
        Arm::new(0.4, vec![0.6, 0.85, 0.6]).unwrap(),
        Arm::new(0.5, vec![0.6, 0.85, 0.6, 0.4]).unwrap(),
    ] {
        let mut scene = Scene::task1();
        scene.theta0 = vec![0.2; arm.dof()];
        scene.arm = arm.clone();
        // In any method: networks for another arm are never installed.
        for method in [Method::NUMERICAL, Method::CASE3] {
            let err = Planner::new(scene.clone(), method, Some(nets.clone())).unwrap_err();
            assert!(
                matches!(&err, Error::NetworksForAnotherArm { trained, arm: mine }
                    if trained.1 == [0.6, 0.85, 0.6] && mine.1 == arm.links()),
                "{err:?}"
            );
        }
        let mut p = Planner::new(scene, Method::NUMERICAL, None).unwrap();
        assert!(matches!(
            p.set_networks(Some(nets.clone())),
            Err(Error::NetworksForAnotherArm { .. })
        ));
        assert!(p.networks().is_none(), "a refused change changes nothing");
    }
}
