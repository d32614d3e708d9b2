//! A feed-forward network as Matlab's `newff` builds it: `tansig` hidden
//! layers, a `purelin` output layer, and `mapminmax` scaling of inputs and
//! outputs to `[-1, 1]` stored with the weights (paper section V).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::nn::activation::tansig;
use crate::nn::rng::Rng;

/// Matlab's `mapminmax` with the default `[-1, 1]` target range:
/// `y = 2 (x - min) / (max - min) - 1` per entry. An entry with
/// `max == min` (a constant) maps to `0` (Matlab passes it through as `ymin`
/// shifted; any constant works because the network sees no variation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MapMinMax {
    /// Smallest value of each entry in the data the map was fitted to.
    pub min: Vec<f64>,
    /// Largest value of each entry.
    pub max: Vec<f64>,
}

impl MapMinMax {
    /// Fits the map to `rows` of `width` values each (row-major data).
    pub fn fit(data: &[f64], width: usize) -> Self {
        let mut min = vec![f64::INFINITY; width];
        let mut max = vec![f64::NEG_INFINITY; width];
        for row in data.chunks_exact(width) {
            for (i, &x) in row.iter().enumerate() {
                min[i] = min[i].min(x);
                max[i] = max[i].max(x);
            }
        }
        for i in 0..width {
            if !min[i].is_finite() || !max[i].is_finite() {
                min[i] = -1.0;
                max[i] = 1.0;
            }
        }
        Self { min, max }
    }

    /// Number of entries.
    pub fn len(&self) -> usize {
        self.min.len()
    }

    /// Whether the map has no entries.
    pub fn is_empty(&self) -> bool {
        self.min.is_empty()
    }

    #[inline]
    fn gain(&self, i: usize) -> f64 {
        let r = self.max[i] - self.min[i];
        if r > 0.0 {
            2.0 / r
        } else {
            1.0
        }
    }

    /// Raw value to `[-1, 1]` (entry `i`).
    #[inline]
    pub fn apply(&self, i: usize, x: f64) -> f64 {
        if self.max[i] > self.min[i] {
            (x - self.min[i]) * self.gain(i) - 1.0
        } else {
            x - self.min[i]
        }
    }

    /// `[-1, 1]` back to a raw value (entry `i`).
    #[inline]
    pub fn reverse(&self, i: usize, y: f64) -> f64 {
        if self.max[i] > self.min[i] {
            (y + 1.0) / self.gain(i) + self.min[i]
        } else {
            y + self.min[i]
        }
    }
}

/// One fully connected layer: `a_out = f(W a_in + b)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Layer {
    /// `W`, `outputs x inputs`, row-major (row `r` holds the weights into neuron `r`).
    pub weights: Vec<f64>,
    /// `b`, one per neuron.
    pub biases: Vec<f64>,
}

/// A multilayer perceptron: `sizes = [inputs, hidden..., outputs]`; every
/// hidden layer uses `tansig` (`tanh`), the output layer is `purelin`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Mlp {
    /// Layer widths, input first: `[3, 35, 14, 6]` is the paper's Phi net with 6 outputs.
    pub sizes: Vec<usize>,
    /// `sizes.len() - 1` layers.
    pub layers: Vec<Layer>,
    /// Scaling of raw inputs to `[-1, 1]`.
    pub input_map: MapMinMax,
    /// Scaling of raw targets to `[-1, 1]`; the network's raw output is its reverse.
    pub output_map: MapMinMax,
}

