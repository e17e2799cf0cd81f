//! Sparse matrices in compressed sparse column (CSC) form and their factorisations.
//!
//! A [`CscPattern`] holds the structure (column pointers and sorted row indices); a
//! [`CscMatrix`] adds one value per stored entry. Symmetric matrices are given by their lower
//! triangle (rows i ≥ j in column j). The factorisations:
//!
//! - [`ordering`]: the fill-reducing approximate-minimum-degree ordering of a symmetric pattern;
//! - [`cholesky`]: A = L Lᵀ for SPD matrices with a fixed pattern, symbolic analysis once and a
//!   numeric refactorisation per call (the in-house [`StaticCholesky`] and the general
//!   [`SparseCholesky`]);
//! - [`block3`]: the same for systems whose unknowns come in groups of up to three with a
//!   shared pattern ([`Block3Cholesky`]: 3×3 blocks, the Ω system of the rigid-bar dynamics);
//! - [`lu`]: P A Q = L U with partial pivoting for general square matrices;
//! - [`rrqr`]: a rank-revealing staircase Householder QR of a banded rectangular matrix that
//!   rejects dependent columns (rank, null spaces and least squares of the equilibrium matrix
//!   of large structures without the SVD's full U and V);
//! - [`frontal`]: a rank-revealing multifrontal QR of Aᵀ along a nested-dissection tree
//!   (rank and certificate of lattices, whose band is too wide for [`rrqr`]).

pub mod block3;
pub mod cholesky;
pub mod frontal;
pub mod lu;
pub mod ordering;
pub mod rrqr;
mod sigma_min;

pub use block3::Block3Cholesky;
pub use cholesky::{cholesky_solve, SparseCholesky, StaticCholesky};
pub use frontal::FrontalQr;
pub use lu::{lu_solve, SparseLu};
pub use ordering::amd_ordering;
pub use rrqr::RankRevealingQr;

use super::failure;
use crate::error::{FactorizationFailure, Result};

/// The structure of a sparse matrix in compressed sparse column form: the row indices of
/// column j are `row_idx[col_ptr[j]..col_ptr[j + 1]]`, strictly increasing. Entry `slot` of a
/// value array belongs to row `row_idx[slot]`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CscPattern {
    nrows: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
}

impl CscPattern {
    /// Checks and wraps a CSC structure with `nrows` rows and `col_ptr.len() − 1` columns.
    ///
    /// ```
    /// use tensegrity_linalg::CscPattern;
    /// // lower triangle of a 2×2 matrix: (0,0), (1,0), (1,1)
    /// let p = CscPattern::new(2, vec![0, 2, 3], vec![0, 1, 1]).unwrap();
    /// assert_eq!(p.slot(1, 0), Some(1));
    /// assert!(CscPattern::new(2, vec![0, 2, 3], vec![1, 0, 1]).is_err());
    /// ```
    pub fn new(nrows: usize, col_ptr: Vec<usize>, row_idx: Vec<usize>) -> Result<Self> {
        let bad = |column| {
            failure(
                "sparse pattern",
                FactorizationFailure::InvalidPattern { column },
            )
        };
        if col_ptr.first() != Some(&0) {
            return Err(bad(0));
        }
        if col_ptr.last() != Some(&row_idx.len()) {
            return Err(bad(col_ptr.len().saturating_sub(2)));
        }
        for (j, w) in col_ptr.windows(2).enumerate() {
            let rows = row_idx.get(w[0]..w[1]).ok_or_else(|| bad(j))?;
            let sorted = rows.windows(2).all(|r| r[0] < r[1]);
            if !sorted || rows.last().is_some_and(|&r| r >= nrows) {
                return Err(bad(j));
            }
        }
        Ok(Self {
            nrows,
            col_ptr,
            row_idx,
        })
    }

    /// Number of rows.
    pub fn nrows(&self) -> usize {
        self.nrows
    }

    /// Number of columns.
    pub fn ncols(&self) -> usize {
        self.col_ptr.len() - 1
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Column pointers (`ncols + 1` of them).
    pub fn col_ptr(&self) -> &[usize] {
        &self.col_ptr
    }

    /// Row index of every stored entry.
    pub fn row_idx(&self) -> &[usize] {
        &self.row_idx
    }

    /// The position of entry (`row`, `col`) in a value array, if it is stored.
    pub fn slot(&self, row: usize, col: usize) -> Option<usize> {
        let (lo, hi) = (*self.col_ptr.get(col)?, *self.col_ptr.get(col + 1)?);
        let k = self.row_idx[lo..hi].binary_search(&row).ok()?;
        Some(lo + k)
    }

    /// Whether the pattern is square with rows i ≥ j only in column j (a lower triangle).
    pub fn is_lower_square(&self) -> bool {
        self.nrows == self.ncols()
            && (0..self.ncols()).all(|j| {
                self.row_idx[self.col_ptr[j]..self.col_ptr[j + 1]]
                    .first()
                    .is_none_or(|&i| i >= j)
            })
    }

    /// The faer view of the structure (valid by construction).
    fn as_faer(&self) -> faer::sparse::SymbolicSparseColMatRef<'_, usize> {
        faer::sparse::SymbolicSparseColMatRef::new_checked(
            self.nrows,
            self.ncols(),
            &self.col_ptr,
            None,
            &self.row_idx,
        )
    }
}

/// A sparse f64 matrix: a [`CscPattern`] and one value per stored entry.
#[derive(Debug, Clone, PartialEq)]
pub struct CscMatrix {
    pattern: CscPattern,
    values: Vec<f64>,
}

