//! Rank-revealing sparse QR of a banded (profile) matrix: Householder QR that processes the
//! columns in a staircase order and rejects the dependent ones.
//!
//! # Method
//!
//! The rows are first put in a caller-given order that keeps the matrix banded (for the
//! equilibrium matrix: a reverse Cuthill–McKee order of the nodes). The columns are then
//! processed in the order of their last row (ties: the longest span last), so that every column ends at
//! or after the columns before it: a "staircase". Column k, with rows `f..=l`, receives the
//! Householder reflectors H_j of the columns accepted before it that reach row f; reflector j
//! acts on rows `j..=e_j` (it starts at its own pivot position j and ends at its column's last
//! row e_j ≤ l), so all the work happens inside the profile and the factor needs no storage
//! outside it. After the reflectors, the column's entries above the current pivot position p
//! are its R entries (its coefficients on the accepted columns), and its entries from p down
//! are its residual: the component orthogonal to the span of the accepted columns.
//!
//! - If the residual norm is at most the absolute tolerance τ, the column is **dependent**:
//!   it is rejected, its coefficients c are kept, and R_acc x = c gives the null vector
//!   e_k − Σ x_j e_{acc(j)} (A times it equals the residual, of norm ≤ τ);
//! - otherwise a reflector maps the residual onto position p (the diagonal entry r_pp = ∓ its
//!   norm) and p advances.
//!
//! - Greedy selection in a fixed order can accept a set of columns that is much worse
//!   conditioned than A itself (a near-dependency among accepted columns that later columns
//!   would have resolved); the residuals of later dependent columns then carry rounding of
//!   order κ(R_acc)·ε‖A‖ and the rank decision fails. An incremental condition estimate
//!   (Bischof's ICE: a unit vector x with ‖xᵀR_acc‖ ≈ σ_min(R_acc), updated in O(window) per
//!   accepted column from a 2 × 2 eigenproblem) watches σ_min(R_acc): a column whose
//!   acceptance would drop the estimate below the caller's `defer_below` is deferred and
//!   processed after all the others, on the window of the reflectors applied before it
//!   (restricted pivoting). By then the columns that span its direction are in, and it is
//!   rejected as dependent or accepted with its true residual.
//!
//! The result is A Pc = Q [R_acc R_dep; 0 0] + E with R_acc (r × r) upper triangular and
//! nonsingular, r the rank and E the rejected residuals. Q's last m − r columns span the left
//! null space (the first-order mechanisms of a structure).
//!
//! # Certificate
//!
//! The rank decision is certified by two numbers that the caller checks against τ: the
//! Frobenius norm of the rejected residuals, an upper bound of σ_{r+1}(A) (A + E′ has rank r
//! with ‖E′‖ ≤ ‖E‖_F), and an estimate of σ_min(R_acc) ≤ σ_r(A) by inverse iteration
//! ([`RankRevealingQr::sigma_min_estimate`]). Greedy column rejection can be fooled by a run of
//! nearly dependent accepted columns (the Kahan matrix); the estimate catches that case,
//! and the caller then falls back to the SVD.
//!
//! # Cost
//!
//! With half-bandwidth b and a pivot position that lags the rows by at most g (g ≤ the number
//! of left null vectors), one column costs O(b·(b + g)) and the factorisation O(n·b·(b + g))
//! flops and O(n·(b + g)) memory, against O(n³) flops and O(n²) memory for the SVD.

use super::CscMatrix;
use crate::error::{FactorizationFailure, Result};
use crate::failure;
use nalgebra::{DMatrix, DVector};

/// Relative drop tolerance of the sparse null vectors
/// ([`RankRevealingQr::sparse_null_vectors`]).
pub const NULL_DROP: f64 = 1e-14;

/// One Householder reflector H = I − β v vᵀ acting on positions `start..start + v.len()`.
#[derive(Debug, Clone)]
struct Reflector {
    start: usize,
    v: Vec<f64>,
    beta: f64,
}

impl Reflector {
    /// Applies H to the window `x` whose first entry is position `x_start`.
    fn apply(&self, x: &mut [f64], x_start: usize) {
        let off = self.start - x_start;
        let seg = &mut x[off..off + self.v.len()];
        let s: f64 = self.v.iter().zip(seg.iter()).map(|(v, x)| v * x).sum();
        if s != 0.0 {
            let s = s * self.beta;
            for (x, v) in seg.iter_mut().zip(&self.v) {
                *x -= s * v;
            }
        }
    }