impl Mlp {
    /// Nguyen-Widrow initialisation (Matlab `initnw`) for `tansig` layers
    /// fed by inputs in `[-1, 1]`: each neuron's weight vector is a random
    /// direction of length `0.7 S^(1/R)` (`S` neurons, `R` inputs) and the
    /// biases spread the active regions evenly over `[-1, 1]`. The `purelin`
    /// output layer starts uniform in `[-1, 1]` scaled by `1/sqrt(fan-in)`.
    pub fn nguyen_widrow(
        sizes: &[usize],
        input_map: MapMinMax,
        output_map: MapMinMax,
        rng: &mut Rng,
    ) -> Result<Self> {
        check_sizes(sizes)?;
        let last = sizes.len() - 2;
        let mut layers = Vec::with_capacity(sizes.len() - 1);
        for (l, w) in sizes.windows(2).enumerate() {
            let (r, s) = (w[0], w[1]);
            let mut weights = vec![0.0; r * s];
            let mut biases = vec![0.0; s];
            if l < last {
                let beta = 0.7 * (s as f64).powf(1.0 / r as f64);
                for i in 0..s {
                    let row = &mut weights[i * r..(i + 1) * r];
                    let mut norm = 0.0;
                    while norm < 1e-8 {
                        for x in row.iter_mut() {
                            *x = rng.range(-1.0, 1.0);
                        }
                        norm = row.iter().map(|x| x * x).sum::<f64>().sqrt();
                    }
                    for x in row.iter_mut() {
                        *x *= beta / norm;
                    }
                    let spread = if s > 1 {
                        -1.0 + 2.0 * i as f64 / (s - 1) as f64
                    } else {
                        0.0
                    };
                    biases[i] = beta * spread * row[0].signum();
                }
            } else {
                let scale = 1.0 / (r as f64).sqrt();
                for x in weights.iter_mut() {
                    *x = rng.range(-1.0, 1.0) * scale;
                }
                for b in biases.iter_mut() {
                    *b = rng.range(-1.0, 1.0) * scale;
                }
            }
            layers.push(Layer { weights, biases });
        }
        let mlp = Self {
            sizes: sizes.to_vec(),
            layers,
            input_map,
            output_map,
        };
        mlp.validate()?;
        Ok(mlp)
    }

    /// Number of inputs.
    pub fn inputs(&self) -> usize {
        self.sizes[0]
    }

    /// Number of outputs.
    pub fn outputs(&self) -> usize {
        self.sizes[self.sizes.len() - 1]
    }

    /// Number of weights and biases.
    pub fn n_params(&self) -> usize {
        self.sizes.windows(2).map(|w| (w[0] + 1) * w[1]).sum()
    }

    /// Checks shapes and finiteness: every weight matrix `sizes[l+1] x sizes[l]`,
    /// every bias vector `sizes[l+1]`, both maps of the right length with
    /// `min <= max`, and every number finite.
    pub fn validate(&self) -> Result<()> {
        check_sizes(&self.sizes)?;
        if self.layers.len() != self.sizes.len() - 1 {
            return Err(Error::Weights(format!(
                "{} layers for sizes {:?} (expected {})",
                self.layers.len(),
                self.sizes,
                self.sizes.len() - 1
            )));
        }
        for (l, (layer, w)) in self.layers.iter().zip(self.sizes.windows(2)).enumerate() {
            if layer.weights.len() != w[0] * w[1] {
                return Err(Error::Weights(format!(
                    "layer {}: {} weights, expected {} x {} = {}",
                    l + 1,
                    layer.weights.len(),
                    w[1],
                    w[0],
                    w[0] * w[1]
                )));
            }
            if layer.biases.len() != w[1] {
                return Err(Error::Weights(format!(
                    "layer {}: {} biases, expected {}",
                    l + 1,
                    layer.biases.len(),
                    w[1]
                )));
            }
            if layer
                .weights
                .iter()
                .chain(&layer.biases)
                .any(|x| !x.is_finite())
            {
                return Err(Error::Weights(format!(
                    "layer {}: a weight or bias is not a finite number",
                    l + 1
                )));
            }
        }
        check_map("input", &self.input_map, self.inputs())?;
        check_map("output", &self.output_map, self.outputs())?;
        Ok(())
    }

    /// Forward pass on raw values, as Matlab computes it: scale `x` with
    /// `mapminmax`, run the layers, scale back. The reference form (the
    /// trainer's view); the planner uses the folded, vectorised
    /// [`Kernel`](crate::nn::kernel::Kernel) built from it. Missing inputs
    /// count as zero.
    pub fn forward(&self, x: &[f64]) -> Vec<f64> {
        let mut a: Vec<f64> = (0..self.inputs())
            .map(|i| self.input_map.apply(i, x.get(i).copied().unwrap_or(0.0)))
            .collect();
        let last = self.layers.len() - 1;
        for (l, layer) in self.layers.iter().enumerate() {
            a = layer
                .weights
                .chunks_exact(self.sizes[l])
                .zip(&layer.biases)
                .map(|(row, bias)| {
                    let z = bias + dot(row, &a);
                    if l < last {
                        tansig(z)
                    } else {
                        z
                    }
                })
                .collect();
        }
        a.iter()
            .enumerate()
            .map(|(i, y)| self.output_map.reverse(i, *y))
            .collect()
    }

