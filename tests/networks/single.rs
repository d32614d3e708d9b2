//! The single-precision kernels (`Precision::F32`, what the page can run):
//! the same bits on every target as a plain `f32` loop, close to the `f64`
//! reference, and the paper's Case 3 run barely moved by them.

use super::*;
use redundant_ik::nn::activation::tansig32;
use redundant_ik::nn::Precision;
#[cfg(target_family = "wasm")]
use wasm_bindgen_test::wasm_bindgen_test as test;

/// `mapminmax` as the kernel folds it, `scaled = g x + c`.
fn affine(m: &MapMinMax, i: usize) -> (f64, f64) {
    let (lo, hi) = (m.min[i], m.max[i]);
    if hi > lo {
        let g = 2.0 / (hi - lo);
        (g, -g * lo - 1.0)
    } else {
        (1.0, -lo)
    }
}

/// The `f32` forward pass written plainly: the maps folded into the first
/// and last layers in `f64` (as `Kernel::new` documents), every weight
/// rounded to `f32`, each neuron's sum from its bias over the inputs in
/// order, `tansig32` between layers.
fn plain_f32_forward(mlp: &Mlp, x: &[f64]) -> Vec<f64> {
    let last = mlp.layers.len() - 1;
    let mut a: Vec<f32> = x.iter().take(mlp.inputs()).map(|&v| v as f32).collect();
    for (l, layer) in mlp.layers.iter().enumerate() {
        let (r, s) = (mlp.sizes[l], mlp.sizes[l + 1]);
        let (mut w, mut b) = (layer.weights.clone(), layer.biases.clone());
        if l == 0 {
            for o in 0..s {
                for j in 0..r {
                    let (g, c) = affine(&mlp.input_map, j);
                    b[o] += w[o * r + j] * c;
                    w[o * r + j] *= g;
                }
            }
        }
        if l == last {
            for o in 0..s {
                let (g, c) = affine(&mlp.output_map, o);
                for j in 0..r {
                    w[o * r + j] /= g;
                }
                b[o] = (b[o] - c) / g;
            }
        }
        a = (0..s)
            .map(|o| {
                let mut z = b[o] as f32;
                for (j, aj) in a.iter().enumerate() {
                    z += aj * (w[o * r + j] as f32);
                }
                if l < last {
                    tansig32(z)
                } else {
                    z
                }
            })
            .collect();
    }
    a.into_iter().map(f64::from).collect()
}

/// Networks of several shapes: the shipped sets' and random ones wider
/// than the stack buffers, with input counts that leave 1, 2 and 3 over
/// a multiple of four.
fn networks_to_check() -> Vec<Mlp> {
    let mut mlps: Vec<Mlp> = Vec::new();
    for set in [networks::NetworkSet::Paper, networks::NetworkSet::Reach] {
        let nets = networks::builtin_set(set).unwrap();
        for file in [nets.phi_file(), nets.v_file()] {
            mlps.extend(file.nets.iter().map(|e| e.mlp.clone()));
        }
    }
    let mut rng = Rng::new(31);
    for sizes in [
        vec![5, 96, 96, 6],
        vec![3, 130, 2],
        vec![70, 8, 3],
        vec![6, 12, 7],
    ] {
        let (n_in, n_out) = (sizes[0], *sizes.last().unwrap());
        let input_map = MapMinMax::fit(&[-1.0, 1.0].repeat(n_in), n_in);
        let output_map = MapMinMax::fit(&[-2.0, 3.0].repeat(n_out), n_out);
        mlps.push(Mlp::nguyen_widrow(&sizes, input_map, output_map, &mut rng).unwrap());
    }
    mlps
}

#[test]
fn the_f32_kernel_gives_the_bits_of_a_plain_f32_loop_on_every_target() {
    // Natively the portable pass, in the page's SIMD build the f32x4 one:
    // both must equal the plain loop bit for bit, so that a run the page
    // makes in f32 replays exactly on the command line.
    let mut rng = Rng::new(7);
    for mlp in networks_to_check() {
        let kernel = Kernel::with_precision(&mlp, Precision::F32);
        assert_eq!(kernel.precision(), Precision::F32);
        let (lo, hi) = (&mlp.input_map.min, &mlp.input_map.max);
        let mut y = vec![0.0; kernel.outputs()];
        for _ in 0..300 {
            let x: Vec<f64> = lo
                .iter()
                .zip(hi)
                .map(|(a, b)| a + (b - a) * rng.range(-0.2, 1.2))
                .collect();
            kernel.forward(&x, &mut y);
            let want = plain_f32_forward(&mlp, &x);
            for (k, (a, b)) in y.iter().zip(&want).enumerate() {
                assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "{:?} output {k}: {a} vs {b}",
                    mlp.sizes
                );
            }
        }
    }
}

