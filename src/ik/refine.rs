//! The refinement of a learned `Phi` toward the pseudoinverse on the
//! pose's `J` (Cases 1 and 3, `refine`): Newton-Schulz steps, the
//! projection onto the range of `J^T`, and the check that the steps can
//! converge.

use super::size_error;
use crate::error::{Error, Result};
use crate::kinematics::jjt;

/// Refines an approximate right inverse `Phi` of `J` in place toward the
/// pseudoinverse `J+ = J^T (J J^T)^-1` (eq. 20 with `delta = 0`, what the
/// network of eq. 19 learns): `steps` Newton-Schulz steps
/// `Phi <- Phi (2 I - J Phi)`, and right after the first of them the
/// projection `Phi <- J^T (Phi^T Phi)`, which is not counted as a step.
///
/// With `J Phi = I + E`, a step gives `J Phi' = (I + E)(I - E) = I - E^2`:
/// the error is squared. Steps alone converge to `Phi_0 (J Phi_0)^-1`, a
/// right inverse with the network's range, whose null-space projector
/// `I - Phi J` stays oblique by the network's error. The projection fixes
/// the range: with `A = J J^T`, `J+^T J+ = A^-1`, so `J+` is its fixed
/// point, and its output `J^T M` keeps that form under the steps
/// (`J^T M (2 I - A M) = J^T M'`), whose only right inverse is `J+`. The
/// later steps therefore converge to `J+` itself, and `I - Phi J` to the
/// orthogonal projector.
///
/// It is applied once, after the first step rather than before it: a
/// second projection would only add error, and the projection's own error
/// is first order in the error of its input. Writing the input as
/// `J+ + D` with `J D = E`, the projection leaves
/// `J Phi - I = E + A E^T A^-1 + A D^T D`; after one step `E` is `-E_0^2`
/// and `D` is the network's null-space error `(I - J+ J) D_0` to first
/// order, so all three terms are of second order. (Projecting first
/// roughly doubles `E_0` and shrinks the region where the steps converge;
/// `docs/learning.md`, "Refinement", has the numbers.) So `steps = 1` is a
/// step and the projection, with `J Phi - I` of the order of `E_0^2`, and
/// every further step squares it. The projection costs one product more
/// (`Phi^T Phi` and `J^T` times it), as much as a step; each step is two
/// small products with the `J` that eq. (21) evaluates anyway. An exact
/// pseudoinverse is left as it is. `phi` row-major (`2n`), `jac`
/// column-major; allocation-free.
///
/// Newton-Schulz converges only where the spectral radius of `E = J Phi -
/// I` is below 1 (`E` is squared at each step): before each step it is
/// checked (in closed form for the `2 x 2` `E`), and where it is 1 or more
/// the refinement gives up, `Ok(false)` (`phi` then holds no refined
/// inverse: the caller hands the step to the exact route, as the spatial
/// refinement does with `|E|_F`, [`crate::space::phi::refine_phi`]);
/// without the check a network far from any inverse made the steps diverge
/// to non-finite numbers. `Ok(true)`: refined. A non-finite `Phi` is
/// refused.
pub fn refine_phi(phi: &mut [f64], jac: &[f64], steps: u32) -> Result<bool> {
    // Phi (n x 2) and J (2 x n) have as many entries.
    if phi.len() != jac.len() {
        return Err(size_error("Phi (n x 2)", jac.len(), phi.len()));
    }
    for step in 0..steps {
        if !newton_schulz_step(phi, jac) {
            return Ok(false);
        }
        if step == 0 {
            project_onto_range_of_jt(phi, jac);
        }
    }
    if phi.iter().any(|x| !x.is_finite()) {
        return Err(Error::NonFinite {
            what: "refined Phi".into(),
        });
    }
    Ok(true)
}

/// `2 I - J Phi`, row-major 2 x 2.
fn two_minus_j_phi(phi: &[f64], jac: &[f64]) -> [f64; 4] {
    let mut m = [2.0, 0.0, 0.0, 2.0];
    for (j, p) in jac.chunks_exact(2).zip(phi.chunks_exact(2)) {
        m[0] -= j[0] * p[0];
        m[1] -= j[0] * p[1];
        m[2] -= j[1] * p[0];
        m[3] -= j[1] * p[1];
    }
    m
}

/// Whether the spectral radius of `E = I - J Phi` is below 1, for `m = 2 I
/// - J Phi` (`E = m - I`; false on NaN): the eigenvalues of the `2 x 2` `E`
/// are `(tr +- sqrt(tr^2 - 4 det)) / 2`, a complex pair of modulus
/// `sqrt(det)` where the root is imaginary.
fn converges(m: &[f64; 4]) -> bool {
    let (a, b, c, d) = (m[0] - 1.0, m[1], m[2], m[3] - 1.0);
    let (tr, det) = (a + d, a * d - b * c);
    let disc = tr * tr - 4.0 * det;
    let radius = if disc >= 0.0 {
        0.5 * (tr.abs() + disc.sqrt())
    } else {
        det.sqrt()
    };
    radius < 1.0
}

/// `Phi <- Phi (2 I - J Phi)` in place (one step of [`refine_phi`]);
/// refused (`false`, `phi` unchanged) where the steps cannot converge
/// ([`converges`]).
fn newton_schulz_step(phi: &mut [f64], jac: &[f64]) -> bool {
    let m = two_minus_j_phi(phi, jac);
    if !converges(&m) {
        return false;
    }
    for row in phi.chunks_exact_mut(2) {
        let (x, y) = (row[0], row[1]);
        row[0] = x * m[0] + y * m[2];
        row[1] = x * m[1] + y * m[3];
    }
    true
}

/// `Phi <- J^T (Phi^T Phi)` in place, the projection of [`refine_phi`]: row
/// `i` of the result is column `i` of `J` times the symmetric 2x2
/// `Phi^T Phi`.
fn project_onto_range_of_jt(phi: &mut [f64], jac: &[f64]) {
    let [p, q, r] = jjt(phi);
    for (row, col) in phi.chunks_exact_mut(2).zip(jac.chunks_exact(2)) {
        row[0] = col[0] * p + col[1] * q;
        row[1] = col[0] * q + col[1] * r;
    }
}
