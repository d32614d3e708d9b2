//! Training the networks (paper section V) for an arm: the data drawn from
//! the numerical route ([`sampling`]), the datasets of each network variant,
//! and [`train_weights`], which runs the Levenberg-Marquardt trainer of
//! [`crate::nn::lm`] and writes a weights file. Kept apart from the run-time
//! networks ([`crate::networks`]): the page's simulation needs none of it.

mod preset;
pub mod sampling;
pub mod space;
mod space_arm;
pub mod tasks;

use serde::{Deserialize, Serialize};

use crate::arm::Arm;
use crate::error::{Error, Result};
use crate::networks::file::{self as weights, InputRange, NetEntry, NetKind, Training, Variant};
use crate::networks::inputs::{self, MAX_INPUTS};
use crate::networks::Encoding;
use crate::networks::{Sampling, WeightsFile};
use crate::nn::adam::{self, AdamOptions};
use crate::nn::lm::{self, Dataset, EpochReport, LmOptions};
use crate::nn::rng::Rng;

pub use preset::Preset;
pub use sampling::{Visited, REACH_SIGN_SMOOTHING};

/// A named way of training an arm's networks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Recipe {
    /// The paper's (section V), as [`TrainSpec::for_arm`] adapts it: raw
    /// angles, data around the poses the tasks visit.
    Paper,
    /// Networks meant to hold over the whole workspace ([`TrainSpec::reach`]):
    /// angle features, `Phi` over the whole joint torus, `v` from runs
    /// with obstacles anywhere in the reach, the sign smoothed.
    Reach,
}

impl Recipe {
    /// Every recipe.
    pub const ALL: [Recipe; 2] = [Recipe::Paper, Recipe::Reach];

    /// The name on the command line and in the page.
    pub fn name(self) -> &'static str {
        match self {
            Recipe::Paper => "paper",
            Recipe::Reach => "reach",
        }
    }

    /// The training spec of this recipe for `arm`, `net` and `seed`.
    pub fn spec(self, arm: &Arm, net: NetKind, seed: u64) -> TrainSpec {
        match self {
            Recipe::Paper => {
                let variant = match net {
                    NetKind::Phi => crate::networks::DEFAULT_PHI_VARIANT,
                    NetKind::V => crate::networks::DEFAULT_V_VARIANT,
                };
                TrainSpec::for_arm(arm, net, variant, seed)
            }
            Recipe::Reach => TrainSpec::reach(arm, net, seed),
        }
    }
}

impl std::str::FromStr for Recipe {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        crate::error::by_name("recipe", s, &Recipe::ALL, Recipe::name)
    }
}

/// What to train: the arm, the quantity, the variant, the data and the
/// optimiser.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrainSpec {
    /// The arm the networks are for.
    pub arm: Arm,
    /// `phi` or `v`.
    pub net: NetKind,
    /// Input/output mapping.
    pub variant: Variant,
    /// How the joint angles enter the networks.
    #[serde(default)]
    pub encoding: Encoding,
    /// Seed for sampling, split and initial weights.
    pub seed: u64,
    /// Samples to draw.
    pub samples: usize,
    /// Hidden layer widths, e.g. `[35, 14]`.
    pub hidden: Vec<usize>,
    /// Levenberg-Marquardt options (unused when `adam` is set).
    pub options: LmOptions,
    /// Train by Adam with these options instead of by Levenberg-Marquardt
    /// (networks too wide for its `J^T J`, [`crate::nn::adam`]).
    #[serde(default)]
    pub adam: Option<AdamOptions>,
    /// How samples are drawn.
    pub sampling: Sampling,
}

impl TrainSpec {
    /// The paper's arm and architecture for `net` (hidden 35-14 for `Phi`,
    /// 25-14 for `v`) with 3000 samples and 400 epochs.
    pub fn paper(net: NetKind, variant: Variant, seed: u64) -> Self {
        Self {
            arm: Arm::paper(),
            net,
            variant,
            encoding: Encoding::Raw,
            seed,
            samples: 3000,
            hidden: match net {
                NetKind::Phi => vec![35, 14],
                NetKind::V => vec![25, 14],
            },
            options: LmOptions::default(),
            adam: None,
            sampling: Sampling::default(),
        }
    }

    /// [`TrainSpec::paper`] for any arm: the same architecture and
    /// optimiser, sampled as [`Sampling::for_arm`] says.
    pub fn for_arm(arm: &Arm, net: NetKind, variant: Variant, seed: u64) -> Self {
        Self {
            arm: arm.clone(),
            sampling: Sampling::for_arm(arm),
            ..Self::paper(net, variant, seed)
        }
    }

    /// Most epochs per network, of the optimiser in use.
    pub fn max_epochs(&self) -> usize {
        self.adam.map_or(self.options.max_epochs, |a| a.max_epochs)
    }

    /// Sets the most epochs per network, of the optimiser in use.
    pub fn set_max_epochs(&mut self, n: usize) {
        match &mut self.adam {
            Some(a) => a.max_epochs = n,
            None => self.options.max_epochs = n,
        }
    }