    /// Last position reached.
    fn end(&self) -> usize {
        self.start + self.v.len() - 1
    }
}

/// The R entries of one column: positions `start..start + vals.len()`.
#[derive(Debug, Clone, Default)]
struct RColumn {
    start: usize,
    vals: Vec<f64>,
}

/// A rank-revealing staircase Householder QR of a sparse m × n matrix (see the module
/// documentation).
#[derive(Debug, Clone)]
pub struct RankRevealingQr {
    nrows: usize,
    ncols: usize,
    tol: f64,
    /// Original row at each position.
    row_at: Vec<usize>,
    /// Reflector of each pivot (pivot j starts at position j).
    reflectors: Vec<Reflector>,
    /// Original column of each pivot.
    pivot_col: Vec<usize>,
    /// R entries of every original column.
    r_cols: Vec<RColumn>,
    /// Rejected columns, in processing order, with the pivot count when they were rejected.
    dependent: Vec<(usize, usize)>,
    rejected_sq: f64,
    /// Deferral level of the condition estimate (0: never defer).
    defer_below: f64,
    /// The incremental condition estimate.
    ice: Ice,
}

/// Incremental condition estimation of an upper triangular matrix growing by columns: x (unit,
/// stored as `scale · raw`) with ‖xᵀR‖ = `delta` ≈ σ_min(R).
#[derive(Debug, Clone)]
struct Ice {
    raw: Vec<f64>,
    scale: f64,
    delta: f64,
}

impl Ice {
    /// The estimate after appending the column with entries `v` (positions `start..`, above
    /// the diagonal) and diagonal `gamma`, with the rotation (s, c) that achieves it.
    fn trial(&self, start: usize, v: &[f64], gamma: f64) -> (f64, f64, f64) {
        if self.raw.is_empty() {
            return (gamma.abs(), 0.0, 1.0);
        }
        let alpha = self.scale
            * v.iter()
                .zip(&self.raw[start..])
                .map(|(a, b)| a * b)
                .sum::<f64>();
        let (a11, a12, a22) = (
            self.delta * self.delta + alpha * alpha,
            alpha * gamma,
            gamma * gamma,
        );
        let tr = a11 + a22;
        let disc = ((a11 - a22) * (a11 - a22) + 4.0 * a12 * a12).sqrt();
        let lambda = (0.5 * (tr - disc)).max(0.0);
        // eigenvector of [[a11, a12], [a12, a22]] for lambda, from the better-conditioned row
        let (s, c) = if (a11 - lambda).abs() > (a22 - lambda).abs() {
            (-a12, a11 - lambda)
        } else {
            (a22 - lambda, -a12)
        };
        let norm = (s * s + c * c).sqrt();
        if norm == 0.0 || !norm.is_finite() {
            return if a11 <= a22 {
                (a11.sqrt(), 1.0, 0.0)
            } else {
                (gamma.abs(), 0.0, 1.0)
            };
        }
        (lambda.sqrt(), s / norm, c / norm)
    }

    /// Accepts a trial: x ← [s·x; c].
    fn accept(&mut self, (delta, s, c): (f64, f64, f64)) {
        let new_scale = self.scale * s;
        if new_scale.abs() < 1e-100 {
            let k = self.scale * s;
            self.raw.iter_mut().for_each(|x| *x *= k);
            self.scale = 1.0;
        } else {
            self.scale = new_scale;
        }
        self.raw.push(c / self.scale);
        self.delta = delta;
    }
}

impl RankRevealingQr {
    /// Factors `a` with the rows taken in `row_order` (`row_order[position] = row`, a
    /// permutation of the rows) and absolute rejection tolerance `tol` ≥ 0.
    ///
    /// ```
    /// use tensegrity_linalg::{CscMatrix, RankRevealingQr};
    /// // columns: e0, e0 + e1, 2·e0 + e1 (dependent on the first two)
    /// let a = CscMatrix::from_triplets(
    ///     2, 3, &[(0, 0, 1.0), (0, 1, 1.0), (1, 1, 1.0), (0, 2, 2.0), (1, 2, 1.0)],
    /// ).unwrap();
    /// let qr = RankRevealingQr::new(&a, &[0, 1], 1e-12).unwrap();
    /// assert_eq!(qr.rank(), 2);
    /// let n = qr.null_vectors();
    /// assert_eq!(n.ncols(), 1);
    /// let an: Vec<f64> = a.mul_vec(n.column(0).as_slice());
    /// assert!(an.iter().all(|x| x.abs() < 1e-14));
    /// ```
    pub fn new(a: &CscMatrix, row_order: &[usize], tol: f64) -> Result<Self> {
        Self::with_deferral(a, row_order, tol, 0.0)
    }

