//! The trained networks of section V: `Phi(theta)` (eq. 19) and the obstacle
//! vector's area gradient `g(theta, O)` (eqs. 14-15, `v = lambda / 4 g`),
//! loaded from weights files and plugged into the planner as its
//! [`Surrogate`].
//!
//! The shipped weights are embedded in the build, so the command-line tool and
//! the page need no files; users may load their own with
//! [`Networks::from_json`]. How they were trained, the schema and the
//! measured accuracy are in `docs/networks.md`.

use serde::{Deserialize, Serialize};

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::kinematics::Pose;
use crate::nn::data::{self, Sampling, Visited};
use crate::nn::lm::{self, Dataset, EpochReport, LmOptions};
use crate::nn::rng::Rng;
use crate::nn::weights::{self, ArmSpec, InputRange, NetEntry, NetKind, Training, Variant};
use crate::nn::{Kernel, WeightsFile};
use crate::planner::Surrogate;

/// Shipped `Phi` networks, paper form: one 3-35-14-6 net over `theta`.
pub const PHI_PLAIN_JSON: &str = include_str!("../weights/phi-plain.json");
/// Shipped `Phi` networks, paper form: three 3-35-14-2 nets, one per row of `Phi`.
pub const PHI_ROWS_JSON: &str = include_str!("../weights/phi-rows.json");
/// Shipped `Phi` network, rotation-equivariant: 2-35-14-6 over `(theta_2, theta_3)`.
pub const PHI_EQUIVARIANT_JSON: &str = include_str!("../weights/phi-equivariant.json");
/// Shipped `v` network, paper form: 5-25-14-3 over `(theta, O)`.
pub const V_PLAIN_JSON: &str = include_str!("../weights/v-plain.json");

/// The `Phi` variant [`Networks::embedded`] uses.
pub const DEFAULT_PHI_VARIANT: Variant = Variant::Equivariant;
/// The `v` variant [`Networks::embedded`] uses.
pub const DEFAULT_V_VARIANT: Variant = Variant::Plain;

/// The shipped `Phi` weights file of a variant (JSON text).
pub fn embedded_phi_json(variant: Variant) -> &'static str {
    match variant {
        Variant::Plain => PHI_PLAIN_JSON,
        Variant::Rows => PHI_ROWS_JSON,
        Variant::Equivariant => PHI_EQUIVARIANT_JSON,
    }
}

/// A `Phi` network family and a `v` network for the same arm.
#[derive(Debug, Clone, PartialEq)]
pub struct Networks {
    phi: WeightsFile,
    v: WeightsFile,
    arm: Arm,
    /// The run-time form of each `Phi` network and of the `v` network
    /// (`mapminmax` folded in, padded, vectorised), built at load.
    phi_kernels: Vec<Kernel>,
    v_kernel: Kernel,
}

/// What the networks were trained on, for the page to show and to warn when a
/// state leaves it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrainedRange {
    /// Variant of the `Phi` networks.
    pub phi_variant: Variant,
    /// Variant of the `v` network.
    pub v_variant: Variant,
    /// Box of the `Phi` networks' inputs, and the `sigma_min(J)` floor.
    pub phi: InputRange,
    /// Box of the `v` network's inputs.
    pub v: InputRange,
    /// Region obstacle centres were drawn from, lower corner.
    pub obstacle_min: [f64; 2],
    /// Region obstacle centres were drawn from, upper corner.
    pub obstacle_max: [f64; 2],
    /// Arm post height the networks were trained for.
    pub post: f64,
    /// Link lengths the networks were trained for.
    pub links: Vec<f64>,
}

