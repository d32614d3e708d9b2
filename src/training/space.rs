//! Training the networks for an arm in space (`redundant-ik train --arm
//! panda`): the whole-reach recipe of the plane ([`super::TrainSpec::reach`])
//! carried to a chain, by Adam (the Levenberg-Marquardt `J^T J` of a `Phi`
//! with 21 outputs and 12 597 weights does not fit a laptop's time).
//!
//! - `Phi`: poses uniform within the joint limits (`theta_1 = 0`, the
//!   equivariant form of [`crate::networks::space`]), those with
//!   `sigma_min(J)` below the floor left out; the target is `J+`.
//! - `v`: the poses of numerical runs (the paper's criterion at `lambda = 4`
//!   around one sphere) of random straight lines from random poses within
//!   the limits, with spheres uniform over the box of the reach; each pose
//!   with its run's sphere (both jittered); the target is the criterion's
//!   area gradient, its norm smoothed by `eps`.

use serde::Serialize;

use crate::error::{Error, Result};
use crate::networks::file::{Encoding, InputRange, NetEntry, NetKind, Variant, FORMAT};
use crate::networks::space::{
    rotated_obstacle, space_input_names, space_shape, SpaceNetworks, SpaceSampling, SpaceTraining,
    SpaceWeightsFile,
};
use crate::nn::adam::{self, AdamOptions};
use crate::nn::lm::{Dataset, EpochReport};
use crate::nn::rng::Rng;
use crate::planner::Method;
use crate::planner::Planner;
use crate::space::{criterion, linalg, phi, Chain, SpacePose, Sphere, Vec3};

pub use super::space_arm::{probe_sphere, TrainArm, SPHERE_CLEARANCE, SPHERE_PER_REACH};

/// The paper's arm's reach (m), the scale the planar recipe's floor and
/// smoothing were chosen at.
fn paper_reach() -> f64 {
    crate::arm::Arm::paper().max_reach()
}

/// A recipe of an arm in space's training: its name, the networks' hidden
/// widths and, for `Phi` and `v`, the samples drawn and the most epochs.
/// The sampling is the whole-reach recipe's for both.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct SpaceRecipe {
    /// `quick` or `reach`.
    pub name: &'static str,
    /// Hidden layer widths.
    pub hidden: [usize; 2],
    /// `Phi`'s samples and most epochs.
    pub phi: [usize; 2],
    /// `v`'s samples and most epochs.
    pub v: [usize; 2],
}

/// The recipes of an arm in space's training, the page's default first:
/// `quick` ([`SpaceTrainSpec::quick`]) and `reach`, the command line's
/// ([`SpaceTrainSpec::reach`]).
pub const SPACE_RECIPES: [SpaceRecipe; 2] = [
    SpaceRecipe {
        name: "quick",
        hidden: [64, 64],
        phi: [8_000, 300],
        v: [30_000, 120],
    },
    SpaceRecipe {
        name: "reach",
        hidden: [96, 96],
        phi: [20_000, 600],
        v: [100_000, 300],
    },
];

/// What to train for an arm in space.
#[derive(Debug, Clone, PartialEq)]
pub struct SpaceTrainSpec {
    /// The arm, its start and its sphere.
    pub arm: TrainArm,
    /// `phi` or `v`.
    pub net: NetKind,
    /// Seed of sampling, split and initial weights.
    pub seed: u64,
    /// Samples drawn.
    pub samples: usize,
    /// Hidden layer widths.
    pub hidden: Vec<usize>,
    /// The optimiser's options.
    pub adam: AdamOptions,
    /// How the samples are drawn.
    pub sampling: SpaceSampling,
}