    /// As [`new`](Self::new), deferring a column whose acceptance would drop the condition
    /// estimate of R_acc below `defer_below` (see the module documentation).
    pub fn with_deferral(
        a: &CscMatrix,
        row_order: &[usize],
        tol: f64,
        defer_below: f64,
    ) -> Result<Self> {
        let (m, n) = (a.pattern().nrows(), a.pattern().ncols());
        let pos_of = inverse_permutation(row_order, m)?;
        let (cp, ri, vals) = (a.pattern().col_ptr(), a.pattern().row_idx(), a.values());
        // staircase order: by last position, then the longest span last (a column that
        // spans from further back is processed after the short ones ending at the same
        // position, so that a dependency closes on it: its circuit — the null vector — stays
        // local instead of telescoping through the shorter columns rejected before)
        let span = |k: usize| {
            let rows = ri[cp[k]..cp[k + 1]].iter().map(|&r| pos_of[r]);
            let (lo, hi) = rows.fold((usize::MAX, 0), |(lo, hi), p| (lo.min(p), hi.max(p)));
            (hi, std::cmp::Reverse(lo))
        };
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by_key(|&k| span(k));
        let mut qr = Self {
            nrows: m,
            ncols: n,
            tol,
            row_at: row_order.to_vec(),
            reflectors: Vec::new(),
            pivot_col: Vec::new(),
            r_cols: vec![RColumn::default(); n],
            dependent: Vec::new(),
            rejected_sq: 0.0,
            defer_below,
            ice: Ice {
                raw: Vec::new(),
                scale: 1.0,
                delta: f64::INFINITY,
            },
        };
        let mut ends: Vec<usize> = Vec::new();
        let mut deferred = Vec::new();
        let column = |k: usize| -> Vec<(usize, f64)> {
            // stored zeros stay: the staircase order was computed with them
            (cp[k]..cp[k + 1])
                .map(|s| (pos_of[ri[s]], vals[s]))
                .collect()
        };
        for k in order {
            if !qr.process(k, &column(k), &mut ends, true) {
                deferred.push(k);
            }
        }
        for k in deferred {
            qr.process(k, &column(k), &mut ends, false);
        }
        Ok(qr)
    }

    /// Processes original column `k` with nonzeros `(position, value)`. With `may_defer`, a
    /// column whose acceptance would drop the condition estimate below `defer_below` is left
    /// untouched and `false` returned; it is processed again after all the others.
    fn process(
        &mut self,
        k: usize,
        nonzero: &[(usize, f64)],
        ends: &mut Vec<usize>,
        may_defer: bool,
    ) -> bool {
        let p = self.reflectors.len();
        let Some(f) = nonzero.iter().map(|e| e.0).min() else {
            // an empty column is its own null vector
            self.r_cols[k] = RColumn {
                start: p,
                vals: Vec::new(),
            };
            self.dependent.push((k, p));
            return true;
        };
        // a deferred column reaches as far as the reflectors applied before it
        let l = nonzero
            .iter()
            .map(|e| e.0)
            .chain(ends.last().copied().filter(|_| !may_defer))
            .max()
            .unwrap_or(f);
        let j0 = ends.partition_point(|&e| e < f);
        let lo = f.min(j0);
        let mut buf = vec![0.0; l - lo + 1];
        for &(pos, v) in nonzero {
            buf[pos - lo] += v;
        }
        for h in &self.reflectors[j0..] {
            h.apply(&mut buf, lo);
        }
        let top = p.max(lo) - lo; // positions below p hold the residual
        let residual = buf[top..].iter().map(|x| x * x).sum::<f64>().sqrt();
        if residual <= self.tol || top >= buf.len() {
            self.rejected_sq += residual * residual;
            buf.truncate(top);
            buf.shrink_to_fit();
            self.r_cols[k] = RColumn {
                start: lo,
                vals: buf,
            };
            self.dependent.push((k, p));
            return true;
        }
        let mut v = buf.split_off(top);
        let alpha = if v[0] > 0.0 { -residual } else { residual };
        let trial = self.ice.trial(lo, &buf, alpha);
        if may_defer && trial.0 < self.defer_below {
            return false;
        }
        self.ice.accept(trial);
        v[0] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        buf.push(alpha);
        // the window's tail went to the reflector: keep only the R entries
        buf.shrink_to_fit();
        self.r_cols[k] = RColumn {
            start: lo,
            vals: buf,
        };
        self.reflectors.push(Reflector {
            start: p,
            v,
            beta: 2.0 / vv,
        });
        ends.push(l);
        self.pivot_col.push(k);
        true
    }