impl Networks {
    /// Pairs a `Phi` file and a `v` file; both must be valid, of the right
    /// kind and trained for the same arm.
    pub fn new(phi: WeightsFile, v: WeightsFile) -> Result<Self> {
        phi.validate()?;
        v.validate()?;
        if phi.net != NetKind::Phi {
            return Err(Error::Weights(
                "the first file holds a v network, expected the Phi network(s)".into(),
            ));
        }
        if v.net != NetKind::V {
            return Err(Error::Weights(
                "the second file holds Phi networks, expected the v network".into(),
            ));
        }
        if phi.arm != v.arm {
            return Err(Error::Weights(
                "the Phi and v files were trained for different arms".into(),
            ));
        }
        let arm = phi.arm()?;
        let phi_kernels = phi.nets.iter().map(|e| Kernel::new(&e.mlp)).collect();
        let v_kernel = Kernel::new(&v.nets[0].mlp);
        Ok(Self {
            phi,
            v,
            arm,
            phi_kernels,
            v_kernel,
        })
    }

    /// Networks from the JSON text of a `Phi` weights file and a `v` weights
    /// file. Corrupt or mismatched files give [`Error::Weights`].
    pub fn from_json(phi_json: &str, v_json: &str) -> Result<Self> {
        let phi = WeightsFile::from_json(phi_json)
            .map_err(|e| Error::Weights(format!("Phi file: {}", inner(&e))))?;
        let v = WeightsFile::from_json(v_json)
            .map_err(|e| Error::Weights(format!("v file: {}", inner(&e))))?;
        Self::new(phi, v)
    }

    /// The shipped networks: the default `Phi` variant ([`DEFAULT_PHI_VARIANT`])
    /// and the `v` network.
    pub fn embedded() -> Result<Self> {
        Self::embedded_with(DEFAULT_PHI_VARIANT)
    }

    /// The shipped networks with the chosen `Phi` variant (`plain` and `rows`
    /// are the paper's form, `equivariant` the measured improvement).
    pub fn embedded_with(phi_variant: Variant) -> Result<Self> {
        Self::from_json(embedded_phi_json(phi_variant), V_PLAIN_JSON)
    }

    /// The `Phi` weights file.
    pub fn phi_file(&self) -> &WeightsFile {
        &self.phi
    }

    /// The `v` weights file.
    pub fn v_file(&self) -> &WeightsFile {
        &self.v
    }

    /// The arm the networks were trained for (the planner refuses them for
    /// another arm).
    pub fn arm(&self) -> &Arm {
        &self.arm
    }

    /// The trained range, for the page.
    pub fn trained_range(&self) -> TrainedRange {
        TrainedRange {
            phi_variant: self.phi.variant,
            v_variant: self.v.variant,
            phi: self.phi.range.clone(),
            v: self.v.range.clone(),
            obstacle_min: self.v.training.sampling.obstacle_min,
            obstacle_max: self.v.training.sampling.obstacle_max,
            post: self.arm.post(),
            links: self.arm.links().to_vec(),
        }
    }

    /// Learned `Phi(theta)` row-major into `out` (`2n` entries),
    /// allocation-free. `theta` is checked (length, finiteness).
    pub fn phi_into(&self, theta: &[f64], out: &mut [f64]) -> Result<()> {
        self.arm.check_angles(theta)?;
        let (s, c) = theta[0].sin_cos();
        self.phi_raw(theta, s, c, out)
    }

    /// The `Phi` networks at `theta` (length checked by the caller), with
    /// `(sin, cos)` of `theta_1` for the equivariant variant's rotation.
    #[inline]
    fn phi_raw(&self, theta: &[f64], s1: f64, c1: f64, out: &mut [f64]) -> Result<()> {
        let n = self.arm.dof();
        if out.len() != 2 * n {
            return Err(dimension("Phi (n x 2) output", 2 * n, out.len()));
        }
        let k = &self.phi_kernels;
        match self.phi.variant {
            Variant::Plain => k[0].forward(theta, out),
            Variant::Rows => {
                for (kernel, row) in k.iter().zip(out.chunks_exact_mut(2)) {
                    kernel.forward(theta, row);
                }
            }
            Variant::Equivariant => {
                k[0].forward(&theta[1..], out);
                // Phi(theta) = Phi(0, theta_2, ..) R(theta_1)^T,
                // R(a) = [[cos a, sin a], [-sin a, cos a]].
                for row in out.chunks_exact_mut(2) {
                    let (p0, p1) = (row[0], row[1]);
                    row[0] = p0 * c1 + p1 * s1;
                    row[1] = -p0 * s1 + p1 * c1;
                }
            }
        }
        if out.iter().any(|x| !x.is_finite()) {
            return Err(Error::NonFinite {
                what: "Phi network output".into(),
            });
        }
        Ok(())
    }

