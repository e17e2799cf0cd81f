//! Fill-reducing ordering of a symmetric sparse matrix.
//!
//! Eliminating the unknowns of a sparse SPD system in a good order keeps the Cholesky factor
//! sparse. The ordering here is faer's approximate minimum degree (AMD), taken from its
//! symbolic Cholesky analysis of the lower triangle, so it is exactly the elimination order of
//! [`super::SparseCholesky`] on the same pattern.

use super::CscPattern;
use crate::error::{FactorizationFailure, Result};
use crate::{failed, failure};
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, SymbolicCholesky, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::Side;

/// The AMD ordering of the symmetric matrix whose lower triangle is `lower`, as `fwd[new] =
/// old` (the identity when faer keeps the natural order).
///
/// ```
/// use tensegrity_linalg::{amd_ordering, CscPattern};
/// // an arrow matrix: row/column 0 couples to everything; AMD eliminates it last
/// let p = CscPattern::new(4, vec![0, 4, 5, 6, 7], vec![0, 1, 2, 3, 1, 2, 3]).unwrap();
/// let fwd = amd_ordering(&p).unwrap();
/// assert_eq!(fwd.len(), 4);
/// assert_eq!(fwd[3], 0);
/// ```
pub fn amd_ordering(lower: &CscPattern) -> Result<Vec<usize>> {
    let symbolic = symbolic_cholesky(lower)?;
    Ok(permutation(&symbolic))
}

/// faer's symbolic Cholesky (AMD ordering) of a lower-triangular square pattern.
pub(super) fn symbolic_cholesky(lower: &CscPattern) -> Result<SymbolicCholesky<usize>> {
    symbolic_cholesky_ordered(lower, None)
}

/// faer's symbolic Cholesky of a lower-triangular square pattern in the elimination order
/// `fwd` (`fwd[new] = old`, a permutation of 0..n), or AMD's when `None`. With an ordering
/// given the numeric factorisation is always supernodal: such an ordering is a structure's
/// nested dissection, whose separators are dense blocks, and faer's automatic choice (by
/// flops per entry of L) kept the simplicial one up to the lattice of K = 13 (2,392
/// members), where the supernodal one halves the margin LP's time (grid K = 5…13 of
/// `tensegrity-statics`' `lp_scaling` example: 0.98–19.3 ms simplicial against 0.69–8.8 ms,
/// and at K = 14, the first supernodal by faer's rule, 9.9 ms: the step that made the
/// LP of K = 13 cost twice that of K = 14).
pub(super) fn symbolic_cholesky_ordered(
    lower: &CscPattern,
    fwd: Option<&[usize]>,
) -> Result<SymbolicCholesky<usize>> {
    if !lower.is_lower_square() {
        let column = (0..lower.ncols())
            .find(|&j| {
                lower.row_idx()[lower.col_ptr()[j]..lower.col_ptr()[j + 1]]
                    .first()
                    .is_some_and(|&i| i < j)
            })
            .unwrap_or(0);
        let reason = FactorizationFailure::InvalidPattern { column };
        return Err(failure("symbolic Cholesky", reason));
    }
    let n = lower.ncols();
    let mut inv = vec![usize::MAX; n];
    if let Some(fwd) = fwd {
        for (new, &old) in fwd.iter().enumerate() {
            if let Some(slot) = inv.get_mut(old) {
                *slot = new;
            }
        }
        if fwd.len() != n || inv.contains(&usize::MAX) {
            let reason = FactorizationFailure::DimensionMismatch {
                expected: n,
                found: fwd.len(),
            };
            return Err(failure("symbolic Cholesky (ordering)", reason));
        }
    }
    let ordering = match fwd {
        Some(fwd) => SymmetricOrdering::Custom(PermRef::new_checked(fwd, &inv, n)),
        None => SymmetricOrdering::Amd,
    };
    factorize_symbolic_cholesky(
        lower.as_faer(),
        Side::Lower,
        ordering,
        CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: match fwd {
                Some(_) => SupernodalThreshold::FORCE_SUPERNODAL,
                None => SupernodalThreshold::AUTO,
            },
            ..Default::default()
        },
    )
    .map_err(failed("symbolic Cholesky", n))
}

/// The fill-reducing permutation of a symbolic factorisation, `fwd[new] = old`.
pub(super) fn permutation(symbolic: &SymbolicCholesky<usize>) -> Vec<usize> {
    match symbolic.perm() {
        Some(p) => p.arrays().0.to_vec(),
        None => (0..symbolic.nrows()).collect(),
    }
}