impl CscMatrix {
    /// Wraps a pattern and its values (`values.len()` must equal the pattern's `nnz`).
    pub fn new(pattern: CscPattern, values: Vec<f64>) -> Result<Self> {
        if values.len() != pattern.nnz() {
            return Err(failure(
                "sparse matrix",
                FactorizationFailure::DimensionMismatch {
                    expected: pattern.nnz(),
                    found: values.len(),
                },
            ));
        }
        Ok(Self { pattern, values })
    }

    /// Builds an `nrows`×`ncols` matrix from `(row, col, value)` triplets; duplicate entries
    /// are summed (in the order given).
    ///
    /// ```
    /// use tensegrity_linalg::CscMatrix;
    /// let a = CscMatrix::from_triplets(2, 2, &[(1, 0, 2.0), (0, 0, 1.0), (1, 0, 0.5)]).unwrap();
    /// assert_eq!(a.mul_vec(&[1.0, 0.0]), vec![1.0, 2.5]);
    /// assert!(CscMatrix::from_triplets(2, 2, &[(2, 0, 1.0)]).is_err());
    /// ```
    pub fn from_triplets(
        nrows: usize,
        ncols: usize,
        entries: &[(usize, usize, f64)],
    ) -> Result<Self> {
        if let Some(&(row, col, _)) = entries.iter().find(|&&(r, c, _)| r >= nrows || c >= ncols) {
            let reason = FactorizationFailure::EntryOutOfBounds {
                row,
                col,
                nrows,
                ncols,
            };
            return Err(failure("sparse matrix", reason));
        }
        // (column, row) order, stable (duplicates summed in the order given): two counting
        // sorts, by row then by column, O(nnz + nrows + ncols) rather than a comparison sort
        let by_row = counting_order(nrows, (0..entries.len()).map(|k| (k, entries[k].0)));
        let order = counting_order(ncols, by_row.into_iter().map(|k| (k, entries[k].1)));
        let mut col_ptr = vec![0usize; ncols + 1];
        let mut row_idx: Vec<usize> = Vec::with_capacity(entries.len());
        let mut values: Vec<f64> = Vec::with_capacity(entries.len());
        let mut last: Option<(usize, usize)> = None;
        for k in order {
            let (r, c, v) = entries[k];
            if last == Some((r, c)) {
                *values.last_mut().expect("an entry was pushed") += v;
                continue;
            }
            row_idx.push(r);
            values.push(v);
            col_ptr[c + 1] += 1;
            last = Some((r, c));
        }
        for j in 0..ncols {
            col_ptr[j + 1] += col_ptr[j];
        }
        Self::new(CscPattern::new(nrows, col_ptr, row_idx)?, values)
    }

    /// The structure.
    pub fn pattern(&self) -> &CscPattern {
        &self.pattern
    }

    /// The stored values, in pattern order.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The product A x.
    ///
    /// # Panics
    /// If `x.len()` differs from the number of columns.
    pub fn mul_vec(&self, x: &[f64]) -> Vec<f64> {
        assert_eq!(x.len(), self.pattern.ncols(), "A x: length of x");
        let mut y = vec![0.0; self.pattern.nrows()];
        let p = &self.pattern;
        for (j, &xj) in x.iter().enumerate() {
            for slot in p.col_ptr[j]..p.col_ptr[j + 1] {
                y[p.row_idx[slot]] += self.values[slot] * xj;
            }
        }
        y
    }

    /// The faer view of the matrix.
    fn as_faer(&self) -> faer::sparse::SparseColMatRef<'_, usize, f64> {
        faer::sparse::SparseColMatRef::new(self.pattern.as_faer(), &self.values)
    }
}

/// The items of `keyed` (item, key < `n_keys`) stably sorted by key: a counting sort.
fn counting_order(
    n_keys: usize,
    keyed: impl Iterator<Item = (usize, usize)> + Clone,
) -> Vec<usize> {
    let mut start = vec![0usize; n_keys + 1];
    for (_, key) in keyed.clone() {
        start[key + 1] += 1;
    }
    for j in 0..n_keys {
        start[j + 1] += start[j];
    }
    let mut order = vec![0usize; start[n_keys]];
    for (item, key) in keyed {
        order[start[key]] = item;
        start[key] += 1;
    }
    order
}

#[cfg(test)]
mod tests {
    use super::CscMatrix;

    /// The counting-sort assembly against the obvious one: every entry of a pseudo-random
    /// list (duplicates included, in no order) summed in the order given, columns sorted.
    #[test]
    fn triplets_are_summed_in_the_order_given_into_sorted_columns() {
        let (nrows, ncols) = (7, 5);
        let mut entries = Vec::new();
        let mut state = 12345u64;
        for k in 0..200 {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let r = (state >> 33) as usize % nrows;
            let c = (state >> 45) as usize % ncols;
            entries.push((
                r,
                c,
                1.0 / (k as f64 + 1.0) * if k % 3 == 0 { -1.0 } else { 1.0 },
            ));
        }
        let a = CscMatrix::from_triplets(nrows, ncols, &entries).unwrap();
        let mut want = std::collections::BTreeMap::new();
        for &(r, c, v) in &entries {
            *want.entry((c, r)).or_insert(0.0) += v;
        }
        let p = a.pattern();
        let mut got = Vec::new();
        for c in 0..ncols {
            for s in p.col_ptr()[c]..p.col_ptr()[c + 1] {
                got.push(((c, p.row_idx()[s]), a.values()[s]));
            }
        }
        let want: Vec<_> = want.into_iter().collect();
        // the same entries, in (column, row) order, and the same bits (the same sums)
        assert_eq!(got, want);
    }
}