    /// Learned area gradient `g(theta, O)` into `out` (`n` entries),
    /// allocation-free. `theta` and `O` are checked.
    pub fn area_gradient_into(&self, theta: &[f64], o: [f64; 2], out: &mut [f64]) -> Result<()> {
        self.arm.check_angles(theta)?;
        if !(o[0].is_finite() && o[1].is_finite()) {
            return Err(Error::NonFinite {
                what: "obstacle point".into(),
            });
        }
        let (s, c) = theta[0].sin_cos();
        self.area_gradient_raw(theta, s, c, o, out)
    }

    #[inline]
    fn area_gradient_raw(
        &self,
        theta: &[f64],
        s1: f64,
        c1: f64,
        o: [f64; 2],
        out: &mut [f64],
    ) -> Result<()> {
        let n = self.arm.dof();
        if out.len() != n {
            return Err(dimension("v network output", n, out.len()));
        }
        let mut input = [0.0; MAX_V_INPUTS];
        self.v_kernel
            .forward(self.v_input(theta, (s1, c1), o, &mut input), out);
        if out.iter().any(|x| !x.is_finite()) {
            return Err(Error::NonFinite {
                what: "v network output".into(),
            });
        }
        Ok(())
    }

    /// Whether `theta` is inside the `Phi` networks' trained box and away from
    /// singular poses (`sigma_min(J) >=` the floor).
    pub fn phi_in_range_slice(&self, theta: &[f64]) -> bool {
        self.arm.check_angles(theta).is_ok()
            && self.phi_in_range_at(&Pose::lenient(&self.arm, theta))
    }

    fn phi_in_range_at(&self, pose: &Pose) -> bool {
        let theta = pose.theta();
        self.phi.range.contains(phi_inputs(self.phi.variant, theta))
            && pose.sigma_min() >= self.phi.range.sigma_floor
    }

    /// Whether `(theta, O)` is inside the `v` network's trained box.
    pub fn v_in_range_slice(&self, theta: &[f64], o: [f64; 2]) -> bool {
        if self.arm.check_angles(theta).is_err() || !(o[0].is_finite() && o[1].is_finite()) {
            return false;
        }
        let (s, c) = theta[0].sin_cos();
        self.v_in_range_raw(theta, s, c, o)
    }

    fn v_in_range_raw(&self, theta: &[f64], s1: f64, c1: f64, o: [f64; 2]) -> bool {
        let mut input = [0.0; MAX_V_INPUTS];
        self.v
            .range
            .contains(self.v_input(theta, (s1, c1), o, &mut input))
    }

    /// The `v` network's inputs for this arm and variant (see [`v_inputs`]).
    fn v_input<'a>(
        &self,
        theta: &[f64],
        sc: (f64, f64),
        o: [f64; 2],
        buf: &'a mut [f64; MAX_V_INPUTS],
    ) -> &'a [f64] {
        v_inputs(self.v.variant, self.arm.post(), theta, sc, o, buf)
    }

    /// Whether `pose` is a pose of an arm with as many joints as the networks'.
    #[inline]
    fn check_pose(&self, pose: &Pose) -> Result<()> {
        if pose.dof() == self.arm.dof() {
            Ok(())
        } else {
            Err(dimension(
                "pose for the networks",
                self.arm.dof(),
                pose.dof(),
            ))
        }
    }
}

