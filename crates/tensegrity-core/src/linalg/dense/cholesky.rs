//! In-place dense Cholesky A = L Lᵀ for small SPD systems given in sparse (lower CSC) form.
//!
//! For a few dozen unknowns the per-call overhead of a sparse factorisation (permutation,
//! dispatch) is several times the flops of the dense one, so the Ω system of a structure with a
//! few class-k joints is factorised densely. L is stored row-major in preallocated storage;
//! [`DenseCholesky::factor`] and [`DenseCholesky::solve_in_place`] do not allocate.
//!
//! A pivot d_j ≤ ε · n · max_i |A_ii| (or NaN) counts as zero: the factorisation fails with
//! [`FactorizationFailure::NonPositivePivot`] (`pivot` = number of pivots that succeeded).

use crate::error::{FactorizationFailure, Result};
use crate::linalg::failure;
use crate::linalg::sparse::CscPattern;

/// A dense Cholesky factor of fixed order n with its storage.
#[derive(Debug, Clone)]
pub struct DenseCholesky {
    n: usize,
    /// Lower-triangular factor, row-major n×n (the strict upper part is scratch).
    l: Vec<f64>,
}

impl DenseCholesky {
    /// Storage for systems of order `n`.
    pub fn new(n: usize) -> Self {
        Self {
            n,
            l: vec![0.0; n * n],
        }
    }

    /// The order n.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// Factorises the SPD matrix whose lower triangle has the pattern `lower` (n×n, rows
    /// i ≥ j in column j) and the values `values`. Allocation-free.
    ///
    /// ```
    /// use tensegrity_core::linalg::{CscPattern, DenseCholesky};
    /// let p = CscPattern::new(2, vec![0, 2, 3], vec![0, 1, 1]).unwrap();
    /// let mut c = DenseCholesky::new(2);
    /// c.factor(&p, &[4.0, 1.0, 3.0]).unwrap();
    /// let mut x = [1.0, 2.0];
    /// c.solve_in_place(&mut x);
    /// assert!((x[0] - 1.0 / 11.0).abs() < 1e-15 && (x[1] - 7.0 / 11.0).abs() < 1e-15);
    /// assert!(c.factor(&p, &[1.0, 2.0, 1.0]).is_err()); // indefinite
    /// ```
    pub fn factor(&mut self, lower: &CscPattern, values: &[f64]) -> Result<()> {
        const OPERATION: &str = "dense Cholesky";
        let n = self.n;
        if lower.ncols() != n || lower.nrows() != n || values.len() != lower.nnz() {
            let reason = FactorizationFailure::DimensionMismatch {
                expected: lower.nnz(),
                found: values.len(),
            };
            return Err(failure(OPERATION, reason));
        }
        let a = self.zeroed();
        let (col_ptr, row_idx) = (lower.col_ptr(), lower.row_idx());
        for j in 0..n {
            for p in col_ptr[j]..col_ptr[j + 1] {
                a[row_idx[p] * n + j] = values[p];
            }
        }
        self.factor_filled()
    }

    /// The storage zeroed, for filling the lower triangle of A directly (row-major, entry
    /// (i, j), i ≥ j, at `i·n + j`) before [`factor_filled`](Self::factor_filled).
    pub(crate) fn zeroed(&mut self) -> &mut [f64] {
        // the lower triangle only: the strict upper part is never read
        let n = self.n;
        for (i, row) in self.l.chunks_exact_mut(n.max(1)).enumerate() {
            row[..=i].iter_mut().for_each(|v| *v = 0.0);
        }
        &mut self.l
    }

    /// Factorises the matrix whose lower triangle was filled into [`zeroed`](Self::zeroed)
    /// storage. Allocation-free.
    pub(crate) fn factor_filled(&mut self) -> Result<()> {
        const OPERATION: &str = "dense Cholesky";
        let n = self.n;
        let a = &mut self.l;
        let dmax = (0..n).map(|i| a[i * n + i].abs()).fold(0.0, f64::max);
        let tol = f64::EPSILON * n as f64 * dmax;
        // Left-looking: L_ij = (A_ij − Σ_{k<j} L_ik L_jk) / L_jj, each sum taken in order k =
        // 0, 1, … (the results are bit-identical to the plain loop). A sum is one dependency
        // chain of adds; four rows at a time run four independent chains side by side.
        for j in 0..n {
            let (head, tail) = a.split_at_mut((j + 1) * n);
            let row_j = &mut head[j * n..];
            let d = row_j[j] - row_j[..j].iter().map(|v| v * v).sum::<f64>();
            if d.is_nan() || d <= tol {
                let reason = FactorizationFailure::NonPositivePivot { pivot: j, dim: n };
                return Err(failure(OPERATION, reason));
            }
            let d = d.sqrt();
            row_j[j] = d;
            let row_j = &head[j * n..j * n + j];
            let mut rows = tail.chunks_exact_mut(n);
            loop {
                match (rows.next(), rows.next(), rows.next(), rows.next()) {
                    (Some(r0), Some(r1), Some(r2), Some(r3)) => {
                        let (mut s0, mut s1, mut s2, mut s3) = (-0.0, -0.0, -0.0, -0.0);
                        for (k, y) in row_j.iter().enumerate() {
                            s0 += r0[k] * y;
                            s1 += r1[k] * y;
                            s2 += r2[k] * y;
                            s3 += r3[k] * y;
                        }
                        r0[j] = (r0[j] - s0) / d;
                        r1[j] = (r1[j] - s1) / d;
                        r2[j] = (r2[j] - s2) / d;
                        r3[j] = (r3[j] - s3) / d;
                    }
                    (r0, r1, r2, _) => {
                        for row_i in [r0, r1, r2].into_iter().flatten() {
                            let v = row_i[j]
                                - row_i[..j]
                                    .iter()
                                    .zip(row_j)
                                    .map(|(x, y)| x * y)
                                    .sum::<f64>();
                            row_i[j] = v / d;
                        }
                        break;
                    }
                }
            }
        }
        Ok(())
    }

    /// Solves A x = b in place with the last factorisation. Allocation-free.
    ///
    /// # Panics
    /// If `b.len()` differs from the order n.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let n = self.n;
        assert_eq!(b.len(), n, "Cholesky solve: length of the right-hand side");
        if n == 0 {
            return;
        }
        let a = &self.l;
        for (i, row) in a.chunks_exact(n).enumerate() {
            let v = b[i]
                - row[..i]
                    .iter()
                    .zip(&b[..i])
                    .map(|(x, y)| x * y)
                    .sum::<f64>();
            b[i] = v / row[i];
        }
        for i in (0..n).rev() {
            let mut v = b[i];
            for k in i + 1..n {
                v -= a[k * n + i] * b[k];
            }
            b[i] = v / a[i * n + i];
        }
    }
}
