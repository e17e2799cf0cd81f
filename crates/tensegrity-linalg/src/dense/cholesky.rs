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
use crate::failure;
use crate::sparse::CscPattern;

/// A dense Cholesky factor of fixed order n with its storage.
#[derive(Debug, Clone)]
pub struct DenseCholesky {
    n: usize,
    /// Lower-triangular factor, row-major n×n; the strict upper part holds Lᵀ (row j: column
    /// j of L below the diagonal).
    l: Vec<f64>,
    /// 1 / L_jj (the solves multiply instead of dividing).
    inv_diag: Vec<f64>,
}

impl DenseCholesky {
    /// Storage for systems of order `n`.
    pub fn new(n: usize) -> Self {
        Self {
            n,
            l: vec![0.0; n * n],
            inv_diag: vec![0.0; n],
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
    /// use tensegrity_linalg::{CscPattern, DenseCholesky};
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
    pub fn zeroed(&mut self) -> &mut [f64] {
        // the lower triangle only: the strict upper part is written before it is read
        let n = self.n;
        for (i, row) in self.l.chunks_exact_mut(n.max(1)).enumerate() {
            row[..=i].iter_mut().for_each(|v| *v = 0.0);
        }
        &mut self.l
    }

    /// Factorises the matrix whose lower triangle was filled into [`zeroed`](Self::zeroed)
    /// storage. Allocation-free.
    pub fn factor_filled(&mut self) -> Result<()> {
        const OPERATION: &str = "dense Cholesky";
        let n = self.n;
        let a = &mut self.l;
        let inv_diag = &mut self.inv_diag;
        let dmax = (0..n).map(|i| a[i * n + i].abs()).fold(0.0, f64::max);
        let tol = f64::EPSILON * n as f64 * dmax;
        // Right-looking (outer-product) form: after step j the trailing rows hold
        // A_ik − Σ_{p≤j} l_ip l_kp. Column j of L is kept twice: in the lower triangle (the
        // factor) and in the strict upper part of row j (contiguous, for the rank-1 update of
        // the trailing rows and the forward solve). The update loops carry no dependency
        // chain, so they pipeline and vectorise; zero multipliers (structural zeros of the
        // constraint systems) skip their row.
        for j in 0..n {
            let (head, tail) = a.split_at_mut((j + 1) * n);
            let row_j = &mut head[j * n..];
            let d = row_j[j];
            if d.is_nan() || d <= tol {
                let reason = FactorizationFailure::NonPositivePivot { pivot: j, dim: n };
                return Err(failure(OPERATION, reason));
            }
            let d = d.sqrt();
            row_j[j] = d;
            let inv_d = 1.0 / d;
            inv_diag[j] = inv_d;
            for (i, row_i) in (j + 1..n).zip(tail.chunks_exact_mut(n)) {
                let l = row_i[j] * inv_d;
                row_i[j] = l;
                row_j[i] = l;
            }
            let col_j = &row_j[..];
            for (i, row_i) in (j + 1..n).zip(tail.chunks_exact_mut(n)) {
                let l = col_j[i];
                if l != 0.0 {
                    for (x, c) in row_i[j + 1..=i].iter_mut().zip(&col_j[j + 1..=i]) {
                        *x -= l * c;
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
        // forward L y = b by columns (column j of L is the upper part of row j), backward
        // Lᵀ x = y by rows of L: both are contiguous axpy updates
        for (j, row) in a.chunks_exact(n).enumerate() {
            let y = b[j] * self.inv_diag[j];
            b[j] = y;
            if y != 0.0 {
                for (x, l) in b[j + 1..].iter_mut().zip(&row[j + 1..]) {
                    *x -= l * y;
                }
            }
        }
        for (i, row) in a.chunks_exact(n).enumerate().rev() {
            let x = b[i] * self.inv_diag[i];
            b[i] = x;
            if x != 0.0 {
                for (v, l) in b[..i].iter_mut().zip(&row[..i]) {
                    *v -= l * x;
                }
            }
        }
    }
}