#[cold]
fn dimension(what: &str, expected: usize, found: usize) -> Error {
    Error::DimensionMismatch {
        what: what.into(),
        expected,
        found,
    }
}

fn inner(e: &Error) -> String {
    match e {
        Error::Weights(m) => m.clone(),
        other => other.to_string(),
    }
}

/// The `Phi` networks' inputs for a pose.
fn phi_inputs(variant: Variant, theta: &[f64]) -> &[f64] {
    match variant {
        Variant::Equivariant => &theta[1..],
        _ => theta,
    }
}

/// Most links the `v` network's input buffer holds (`n + 2` inputs); weights
/// files for longer arms are refused when they load.
pub const MAX_V_INPUTS: usize = 64;

/// The `v` network's inputs for a pose and obstacle point, written into `buf`
/// (`sc` = sine and cosine of `theta_1`).
fn v_inputs<'a>(
    variant: Variant,
    post: f64,
    theta: &[f64],
    (s, c): (f64, f64),
    o: [f64; 2],
    buf: &'a mut [f64; MAX_V_INPUTS],
) -> &'a [f64] {
    let n = theta.len().min(MAX_V_INPUTS - 2);
    match variant {
        Variant::Equivariant => {
            // Rotate O by -theta_1 about P(0): the arm at theta_1 is the arm at
            // theta_1 = 0 turned by R(theta_1), so O' = R(theta_1)^T (O - P(0)) + P(0).
            let (dx, dy) = (o[0], o[1] - post);
            buf[..n - 1].copy_from_slice(&theta[1..n]);
            buf[n - 1] = c * dx - s * dy;
            buf[n] = s * dx + c * dy + post;
            &buf[..n + 1]
        }
        _ => {
            buf[..n].copy_from_slice(&theta[..n]);
            buf[n] = o[0];
            buf[n + 1] = o[1];
            &buf[..n + 2]
        }
    }
}

impl Surrogate for Networks {
    fn arm(&self) -> &Arm {
        &self.arm
    }

    fn phi(&self, pose: &Pose, out: &mut [f64]) -> Result<()> {
        self.check_pose(pose)?;
        self.phi_raw(pose.theta(), pose.sin()[0], pose.cos()[0], out)
    }

    fn area_gradient(&self, pose: &Pose, o: [f64; 2], out: &mut [f64]) -> Result<()> {
        self.check_pose(pose)?;
        self.area_gradient_raw(pose.theta(), pose.sin()[0], pose.cos()[0], o, out)
    }

    fn phi_in_range(&self, pose: &Pose) -> bool {
        self.check_pose(pose).is_ok() && self.phi_in_range_at(pose)
    }

    fn v_in_range(&self, pose: &Pose, o: [f64; 2]) -> bool {
        self.check_pose(pose).is_ok()
            && o[0].is_finite()
            && o[1].is_finite()
            && self.v_in_range_raw(pose.theta(), pose.sin()[0], pose.cos()[0], o)
    }
}

/// What to train: the quantity, the variant, the data and the optimiser.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrainSpec {
    /// `phi` or `v`.
    pub net: NetKind,
    /// Input/output mapping.
    pub variant: Variant,
    /// Seed for sampling, split and initial weights.
    pub seed: u64,
    /// Samples to draw.
    pub samples: usize,
    /// Hidden layer widths, e.g. `[35, 14]`.
    pub hidden: Vec<usize>,
    /// Levenberg-Marquardt options.
    pub options: LmOptions,
    /// How samples are drawn.
    pub sampling: Sampling,
}

impl TrainSpec {
    /// The paper's architecture for `net` (hidden 35-14 for `Phi`, 25-14 for
    /// `v`) with 3000 samples and 400 epochs.
    pub fn paper(net: NetKind, variant: Variant, seed: u64) -> Self {
        Self {
            net,
            variant,
            seed,
            samples: 3000,
            hidden: match net {
                NetKind::Phi => vec![35, 14],
                NetKind::V => vec![25, 14],
            },
            options: LmOptions::default(),
            sampling: Sampling::default(),
        }
    }
}

