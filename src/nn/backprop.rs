//! The batched forward pass and back-propagation of an [`Mlp`] (`tansig`
//! hidden layers, `purelin` output) for first-order training
//! ([`crate::nn::adam`]): the gradient of a minibatch's mean squared error
//! by vector-Jacobian products, never a per-sample Jacobian.
//!
//! A batch of `b` samples is a matrix per layer, one column of `n_l`
//! contiguous activations per sample. With `W_l` (`s x r`, row-major in the
//! parameter vector of [`Mlp::params`]) and `A_l` (`r x b`):
//!
//! - forward: `A_{l+1} = f(W_l A_l + b_l 1^T)`;
//! - output error: `G_L = 2 (Y - T) / (b n_out)`, the derivative of the
//!   batch MSE;
//! - backward: `dW_l = G_{l+1} A_l^T`, `db_l = G_{l+1} 1`,
//!   `G_l = (W_l^T G_{l+1}) .* (1 - A_l .* A_l)`.
//!
//! Each product is one [`gemm`] over the batch. The workspace holds every buffer for the largest
//! batch, so a step allocates nothing.

use crate::error::{Error, Result};
use crate::nn::activation::tansig;
use crate::nn::gemm::{gemm, Mat, MatMut, Scratch};
use crate::nn::mlp::Mlp;

/// Buffers of the batched passes for one network shape and a largest batch.
#[derive(Debug, Clone)]
pub struct Backprop {
    /// Layer widths, input first.
    sizes: Vec<usize>,
    /// Offset of each layer's block (weights, then biases) in the parameters.
    offsets: Vec<usize>,
    /// Largest batch.
    capacity: usize,
    /// Activations of each layer (`acts[0]`: the inputs), `sizes[l] x capacity`.
    acts: Vec<Vec<f64>>,
    /// Error signals `G_l` of layers `1..`, `sizes[l] x capacity`.
    grads: Vec<Vec<f64>>,
    /// Targets of the batch, `n_out x capacity`.
    targets: Vec<f64>,
    scratch: Scratch,
}

impl Backprop {
    /// A workspace for networks of layer widths `sizes` (at least two, none
    /// zero: [`Mlp::validate`]'s rule) and batches of at most `capacity`
    /// samples (at least 1).
    pub fn new(sizes: &[usize], capacity: usize) -> Self {
        let capacity = capacity.max(1);
        let offsets = sizes
            .windows(2)
            .scan(0, |k, w| {
                let off = *k;
                *k += (w[0] + 1) * w[1];
                Some(off)
            })
            .collect();
        Self {
            sizes: sizes.to_vec(),
            offsets,
            capacity,
            acts: sizes.iter().map(|&n| vec![0.0; n * capacity]).collect(),
            grads: sizes.iter().map(|&n| vec![0.0; n * capacity]).collect(),
            targets: vec![0.0; sizes.last().copied().unwrap_or(0) * capacity],
            scratch: Scratch::default(),
        }
    }

    /// Largest batch.
    pub fn capacity(&self) -> usize {
        self.capacity
    }

    /// Number of parameters of the network shape.
    pub fn n_params(&self) -> usize {
        self.sizes.windows(2).map(|w| (w[0] + 1) * w[1]).sum()
    }

    /// Sample `c` of the batch: its input and target slots, to fill before
    /// [`Backprop::forward`] and [`Backprop::backward`].
    pub fn slots(&mut self, c: usize) -> (&mut [f64], &mut [f64]) {
        let (n_in, n_out) = (self.sizes[0], self.sizes[self.sizes.len() - 1]);
        (
            &mut self.acts[0][c * n_in..(c + 1) * n_in],
            &mut self.targets[c * n_out..(c + 1) * n_out],
        )
    }

    /// The network's scaled outputs for the first `b` samples, `n_out x b`
    /// column-major, after [`Backprop::forward`].
    pub fn outputs(&self, b: usize) -> &[f64] {
        let n_out = self.sizes[self.sizes.len() - 1];
        &self.acts[self.acts.len() - 1][..n_out * b]
    }