impl SpaceTrainSpec {
    /// The whole-reach recipe for the preset `p`: 96-96 networks by Adam
    /// for both (the plane's `Phi`; the plane's 25-14 `v` by
    /// Levenberg-Marquardt is too slow for 7 outputs), `Phi` on 20 000
    /// samples, `v` on 100 000 from 1 000 tasks (40 tasks, the plane's
    /// number, cover seven joints so thinly that `v` fitted its training
    /// states and missed fresh ones by a median relative error of 1.0),
    /// the floor and the smoothing scaled from the paper's arm by the
    /// reach (the floor linearly, the smoothing, an area, by its square).
    /// `arm`: a preset (`&PANDA`) or a [`TrainArm`].
    pub fn reach(arm: impl Into<TrainArm>, net: NetKind, seed: u64) -> Self {
        let arm = arm.into();
        let chain = arm.chain();
        let r = chain.reach();
        let scale = r / paper_reach();
        let shoulder =
            SpacePose::new(chain, &arm.scene.theta0).map_or([0.0; 3], |q| q.joint_origin(0));
        // v's states spread over seven joints and a sphere anywhere: 100 000
        // samples for 300 epochs (a median relative error of 0.63 on fresh
        // states, against 0.71 with 20 000 for 600).
        let recipe = &SPACE_RECIPES[1];
        let [samples, epochs] = match net {
            NetKind::Phi => recipe.phi,
            NetKind::V => recipe.v,
        };
        Self {
            arm,
            net,
            seed,
            samples,
            hidden: recipe.hidden.to_vec(),
            adam: AdamOptions {
                max_epochs: epochs,
                ..AdamOptions::default()
            },
            sampling: SpaceSampling {
                sigma_floor: 0.15 * scale,
                tasks: 1000,
                obstacles_per_task: 2,
                line_length: 0.3,
                obstacle_min: [shoulder[0] - r, shoulder[1] - r, 0.0],
                obstacle_max: [shoulder[0] + r, shoulder[1] + r, shoulder[2] + r],
                theta_noise: 0.08,
                obstacle_noise: 0.03,
                sign_smoothing: super::REACH_SIGN_SMOOTHING * scale * scale,
            },
        }
    }

    /// The page's quick recipe for the preset `p`: the whole-reach
    /// recipe's sampling with 64-64 networks on fewer samples for fewer
    /// epochs (`Phi` 8 000 for 300, `v` 30 000 for 120), so that a browser
    /// trains both in seconds. Less accurate than [`SpaceTrainSpec::reach`]
    /// (on the Panda, median relative errors 0.23 and 0.63 against 0.15
    /// and 0.60): `docs/space.md` gives both.
    pub fn quick(arm: impl Into<TrainArm>, net: NetKind, seed: u64) -> Self {
        let mut spec = Self::reach(arm, net, seed);
        let recipe = &SPACE_RECIPES[0];
        let [samples, epochs] = match net {
            NetKind::Phi => recipe.phi,
            NetKind::V => recipe.v,
        };
        spec.samples = samples;
        spec.hidden = recipe.hidden.to_vec();
        spec.adam.max_epochs = epochs;
        spec
    }

    /// The recipe called `name` ([`SPACE_RECIPES`]) for `arm`.
    pub fn recipe(name: &str, arm: impl Into<TrainArm>, net: NetKind, seed: u64) -> Result<Self> {
        match name {
            "quick" => Ok(Self::quick(arm, net, seed)),
            "reach" => Ok(Self::reach(arm, net, seed)),
            other => Err(Error::UnknownName {
                kind: "training recipe in space",
                name: other.into(),
                choices: crate::error::choices(&SPACE_RECIPES.map(|r| r.name)),
            }),
        }
    }
}

/// A pose and a sphere centre drawn for training.
#[derive(Debug, Clone, PartialEq)]
pub struct SpaceVisited {
    /// Joint angles (rad).
    pub theta: Vec<f64>,
    /// The sphere's centre (m).
    pub obstacle: Vec3,
}

/// Angles uniform within `chain`'s limits (`[-pi, pi]` where it has none),
/// shrunk toward their middle by `shrink`.
fn uniform_pose(chain: &Chain, shrink: f64, rng: &mut Rng) -> Vec<f64> {
    use std::f64::consts::PI;
    (0..chain.dof())
        .map(|i| {
            let [lo, hi] = chain.joint_limits().map_or([-PI, PI], |l| l.ranges()[i]);
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo) * (1.0 - shrink));
            rng.range(mid - half, mid + half)
        })
        .collect()
}

fn uniform_in(min: Vec3, max: Vec3, rng: &mut Rng) -> Vec3 {
    [0, 1, 2].map(|k| rng.range(min[k], max[k]))
}

/// `n` poses for the `Phi` network: uniform within the limits with
/// `theta_1 = 0`, none below the floor.
pub fn phi_poses(
    chain: &Chain,
    s: &SpaceSampling,
    n: usize,
    rng: &mut Rng,
) -> Result<Vec<Vec<f64>>> {
    let mut out = Vec::with_capacity(n);
    let mut pose = SpacePose::of(chain);
    let mut tries = 0usize;
    while out.len() < n {
        tries += 1;
        if tries > 100 * n + 1000 {
            return Err(Error::Training(format!(
                "only {} of {n} poses clear the sigma floor {} m",
                out.len(),
                s.sigma_floor
            )));
        }
        let mut theta = uniform_pose(chain, 0.0, rng);
        theta[0] = 0.0;
        pose.update(chain, &theta)?;
        if linalg::smallest_singular_value3(pose.jjt()) >= s.sigma_floor {
            out.push(theta);
        }
    }
    Ok(out)
}