    /// All weights and biases, layer by layer, each layer's weights row-major
    /// followed by its biases: the parameter vector the trainer updates.
    pub fn params(&self) -> Vec<f64> {
        let mut p = Vec::with_capacity(self.n_params());
        for layer in &self.layers {
            p.extend_from_slice(&layer.weights);
            p.extend_from_slice(&layer.biases);
        }
        p
    }

    /// Sets the parameters from a vector in [`Mlp::params`] order.
    pub fn set_params(&mut self, p: &[f64]) {
        let mut k = 0;
        for layer in &mut self.layers {
            let nw = layer.weights.len();
            layer.weights.copy_from_slice(&p[k..k + nw]);
            k += nw;
            let nb = layer.biases.len();
            layer.biases.copy_from_slice(&p[k..k + nb]);
            k += nb;
        }
    }

    /// Forward pass in the scaled domain (input and output both in mapminmax
    /// units), keeping every layer's activation in `acts` (`acts[0]` is the
    /// input). Used by the trainer.
    pub fn forward_scaled(&self, xn: &[f64], acts: &mut Activations) {
        acts.a[0].copy_from_slice(&xn[..self.inputs()]);
        let last = self.layers.len() - 1;
        for (l, layer) in self.layers.iter().enumerate() {
            let (before, after) = acts.a.split_at_mut(l + 1);
            let input = &before[l];
            let out = &mut after[0];
            for (o, (row, bias)) in out
                .iter_mut()
                .zip(layer.weights.chunks_exact(self.sizes[l]).zip(&layer.biases))
            {
                let z = bias + dot(row, input);
                *o = if l < last { tansig(z) } else { z };
            }
        }
    }

    /// Offset of each layer's block (weights row-major, then biases) in the
    /// parameter vector of [`Mlp::params`].
    pub fn param_offsets(&self) -> Vec<usize> {
        self.sizes
            .windows(2)
            .scan(0, |k, w| {
                let off = *k;
                *k += (w[0] + 1) * w[1];
                Some(off)
            })
            .collect()
    }

    /// Back-propagated sensitivities at the activations of the last
    /// [`Mlp::forward_scaled`] call: `delta_l^m = d y_m / d z_l`, the
    /// derivative of scaled output `m` with respect to the pre-activations
    /// `z_l` of layer `l`. Written to `out` as `[m][l][o]`: for each output,
    /// every layer's `sizes[l + 1]` values in turn (`outputs() x` the sum of
    /// the layer widths). The top layer is `purelin`, so `delta_top^m = e_m`;
    /// below, `delta_{l-1} = (W_l^T delta_l) (1 - a_{l-1}^2)` (`tansig`).
    pub fn sensitivities(&self, acts: &Activations, out: &mut [f64]) {
        let n_layers = self.layers.len();
        let widths = &self.sizes[1..];
        let total: usize = widths.iter().sum();
        let offsets: Vec<usize> = widths
            .iter()
            .scan(0, |k, s| {
                let off = *k;
                *k += s;
                Some(off)
            })
            .collect();
        for (m, block) in out.chunks_exact_mut(total).take(self.outputs()).enumerate() {
            let top = &mut block[offsets[n_layers - 1]..];
            top.iter_mut().for_each(|d| *d = 0.0);
            top[m] = 1.0;
            for l in (1..n_layers).rev() {
                let (r, s) = (self.sizes[l], self.sizes[l + 1]);
                let (lower, upper) = block.split_at_mut(offsets[l]);
                let delta = &upper[..s];
                let prev = &mut lower[offsets[l - 1]..offsets[l - 1] + r];
                prev.iter_mut().for_each(|x| *x = 0.0);
                let weights = &self.layers[l].weights;
                for (o, &d) in delta.iter().enumerate() {
                    if d != 0.0 {
                        for (pv, w) in prev.iter_mut().zip(&weights[o * r..(o + 1) * r]) {
                            *pv += w * d;
                        }
                    }
                }
                for (pv, a) in prev.iter_mut().zip(&acts.a[l]) {
                    *pv *= 1.0 - a * a;
                }
            }
        }
    }

