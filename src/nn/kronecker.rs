//! The normal equations of Levenberg-Marquardt, `J^T J` and `J^T e`, from
//! the layer structure of a feed-forward network's Jacobian.
//!
//! Written by hand because no library knows this structure. For sample `s`
//! and output `m`, the gradient with respect to layer `l`'s weights and
//! biases is an outer product: `dy_m / dW_l[o][j] = delta_l^m[o] a_{l-1}[j]`
//! and `dy_m / db_l[o] = delta_l^m[o]`, i.e. `delta_l^m (x) a~_{l-1}` with
//! `a~ = (a, 1)` ([`Mlp::sensitivities`]). So the block of `J^T J` between
//! layers `l` and `k` is
//!
//! `sum_s sum_m (delta_l^m (x) a~_l)(delta_k^m (x) a~_k)^T
//!  = sum_s D_lk^s (x) (a~_l^s a~_k^sT)`, with `D_lk^s = sum_m delta_l^m delta_k^mT`.
//!
//! Entry `((o, j), (p, i))` of the block is `sum_s D^s[o][p] a~^s[j] a~'^s[i]`:
//! one matrix product `Z_lk = W^T D` over the samples, where row `s` of `W`
//! holds the products `a~^s[j] a~'^s[i]` and row `s` of `D` the entries of
//! `D^s`. That costs `P^2` multiply-adds per sample instead of `P^2` per
//! sample *and output* when `J^T J` is summed over `J`'s rows: 8 times fewer
//! for the paper's 2-35-14-6 network (6 outputs; 0.80e9 against 6.2e9 per
//! epoch on 2,100 samples), in large products that `matrixmultiply` runs
//! near the machine's peak (in the page's SIMD build, [`crate::nn::gemm`]'s
//! wasm kernel instead). Only the blocks `l >= k` are computed; the
//! matrix is then filled symmetrically.

use nalgebra::{DMatrix, DVector};
#[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
use nalgebra::{Dyn, MatrixView, U1};

use crate::nn::gemm::Scratch;
#[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
use crate::nn::gemm::{gemm, Mat, MatMut};
use crate::nn::mlp::{Activations, Mlp};

/// Largest `W` buffer (entries): the sample block shrinks for wide layers so
/// the workspace stays below 16 MB.
const MAX_W_ENTRIES: usize = 1 << 21;

/// Workspace of the normal equations, owned by the trainer and reused every
/// epoch.
#[derive(Debug, Clone, Default)]
pub struct Normal {
    /// Layer widths, input first.
    sizes: Vec<usize>,
    /// Samples per block.
    block: usize,
    /// For each layer, its inputs with a trailing 1 (`a~`), one row of
    /// `sizes[l] + 1` per sample of the block.
    inputs: Vec<Vec<f64>>,
    /// Sensitivities per sample of the block ([`Mlp::sensitivities`] layout).
    sens: Vec<f64>,
    /// Output errors `e = t - y` per sample of the block.
    err: Vec<f64>,
    /// `W` and `D` of one layer pair, row-major, one row per sample.
    w: Vec<f64>,
    d: Vec<f64>,
    /// The layer pairs `(l, k)`, `l >= k`, and their accumulated `Z_lk`
    /// (`(r_l + 1)(r_k + 1) x s_l s_k`).
    pairs: Vec<(usize, usize)>,
    z: Vec<DMatrix<f64>>,
    /// Packing space of the SIMD build's products.
    #[cfg_attr(
        not(all(target_arch = "wasm32", target_feature = "simd128")),
        allow(dead_code)
    )]
    scratch: Scratch,
}

