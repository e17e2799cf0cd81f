//! Thin QR: for A (m × n, m ≥ n) the Q (m × n) with orthonormal columns and A = Q R, R upper
//! triangular (Householder reflections, faer). Used to orthonormalise a basis that is known
//! to have full column rank (no rank decision here: that is the SVD's job).

use super::{from_faer, to_faer};
use nalgebra::DMatrix;

/// The thin Q factor of `a` (its columns span the column space of `a` when `a` has full
/// column rank).
pub fn thin_q(a: &DMatrix<f64>) -> DMatrix<f64> {
    let q = to_faer(a).qr().compute_thin_Q();
    from_faer(q.as_ref())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn q_is_orthonormal_and_spans_a() {
        let a = DMatrix::from_row_slice(4, 2, &[1.0, 2.0, 0.0, 1.0, 3.0, -1.0, 1.0, 1.0]);
        let q = thin_q(&a);
        let qtq = q.transpose() * &q;
        assert!((qtq - DMatrix::identity(2, 2)).norm() < 1e-14);
        // A = Q Qᵀ A when Q spans the columns of A
        assert!((&q * (q.transpose() * &a) - &a).norm() < 1e-13);
    }
}