    /// Number of rows m.
    pub fn nrows(&self) -> usize {
        self.nrows
    }

    /// Number of columns n.
    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// The rank r: the number of accepted columns.
    pub fn rank(&self) -> usize {
        self.reflectors.len()
    }

    /// The absolute rejection tolerance τ.
    pub fn tolerance(&self) -> f64 {
        self.tol
    }

    /// The original columns that were accepted, in pivot order.
    pub fn accepted_columns(&self) -> &[usize] {
        &self.pivot_col
    }

    /// Frobenius norm of the rejected residuals: an upper bound of σ_{r+1}(A).
    pub fn rejected_residual(&self) -> f64 {
        self.rejected_sq.sqrt()
    }

    /// Stored entries of the factor (reflectors and R), a measure of its memory.
    pub fn stored_entries(&self) -> usize {
        let v: usize = self.reflectors.iter().map(|h| h.v.len()).sum();
        v + self.r_cols.iter().map(|c| c.vals.len()).sum::<usize>()
    }

    /// Back substitution R_acc[..p, ..p] x = c in place (`c` of length p, pivot order).
    fn back_substitute(&self, c: &mut [f64]) {
        for j in (0..c.len()).rev() {
            let col = &self.r_cols[self.pivot_col[j]];
            let diag = col.vals[j - col.start];
            let x = c[j] / diag;
            c[j] = x;
            for (i, r) in col.vals[..j - col.start].iter().enumerate() {
                c[col.start + i] -= r * x;
            }
        }
    }

    /// Forward substitution R_accᵀ y = c in place.
    fn forward_substitute_transposed(&self, c: &mut [f64]) {
        for j in 0..c.len() {
            let col = &self.r_cols[self.pivot_col[j]];
            let above = &col.vals[..j - col.start];
            let s: f64 = above.iter().zip(&c[col.start..j]).map(|(r, y)| r * y).sum();
            c[j] = (c[j] - s) / col.vals[j - col.start];
        }
    }

    /// A basis of the (numerical) null space, one column per rejected column k:
    /// e_k − Σ x_j e_{acc(j)} with R_acc x = (k's coefficients). Not orthonormal; each vector
    /// has a 1 at its own rejected column and 0 at the other rejected columns. Dense copy of
    /// [`sparse_null_vectors`](Self::sparse_null_vectors).
    pub fn null_vectors(&self) -> DMatrix<f64> {
        let mut out = DMatrix::zeros(self.ncols, self.dependent.len());
        let all = self.null_vector_entries(usize::MAX).unwrap_or_default();
        for (d, entries) in all.into_iter().enumerate() {
            for (k, v) in entries {
                out[(k, d)] = v;
            }
        }
        out
    }