/// Draws `n` samples (poses and obstacle points) as `sampling` describes, from
/// a generator seeded with `seed`.
pub fn draw_samples(arm: &Arm, sampling: &Sampling, n: usize, seed: u64) -> Result<Vec<Visited>> {
    let mut rng = Rng::new(seed);
    let pool = sampling.visited(&mut rng)?;
    sampling.draw(arm, &pool, n, &mut rng)
}

/// Training sets for `Phi` networks of `variant`: one per network.
pub fn phi_datasets(arm: &Arm, variant: Variant, samples: &[Visited]) -> Result<Vec<Dataset>> {
    let n = arm.dof();
    let (count, n_in, n_out) = weights::shape(NetKind::Phi, variant, n)?;
    let mut sets = vec![Dataset::new(n_in, n_out); count];
    for s in samples {
        let theta = &s.theta[..];
        let target = match variant {
            Variant::Equivariant => {
                let mut t0 = theta.to_vec();
                t0[0] = 0.0;
                data::phi_target(arm, &t0)?
            }
            _ => data::phi_target(arm, theta)?,
        };
        let x = phi_inputs(variant, theta);
        match variant {
            Variant::Rows => {
                for (i, set) in sets.iter_mut().enumerate() {
                    set.push(x, &target[2 * i..2 * i + 2]);
                }
            }
            _ => sets[0].push(x, &target),
        }
    }
    Ok(sets)
}

/// Training set for the `v` network of `variant`.
pub fn v_dataset(arm: &Arm, variant: Variant, samples: &[Visited]) -> Result<Dataset> {
    let (_, n_in, n_out) = weights::shape(NetKind::V, variant, arm.dof())?;
    let mut set = Dataset::new(n_in, n_out);
    let mut buf = [0.0; MAX_V_INPUTS];
    for s in samples {
        let x = v_inputs(
            variant,
            arm.post(),
            &s.theta,
            s.theta[0].sin_cos(),
            s.obstacle,
            &mut buf,
        );
        set.push(x, &data::v_target(arm, &s.theta, s.obstacle));
    }
    Ok(set)
}

fn input_names(net: NetKind, variant: Variant, n: usize) -> Vec<String> {
    let thetas = |from: usize| (from..=n).map(|i| format!("theta{i}"));
    match (net, variant) {
        (NetKind::Phi, Variant::Equivariant) => thetas(2).collect(),
        (NetKind::Phi, _) => thetas(1).collect(),
        (NetKind::V, Variant::Equivariant) => thetas(2)
            .chain(["o1_rotated".to_string(), "o2_rotated".to_string()])
            .collect(),
        (NetKind::V, _) => thetas(1)
            .chain(["o1".to_string(), "o2".to_string()])
            .collect(),
    }
}

