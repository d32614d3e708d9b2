//! What every trainer of [`crate::nn`] shares: the [`Dataset`], the fresh
//! network it starts from (mapminmax maps fitted to the data, Nguyen-Widrow
//! weights) and the [`Prepared`] data (scaled to mapminmax units and split
//! at random into training, validation and test sets, as Matlab's
//! `dividerand` does). The Levenberg-Marquardt trainer ([`crate::nn::lm`])
//! and Adam ([`crate::nn::adam`]) draw from one seeded [`Rng`] in the same
//! order (initial weights, then the split), so for a seed both start from
//! the same network and the same split.

use crate::error::{Error, Result};
use crate::nn::mlp::{Activations, MapMinMax, Mlp};
use crate::nn::rng::Rng;

/// Training samples: `inputs` and `targets` row-major, one row per sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Dataset {
    /// Inputs per sample.
    pub n_in: usize,
    /// Targets per sample.
    pub n_out: usize,
    /// `len() * n_in` raw inputs.
    pub inputs: Vec<f64>,
    /// `len() * n_out` raw targets.
    pub targets: Vec<f64>,
}

impl Dataset {
    /// An empty set with the given widths.
    pub fn new(n_in: usize, n_out: usize) -> Self {
        Self {
            n_in,
            n_out,
            inputs: Vec::new(),
            targets: Vec::new(),
        }
    }

    /// Appends one sample.
    pub fn push(&mut self, input: &[f64], target: &[f64]) {
        self.inputs.extend_from_slice(&input[..self.n_in]);
        self.targets.extend_from_slice(&target[..self.n_out]);
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.inputs.len().checked_div(self.n_in).unwrap_or(0)
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// A fresh network of layer widths `sizes` for `data`: mapminmax maps
/// fitted to the data's inputs and targets, Nguyen-Widrow weights drawn
/// from `rng`. Fails if the first and last widths do not match the data.
pub fn fresh_network(sizes: &[usize], data: &Dataset, rng: &mut Rng) -> Result<Mlp> {
    if sizes.first() != Some(&data.n_in) || sizes.last() != Some(&data.n_out) {
        return Err(Error::Training(format!(
            "layer sizes {sizes:?} do not fit data with {} inputs and {} targets",
            data.n_in, data.n_out
        )));
    }
    let input_map = MapMinMax::fit(&data.inputs, data.n_in);
    let output_map = MapMinMax::fit(&data.targets, data.n_out);
    Mlp::nguyen_widrow(sizes, input_map, output_map, rng)
}

/// The data in the network's mapminmax units, split into training,
/// validation and test sets (indices into the rows of `x` and `t`).
#[derive(Debug, Clone)]
pub struct Prepared {
    /// Inputs per sample.
    pub n_in: usize,
    /// Targets per sample.
    pub n_out: usize,
    /// Scaled inputs, row-major.
    pub x: Vec<f64>,
    /// Scaled targets, row-major.
    pub t: Vec<f64>,
    /// Rows of the training set.
    pub train: Vec<usize>,
    /// Rows of the validation set.
    pub val: Vec<usize>,
    /// Rows of the test set (the rest).
    pub test: Vec<usize>,
}

impl Prepared {
    /// Checks `mlp` and `data` against each other (widths, finite numbers)
    /// and the split fractions `[train, validation]` against the number of
    /// samples, then scales the data with `mlp`'s maps and splits it by a
    /// shuffle drawn from `rng`.
    pub fn new(mlp: &Mlp, data: &Dataset, split: [f64; 2], rng: &mut Rng) -> Result<Self> {
        mlp.validate()?;
        if data.n_in != mlp.inputs() || data.n_out != mlp.outputs() {
            return Err(Error::Training(format!(
                "data has {} inputs and {} targets, the network {} and {}",
                data.n_in,
                data.n_out,
                mlp.inputs(),
                mlp.outputs()
            )));
        }
        if data.inputs.len() != data.len() * data.n_in
            || data.targets.len() != data.len() * data.n_out
        {
            return Err(Error::Training(format!(
                "data has {} inputs and {} targets, not whole rows of {} and {}",
                data.inputs.len(),
                data.targets.len(),
                data.n_in,
                data.n_out
            )));
        }
        if data
            .inputs
            .iter()
            .chain(&data.targets)
            .any(|v| !v.is_finite())
        {
            return Err(Error::NonFinite {
                what: "training data".into(),
            });
        }
        let n = data.len();
        let [ftrain, fval] = split;
        let ok = ftrain > 0.0 && fval >= 0.0 && ftrain + fval <= 1.0;
        if !ok {
            return Err(Error::Training(format!(
                "split fractions {ftrain} / {fval} must be positive and sum to at most 1"
            )));
        }
        let n_train = ((n as f64) * ftrain).round() as usize;
        let n_val = ((n as f64) * fval).round() as usize;
        if n_train == 0 || n_train + n_val > n {
            return Err(Error::Training(format!(
                "{n} samples are too few to split {ftrain} / {fval}"
            )));
        }
        let mut idx: Vec<usize> = (0..n).collect();
        rng.shuffle(&mut idx);
        let train = idx[..n_train].to_vec();
        let val = idx[n_train..n_train + n_val].to_vec();
        let test = idx[n_train + n_val..].to_vec();
        let (n_in, n_out) = (data.n_in, data.n_out);
        let mut x = Vec::with_capacity(data.inputs.len());
        for row in data.inputs.chunks_exact(n_in) {
            x.extend(
                row.iter()
                    .enumerate()
                    .map(|(i, &v)| mlp.input_map.apply(i, v)),
            );
        }
        let mut t = Vec::with_capacity(data.targets.len());
        for row in data.targets.chunks_exact(n_out) {
            t.extend(
                row.iter()
                    .enumerate()
                    .map(|(i, &v)| mlp.output_map.apply(i, v)),
            );
        }
        Ok(Self {
            n_in,
            n_out,
            x,
            t,
            train,
            val,
            test,
        })
    }

    /// Samples in the training, validation and test sets.
    pub fn split(&self) -> [usize; 3] {
        [self.train.len(), self.val.len(), self.test.len()]
    }

    /// Mean squared error (scaled units) of `mlp` on the rows `idx`, one
    /// sample at a time through [`Mlp::forward_scaled`]; 0 for no rows.
    pub fn mse(&self, mlp: &Mlp, idx: &[usize], acts: &mut Activations) -> f64 {
        if idx.is_empty() {
            return 0.0;
        }
        let mut sse = 0.0;
        for &i in idx {
            mlp.forward_scaled(&self.x[i * self.n_in..(i + 1) * self.n_in], acts);
            let y = acts.output();
            sse += y
                .iter()
                .zip(&self.t[i * self.n_out..(i + 1) * self.n_out])
                .map(|(a, b)| (b - a) * (b - a))
                .sum::<f64>();
        }
        sse / (idx.len() * self.n_out) as f64
    }
}