    /// Derivative of every scaled output with respect to every parameter at
    /// the activations of the last [`Mlp::forward_scaled`] call: output `j`'s
    /// gradient goes to `jac[j * n_params .. (j + 1) * n_params]`, in
    /// [`Mlp::params`] order: `dy_j / dW_l[o][i] = delta_l^j[o] a_{l-1}[i]`,
    /// `dy_j / db_l[o] = delta_l^j[o]` (see [`Mlp::sensitivities`]).
    pub fn output_jacobian(&self, acts: &mut Activations, jac: &mut [f64]) {
        let p = self.n_params();
        let offsets = self.param_offsets();
        let total: usize = self.sizes[1..].iter().sum();
        let mut sens = std::mem::take(&mut acts.sens);
        sens.resize(self.outputs() * total, 0.0);
        self.sensitivities(acts, &mut sens);
        for (row, block) in jac.chunks_exact_mut(p).zip(sens.chunks_exact(total)) {
            let mut d0 = 0;
            for (l, &off) in offsets.iter().enumerate() {
                let (r, s) = (self.sizes[l], self.sizes[l + 1]);
                let delta = &block[d0..d0 + s];
                for (o, &d) in delta.iter().enumerate() {
                    for (x, a) in row[off + o * r..off + (o + 1) * r]
                        .iter_mut()
                        .zip(&acts.a[l])
                    {
                        *x = d * a;
                    }
                    row[off + r * s + o] = d;
                }
                d0 += s;
            }
        }
        acts.sens = sens;
    }

    /// Layer `l`'s input in the last [`Mlp::forward_scaled`] call (`l = 0`:
    /// the scaled network input).
    pub fn layer_input<'a>(&self, acts: &'a Activations, l: usize) -> &'a [f64] {
        &acts.a[l]
    }
}

/// Scratch space for [`Mlp::forward_scaled`] and [`Mlp::output_jacobian`].
#[derive(Debug, Clone)]
pub struct Activations {
    a: Vec<Vec<f64>>,
    /// Sensitivities for [`Mlp::output_jacobian`].
    sens: Vec<f64>,
}

impl Activations {
    /// Buffers for a network with these layer widths.
    pub fn new(sizes: &[usize]) -> Self {
        Self {
            a: sizes.iter().map(|&s| vec![0.0; s]).collect(),
            sens: Vec::new(),
        }
    }

    /// Scaled outputs of the last forward pass.
    pub fn output(&self) -> &[f64] {
        &self.a[self.a.len() - 1]
    }
}

#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    // Four accumulators let the compiler keep several multiply-adds in flight.
    let mut s = [0.0; 4];
    let ca = a.chunks_exact(4);
    let cb = b.chunks_exact(4);
    let (ra, rb) = (ca.remainder(), cb.remainder());
    for (x, y) in ca.zip(cb) {
        s[0] += x[0] * y[0];
        s[1] += x[1] * y[1];
        s[2] += x[2] * y[2];
        s[3] += x[3] * y[3];
    }
    let mut t = (s[0] + s[1]) + (s[2] + s[3]);
    for (x, y) in ra.iter().zip(rb) {
        t += x * y;
    }
    t
}

fn check_sizes(sizes: &[usize]) -> Result<()> {
    if sizes.len() < 2 {
        return Err(Error::Weights(format!(
            "layer sizes {sizes:?}: need at least an input and an output size"
        )));
    }
    if sizes.contains(&0) {
        return Err(Error::Weights(format!(
            "layer sizes {sizes:?}: every layer needs at least one neuron"
        )));
    }
    if sizes.iter().any(|&s| s > 100_000) {
        return Err(Error::Weights(format!(
            "layer sizes {sizes:?}: a layer wider than 100000 is not supported"
        )));
    }
    Ok(())
}

fn check_map(what: &str, map: &MapMinMax, n: usize) -> Result<()> {
    if map.min.len() != n || map.max.len() != n {
        return Err(Error::Weights(format!(
            "{what} mapminmax has {} min / {} max entries, expected {n}",
            map.min.len(),
            map.max.len()
        )));
    }
    for i in 0..n {
        let (lo, hi) = (map.min[i], map.max[i]);
        if !lo.is_finite() || !hi.is_finite() {
            return Err(Error::Weights(format!(
                "{what} mapminmax entry {i} is not finite"
            )));
        }
        if lo > hi {
            return Err(Error::Weights(format!(
                "{what} mapminmax entry {i}: min {lo} exceeds max {hi}"
            )));
        }
    }
    Ok(())
}