    /// Forward pass of the first `b` samples (`b <= capacity`) with the
    /// parameters `params` ([`Mlp::params`] order).
    pub fn forward(&mut self, params: &[f64], b: usize) {
        let last = self.sizes.len() - 2;
        for l in 0..=last {
            let (r, s) = (self.sizes[l], self.sizes[l + 1]);
            let block = &params[self.offsets[l]..self.offsets[l] + (r + 1) * s];
            let (w, bias) = block.split_at(r * s);
            let (lower, upper) = self.acts.split_at_mut(l + 1);
            let out = &mut upper[0][..s * b];
            for col in out.chunks_exact_mut(s) {
                col.copy_from_slice(bias);
            }
            gemm(
                1.0,
                Mat::row_major(w, s, r),
                Mat::col_major(&lower[l][..r * b], r, b),
                1.0,
                &mut MatMut::col_major(out, s, b),
                &mut self.scratch,
            );
            if l < last {
                out.iter_mut().for_each(|v| *v = tansig(*v));
            }
        }
    }

    /// Back-propagation after [`Backprop::forward`] of the same `b`
    /// samples: writes the gradient of the batch's mean squared error
    /// `sum (y - t)^2 / (b n_out)` with respect to `params` into `grad`
    /// and returns that error.
    pub fn backward(&mut self, params: &[f64], b: usize, grad: &mut [f64]) -> f64 {
        let n_layers = self.sizes.len() - 1;
        let n_out = self.sizes[n_layers];
        let scale = 2.0 / (b * n_out) as f64;
        let mut sse = 0.0;
        {
            let y = &self.acts[n_layers][..n_out * b];
            let g = &mut self.grads[n_layers][..n_out * b];
            for ((g, y), t) in g.iter_mut().zip(y).zip(&self.targets[..n_out * b]) {
                let e = y - t;
                sse += e * e;
                *g = scale * e;
            }
        }
        for l in (0..n_layers).rev() {
            let (r, s) = (self.sizes[l], self.sizes[l + 1]);
            let off = self.offsets[l];
            let (lower, upper) = self.grads.split_at_mut(l + 1);
            let g_out = &upper[0][..s * b];
            let a_in = &self.acts[l][..r * b];
            let (gw, gb) = grad[off..off + (r + 1) * s].split_at_mut(r * s);
            gemm(
                1.0,
                Mat::col_major(g_out, s, b),
                Mat::col_major(a_in, r, b).t(),
                0.0,
                &mut MatMut::row_major(gw, s, r),
                &mut self.scratch,
            );
            gb.iter_mut().for_each(|v| *v = 0.0);
            for col in g_out.chunks_exact(s) {
                for (v, g) in gb.iter_mut().zip(col) {
                    *v += g;
                }
            }
            if l > 0 {
                let w = &params[off..off + r * s];
                let g_in = &mut lower[l][..r * b];
                gemm(
                    1.0,
                    Mat::row_major(w, s, r).t(),
                    Mat::col_major(g_out, s, b),
                    0.0,
                    &mut MatMut::col_major(g_in, r, b),
                    &mut self.scratch,
                );
                for (g, a) in g_in.iter_mut().zip(a_in) {
                    *g *= 1.0 - a * a;
                }
            }
        }
        sse / (b * n_out) as f64
    }

    /// The batch mean squared error of `mlp` on scaled inputs `x` and
    /// targets `t` (row-major, one row per sample) and its gradient with
    /// respect to [`Mlp::params`], written to `grad`: the two passes above
    /// in one call, for checking them. Fails if the shapes disagree or the
    /// batch is empty or larger than the workspace.
    pub fn loss_and_gradient(
        &mut self,
        mlp: &Mlp,
        x: &[f64],
        t: &[f64],
        grad: &mut [f64],
    ) -> Result<f64> {
        let (n_in, n_out) = (self.sizes[0], self.sizes[self.sizes.len() - 1]);
        let b = x.len() / n_in;
        if mlp.sizes != self.sizes
            || b == 0
            || b > self.capacity
            || x.len() != b * n_in
            || t.len() != b * n_out
            || grad.len() != self.n_params()
        {
            return Err(Error::Training(format!(
                "a batch of {} inputs and {} targets does not fit a workspace for {:?} with room for {} samples",
                x.len(),
                t.len(),
                self.sizes,
                self.capacity
            )));
        }
        for c in 0..b {
            let (xi, ti) = self.slots(c);
            xi.copy_from_slice(&x[c * n_in..(c + 1) * n_in]);
            ti.copy_from_slice(&t[c * n_out..(c + 1) * n_out]);
        }
        let params = mlp.params();
        self.forward(&params, b);
        Ok(self.backward(&params, b, grad))
    }
}