    /// The null vectors of [`null_vectors`](Self::null_vectors) as a sparse n × s matrix.
    ///
    /// Each is found by a sparse back substitution R_acc x = c that visits only the pivots
    /// its right-hand side reaches (a max-heap of positions: R_acc is upper triangular, so
    /// every update goes to a lower position); a coefficient below [`NULL_DROP`] times the
    /// largest of its vector is dropped and not propagated. The null vector of a rejected
    /// member is the unique dependency among it and the members accepted before it (a
    /// circuit); on a banded structure it is local, so the cost is the circuit's size times
    /// the band, not the rank. Dropping |x_j| ≤ δ·max|x| changes A n by at most
    /// δ·max|x|·‖a_j‖, below the rank tolerance for δ = 10⁻¹⁴.
    ///
    /// ```
    /// use tensegrity_linalg::{CscMatrix, RankRevealingQr};
    /// let a = CscMatrix::from_triplets(
    ///     2, 3, &[(0, 0, 1.0), (0, 1, 1.0), (1, 1, 1.0), (0, 2, 2.0), (1, 2, 1.0)],
    /// ).unwrap();
    /// let qr = RankRevealingQr::new(&a, &[0, 1], 1e-12).unwrap();
    /// let n = qr.sparse_null_vectors().unwrap();
    /// assert_eq!((n.pattern().nrows(), n.pattern().ncols(), n.pattern().nnz()), (3, 1, 3));
    /// ```
    pub fn sparse_null_vectors(&self) -> Result<CscMatrix> {
        Ok(self
            .sparse_null_vectors_within(usize::MAX)?
            .expect("no entry limit"))
    }

    /// As [`sparse_null_vectors`](Self::sparse_null_vectors), or `None` as soon as the
    /// vectors hold more than `max_entries` entries (they are not local).
    pub fn sparse_null_vectors_within(&self, max_entries: usize) -> Result<Option<CscMatrix>> {
        let Some(entries) = self.null_vector_entries(max_entries) else {
            return Ok(None);
        };
        let t: Vec<(usize, usize, f64)> = entries
            .iter()
            .enumerate()
            .flat_map(|(d, e)| e.iter().map(move |&(k, v)| (k, d, v)))
            .collect();
        CscMatrix::from_triplets(self.ncols, entries.len(), &t).map(Some)
    }

    /// The (original column, value) entries of each null vector (see
    /// [`sparse_null_vectors`](Self::sparse_null_vectors)); `None` beyond `max_entries`.
    fn null_vector_entries(&self, max_entries: usize) -> Option<Vec<Vec<(usize, f64)>>> {
        let mut total = 0usize;
        let r = self.rank();
        let mut w = vec![0.0; r];
        let mut queued = vec![false; r];
        let mut heap = std::collections::BinaryHeap::new();
        let mut out = Vec::with_capacity(self.dependent.len());
        for &(k, p) in &self.dependent {
            let mut entries = vec![(k, 1.0)];
            let col = &self.r_cols[k];
            for (i, &v) in col.vals.iter().enumerate() {
                if col.start + i < p && v != 0.0 {
                    enqueue(col.start + i, v, &mut w, &mut queued, &mut heap);
                }
            }
            let mut largest = 1.0f64;
            while let Some(j) = heap.pop() {
                queued[j] = false;
                let col = &self.r_cols[self.pivot_col[j]];
                let x = w[j] / col.vals[j - col.start];
                w[j] = 0.0;
                if x.is_nan() || x.abs() <= NULL_DROP * largest {
                    continue;
                }
                largest = largest.max(x.abs());
                entries.push((self.pivot_col[j], -x));
                for (i, &rv) in col.vals[..j - col.start].iter().enumerate() {
                    if rv != 0.0 {
                        enqueue(col.start + i, -rv * x, &mut w, &mut queued, &mut heap);
                    }
                }
            }
            total += entries.len();
            if total > max_entries {
                return None;
            }
            out.push(entries);
        }
        Some(out)
    }

    /// An orthonormal basis of the null space: [`null_vectors`](Self::null_vectors)
    /// orthonormalised by a thin (blocked) Householder QR, O(n·s²).
    pub fn orthonormal_null_space(&self) -> DMatrix<f64> {
        let basic = self.null_vectors();
        if basic.ncols() == 0 {
            return basic;
        }
        let f = faer::Mat::from_fn(basic.nrows(), basic.ncols(), |i, j| basic[(i, j)]);
        let q = f.qr().compute_thin_Q();
        DMatrix::from_fn(q.nrows(), q.ncols(), |i, j| q[(i, j)])
    }

    /// Qᵀ b for `b` in original row order; the result is in position order (its first r
    /// entries pair with R, the rest is the part of b outside the range of A).
    pub fn apply_qt(&self, b: &[f64]) -> Vec<f64> {
        let mut y: Vec<f64> = self.row_at.iter().map(|&r| b[r]).collect();
        for h in &self.reflectors {
            h.apply(&mut y, 0);
        }
        y
    }

