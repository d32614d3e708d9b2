//! In-process benchmarks of the planner, the networks and the trainer, the
//! same code natively (`redundant-ik bench`) and in the browser
//! (`window.demo.bench()`).
//!
//! The core knows no clock: the caller passes one (`std::time::Instant`
//! natively, `performance.now()` in a page), and optionally a counter of heap
//! allocations. Every figure is the median of at least five timed batches
//! after one warm-up batch; a batch repeats the measured operation until it
//! has run for at least [`Options::batch_ms`], so coarse browser clocks still
//! give exact-enough means.

pub mod space;

use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::atlas;
use crate::error::{Error, Result};
use crate::nalgebra::Vector2;
use crate::networks::{Encoding, NetworkSet, Networks, Sampling, Variant};
use crate::nn::lm::{LmOptions, LmTrainer};
use crate::nn::mlp::{MapMinMax, Mlp};
use crate::nn::{Precision, Rng};
use crate::planner::{methods, Method, Planner, Surrogate};
use crate::scene::Scene;
use crate::training;
use crate::Arm;

/// The verdict's pair: the learned route (both networks, Case 3) and the
/// exact route it imitates (the numerical one). The README's and the
/// page's "the networks are slower" compares their step times.
pub const VERDICT: [Method; 2] = [methods::CASE3, methods::NUMERICAL];

/// What to measure and how long.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Options {
    /// Shortest timed batch (ms).
    pub batch_ms: f64,
    /// Timed batches per figure (the median is reported); at least 5.
    pub batches: usize,
    /// Whether to time one Levenberg-Marquardt epoch (about 0.1 s each).
    pub lm_epoch: bool,
    /// Whether to time the paper's `Phi` variants too (their weights are
    /// not in the page's build).
    pub paper_variants: bool,
    /// Whether to time the default atlas (about 0.6 s natively per run).
    pub atlas: bool,
    /// The methods to time (the paper's five by default).
    #[serde(default = "paper_methods")]
    pub methods: Vec<Method>,
    /// The shipped network set the network methods run (the paper's by
    /// default).
    #[serde(default)]
    pub networks: NetworkSet,
    /// Newton-Schulz steps on the learned `Phi` (0, the paper's, by default).
    #[serde(default)]
    pub refine: u32,
    /// The networks' kernels' arithmetic (`f64` by default).
    #[serde(default)]
    pub precision: Precision,
}

fn paper_methods() -> Vec<Method> {
    methods::PAPER.to_vec()
}

impl Default for Options {
    fn default() -> Self {
        Self {
            batch_ms: 20.0,
            batches: 7,
            lm_epoch: true,
            paper_variants: true,
            atlas: true,
            methods: paper_methods(),
            networks: NetworkSet::Paper,
            refine: 0,
            precision: Precision::F64,
        }
    }
}

/// One figure per method, in the order measured; serialised as one key per
/// method name (`{"none": .., "numerical": .., ...}`).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct PerMethod(pub Vec<(Method, f64)>);

impl PerMethod {
    fn from_fn(methods: &[Method], mut f: impl FnMut(Method) -> Result<f64>) -> Result<Self> {
        methods
            .iter()
            .map(|&m| Ok((m, f(m)?)))
            .collect::<Result<Vec<_>>>()
            .map(PerMethod)
    }

    /// The figure of `method`, if it was measured.
    pub fn get(&self, method: Method) -> Option<f64> {
        self.0.iter().find(|(m, _)| *m == method).map(|(_, v)| *v)
    }
}

impl Serialize for PerMethod {
    fn serialize<S: serde::Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (m, v) in &self.0 {
            map.serialize_entry(m.name(), v)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for PerMethod {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        struct Visitor;
        impl<'de> serde::de::Visitor<'de> for Visitor {
            type Value = PerMethod;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a map from method names to numbers")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut map: A,
            ) -> std::result::Result<PerMethod, A::Error> {
                let mut out = Vec::new();
                while let Some((name, value)) = map.next_entry::<String, f64>()? {
                    let m: Method = name.parse().map_err(serde::de::Error::custom)?;
                    out.push((m, value));
                }
                Ok(PerMethod(out))
            }
        }
        d.deserialize_map(Visitor)
    }
}