/// Trains the networks `spec` describes on the paper's arm and returns the
/// weights file (with `training.seconds` unset: the caller may time it).
/// `on_epoch(net_index, report)` sees every epoch of every network;
/// returning `false` stops that network's training.
pub fn train_weights(
    spec: &TrainSpec,
    mut on_epoch: impl FnMut(usize, &EpochReport) -> bool,
) -> Result<WeightsFile> {
    if spec.samples < 20 {
        return Err(Error::Training(format!(
            "{} samples are too few to train on (at least 20)",
            spec.samples
        )));
    }
    let arm = Arm::paper();
    let samples = draw_samples(&arm, &spec.sampling, spec.samples, spec.seed)?;
    let sets = match spec.net {
        NetKind::Phi => phi_datasets(&arm, spec.variant, &samples)?,
        NetKind::V => vec![v_dataset(&arm, spec.variant, &samples)?],
    };
    let n_in = sets[0].n_in;
    let mut min = vec![f64::INFINITY; n_in];
    let mut max = vec![f64::NEG_INFINITY; n_in];
    for row in sets[0].inputs.chunks_exact(n_in) {
        for i in 0..n_in {
            min[i] = min[i].min(row[i]);
            max[i] = max[i].max(row[i]);
        }
    }
    let mut nets = Vec::with_capacity(sets.len());
    for (k, set) in sets.iter().enumerate() {
        let mut sizes = vec![set.n_in];
        sizes.extend_from_slice(&spec.hidden);
        sizes.push(set.n_out);
        let seed = spec
            .seed
            .wrapping_add(0x9E37_79B9_7F4A_7C15u64.wrapping_mul(k as u64 + 1));
        let (mlp, report) = lm::train(&sizes, set, spec.options, seed, |r| on_epoch(k, r))?;
        nets.push(NetEntry { mlp, report });
    }
    let file = WeightsFile {
        format: weights::FORMAT.to_string(),
        net: spec.net,
        variant: spec.variant,
        tool_version: env!("CARGO_PKG_VERSION").to_string(),
        arm: ArmSpec {
            post: arm.post(),
            links: arm.links().to_vec(),
        },
        range: InputRange {
            names: input_names(spec.net, spec.variant, arm.dof()),
            min,
            max,
            sigma_floor: spec.sampling.sigma_floor,
        },
        training: Training {
            seed: spec.seed,
            samples: spec.samples,
            hidden: spec.hidden.clone(),
            options: spec.options,
            sampling: spec.sampling.clone(),
            seconds: None,
        },
        nets,
    };
    file.validate()?;
    Ok(file)
}

/// Median, 99th percentile and largest of a set of errors.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ErrorStats {
    /// Number of samples.
    pub samples: usize,
    /// Median.
    pub median: f64,
    /// 99th percentile.
    pub p99: f64,
    /// Largest.
    pub max: f64,
}

impl ErrorStats {
    /// Statistics of `errors` (NaN counts as the largest).
    pub fn of(mut errors: Vec<f64>) -> Self {
        errors.sort_by(|a, b| a.partial_cmp(b).unwrap_or(std::cmp::Ordering::Greater));
        let n = errors.len();
        let at = |q: f64| {
            if n == 0 {
                f64::NAN
            } else {
                errors[((q * (n - 1) as f64).round() as usize).min(n - 1)]
            }
        };
        Self {
            samples: n,
            median: at(0.5),
            p99: at(0.99),
            max: at(1.0),
        }
    }
}

impl Networks {
    /// Relative Frobenius error `|Phi_net - Phi| / |Phi|` at each pose.
    pub fn phi_relative_errors(&self, samples: &[Visited]) -> Result<Vec<f64>> {
        let mut out = Vec::with_capacity(samples.len());
        let mut y = vec![0.0; 2 * self.arm.dof()];
        for s in samples {
            let exact = data::phi_target(&self.arm, &s.theta)?;
            self.phi_into(&s.theta, &mut y)?;
            out.push(rel(&y, &exact));
        }
        Ok(out)
    }

    /// Relative error `|g_net - g| / |g|` at each pose and obstacle point.
    pub fn v_relative_errors(&self, samples: &[Visited]) -> Result<Vec<f64>> {
        let mut out = Vec::with_capacity(samples.len());
        let mut y = vec![0.0; self.arm.dof()];
        for s in samples {
            let exact = data::v_target(&self.arm, &s.theta, s.obstacle);
            self.area_gradient_into(&s.theta, s.obstacle, &mut y)?;
            out.push(rel(&y, &exact));
        }
        Ok(out)
    }

    /// A fresh test set drawn as the `Phi` file's training data was, with another seed.
    pub fn fresh_samples(&self, n: usize, seed: u64) -> Result<Vec<Visited>> {
        draw_samples(&self.arm, &self.phi.training.sampling, n, seed)
    }
}