impl Normal {
    /// A workspace for a network of layer widths `sizes`, summing `block`
    /// samples per product (fewer for very wide layers).
    pub fn new(sizes: &[usize], block: usize) -> Self {
        let n_layers = sizes.len() - 1;
        let r = |l: usize| sizes[l] + 1;
        let s = |l: usize| sizes[l + 1];
        let mut pairs = Vec::new();
        for l in 0..n_layers {
            for k in 0..=l {
                pairs.push((l, k));
            }
        }
        let widest_w = pairs.iter().map(|&(l, k)| r(l) * r(k)).max().unwrap_or(1);
        let widest_d = pairs.iter().map(|&(l, k)| s(l) * s(k)).max().unwrap_or(1);
        let block = block.clamp(1, (MAX_W_ENTRIES / widest_w).max(1));
        let total: usize = sizes[1..].iter().sum();
        Self {
            sizes: sizes.to_vec(),
            block,
            inputs: (0..n_layers).map(|l| vec![0.0; block * r(l)]).collect(),
            sens: vec![0.0; block * sizes[n_layers] * total],
            err: vec![0.0; block * sizes[n_layers]],
            w: vec![0.0; block * widest_w],
            d: vec![0.0; block * widest_d],
            z: pairs
                .iter()
                .map(|&(l, k)| DMatrix::zeros(r(l) * r(k), s(l) * s(k)))
                .collect(),
            pairs,
            scratch: Scratch::default(),
        }
    }

