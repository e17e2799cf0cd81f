//! Dense factorisations on nalgebra matrices: SVD ([`svd()`]), symmetric eigendecomposition
//! ([`eigen`]), an in-place Cholesky for small SPD systems ([`cholesky`]) and an in-place LU
//! with partial pivoting for small general systems ([`lu`]) and the thin Q of a QR ([`thin_q`]).

pub mod cholesky;
pub mod eigen;
pub mod lu;
pub mod qr;
pub mod svd;

pub use cholesky::DenseCholesky;
pub use eigen::symmetric_eigen;
pub use lu::DenseLu;
pub use qr::thin_q;
pub use svd::{orthonormal_basis, rank_tolerance, svd, Svd};

use faer::Mat;
use nalgebra::DMatrix;

/// Copies a nalgebra matrix into faer storage.
fn to_faer(a: &DMatrix<f64>) -> Mat<f64> {
    Mat::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)])
}

/// Copies a faer matrix view into a nalgebra matrix.
fn from_faer(a: faer::MatRef<'_, f64>) -> DMatrix<f64> {
    DMatrix::from_fn(a.nrows(), a.ncols(), |i, j| a[(i, j)])
}