/// `n` states for the `v` network: every pose of the numerical runs of
/// `s.tasks` random lines, each with `s.obstacles_per_task` spheres, drawn
/// with replacement and jittered.
pub fn v_states(
    arm: &TrainArm,
    s: &SpaceSampling,
    n: usize,
    rng: &mut Rng,
) -> Result<Vec<SpaceVisited>> {
    let base = &arm.scene;
    let chain = &base.arm;
    let radius = arm.sphere_radius();
    let mut pool: Vec<SpaceVisited> = Vec::new();
    for _ in 0..s.tasks {
        let theta0 = uniform_pose(chain, 0.1, rng);
        let start = SpacePose::new(chain, &theta0)?.hand();
        let d = loop {
            let d = [rng.normal(), rng.normal(), rng.normal()];
            let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            if len > 1e-6 {
                break d.map(|x| x / len * s.line_length);
            }
        };
        for _ in 0..s.obstacles_per_task {
            let centre = uniform_in(s.obstacle_min, s.obstacle_max, rng);
            let mut scene = base.clone();
            scene.theta0.clone_from(&theta0);
            scene.target = [0, 1, 2].map(|k| start[k] + d[k]);
            scene.obstacles = vec![Sphere::new(centre, radius)];
            // A run that fails (a singular pose, a divergence) gives no poses.
            let Ok(run) = Planner::run(scene, Method::NUMERICAL, None) else {
                continue;
            };
            pool.extend(run.steps.into_iter().map(|x| SpaceVisited {
                theta: x.theta,
                obstacle: centre,
            }));
        }
    }
    if pool.is_empty() {
        return Err(Error::Training(
            "no numerical run of the random tasks finished".into(),
        ));
    }
    Ok((0..n)
        .map(|_| {
            let v = &pool[rng.below(pool.len())];
            SpaceVisited {
                theta: v
                    .theta
                    .iter()
                    .map(|t| t + s.theta_noise * rng.normal())
                    .collect(),
                obstacle: v.obstacle.map(|c| c + s.obstacle_noise * rng.normal()),
            }
        })
        .collect())
}

/// The training set of `spec`'s network.
pub fn space_dataset(spec: &SpaceTrainSpec) -> Result<Dataset> {
    let chain = spec.arm.chain();
    let n = chain.dof();
    let (n_in, n_out) = space_shape(spec.net, n);
    let mut set = Dataset::new(n_in, n_out);
    let mut rng = Rng::new(spec.seed);
    let mut x = vec![0.0; n_in];
    let mut y = vec![0.0; n_out];
    let mut pose = SpacePose::of(chain);
    let encode = |theta: &[f64], x: &mut [f64]| {
        for (pair, a) in x.chunks_exact_mut(2).zip(&theta[1..]) {
            let (s, c) = crate::kinematics::sin_cos(*a);
            pair[0] = s;
            pair[1] = c;
        }
    };
    match spec.net {
        NetKind::Phi => {
            for theta in phi_poses(chain, &spec.sampling, spec.samples, &mut rng)? {
                pose.update(chain, &theta)?;
                phi::pseudoinverse(pose.jacobian(), &mut y)?;
                encode(&theta, &mut x);
                set.push(&x, &y);
            }
        }
        NetKind::V => {
            for s in v_states(&spec.arm, &spec.sampling, spec.samples, &mut rng)? {
                pose.update(chain, &s.theta)?;
                y.iter_mut().for_each(|g| *g = 0.0);
                criterion::area_gradient_add(
                    chain,
                    &pose,
                    s.obstacle,
                    spec.sampling.sign_smoothing,
                    &mut y,
                );
                encode(&s.theta, &mut x);
                x[n_in - 3..].copy_from_slice(&rotated_obstacle(&pose, s.obstacle));
                set.push(&x, &y);
            }
        }
    }
    Ok(set)
}