/// Forward-pass times of the shipped networks (ns).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Forward {
    /// The set's `Phi` network (the paper's set: rotation-equivariant
    /// 2-35-14-6; the reach set: 4-96-96-6).
    pub phi: f64,
    /// The set's `v` network (5-25-14-3; 6-25-14-3).
    pub v: f64,
    /// The paper's single `Phi` net (3-35-14-6), when measured.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phi_plain: Option<f64>,
    /// The paper's three row nets (3 x 3-35-14-2), when measured.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub phi_rows: Option<f64>,
}

/// Everything `redundant-ik bench` reports.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Report {
    /// The network kernels measured: `avx2+fma`, `simd128`, `fma` or
    /// `portable` ([`crate::nn::kernel::kernel_isa`]).
    pub kernels: String,
    /// One `theta_dot` at Task 1's start pose (ns).
    pub theta_dot_ns: PerMethod,
    /// One RK4 step of Task 1, with the sample bookkeeping (ns).
    pub step_ns: PerMethod,
    /// One forward pass of each shipped network (ns).
    pub forward_ns: Forward,
    /// One `trainlm` epoch of the 2-35-14-6 `Phi` net on 3,000 samples (2,100
    /// in the training split), in ms; `None` when not measured.
    pub lm_epoch_ms: Option<f64>,
    /// Heap allocations per RK4 step; `None` when no counter was given.
    pub allocs_per_step: Option<PerMethod>,
    /// One 41 x 41 atlas of Task 1 in the paper's five methods (8,405 runs) on one
    /// thread, in ms ([`atlas_ms`]); `None` when not measured.
    #[serde(default)]
    pub atlas_ms: Option<f64>,
}

/// A clock in milliseconds (any origin) and an optional allocation counter.
pub struct Probes<'a> {
    /// Current time in milliseconds.
    pub now_ms: &'a dyn Fn() -> f64,
    /// Heap allocations so far, if the caller can count them.
    pub allocations: Option<&'a dyn Fn() -> u64>,
}

