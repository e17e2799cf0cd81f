//! Sparse LU factorisation P A Q = L U with partial pivoting, for general square systems (the
//! global Michell equilibrium).
//!
//! faer computes a COLAMD column ordering Q and chooses a supernodal or simplicial numeric
//! factorisation by its flop-ratio heuristic; rows are pivoted during the numeric phase. A
//! structurally singular matrix fails with [`FactorizationFailure::StructurallySingular`]; a
//! numerically singular one may factorise, so callers should check the residual of the
//! solution.

use super::CscMatrix;
use crate::error::{FactorizationFailure, Result};
use crate::{failed, failure};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::lu::{
    factorize_symbolic_lu, LuRef, LuSymbolicParams, NumericLu, SymbolicLu,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::{Conj, MatMut, Par};

/// A sparse LU factorisation, ready for solves.
pub struct SparseLu {
    n: usize,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    buf: MemBuffer,
}

impl std::fmt::Debug for SparseLu {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseLu").field("dim", &self.n).finish()
    }
}

impl SparseLu {
    /// Symbolic and numeric factorisation of the square matrix `a`.
    pub fn new(a: &CscMatrix) -> Result<Self> {
        let n = a.pattern().ncols();
        if a.pattern().nrows() != n {
            let reason = FactorizationFailure::DimensionMismatch {
                expected: n,
                found: a.pattern().nrows(),
            };
            return Err(failure("sparse LU", reason));
        }
        let symbolic = factorize_symbolic_lu(
            a.pattern().as_faer(),
            LuSymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::AUTO,
                ..Default::default()
            },
        )
        .map_err(failed("sparse LU (symbolic)", n))?;
        let mut numeric = NumericLu::<usize, f64>::new();
        let scratch = symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default());
        let mut buf = MemBuffer::try_new(scratch).map_err(failed("sparse LU (numeric)", n))?;
        symbolic
            .factorize_numeric_lu(
                &mut numeric,
                a.as_faer(),
                Par::Seq,
                MemStack::new(&mut buf),
                Default::default(),
            )
            .map_err(failed("sparse LU (numeric)", n))?;
        let scratch = symbolic.solve_in_place_scratch::<f64>(1, Par::Seq);
        let buf = MemBuffer::try_new(scratch).map_err(failed("sparse LU (solve)", n))?;
        Ok(Self {
            n,
            symbolic,
            numeric,
            buf,
        })
    }

    /// The order n of the system.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Solves A x = b in place. Allocation-free.
    ///
    /// # Panics
    /// If `b.len()` differs from the order of the system.
    pub fn solve_in_place(&mut self, b: &mut [f64]) {
        assert_eq!(b.len(), self.n, "LU solve: length of the right-hand side");
        let lu = LuRef::new_unchecked(&self.symbolic, &self.numeric);
        let x = MatMut::from_column_major_slice_mut(b, self.n, 1);
        lu.solve_in_place_with_conj(Conj::No, x, Par::Seq, MemStack::new(&mut self.buf));
    }
}

/// Solves the square system A x = b by sparse LU (allocating: one factorisation per call).
///
/// ```
/// use tensegrity_linalg::{lu_solve, CscMatrix};
/// // [[0, 2], [1, 1]] x = [2, 3]  →  x = [2, 1] (needs a row exchange)
/// let a = CscMatrix::from_triplets(2, 2, &[(1, 0, 1.0), (0, 1, 2.0), (1, 1, 1.0)]).unwrap();
/// let x = lu_solve(&a, &[2.0, 3.0]).unwrap();
/// assert!((x[0] - 2.0).abs() < 1e-15 && (x[1] - 1.0).abs() < 1e-15);
/// ```
pub fn lu_solve(a: &CscMatrix, b: &[f64]) -> Result<Vec<f64>> {
    let mut lu = SparseLu::new(a)?;
    if b.len() != lu.dim() {
        let reason = FactorizationFailure::DimensionMismatch {
            expected: lu.dim(),
            found: b.len(),
        };
        return Err(failure("sparse LU (solve)", reason));
    }
    let mut x = b.to_vec();
    lu.solve_in_place(&mut x);
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    #[test]
    fn matches_a_dense_solve_and_reuses_the_factorisation() {
        // a nonsymmetric, diagonally weak 30×30 banded matrix with a zero diagonal entry
        let n = 30;
        let mut t = Vec::new();
        for i in 0..n {
            if i != 7 {
                t.push((i, i, 0.5 + (i as f64 * 0.3).sin()));
            }
            t.push(((i + 1) % n, i, 2.0 + 0.1 * i as f64));
            t.push(((i + 5) % n, i, -1.0));
        }
        let a = CscMatrix::from_triplets(n, n, &t).unwrap();
        let mut dense = DMatrix::zeros(n, n);
        for &(r, c, v) in &t {
            dense[(r, c)] += v;
        }
        let mut lu = SparseLu::new(&a).unwrap();
        for k in 0..2 {
            let b: Vec<f64> = (0..n).map(|i| ((i + k) as f64).cos()).collect();
            let expected = dense
                .clone()
                .lu()
                .solve(&DVector::from_column_slice(&b))
                .unwrap();
            let mut x = b.clone();
            lu.solve_in_place(&mut x);
            let once = lu_solve(&a, &b).unwrap();
            for i in 0..n {
                assert!((x[i] - expected[i]).abs() < 1e-10 * expected.amax());
                assert_eq!(x[i], once[i]);
            }
        }
    }

    #[test]
    fn structurally_singular_and_bad_input_fail() {
        // column 1 is empty
        let a = CscMatrix::from_triplets(2, 2, &[(0, 0, 1.0), (1, 0, 1.0)]).unwrap();
        assert!(matches!(
            lu_solve(&a, &[1.0, 1.0]),
            Err(crate::LinalgError { .. })
        ));
        let ok = CscMatrix::from_triplets(2, 2, &[(0, 0, 1.0), (1, 1, 1.0)]).unwrap();
        assert!(lu_solve(&ok, &[1.0]).is_err());
        let rect = CscMatrix::from_triplets(3, 2, &[(0, 0, 1.0), (1, 1, 1.0)]).unwrap();
        assert!(SparseLu::new(&rect).is_err());
    }
}
