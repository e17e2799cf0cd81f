//! Complex dense SVD A = U Σ Vᴴ for the small Hermitian-free blocks of the symmetry-adapted
//! statics (`tensegrity_statics::symmetry`): one block per irreducible representation of Cₙ,
//! complex for the representations k ≠ 0, n/2.
//!
//! The singular values of a complex block are real, non-negative and non-increasing; the rank
//! decision uses the same tolerance convention as the real SVD ([`super::rank_tolerance`]).

use crate::error::Result;
use crate::failed;
use faer::{c64, Mat};
use nalgebra::{Complex, DMatrix};

/// A full complex singular value decomposition A = U Σ Vᴴ.
#[derive(Debug, Clone)]
pub struct ComplexSvd {
    /// Left singular vectors (m×m, unitary).
    pub u: DMatrix<Complex<f64>>,
    /// Singular values, non-increasing (min(m, n) of them).
    pub s: Vec<f64>,
    /// Right singular vectors (n×n, unitary).
    pub v: DMatrix<Complex<f64>>,
}

impl ComplexSvd {
    /// Number of singular values above `tol` (absolute).
    pub fn rank(&self, tol: f64) -> usize {
        self.s.iter().take_while(|&&s| s > tol).count()
    }
}

fn to_faer(a: &DMatrix<Complex<f64>>) -> Mat<c64> {
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| {
        let z = a[(i, j)];
        c64::new(z.re, z.im)
    })
}

fn from_faer(a: faer::MatRef<'_, c64>) -> DMatrix<Complex<f64>> {
    DMatrix::from_fn(a.nrows(), a.ncols(), |i, j| {
        let z = a[(i, j)];
        Complex::new(z.re, z.im)
    })
}

/// Full SVD of a complex matrix (empty matrices give identities and no singular values).
///
/// ```
/// use nalgebra::{Complex, DMatrix};
/// // [[i, 0], [0, 2]]: singular values 2 and 1
/// let a = DMatrix::from_row_slice(2, 2, &[
///     Complex::new(0.0, 1.0), Complex::new(0.0, 0.0),
///     Complex::new(0.0, 0.0), Complex::new(2.0, 0.0),
/// ]);
/// let d = tensegrity_linalg::complex_svd(&a).unwrap();
/// assert!((d.s[0] - 2.0).abs() < 1e-14 && (d.s[1] - 1.0).abs() < 1e-14);
/// ```
pub fn complex_svd(a: &DMatrix<Complex<f64>>) -> Result<ComplexSvd> {
    let (m, n) = a.shape();
    if m == 0 || n == 0 {
        return Ok(ComplexSvd {
            u: DMatrix::identity(m, m),
            s: Vec::new(),
            v: DMatrix::identity(n, n),
        });
    }
    let dec = to_faer(a).svd().map_err(failed("complex SVD", m.min(n)))?;
    let s = dec.S().column_vector();
    Ok(ComplexSvd {
        u: from_faer(dec.U()),
        s: (0..m.min(n)).map(|i| s[i].re).collect(),
        v: from_faer(dec.V()),
    })
}

/// The singular values of a complex matrix, non-increasing (no singular vectors: cheaper).
///
/// ```
/// use nalgebra::{Complex, DMatrix};
/// // a rank-one matrix u vᴴ with |u| = √2, |v| = √2: one singular value 2
/// let one = Complex::new(1.0, 0.0);
/// let i = Complex::new(0.0, 1.0);
/// let a = DMatrix::from_row_slice(2, 2, &[one, -i, i, one]);
/// let s = tensegrity_linalg::complex_singular_values(&a).unwrap();
/// assert!((s[0] - 2.0).abs() < 1e-14 && s[1].abs() < 1e-14);
/// ```
pub fn complex_singular_values(a: &DMatrix<Complex<f64>>) -> Result<Vec<f64>> {
    let (m, n) = a.shape();
    if m == 0 || n == 0 {
        return Ok(Vec::new());
    }
    let mut s = to_faer(a)
        .singular_values()
        .map_err(failed("complex singular values", m.min(n)))?;
    s.sort_by(|x, y| y.total_cmp(x));
    Ok(s)
}