/// Median of the per-iteration time (ns) of `f` over `opts.batches` batches,
/// after one warm-up batch. Each batch runs `f` until `opts.batch_ms` passed.
fn time_ns(opts: &Options, probes: &Probes, mut f: impl FnMut() -> Result<()>) -> Result<f64> {
    let now = probes.now_ms;
    // Warm-up, and the batch size: double until a batch lasts batch_ms.
    let mut iters: u64 = 1;
    loop {
        let t0 = now();
        for _ in 0..iters {
            f()?;
        }
        let dt = now() - t0;
        if dt >= opts.batch_ms || iters >= 1 << 30 {
            break;
        }
        iters *= if dt < opts.batch_ms / 8.0 { 8 } else { 2 };
    }
    let mut times = Vec::with_capacity(opts.batches.max(5));
    for _ in 0..opts.batches.max(5) {
        let t0 = now();
        for _ in 0..iters {
            f()?;
        }
        times.push((now() - t0) * 1e6 / iters as f64);
    }
    Ok(median(&mut times))
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn shipped(opts: &Options) -> Result<Arc<dyn Surrogate>> {
    Ok(shipped_networks(opts)?)
}

/// The options' shipped set in the options' precision.
fn shipped_networks(opts: &Options) -> Result<Arc<Networks>> {
    Ok(crate::networks::builtin_set(opts.networks)?.in_precision(opts.precision))
}

/// Task 1 with the refinement the options ask for.
fn scene(opts: &Options) -> Result<Scene> {
    let mut scene = Scene::task1();
    scene.set_param(&crate::planner::methods::REFINE, f64::from(opts.refine))?;
    Ok(scene)
}

/// Task 1's line velocity, the `Xdot` of every `theta_dot` measured.
fn task1_xdot() -> Vector2<f64> {
    let scene = Scene::task1();
    let x0 = scene.arm.forward(&scene.theta0_vector());
    (scene.target_vector() - x0) / scene.tf
}

/// One `theta_dot` of `method` at Task 1's start pose (ns).
pub fn theta_dot_ns(method: Method, opts: &Options, probes: &Probes) -> Result<f64> {
    let mut p = Planner::new(scene(opts)?, method, Some(shipped(opts)?))?;
    let th: Vec<f64> = p.theta().iter().copied().collect();
    let xdot = task1_xdot();
    let xdot = [xdot[0], xdot[1]];
    let mut out = vec![0.0; th.len()];
    time_ns(opts, probes, || {
        p.theta_dot_into(std::hint::black_box(&th), xdot, &mut out)?;
        std::hint::black_box(&out);
        Ok(())
    })
}

/// One RK4 step of Task 1 in `method`, sample included (ns); the task restarts
/// every 100 steps.
pub fn step_ns(method: Method, opts: &Options, probes: &Probes) -> Result<f64> {
    let mut p = Planner::new(scene(opts)?, method, Some(shipped(opts)?))?;
    let n = p.scene().steps();
    let mut k = 0;
    time_ns(opts, probes, || {
        if k == n {
            p.reset();
            k = 0;
        }
        k += 1;
        std::hint::black_box(p.step()?);
        Ok(())
    })
}

/// Heap allocations per RK4 step of Task 1 in `method`, over one whole run,
/// once the planner exists.
pub fn allocs_per_step(method: Method, opts: &Options, count: &dyn Fn() -> u64) -> Result<f64> {
    let mut p = Planner::new(scene(opts)?, method, Some(shipped(opts)?))?;
    let n = p.scene().steps();
    let before = count();
    for _ in 0..n {
        std::hint::black_box(p.step()?);
    }
    Ok((count() - before) as f64 / n as f64)
}

/// Forward passes of the `Phi` and `v` networks of the options' set (ns).
pub fn forward_ns(opts: &Options, probes: &Probes) -> Result<Forward> {
    let theta = Scene::task1().theta0;
    let nets = shipped_networks(opts)?;
    let mut out = [0.0; 6];
    let phi = time_ns(opts, probes, || {
        nets.phi_into(std::hint::black_box(&theta), &mut out)
    })?;
    let mut g = [0.0; 3];
    let v = time_ns(opts, probes, || {
        nets.area_gradient_into(std::hint::black_box(&theta), [0.5, 0.5], &mut g)
    })?;
    Ok(Forward {
        phi,
        v,
        phi_plain: None,
        phi_rows: None,
    })
}

/// Forward passes of the paper's two `Phi` forms, the single 3-35-14-6 net
/// and the three 3-35-14-2 row nets (ns). Separate from [`forward_ns`] so
/// that the workers' module, which is handed only the shipped sets' files,
/// does not embed their weights; compiled in with `embedded-weights`.
#[cfg(feature = "embedded-weights")]
pub fn forward_paper_ns(opts: &Options, probes: &Probes) -> Result<(f64, f64)> {
    let theta = Scene::task1().theta0;
    let mut out = [0.0; 6];
    let mut time = |variant| -> Result<f64> {
        let nets = Networks::embedded_with(variant)?;
        time_ns(opts, probes, || {
            nets.phi_into(std::hint::black_box(&theta), &mut out)
        })
    };
    Ok((time(Variant::Plain)?, time(Variant::Rows)?))
}

/// Without `embedded-weights` (the workers' module) the paper's two `Phi`
/// forms are not there to time: says so.
#[cfg(not(feature = "embedded-weights"))]
pub fn forward_paper_ns(_opts: &Options, _probes: &Probes) -> Result<(f64, f64)> {
    Err(Error::NetworksUnavailable(
        "the paper's plain and rows Phi networks are built into the command-line tool only".into(),
    ))
}

/// One `trainlm` epoch (ms) of a fresh 2-35-14-6 `Phi` network on 3,000
/// samples drawn as the shipped file's were (seed 1), 2,100 of them in the
/// training split. Each timed epoch starts from the same trainer state.
pub fn lm_epoch_ms(opts: &Options, probes: &Probes) -> Result<f64> {
    let arm = Arm::paper();
    let sampling = Sampling::default();
    let samples = training::draw_samples(&arm, &sampling, 3000, 1)?;
    let sets = training::phi_datasets(&arm, Variant::Equivariant, Encoding::Raw, &samples)?;
    let data = sets
        .first()
        .ok_or_else(|| Error::Training("no training set".into()))?;
    let mut rng = Rng::new(1);
    let mlp = Mlp::nguyen_widrow(
        &[data.n_in, 35, 14, data.n_out],
        MapMinMax::fit(&data.inputs, data.n_in),
        MapMinMax::fit(&data.targets, data.n_out),
        &mut rng,
    )?;
    let trainer = LmTrainer::new(mlp, data, LmOptions::default(), &mut rng)?;
    let now = probes.now_ms;
    let mut times = Vec::new();
    for i in 0..=opts.batches.max(5) {
        let mut t = trainer.clone();
        let t0 = now();
        std::hint::black_box(t.epoch());
        let dt = now() - t0;
        if i > 0 {
            times.push(dt);
        }
    }
    Ok(median(&mut times))
}

/// Runs of the atlas timed by [`atlas_ms`] (the median is reported).
pub const ATLAS_RUNS: usize = 3;

/// One default atlas ([`atlas::Spec::task`]: Task 1, 41 x 41 cells, the
/// paper's five methods, 8,405 runs of 100 RK4 steps, of which the 195 in the
/// 39 cells where the disc lies on the arm at `t = 0` are classified without
/// stepping) computed on this thread, in ms: the median of [`ATLAS_RUNS`]
/// runs.
pub fn atlas_ms(probes: &Probes) -> Result<f64> {
    let nets = crate::networks::builtin()?;
    let now = probes.now_ms;
    let mut times = Vec::with_capacity(ATLAS_RUNS);
    for _ in 0..ATLAS_RUNS {
        let spec = atlas::Spec::task(1)?;
        let t0 = now();
        std::hint::black_box(atlas::Atlas::run(spec, Some(nets.clone()))?);
        times.push(now() - t0);
    }
    Ok(median(&mut times))
}

/// Runs every measurement.
pub fn run(opts: &Options, probes: &Probes) -> Result<Report> {
    let theta_dot = PerMethod::from_fn(&opts.methods, |m| theta_dot_ns(m, opts, probes))?;
    let step = PerMethod::from_fn(&opts.methods, |m| step_ns(m, opts, probes))?;
    let mut forward = forward_ns(opts, probes)?;
    if opts.paper_variants {
        let (plain, rows) = forward_paper_ns(opts, probes)?;
        forward.phi_plain = Some(plain);
        forward.phi_rows = Some(rows);
    }
    let lm = if opts.lm_epoch {
        Some(lm_epoch_ms(opts, probes)?)
    } else {
        None
    };
    let atlas = if opts.atlas {
        Some(atlas_ms(probes)?)
    } else {
        None
    };
    let allocs = match probes.allocations {
        Some(count) => Some(PerMethod::from_fn(&opts.methods, |m| {
            allocs_per_step(m, opts, count)
        })?),
        None => None,
    };
    Ok(Report {
        kernels: crate::nn::kernel::kernel_isa().to_string(),
        theta_dot_ns: theta_dot,
        step_ns: step,
        forward_ns: forward,
        lm_epoch_ms: lm,
        allocs_per_step: allocs,
        atlas_ms: atlas,
    })
}