#[test]
fn the_f32_kernel_stays_within_1e_5_of_the_f64_kernel_relative_to_the_output_range() {
    // Measured: 3.7e-6 of the output range at most (2 December).
    let mut rng = Rng::new(8);
    let mut worst = 0.0f64;
    for mlp in networks_to_check() {
        let (k64, k32) = (
            Kernel::new(&mlp),
            Kernel::with_precision(&mlp, Precision::F32),
        );
        assert_eq!(k64.precision(), Precision::F64);
        let (lo, hi) = (&mlp.input_map.min, &mlp.input_map.max);
        let (mut y64, mut y32) = (vec![0.0; k64.outputs()], vec![0.0; k64.outputs()]);
        for _ in 0..300 {
            let x: Vec<f64> = lo
                .iter()
                .zip(hi)
                .map(|(a, b)| a + (b - a) * rng.range(0.0, 1.0))
                .collect();
            k64.forward(&x, &mut y64);
            k32.forward(&x, &mut y32);
            for (i, (a, b)) in y32.iter().zip(&y64).enumerate() {
                // The trained output range; 1 + |y| for the random
                // networks, whose maps are degenerate.
                let range = mlp.output_map.max[i] - mlp.output_map.min[i];
                let scale = if range > 0.0 { range } else { 1.0 + b.abs() };
                worst = worst.max((a - b).abs() / scale);
            }
        }
    }
    assert!(worst < 1e-5, "largest change {worst:e} of the output range");
    assert!(worst > 0.0, "the f32 kernel must round");
}

#[test]
fn tansig32_is_within_1e_6_of_tanh_and_odd() {
    let mut worst = 0.0f64;
    let n = 400_000;
    for i in 0..=n {
        for x in [
            -25.0 + 50.0 * i as f64 / n as f64,
            (i as f64 / n as f64 - 0.5) * 1e-3,
        ] {
            let z = x as f32;
            let t = tansig32(z);
            worst = worst.max((f64::from(t) - f64::from(z).tanh()).abs());
            assert_eq!(tansig32(-z).to_bits(), (-t).to_bits(), "odd at {z}");
        }
    }
    assert!(worst < 1e-6, "{worst:e}");
    assert_eq!(tansig32(0.0), 0.0);
    assert!((tansig32(f32::INFINITY) - 1.0).abs() < 1e-6);
    assert!(tansig32(f32::INFINITY) <= 1.0 && tansig32(f32::NEG_INFINITY) >= -1.0);
    assert!(tansig32(f32::NAN).is_nan());
}

#[test]
fn case3_on_task1_with_f32_networks_ends_within_1e_5_m_of_the_f64_run() {
    let f64_nets = networks::builtin().unwrap();
    let f32_nets = Arc::new(Networks::clone(&f64_nets).with_precision(Precision::F32));
    assert_eq!(f32_nets.precision(), Precision::F32);
    assert_eq!(f64_nets.precision(), Precision::F64);
    let run = |n: Arc<Networks>| {
        Planner::run_summary(Scene::task1(), Method::CASE3, Some(n as Arc<dyn Surrogate>)).unwrap()
    };
    let (a, b) = (run(f64_nets), run(f32_nets));
    assert!(
        (a.final_error - b.final_error).abs() < 1e-5,
        "{} vs {}",
        a.final_error,
        b.final_error
    );
    let (ca, cb) = (a.min_clearance.unwrap(), b.min_clearance.unwrap());
    assert!((ca - cb).abs() < 1e-5, "{ca} vs {cb}");
    assert_eq!(a.collided, b.collided);
    assert_ne!(a.final_error, b.final_error, "the f32 run is its own");
}
