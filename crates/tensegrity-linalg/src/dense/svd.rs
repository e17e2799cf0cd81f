//! The full singular value decomposition A = U Σ Vᵀ, the rank tolerance convention and the
//! orthonormal basis of a column span.

use super::{from_faer, to_faer};
use crate::error::Result;
use crate::failed;
use nalgebra::{DMatrix, DVector};

/// A full singular value decomposition A = U Σ Vᵀ.
#[derive(Debug, Clone)]
pub struct Svd {
    /// Left singular vectors (m×m).
    pub u: DMatrix<f64>,
    /// Singular values, non-increasing (min(m, n) of them).
    pub s: Vec<f64>,
    /// Right singular vectors (n×n).
    pub v: DMatrix<f64>,
}

impl Svd {
    /// Number of singular values above `tol` (absolute).
    pub fn rank(&self, tol: f64) -> usize {
        self.s.iter().take_while(|&&s| s > tol).count()
    }

    /// Minimal-norm least-squares solution x = V_r Σ_r⁻¹ U_rᵀ b, using the first `rank`
    /// singular triplets.
    pub fn solve_min_norm(&self, b: &DVector<f64>, rank: usize) -> DVector<f64> {
        let mut x = DVector::zeros(self.v.nrows());
        for k in 0..rank {
            let coef = self.u.column(k).dot(b) / self.s[k];
            x.axpy(coef, &self.v.column(k), 1.0);
        }
        x
    }
}

/// Full SVD of `a`. Empty matrices are handled (U and V are identities, no singular values).
///
/// ```
/// use nalgebra::DMatrix;
/// let a = DMatrix::from_row_slice(2, 2, &[3.0, 0.0, 0.0, -2.0]);
/// let svd = tensegrity_linalg::svd(&a).unwrap();
/// assert!((svd.s[0] - 3.0).abs() < 1e-14 && (svd.s[1] - 2.0).abs() < 1e-14);
/// ```
pub fn svd(a: &DMatrix<f64>) -> Result<Svd> {
    let (m, n) = a.shape();
    if m == 0 || n == 0 {
        return Ok(Svd {
            u: DMatrix::identity(m, m),
            s: Vec::new(),
            v: DMatrix::identity(n, n),
        });
    }
    let dec = to_faer(a).svd().map_err(failed("SVD", m.min(n)))?;
    let s = dec.S().column_vector();
    Ok(Svd {
        u: from_faer(dec.U()),
        s: (0..m.min(n)).map(|i| s[i]).collect(),
        v: from_faer(dec.V()),
    })
}

/// Absolute rank tolerance for an m×n matrix with largest singular value `s_max`:
/// `rel · s_max` when a relative tolerance is given, else `max(m, n) · ε · s_max`.
///
/// ```
/// let tol = tensegrity_linalg::rank_tolerance(10, 4, 2.0, None);
/// assert_eq!(tol, 10.0 * f64::EPSILON * 2.0);
/// ```
pub fn rank_tolerance(m: usize, n: usize, s_max: f64, rel: Option<f64>) -> f64 {
    match rel {
        Some(r) => r * s_max,
        None => m.max(n) as f64 * f64::EPSILON * s_max,
    }
}

/// An orthonormal basis (as columns) of the span of the columns of `a`, using the SVD with the
/// default rank tolerance (relative `rel` when given).
///
/// ```
/// use nalgebra::DMatrix;
/// // two parallel columns span a line
/// let a = DMatrix::from_row_slice(3, 2, &[1.0, 2.0, 0.0, 0.0, 1.0, 2.0]);
/// let q = tensegrity_linalg::orthonormal_basis(&a, None).unwrap();
/// assert_eq!(q.ncols(), 1);
/// assert!((q.column(0).norm() - 1.0).abs() < 1e-14);
/// ```
pub fn orthonormal_basis(a: &DMatrix<f64>, rel: Option<f64>) -> Result<DMatrix<f64>> {
    if a.ncols() == 0 || a.nrows() == 0 {
        return Ok(DMatrix::zeros(a.nrows(), 0));
    }
    let d = svd(a)?;
    let tol = rank_tolerance(a.nrows(), a.ncols(), d.s[0], rel);
    let r = d.rank(tol);
    Ok(d.u.columns(0, r).into_owned())
}
