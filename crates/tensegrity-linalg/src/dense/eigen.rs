//! The symmetric eigendecomposition A = Q Λ Qᵀ.

use super::{from_faer, to_faer};
use crate::error::Result;
use crate::failed;
use faer::Side;
use nalgebra::DMatrix;

/// Eigenvalues (non-decreasing) and orthonormal eigenvectors (as columns) of a symmetric
/// matrix; only the lower triangle of `a` is read.
///
/// ```
/// use nalgebra::DMatrix;
/// let a = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 2.0]);
/// let (w, _) = tensegrity_linalg::symmetric_eigen(&a).unwrap();
/// assert!((w[0] - 1.0).abs() < 1e-14 && (w[1] - 3.0).abs() < 1e-14);
/// ```
pub fn symmetric_eigen(a: &DMatrix<f64>) -> Result<(Vec<f64>, DMatrix<f64>)> {
    let n = a.nrows();
    if n == 0 {
        return Ok((Vec::new(), DMatrix::zeros(0, 0)));
    }
    let dec = to_faer(a)
        .self_adjoint_eigen(Side::Lower)
        .map_err(failed("symmetric eigendecomposition", n))?;
    let s = dec.S().column_vector();
    Ok(((0..n).map(|i| s[i]).collect(), from_faer(dec.U())))
}