    /// An orthonormal basis of the left null space (m × (m − r)): Q's last columns, in
    /// original row order.
    pub fn left_null_vectors(&self) -> DMatrix<f64> {
        let (m, r) = (self.nrows, self.rank());
        // Q e_p = H_0 ⋯ H_{r−1} e_p for every p ≥ r, in position order; a column is touched
        // only once a reflector reaches its lowest nonzero position
        let mut y = DMatrix::zeros(m, m - r);
        let mut low: Vec<usize> = (r..m).collect();
        for (c, p) in (r..m).enumerate() {
            y[(p, c)] = 1.0;
        }
        for h in self.reflectors.iter().rev() {
            for (c, mut col) in y.column_iter_mut().enumerate() {
                if h.end() >= low[c] {
                    h.apply(col.as_mut_slice(), 0);
                    low[c] = low[c].min(h.start);
                }
            }
        }
        let mut out = DMatrix::zeros(m, m - r);
        for (pos, &row) in self.row_at.iter().enumerate() {
            out.row_mut(row).copy_from(&y.row(pos));
        }
        out
    }

    /// The basic least-squares solution: x with R_acc x_acc = (Qᵀb)[..r] and zeros at the
    /// rejected columns, and the residual norm ‖(Qᵀb)[r..]‖ (plus the rejected part).
    pub fn solve_basic(&self, b: &[f64]) -> (DVector<f64>, f64) {
        let y = self.apply_qt(b);
        let r = self.rank();
        let mut c = y[..r].to_vec();
        self.back_substitute(&mut c);
        let mut x = DVector::zeros(self.ncols);
        for (j, v) in c.iter().enumerate() {
            x[self.pivot_col[j]] = *v;
        }
        let res = y[r..].iter().map(|v| v * v).sum::<f64>().sqrt();
        (x, res)
    }

    /// The r × n matrix [R_acc R_dep] (rows in pivot order, original columns): Qᵀ A without its
    /// zero rows, so that R x = 0 describes the null space of A.
    pub fn r_factor(&self) -> Result<CscMatrix> {
        let r = self.rank();
        let mut t = Vec::new();
        for (k, col) in self.r_cols.iter().enumerate() {
            for (i, &v) in col.vals.iter().enumerate() {
                if v != 0.0 && col.start + i < r {
                    t.push((col.start + i, k, v));
                }
            }
        }
        CscMatrix::from_triplets(r, self.ncols, &t)
    }

    /// An estimate of σ_min(R_acc) (a lower bound of σ_r(A)) by `iterations` steps of inverse
    /// iteration on R_accᵀ R_acc; +∞ when r = 0. Inverse iteration converges from above, so
    /// this is an upper estimate of σ_min(R_acc); a few steps are accurate to a small factor.
    pub fn sigma_min_estimate(&self, iterations: usize) -> f64 {
        super::sigma_min::sigma_min_by_inverse_iteration(self.rank(), iterations, |x| {
            self.forward_substitute_transposed(x);
            self.back_substitute(x);
        })
    }
}

/// Adds `v` at position `pos` of the work vector and queues the position once.
fn enqueue(
    pos: usize,
    v: f64,
    w: &mut [f64],
    queued: &mut [bool],
    heap: &mut std::collections::BinaryHeap<usize>,
) {
    w[pos] += v;
    if !queued[pos] {
        queued[pos] = true;
        heap.push(pos);
    }
}

