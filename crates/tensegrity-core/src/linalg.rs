//! The only module that touches faer: dense SVD and symmetric eigendecomposition on nalgebra
//! matrices.
//!
//! faer runs sequentially here (its `rayon` feature is off), so that parallel parameter sweeps
//! own the cores. Rank decisions use [`rank_tolerance`]: a singular value σ counts as zero when
//! σ ≤ max(m, n) · ε · σ_max (the MATLAB/NumPy convention), unless a caller supplies its own
//! relative tolerance.

use crate::error::{CoreError, Result};
use faer::{Mat, Side};
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

fn to_faer(a: &DMatrix<f64>) -> Mat<f64> {
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)])
}

fn from_faer(a: faer::MatRef<'_, f64>) -> DMatrix<f64> {
    DMatrix::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)])
}

/// Full SVD of `a`. Empty matrices are handled (U and V are identities, no singular values).
///
/// ```
/// use nalgebra::DMatrix;
/// let a = DMatrix::from_row_slice(2, 2, &[3.0, 0.0, 0.0, -2.0]);
/// let svd = tensegrity_core::linalg::svd(&a).unwrap();
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
    let f = to_faer(a);
    let dec = f
        .svd()
        .map_err(|_| CoreError::NoConvergence { operation: "SVD" })?;
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
/// let tol = tensegrity_core::linalg::rank_tolerance(10, 4, 2.0, None);
/// assert_eq!(tol, 10.0 * f64::EPSILON * 2.0);
/// ```
pub fn rank_tolerance(m: usize, n: usize, s_max: f64, rel: Option<f64>) -> f64 {
    match rel {
        Some(r) => r * s_max,
        None => m.max(n) as f64 * f64::EPSILON * s_max,
    }
}

/// Eigenvalues (non-decreasing) and orthonormal eigenvectors of a symmetric matrix.
///
/// ```
/// use nalgebra::DMatrix;
/// let a = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 2.0]);
/// let (w, _) = tensegrity_core::linalg::symmetric_eigen(&a).unwrap();
/// assert!((w[0] - 1.0).abs() < 1e-14 && (w[1] - 3.0).abs() < 1e-14);
/// ```
pub fn symmetric_eigen(a: &DMatrix<f64>) -> Result<(Vec<f64>, DMatrix<f64>)> {
    let n = a.nrows();
    if n == 0 {
        return Ok((Vec::new(), DMatrix::zeros(0, 0)));
    }
    let f = to_faer(a);
    let dec = f
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| CoreError::NoConvergence {
            operation: "symmetric eigendecomposition",
        })?;
    let s = dec.S().column_vector();
    Ok(((0..n).map(|i| s[i]).collect(), from_faer(dec.U())))
}

/// An orthonormal basis (as columns) of the span of the columns of `a`, using the SVD with the
/// default rank tolerance (relative `rel` when given).
pub fn orthonormal_basis(a: &DMatrix<f64>, rel: Option<f64>) -> Result<DMatrix<f64>> {
    if a.ncols() == 0 || a.nrows() == 0 {
        return Ok(DMatrix::zeros(a.nrows(), 0));
    }
    let d = svd(a)?;
    let tol = rank_tolerance(a.nrows(), a.ncols(), d.s[0], rel);
    let r = d.rank(tol);
    Ok(d.u.columns(0, r).into_owned())
}