    /// `J^T J` (full, symmetric) and `J^T e` of `mlp` over the samples
    /// `idx` of the scaled data `x` (inputs) and `t` (targets).
    pub fn accumulate(
        &mut self,
        mlp: &Mlp,
        x: &[f64],
        t: &[f64],
        idx: &[usize],
        acts: &mut Activations,
    ) -> (DMatrix<f64>, DVector<f64>) {
        let sizes = self.sizes.clone();
        let n_layers = sizes.len() - 1;
        let (n_in, n_out) = (sizes[0], sizes[n_layers]);
        let total: usize = sizes[1..].iter().sum();
        let sens_len = n_out * total;
        let offsets = mlp.param_offsets();
        let n_params = mlp.n_params();
        let mut jte = DVector::<f64>::zeros(n_params);
        self.z.iter_mut().for_each(|z| z.fill(0.0));
        // Where each layer's sensitivities start in a [m][l][o] block.
        let sens_off: Vec<usize> = sizes[1..]
            .iter()
            .scan(0, |k, s| {
                let off = *k;
                *k += s;
                Some(off)
            })
            .collect();
        for chunk in idx.chunks(self.block) {
            for (c, &i) in chunk.iter().enumerate() {
                mlp.forward_scaled(&x[i * n_in..(i + 1) * n_in], acts);
                let y = acts.output();
                let e = &mut self.err[c * n_out..(c + 1) * n_out];
                for (o, eo) in e.iter_mut().enumerate() {
                    *eo = t[i * n_out + o] - y[o];
                }
                for (l, inputs) in self.inputs.iter_mut().enumerate() {
                    let r1 = sizes[l] + 1;
                    let row = &mut inputs[c * r1..(c + 1) * r1];
                    row[..r1 - 1].copy_from_slice(mlp.layer_input(acts, l));
                    row[r1 - 1] = 1.0;
                }
                let sens = &mut self.sens[c * sens_len..(c + 1) * sens_len];
                mlp.sensitivities(acts, sens);
                // J^T e, layer by layer: (sum_m e_m delta_l^m) (x) a~.
                for l in 0..n_layers {
                    let (r, s) = (sizes[l], sizes[l + 1]);
                    let a = &self.inputs[l][c * (r + 1)..(c + 1) * (r + 1)];
                    for o in 0..s {
                        let u: f64 = (0..n_out)
                            .map(|m| e[m] * sens[m * total + sens_off[l] + o])
                            .sum();
                        let base = offsets[l];
                        for (j, aj) in a[..r].iter().enumerate() {
                            jte[base + o * r + j] += u * aj;
                        }
                        jte[base + r * s + o] += u;
                    }
                }
            }
            let n = chunk.len();
            for (pair, z) in self.pairs.iter().zip(self.z.iter_mut()) {
                let (l, k) = *pair;
                let (rl, rk) = (sizes[l] + 1, sizes[k] + 1);
                let (sl, sk) = (sizes[l + 1], sizes[k + 1]);
                let (cw, cd) = (rl * rk, sl * sk);
                for c in 0..n {
                    let al = &self.inputs[l][c * rl..(c + 1) * rl];
                    let ak = &self.inputs[k][c * rk..(c + 1) * rk];
                    let wrow = &mut self.w[c * cw..(c + 1) * cw];
                    for (wj, aj) in wrow.chunks_exact_mut(rk).zip(al) {
                        for (w, ai) in wj.iter_mut().zip(ak) {
                            *w = aj * ai;
                        }
                    }
                    let sens = &self.sens[c * sens_len..(c + 1) * sens_len];
                    let drow = &mut self.d[c * cd..(c + 1) * cd];
                    drow.iter_mut().for_each(|v| *v = 0.0);
                    for m in 0..n_out {
                        let dl = &sens[m * total + sens_off[l]..][..sl];
                        let dk = &sens[m * total + sens_off[k]..][..sk];
                        for (dro, &x) in drow.chunks_exact_mut(sk).zip(dl) {
                            if x != 0.0 {
                                for (v, &y) in dro.iter_mut().zip(dk) {
                                    *v += x * y;
                                }
                            }
                        }
                    }
                }
                // Z (cw x cd) += W^T (cw x n) D (n x cd). W row-major n x cw
                // is W^T column-major; D row-major n x cd is a strided view.
                #[cfg(not(all(target_arch = "wasm32", target_feature = "simd128")))]
                {
                    let wt = MatrixView::<f64, Dyn, Dyn, U1, Dyn>::from_slice_with_strides_generic(
                        &self.w[..n * cw],
                        Dyn(cw),
                        Dyn(n),
                        U1,
                        Dyn(cw),
                    );
                    let dm = MatrixView::<f64, Dyn, Dyn, Dyn, U1>::from_slice_with_strides_generic(
                        &self.d[..n * cd],
                        Dyn(n),
                        Dyn(cd),
                        Dyn(cd),
                        U1,
                    );
                    z.gemm(1.0, &wt, &dm, 1.0);
                }
                // matrixmultiply's scalar kernel in wasm: the SIMD one instead.
                #[cfg(all(target_arch = "wasm32", target_feature = "simd128"))]
                gemm(
                    1.0,
                    Mat::col_major(&self.w[..n * cw], cw, n),
                    Mat::row_major(&self.d[..n * cd], n, cd),
                    1.0,
                    &mut MatMut::col_major(z.as_mut_slice(), cw, cd),
                    &mut self.scratch,
                );
            }
        }
        // Scatter Z_lk into J^T J in the parameter order of `Mlp::params`:
        // within layer l, weight (o, j) at o r + j, bias o at r s + o.
        let mut jtj = DMatrix::<f64>::zeros(n_params, n_params);
        let index = |l: usize, o: usize, j: usize| {
            let (r, s) = (sizes[l], sizes[l + 1]);
            offsets[l] + if j < r { o * r + j } else { r * s + o }
        };
        for (&(l, k), z) in self.pairs.iter().zip(&self.z) {
            let (rl, rk) = (sizes[l] + 1, sizes[k] + 1);
            let (sl, sk) = (sizes[l + 1], sizes[k + 1]);
            for o in 0..sl {
                for p in 0..sk {
                    let col = o * sk + p;
                    for j in 0..rl {
                        let row_param = index(l, o, j);
                        for i in 0..rk {
                            let col_param = index(k, p, i);
                            if l == k && col_param > row_param {
                                continue;
                            }
                            let v = z[(j * rk + i, col)];
                            jtj[(row_param, col_param)] = v;
                            jtj[(col_param, row_param)] = v;
                        }
                    }
                }
            }
        }
        (jtj, jte)
    }
}
