//! In-place dense LU with partial pivoting, P A = L U, for small general systems.
//!
//! The implicit integrator (`tensegrity_dynamics::sdirk`) solves (I − h γ J) Δ = r with a dense
//! Jacobian J of a few dozen to a few hundred unknowns, refactored whenever h or J changes
//! and solved several times per factorisation. A row-major Doolittle elimination with row
//! pivoting (the largest |a_ij| of the column) in preallocated storage does this without
//! allocating; faer's dense LU would need a copy into its own storage at every factorisation.
//!
//! A pivot |u_jj| ≤ ε · n · max_ij |a_ij| (or NaN) counts as zero: the factorisation fails with
//! [`FactorizationFailure::StructurallySingular`] (`step` = the failing elimination step).

use crate::error::{FactorizationFailure, Result};
use crate::failure;

/// A dense LU factor of fixed order n with its storage and row permutation.
#[derive(Debug, Clone)]
pub struct DenseLu {
    n: usize,
    /// L (unit lower, below the diagonal) and U (upper), row-major n×n.
    lu: Vec<f64>,
    /// Row k of the factor is row `perm[k]` of A.
    perm: Vec<usize>,
}

impl DenseLu {
    /// Storage for systems of order `n`.
    pub fn new(n: usize) -> Self {
        Self {
            n,
            lu: vec![0.0; n * n],
            perm: (0..n).collect(),
        }
    }

    /// The order n.
    pub fn dim(&self) -> usize {
        self.n
    }

    /// The row-major n×n storage to fill with A before [`factor`](Self::factor).
    pub fn matrix_mut(&mut self) -> &mut [f64] {
        &mut self.lu
    }

    /// Factorises the matrix held in [`matrix_mut`](Self::matrix_mut) in place.
    /// Allocation-free.
    ///
    /// ```
    /// use tensegrity_linalg::DenseLu;
    /// let mut lu = DenseLu::new(2);
    /// lu.matrix_mut().copy_from_slice(&[0.0, 2.0, 3.0, 1.0]); // needs a row swap
    /// lu.factor().unwrap();
    /// let mut x = [4.0, 5.0];
    /// lu.solve_in_place(&mut x);
    /// assert!((x[0] - 1.0).abs() < 1e-15 && (x[1] - 2.0).abs() < 1e-15);
    /// lu.matrix_mut().copy_from_slice(&[1.0, 2.0, 2.0, 4.0]);
    /// assert!(lu.factor().is_err()); // singular
    /// ```
    pub fn factor(&mut self) -> Result<()> {
        let n = self.n;
        let a = &mut self.lu;
        self.perm.iter_mut().enumerate().for_each(|(i, p)| *p = i);
        let amax = a.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let tol = f64::EPSILON * n as f64 * amax;
        for j in 0..n {
            let (mut p, mut best) = (j, -1.0);
            for i in j..n {
                let v = a[i * n + j].abs();
                if v > best {
                    (p, best) = (i, v);
                }
            }
            if best.is_nan() || best <= tol {
                let reason = FactorizationFailure::StructurallySingular { step: j, dim: n };
                return Err(failure("dense LU", reason));
            }
            if p != j {
                for k in 0..n {
                    a.swap(j * n + k, p * n + k);
                }
                self.perm.swap(j, p);
            }
            let (head, tail) = a.split_at_mut((j + 1) * n);
            let row_j = &head[j * n..];
            let inv = 1.0 / row_j[j];
            for row_i in tail.chunks_exact_mut(n) {
                let l = row_i[j] * inv;
                row_i[j] = l;
                if l != 0.0 {
                    for k in j + 1..n {
                        row_i[k] -= l * row_j[k];
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
        assert_eq!(b.len(), n, "LU solve: length of the right-hand side");
        // P b: row k of the factor is row perm[k] of A.
        if self.perm.iter().enumerate().any(|(k, &p)| p != k) {
            permute(&self.perm, b);
        }
        let a = &self.lu;
        for i in 0..n {
            let row = &a[i * n..i * n + i];
            b[i] -= row.iter().zip(&b[..i]).map(|(x, y)| x * y).sum::<f64>();
        }
        for i in (0..n).rev() {
            let row = &a[i * n..(i + 1) * n];
            let s = row[i + 1..]
                .iter()
                .zip(&b[i + 1..])
                .map(|(x, y)| x * y)
                .sum::<f64>();
            b[i] = (b[i] - s) / row[i];
        }
    }
}

/// b ← (b[perm[0]], b[perm[1]], …) in place, following the cycles of `perm`.
fn permute(perm: &[usize], b: &mut [f64]) {
    // Each cycle i → perm[i] → perm[perm[i]] … is rotated once; a cycle is handled from its
    // smallest index, found by walking it.
    for start in 0..perm.len() {
        let mut j = perm[start];
        while j > start {
            j = perm[j];
        }
        if j < start {
            continue; // already rotated from a smaller index
        }
        let first = b[start];
        let mut i = start;
        loop {
            let next = perm[i];
            if next == start {
                b[i] = first;
                break;
            }
            b[i] = b[next];
            i = next;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 5×5 non-symmetric system against its known solution (pivoting needed: zero leading
    /// entry).
    #[test]
    fn solves_a_pivoted_system() {
        let n = 5;
        let mut lu = DenseLu::new(n);
        let x_true = [1.0, -2.0, 3.0, 0.5, -1.5];
        let mut a = vec![0.0; n * n];
        for i in 0..n {
            for j in 0..n {
                a[i * n + j] = ((i * 7 + j * 3) % 5) as f64 - 1.0 + if i == j { 0.0 } else { 0.3 };
            }
        }
        a[0] = 0.0;
        let mut b = vec![0.0; n];
        for i in 0..n {
            b[i] = (0..n).map(|j| a[i * n + j] * x_true[j]).sum();
        }
        lu.matrix_mut().copy_from_slice(&a);
        lu.factor().unwrap();
        lu.solve_in_place(&mut b);
        for (x, t) in b.iter().zip(&x_true) {
            assert!((x - t).abs() < 1e-12, "{x} vs {t}");
        }
    }

    #[test]
    fn permutation_by_cycles() {
        let perm = [2, 0, 3, 1, 4];
        let mut b = [10.0, 11.0, 12.0, 13.0, 14.0];
        permute(&perm, &mut b);
        assert_eq!(b, [12.0, 10.0, 13.0, 11.0, 14.0]);
    }
}