/// `inv[row] = position` of a permutation given as `order[position] = row`.
fn inverse_permutation(order: &[usize], m: usize) -> Result<Vec<usize>> {
    let bad = || {
        let reason = FactorizationFailure::DimensionMismatch {
            expected: m,
            found: order.len(),
        };
        failure("rank-revealing QR (row order)", reason)
    };
    if order.len() != m {
        return Err(bad());
    }
    let mut inv = vec![usize::MAX; m];
    for (pos, &r) in order.iter().enumerate() {
        if r >= m || inv[r] != usize::MAX {
            return Err(bad());
        }
        inv[r] = pos;
    }
    Ok(inv)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic entry in [0.5, 1.5) with a random-looking sign.
    fn entry(i: usize, k: usize) -> f64 {
        let x = ((i * 7919 + k * 104_729) as f64 * 0.618_033_988_7).sin() * 43_758.545_3;
        let f = x - x.floor();
        if f < 0.5 {
            -(0.5 + 2.0 * f)
        } else {
            2.0 * f - 0.5
        }
    }

    /// A banded m × n matrix of known rank: `dependent` columns are combinations of their
    /// neighbours.
    fn banded(m: usize, n: usize, every: usize) -> (CscMatrix, DMatrix<f64>, usize) {
        let mut dense = DMatrix::zeros(m, n);
        let mut dependent = 0;
        for k in 0..n {
            let row0 = (k * m) / n;
            if k >= 2 && k % every == 0 {
                let c = dense.column(k - 1) * 0.7 - dense.column(k - 2) * 1.3;
                dense.set_column(k, &c);
                dependent += 1;
            } else {
                for i in row0..(row0 + 4).min(m) {
                    dense[(i, k)] = entry(i, k);
                }
            }
        }
        let mut t = Vec::new();
        for k in 0..n {
            for i in 0..m {
                if dense[(i, k)] != 0.0 {
                    t.push((i, k, dense[(i, k)]));
                }
            }
        }
        (
            CscMatrix::from_triplets(m, n, &t).unwrap(),
            dense,
            n - dependent,
        )
    }

    #[test]
    fn rank_null_spaces_and_least_squares_match_the_svd() {
        for (m, n, every) in [(40, 50, 5), (60, 45, 7), (30, 30, 4)] {
            let (a, dense, expected_rank) = banded(m, n, every);
            let order: Vec<usize> = (0..m).rev().collect(); // any order is valid
            let qr = RankRevealingQr::new(&a, &order, 1e-10).unwrap();
            let svd = crate::svd(&dense).unwrap();
            let svd_rank = svd.rank(1e-10 * svd.s[0]);
            assert_eq!(qr.rank(), svd_rank, "{m}×{n}");
            assert!(qr.rank() <= expected_rank);
            let nv = qr.null_vectors();
            assert_eq!(nv.ncols(), n - svd_rank);
            assert!((&dense * &nv).amax() < 1e-10 * nv.amax().max(1.0));
            let lv = qr.left_null_vectors();
            assert_eq!(lv.ncols(), m - svd_rank);
            assert!((lv.transpose() * &dense).amax() < 1e-12);
            let gram = lv.transpose() * &lv;
            assert!((gram - DMatrix::identity(m - svd_rank, m - svd_rank)).amax() < 1e-12);
            // the basic solution has the SVD's residual
            let b: Vec<f64> = (0..m).map(|i| (i as f64 * 0.37).sin()).collect();
            let (x, res) = qr.solve_basic(&b);
            let bv = DVector::from_column_slice(&b);
            let x_svd = svd.solve_min_norm(&bv, svd_rank);
            let res_svd = (&dense * x_svd - &bv).norm();
            assert!((res - res_svd).abs() < 1e-10, "{res} vs {res_svd}");
            assert!(((&dense * x - &bv).norm() - res_svd).abs() < 1e-9);
            // R x = 0 on the null vectors
            let r = qr.r_factor().unwrap();
            for c in nv.column_iter() {
                let rx = r.mul_vec(c.as_slice());
                assert!(rx.iter().all(|v| v.abs() < 1e-10));
            }
        }
    }

    #[test]
    fn sigma_min_estimate_is_close_to_the_smallest_singular_value() {
        let (a, dense, _) = banded(50, 50, 1000); // no dependent column: full rank
        let qr = RankRevealingQr::new(&a, &(0..50).collect::<Vec<_>>(), 1e-12).unwrap();
        let svd = crate::svd(&dense).unwrap();
        let s_min = *svd.s.last().unwrap();
        assert_eq!(qr.rank(), 50);
        let est = qr.sigma_min_estimate(30);
        assert!(
            est >= s_min * (1.0 - 1e-9) && est < 2.0 * s_min,
            "{est} vs {s_min}"
        );
    }

    #[test]
    fn a_bad_row_order_is_an_error() {
        let (a, _, _) = banded(10, 10, 3);
        assert!(RankRevealingQr::new(&a, &[0, 1, 2], 1e-12).is_err());
        assert!(RankRevealingQr::new(&a, &[0; 10], 1e-12).is_err());
    }
}