/// Trains `spec`'s network and returns its weights file (`seconds` unset).
/// `on_epoch` sees every epoch; returning `false` stops.
pub fn train_space(
    spec: &SpaceTrainSpec,
    mut on_epoch: impl FnMut(&EpochReport) -> bool,
) -> Result<SpaceWeightsFile> {
    if spec.samples < 20 {
        return Err(Error::Training(format!(
            "{} samples are too few to train on (at least 20)",
            spec.samples
        )));
    }
    let chain = spec.arm.chain();
    let set = space_dataset(spec)?;
    let n_in = set.n_in;
    let mut min = vec![f64::INFINITY; n_in];
    let mut max = vec![f64::NEG_INFINITY; n_in];
    for row in set.inputs.chunks_exact(n_in) {
        for i in 0..n_in {
            min[i] = min[i].min(row[i]);
            max[i] = max[i].max(row[i]);
        }
    }
    let mut sizes = vec![set.n_in];
    sizes.extend_from_slice(&spec.hidden);
    sizes.push(set.n_out);
    let (mlp, report) = adam::train(&sizes, &set, spec.adam, spec.seed ^ 0x5EED, |r| on_epoch(r))?;
    let file = SpaceWeightsFile {
        format: FORMAT.into(),
        net: spec.net,
        variant: Variant::Equivariant,
        encoding: Encoding::Angles,
        tool_version: env!("CARGO_PKG_VERSION").into(),
        arm: chain.clone(),
        range: InputRange {
            names: space_input_names(spec.net, chain.dof()),
            min,
            max,
            sigma_floor: if spec.net == NetKind::Phi {
                spec.sampling.sigma_floor
            } else {
                0.0
            },
        },
        training: SpaceTraining {
            seed: spec.seed,
            samples: spec.samples,
            hidden: spec.hidden.clone(),
            adam: spec.adam,
            sampling: spec.sampling.clone(),
            seconds: None,
        },
        nets: vec![NetEntry { mlp, report }],
    };
    file.validate()?;
    Ok(file)
}

/// Median relative errors of `nets` on fresh samples of each network's
/// distribution (seed `seed`): `|Phi - J+| / |J+|` (Frobenius) and
/// `|g_net - g| / |g|`.
pub fn space_accuracy(
    arm: &TrainArm,
    nets: &SpaceNetworks,
    samples: usize,
    seed: u64,
) -> Result<(f64, f64)> {
    let phi_spec = SpaceTrainSpec {
        samples,
        seed,
        ..SpaceTrainSpec::reach(arm.clone(), NetKind::Phi, seed)
    };
    let v_spec = SpaceTrainSpec {
        samples,
        seed,
        ..SpaceTrainSpec::reach(arm.clone(), NetKind::V, seed)
    };
    let chain = arm.chain();
    let n = chain.dof();
    let mut rng = Rng::new(seed);
    let mut pose = SpacePose::of(chain);
    let (mut a, mut b) = (vec![0.0; 3 * n], vec![0.0; 3 * n]);
    let mut errs = Vec::with_capacity(samples);
    for mut theta in phi_poses(chain, &phi_spec.sampling, samples, &mut rng)? {
        theta[0] = rng.range(-2.8, 2.8);
        pose.update(chain, &theta)?;
        phi::pseudoinverse(pose.jacobian(), &mut a)?;
        nets.phi(&pose, &mut b)?;
        errs.push(relative(&b, &a));
    }
    let phi_err = median(&mut errs);
    errs.clear();
    let (mut g, mut h) = (vec![0.0; n], vec![0.0; n]);
    for s in v_states(arm, &v_spec.sampling, samples, &mut rng)? {
        pose.update(chain, &s.theta)?;
        g.iter_mut().for_each(|x| *x = 0.0);
        criterion::area_gradient_add(
            chain,
            &pose,
            s.obstacle,
            v_spec.sampling.sign_smoothing,
            &mut g,
        );
        nets.area_gradient(&pose, s.obstacle, &mut h)?;
        errs.push(relative(&h, &g));
    }
    Ok((phi_err, median(&mut errs)))
}

fn relative(got: &[f64], want: &[f64]) -> f64 {
    let d: f64 = got.iter().zip(want).map(|(x, y)| (x - y) * (x - y)).sum();
    let w: f64 = want.iter().map(|y| y * y).sum();
    (d / w.max(1e-300)).sqrt()
}

fn median(x: &mut [f64]) -> f64 {
    x.sort_by(f64::total_cmp);
    x.get(x.len() / 2).copied().unwrap_or(f64::NAN)
}