    /// The `reach` recipe for `arm` and `net`: rotation-equivariant
    /// networks over `(sin, cos)` of the angles, sampled as
    /// [`Sampling::reach`] says.
    /// `Phi` is a 96-96 network trained by Adam on 20 000 samples: the
    /// paper's 35-14 by Levenberg-Marquardt reaches a median relative
    /// error of 3.7e-2 over the torus, which two refinement steps cannot
    /// fix open loop (85% / 95% of the numerical route's atlas cells);
    /// 96-96 reaches 4.9e-3 (99% / 96%). `v` keeps the paper's 25-14 and
    /// optimiser, with 10 000 samples: its states, over many tasks and
    /// obstacles anywhere, are harder to fit than the paper's (3 000
    /// stopped at a validation MSE of 1e-2 against 6e-3). `docs/learning.md`.
    pub fn reach(arm: &Arm, net: NetKind, seed: u64) -> Self {
        let base = Self {
            encoding: Encoding::Angles,
            sampling: Sampling::reach(arm, net),
            ..Self::for_arm(arm, net, Variant::Equivariant, seed)
        };
        match net {
            NetKind::Phi => Self {
                samples: 20_000,
                hidden: vec![96, 96],
                adam: Some(AdamOptions::default()),
                ..base
            },
            NetKind::V => Self {
                samples: 10_000,
                ..base
            },
        }
    }
}

/// Draws `n` samples (poses and obstacle points) as `sampling` describes, from
/// a generator seeded with `seed`.
pub fn draw_samples(arm: &Arm, sampling: &Sampling, n: usize, seed: u64) -> Result<Vec<Visited>> {
    sampling.validate()?;
    let mut rng = Rng::new(seed);
    if sampling.whole_torus {
        return sampling.torus(arm, n, &mut rng);
    }
    let pool = sampling.visited(arm, &mut rng)?;
    sampling.draw(arm, &pool, n, &mut rng)
}

/// Training sets for `Phi` networks of `variant` and `encoding`: one per network.
pub fn phi_datasets(
    arm: &Arm,
    variant: Variant,
    encoding: Encoding,
    samples: &[Visited],
) -> Result<Vec<Dataset>> {
    let n = arm.dof();
    let (count, n_in, n_out) = weights::shape(NetKind::Phi, variant, encoding, n, 2)?;
    let mut sets = vec![Dataset::new(n_in, n_out); count];
    let mut buf = [0.0; MAX_INPUTS];
    for s in samples {
        check_sample(arm, s)?;
        let theta = &s.theta[..];
        let target = match variant {
            Variant::Equivariant => {
                let mut t0 = theta.to_vec();
                t0[0] = 0.0;
                sampling::phi_target(arm, &t0)?
            }
            _ => sampling::phi_target(arm, theta)?,
        };
        let x = inputs::phi_inputs(variant, encoding, theta, &mut buf);
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

/// Training set for the `v` network of `variant` and `encoding`, its
/// targets' sign smoothed by `eps` ([`crate::obstacle::smoothed_sign`]).
pub fn v_dataset(
    arm: &Arm,
    variant: Variant,
    encoding: Encoding,
    eps: f64,
    samples: &[Visited],
) -> Result<Dataset> {
    let (_, n_in, n_out) = weights::shape(NetKind::V, variant, encoding, arm.dof(), 2)?;
    let mut set = Dataset::new(n_in, n_out);
    let mut buf = [0.0; MAX_INPUTS];
    for s in samples {
        check_sample(arm, s)?;
        let x = inputs::v_inputs(
            variant,
            encoding,
            arm.post(),
            &s.theta,
            s.theta[0].sin_cos(),
            s.obstacle,
            &mut buf,
        );
        set.push(x, &sampling::v_target(arm, &s.theta, s.obstacle, eps));
    }
    Ok(set)
}

/// A sample fits `arm` and is finite: the right number of angles, none
/// beyond [`crate::arm::MAX_ANGLE`], an obstacle point within
/// [`crate::error::MAX_COORDINATE`]. (Drawn samples always are; samples
/// handed in by a caller are checked, since a non-finite one would
/// poison the `mapminmax` ranges of the whole set.)
fn check_sample(arm: &Arm, s: &Visited) -> Result<()> {
    arm.check_angles(&s.theta)?;
    crate::error::coordinate("obstacle x", s.obstacle[0])?;
    crate::error::coordinate("obstacle y", s.obstacle[1])?;
    Ok(())
}

/// Trains the networks `spec` describes for its arm and returns the
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
    let arm = &spec.arm;
    let samples = draw_samples(arm, &spec.sampling, spec.samples, spec.seed)?;
    let sets = match spec.net {
        NetKind::Phi => phi_datasets(arm, spec.variant, spec.encoding, &samples)?,
        NetKind::V => vec![v_dataset(
            arm,
            spec.variant,
            spec.encoding,
            spec.sampling.sign_smoothing,
            &samples,
        )?],
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
        let (mlp, report) = match spec.adam {
            Some(opts) => adam::train(&sizes, set, opts, seed, |r| on_epoch(k, r))?,
            None => lm::train(&sizes, set, spec.options, seed, |r| on_epoch(k, r))?,
        };
        nets.push(NetEntry { mlp, report });
    }
    let file = WeightsFile {
        format: weights::FORMAT.to_string(),
        net: spec.net,
        variant: spec.variant,
        encoding: spec.encoding,
        tool_version: env!("CARGO_PKG_VERSION").to_string(),
        arm: arm.clone(),
        range: InputRange {
            names: inputs::input_names(spec.net, spec.variant, spec.encoding, arm.dof()),
            min,
            max,
            sigma_floor: spec.sampling.sigma_floor,
        },
        training: Training {
            seed: spec.seed,
            samples: spec.samples,
            hidden: spec.hidden.clone(),
            options: spec.options,
            adam: spec.adam,
            sampling: spec.sampling.clone(),
            seconds: None,
        },
        nets,
    };
    file.validate()?;
    Ok(file)
}