fn rel(y: &[f64], exact: &[f64]) -> f64 {
    let num: f64 = y.iter().zip(exact).map(|(a, b)| (a - b) * (a - b)).sum();
    let den: f64 = exact.iter().map(|b| b * b).sum();
    (num / den.max(1e-300)).sqrt()
}

/// One planner run's outcome, as `eval` reports it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TaskOutcome {
    /// Paper task (1 or 2).
    pub task: u32,
    /// Mode run.
    pub mode: crate::planner::Mode,
    /// Obstacle centre.
    pub obstacle: [f64; 2],
    /// Closed-loop gain `K` (0 = open loop).
    pub feedback_gain: f64,
    /// Smallest link-to-obstacle-centre distance.
    pub min_distance: f64,
    /// Whether a link entered the obstacle disc.
    pub collided: bool,
    /// Final end-effector error (m).
    pub final_error: f64,
    /// Steps where a network's input left its trained range.
    pub out_of_range_steps: usize,
    /// Error message when the run failed.
    pub error: Option<String>,
}

impl TaskOutcome {
    /// No collision and final error within [`crate::planner::REACH_TOLERANCE`] (5 mm).
    pub fn success(&self) -> bool {
        self.error.is_none()
            && !self.collided
            && self.final_error <= crate::planner::REACH_TOLERANCE
    }
}

/// Runs `mode` on paper task `task` with its obstacle moved to `obstacle`
/// (if given) and closed-loop gain `feedback_gain`.
pub fn run_task(
    nets: &Networks,
    task: u32,
    mode: crate::planner::Mode,
    obstacle: Option<[f64; 2]>,
    feedback_gain: f64,
) -> Result<TaskOutcome> {
    use crate::planner::Planner;
    use std::sync::Arc;
    let mut scene = crate::scene::Scene::task(task)?;
    if let Some(o) = obstacle {
        for ob in &mut scene.obstacles {
            ob.centre = o;
        }
    }
    scene.feedback_gain = feedback_gain;
    let centre = scene.obstacles.first().map_or([f64::NAN; 2], |o| o.centre);
    let surrogate: Arc<dyn Surrogate> = Arc::new(nets.clone());
    let mut out = TaskOutcome {
        task,
        mode,
        obstacle: centre,
        feedback_gain,
        min_distance: f64::NAN,
        collided: false,
        final_error: f64::NAN,
        out_of_range_steps: 0,
        error: None,
    };
    match Planner::run(scene, mode, Some(surrogate)) {
        Ok(run) => {
            let s = run.summary;
            out.min_distance = s.min_distance.unwrap_or(f64::INFINITY);
            out.collided = s.collided;
            out.final_error = s.final_error;
            out.out_of_range_steps = s.out_of_range_steps;
        }
        Err(e) => out.error = Some(e.to_string()),
    }
    Ok(out)
}

/// All five modes on both paper tasks with their canonical obstacles.
pub fn task_outcomes(nets: &Networks, feedback_gain: f64) -> Result<Vec<TaskOutcome>> {
    let mut out = Vec::new();
    for task in [1, 2] {
        for mode in crate::planner::Mode::ALL {
            out.push(run_task(nets, task, mode, None, feedback_gain)?);
        }
    }
    Ok(out)
}

/// The generalisation scenes of `docs/networks.md`: ten obstacle positions
/// other than the canonical ones, inside the trained obstacle region, with
/// the task each is run on.
pub const GENERALISATION_SCENES: [(u32, [f64; 2]); 10] = [
    (1, [0.45, 0.55]),
    (1, [0.55, 0.45]),
    (1, [0.40, 0.60]),
    (1, [0.60, 0.50]),
    (1, [0.50, 0.65]),
    (2, [0.55, 0.65]),
    (2, [0.65, 0.55]),
    (2, [0.70, 0.60]),
    (2, [0.60, 0.70]),
    (2, [0.65, 0.65]),
];
