//! Rank-revealing multifrontal QR of Aᵀ along an elimination tree (nested dissection).
//!
//! # Method
//!
//! The matrix factored is B = Aᵀ for a sparse m × n matrix A given by its columns (for the
//! equilibrium matrix: B has one row per member and one column per free dof). B's columns
//! are grouped into **fronts** that form a tree (a nested dissection of the structure: the
//! leaves are small sub-domains, every inner front is the separator of its two children),
//! numbered in post order, so that a row of B touches one front and its ancestors only. A
//! row is assembled into the front of its earliest column. Front F then holds, as a dense
//! matrix, its assembled rows and the contribution blocks of its children, over its own
//! (pivot) columns followed by the border columns (ancestors' columns the rows touch):
//!
//! - Householder QR with column pivoting restricted to the pivot columns: at each step the
//!   remaining pivot column of largest residual norm becomes the next pivot; when the largest
//!   residual is at most the rejection tolerance τ, the remaining pivot columns are
//!   **rejected** (dependent on the pivots before them, inside F's subtree): their residuals,
//!   of norm ≤ τ each, are dropped (they form E) and their R entries kept as R_dep;
//!   (on a large front the reflectors reach the border columns afterwards, in blocks of
//!   32: H_{r0} ⋯ H_{r1−1} = I − V T Vᵀ, applied as two matrix products);
//! - the accepted rows are R's rows (entries on F's later pivots and on border columns);
//! - the rows left over the border columns are the contribution block passed to the parent,
//!   reduced by an unpivoted QR (faer's blocked one from 32 columns: a separator's block has
//!   hundreds, and one reflector at a time was two thirds of a lattice's factorisation) to
//!   at most as many rows as border columns (rows beyond are exactly zero after it: each is
//!   a left null vector of B, a self-stress).
//!
//! The result is B Pc = Q [R_acc R_dep; 0 0] + E, R_acc (r × r) upper triangular in the
//! pivot order, r the rank: the self-stress dimension n − r (rows of B) and the mechanisms
//! m − r (columns of B) follow. With a separator of s columns the top front costs
//! O(rows·s²) flops; on a structure of planar extent (separators ∝ √m) the whole
//! factorisation costs O(m^1.5) flops and O(m log m) stored entries, on a long one (a tower:
//! separators of bounded size) O(m).
//!
//! # Certificate
//!
//! As for the banded QR ([`super::rrqr`]): ‖E‖_F bounds σ_{r+1}(A) from above and
//! σ_min(R_acc) ≤ σ_r(A) from below ([`FrontalQr::sigma_min_estimate`], inverse iteration with
//! the sparse triangular R_acc); the caller compares both with τ.

use super::CscMatrix;
use crate::error::{FactorizationFailure, Result};
use crate::failure;

/// Relative drop tolerance of the null vectors ([`FrontalQr::sparse_null_vectors_within`]).
/// Larger than the banded QR's ([`super::rrqr::NULL_DROP`]): a separator's rows reach every
/// pivot of its subtree, so the back substitution spreads the rounding of a local circuit
/// (entries of 10⁻¹³ of its largest on a tower) over the subtree. Dropping entries below
/// 10⁻¹¹ of the largest moves A times the vector by about 10⁻¹¹‖A‖, far below the rejected
/// residual it already carries (up to 1000·τ).
pub const NULL_DROP: f64 = 1e-11;

/// One row of R: its entries from the diagonal rightwards, the diagonal first. During the
/// factorisation `cols` holds original columns of B; afterwards the pivot indices of the
/// accepted ones (R_acc), the rejected columns' entries moved to `dep` (R_dep).
#[derive(Debug, Clone)]
struct RRow {
    cols: Vec<usize>,
    vals: Vec<f64>,
    dep: Vec<(usize, f64)>,
}

/// A dense contribution block: rows × `cols.len()`, column-major.
#[derive(Debug, Clone, Default)]
struct Contribution {
    cols: Vec<usize>,
    rows: usize,
    data: Vec<f64>,
}

/// The rank-revealing multifrontal QR of Aᵀ (see the module documentation).
#[derive(Debug, Clone)]
pub struct FrontalQr {
    /// Columns of B (rows of A).
    ncols: usize,
    /// Rows of B (columns of A).
    nrows: usize,
    tol: f64,
    /// Threshold of the pivot choice ([`FrontalQr::with_threshold`]).
    theta: f64,
    /// R's rows in pivot order.
    r_rows: Vec<RRow>,
    /// Pivot index of every column of B (`None`: rejected).
    pivot_of: Vec<Option<usize>>,
    rejected_sq: f64,
    /// Largest number of rows × columns of a front (a measure of the work).
    largest_front: (usize, usize),
}

impl FrontalQr {
    /// Factors Aᵀ for the m × n matrix `a` (each column of `a` is a row of B) with B's columns
    /// (`a`'s rows) grouped into `fronts` (each a list of columns, every column in exactly one
    /// front), `parent[f]` the parent front (`None` at a root; a parent comes after its
    /// children), and absolute rejection tolerance `tol`.
    ///
    /// ```
    /// use tensegrity_linalg::{CscMatrix, FrontalQr};
    /// // A (2 × 3): columns e0, e0 + e1, 2·e0 + e1 — rank 2, one dependent column
    /// let a = CscMatrix::from_triplets(
    ///     2, 3, &[(0, 0, 1.0), (0, 1, 1.0), (1, 1, 1.0), (0, 2, 2.0), (1, 2, 1.0)],
    /// ).unwrap();
    /// let qr = FrontalQr::new(&a, &[vec![0], vec![1]], &[Some(1), None], 1e-12).unwrap();
    /// assert_eq!(qr.rank(), 2);
    /// assert!(qr.sigma_min_estimate(20) > 0.1);
    /// ```
    pub fn new(
        a: &CscMatrix,
        fronts: &[Vec<usize>],
        parent: &[Option<usize>],
        tol: f64,
    ) -> Result<Self> {
        Self::with_threshold(a, fronts, parent, tol, 1.0)
    }

    /// As [`new`](Self::new) with threshold pivoting: in each front the next pivot is the
    /// first remaining pivot column, in the order given in `fronts`, whose residual norm is at
    /// least `theta` times the largest (θ = 1: the largest, column pivoting; 0 < θ < 1 keeps
    /// the given order where the columns are well conditioned, so a caller's order decides
    /// which columns close a dependency and are rejected, as the banded QR's staircase
    /// does). The rejection rule is unchanged: the remaining columns are rejected when the
    /// largest residual is at most `tol`.
    pub fn with_threshold(
        a: &CscMatrix,
        fronts: &[Vec<usize>],
        parent: &[Option<usize>],
        tol: f64,
        theta: f64,
    ) -> Result<Self> {
        let (m, n) = (a.pattern().nrows(), a.pattern().ncols());
        let bad = |expected: usize, found: usize| {
            let reason = FactorizationFailure::DimensionMismatch { expected, found };
            failure("multifrontal QR (elimination tree)", reason)
        };
        if parent.len() != fronts.len() {
            return Err(bad(fronts.len(), parent.len()));
        }
        let mut front_of = vec![usize::MAX; m];
        for (f, cols) in fronts.iter().enumerate() {
            for &c in cols {
                if c >= m || front_of[c] != usize::MAX {
                    return Err(bad(m, c));
                }
                front_of[c] = f;
            }
        }
        if let Some(c) = front_of.iter().position(|&f| f == usize::MAX) {
            return Err(bad(m, c));
        }
        if let Some(f) = (0..fronts.len()).find(|&f| parent[f].is_some_and(|p| p <= f)) {
            return Err(bad(f + 1, parent[f].unwrap_or(0)));
        }
        // rows of B (columns of A) by the front of their earliest column
        let (cp, ri, vals) = (a.pattern().col_ptr(), a.pattern().row_idx(), a.values());
        let mut assembled: Vec<Vec<usize>> = vec![Vec::new(); fronts.len()];
        for k in 0..n {
            if let Some(f) = ri[cp[k]..cp[k + 1]].iter().map(|&r| front_of[r]).min() {
                assembled[f].push(k);
            }
        }
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); fronts.len()];
        for (f, p) in parent.iter().enumerate() {
            if let Some(p) = p {
                children[*p].push(f);
            }
        }
        let mut qr = Self {
            ncols: m,
            nrows: n,
            tol,
            theta: theta.clamp(f64::MIN_POSITIVE, 1.0),
            r_rows: Vec::new(),
            pivot_of: vec![None; m],
            rejected_sq: 0.0,
            largest_front: (0, 0),
        };
        let mut pending: Vec<Contribution> = vec![Contribution::default(); fronts.len()];
        let mut local = vec![usize::MAX; m];
        for f in 0..fronts.len() {
            let kids: Vec<Contribution> = children[f]
                .iter()
                .map(|&c| std::mem::take(&mut pending[c]))
                .collect();
            let rows: Vec<(&[usize], &[f64])> = assembled[f]
                .iter()
                .map(|&k| (&ri[cp[k]..cp[k + 1]], &vals[cp[k]..cp[k + 1]]))
                .collect();
            let out = qr.front(&fronts[f], &rows, &kids, &mut local);
            if parent[f].is_none() && !out.cols.is_empty() {
                return Err(bad(0, out.cols[0]));
            }
            pending[f] = out;
        }
        // R's columns → pivot indices (R_acc), the rejected ones apart (R_dep)
        for row in &mut qr.r_rows {
            let (mut k, cols) = (0, std::mem::take(&mut row.cols));
            for (&c, idx) in cols.iter().zip(0..) {
                let v = row.vals[idx];
                match qr.pivot_of[c] {
                    Some(p) => {
                        row.vals[k] = v;
                        row.cols.push(p);
                        k += 1;
                    }
                    None => row.dep.push((c, v)),
                }
            }
            row.vals.truncate(k);
        }
        Ok(qr)
    }

    /// The fronts' sizes before factoring (every pivot accepted): for each front its rows,
    /// pivot columns and all columns, from the pattern of `a` and the tree as for
    /// [`new`](Self::new) (which must accept them). For an estimate of the memory (R holds
    /// Σ pivots·columns entries) and of the work (Σ 2·rows·columns·pivots flops).
    ///
    /// ```
    /// use tensegrity_linalg::{CscMatrix, FrontalQr};
    /// let a = CscMatrix::from_triplets(
    ///     2, 3, &[(0, 0, 1.0), (0, 1, 1.0), (1, 1, 1.0), (0, 2, 2.0), (1, 2, 1.0)],
    /// ).unwrap();
    /// let sizes = FrontalQr::symbolic(&a, &[vec![0], vec![1]], &[Some(1), None]);
    /// assert_eq!(sizes, vec![(3, 1, 2), (1, 1, 1)]);
    /// ```
    pub fn symbolic(
        a: &CscMatrix,
        fronts: &[Vec<usize>],
        parent: &[Option<usize>],
    ) -> Vec<(usize, usize, usize)> {
        let m = a.pattern().nrows();
        let mut front_of = vec![usize::MAX; m];
        for (f, cols) in fronts.iter().enumerate() {
            for &c in cols.iter().filter(|&&c| c < m) {
                front_of[c] = f;
            }
        }
        let (cp, ri) = (a.pattern().col_ptr(), a.pattern().row_idx());
        let mut rows = vec![0usize; fronts.len()];
        let mut touched: Vec<Vec<usize>> = vec![Vec::new(); fronts.len()];
        for k in 0..a.pattern().ncols() {
            let cols = &ri[cp[k]..cp[k + 1]];
            if let Some(f) = cols
                .iter()
                .map(|&r| front_of[r])
                .filter(|&f| f != usize::MAX)
                .min()
            {
                rows[f] += 1;
                touched[f].extend(cols.iter().filter(|&&c| front_of[c] != f));
            }
        }
        let mut out = Vec::with_capacity(fronts.len());
        for f in 0..fronts.len() {
            let mut border = std::mem::take(&mut touched[f]);
            border.sort_unstable();
            border.dedup();
            let (np, nb) = (fronts[f].len(), border.len());
            let nr = rows[f];
            out.push((nr, np, np + nb));
            if let Some(p) = parent
                .get(f)
                .copied()
                .flatten()
                .filter(|&p| p < fronts.len())
            {
                rows[p] += nr.saturating_sub(np).min(nb);
                touched[p].extend(border.into_iter().filter(|&c| front_of[c] != p));
            }
        }
        out
    }

    /// Assembles, factors and reduces one front; returns its contribution block.
    fn front(
        &mut self,
        pivots: &[usize],
        rows: &[(&[usize], &[f64])],
        kids: &[Contribution],
        local: &mut [usize],
    ) -> Contribution {
        // the front's columns: pivots, then the border
        let mut cols: Vec<usize> = pivots.to_vec();
        for (i, &c) in cols.iter().enumerate() {
            local[c] = i;
        }
        let np = cols.len();
        let touched = rows
            .iter()
            .flat_map(|r| r.0.iter())
            .chain(kids.iter().flat_map(|k| k.cols.iter()));
        for &c in touched {
            if local[c] == usize::MAX {
                local[c] = cols.len();
                cols.push(c);
            }
        }
        let nc = cols.len();
        let nr = rows.len() + kids.iter().map(|k| k.rows).sum::<usize>();
        self.largest_front = self.largest_front.max((nr, nc));
        let mut w = vec![0.0; nr * nc];
        for (i, (idx, v)) in rows.iter().enumerate() {
            for (&c, &x) in idx.iter().zip(v.iter()) {
                w[local[c] * nr + i] += x;
            }
        }
        let mut r0 = rows.len();
        for k in kids {
            for (j, &c) in k.cols.iter().enumerate() {
                let dst = local[c] * nr + r0;
                w[dst..dst + k.rows].copy_from_slice(&k.data[j * k.rows..(j + 1) * k.rows]);
            }
            r0 += k.rows;
        }
        for &c in &cols {
            local[c] = usize::MAX;
        }
        // pivoted Householder on the pivot columns; on a large front the reflectors are kept
        // (`refl`, one column of nr a reflector) and applied to the border columns afterwards
        // in blocks (small fronts, a tower's, apply them column by column as they come)
        let blocked = nr >= BLOCKED_MIN && nc - np >= BLOCKED_MIN;
        let reach = if blocked { np } else { nc };
        let mut perm: Vec<usize> = (0..nc).collect();
        let mut refl: Vec<f64> = Vec::new();
        let mut betas: Vec<f64> = Vec::new();
        let mut accepted = 0;
        while accepted < np.min(nr) {
            let i = accepted;
            let norm_of = |j: usize, w: &[f64]| {
                let col = &w[j * nr + i..(j + 1) * nr];
                dot(col, col)
            };
            let (best, best_sq) = (i..np)
                .map(|j| (j, norm_of(j, &w)))
                .fold((i, -1.0), |acc, x| if x.1 > acc.1 { x } else { acc });
            if best_sq.sqrt() <= self.tol {
                break;
            }
            let pivot_sq = if self.theta < 1.0 {
                // the first column in order above the threshold; the others keep their order
                let floor = self.theta * self.theta * best_sq;
                let (first, first_sq) = (i..np)
                    .map(|j| (j, norm_of(j, &w)))
                    .find(|&(_, sq)| sq >= floor)
                    .unwrap_or((best, best_sq));
                perm[i..=first].rotate_right(1);
                w[i * nr..(first + 1) * nr].rotate_right(nr);
                first_sq
            } else {
                if best != i {
                    perm.swap(i, best);
                    for r in 0..nr {
                        w.swap(i * nr + r, best * nr + r);
                    }
                }
                best_sq
            };
            let kept = if blocked {
                refl.resize((accepted + 1) * nr, 0.0);
                Some(&mut refl[accepted * nr..])
            } else {
                None
            };
            let beta = householder_step(&mut w, nr, reach, i, i, pivot_sq.sqrt(), kept);
            betas.push(beta);
            accepted += 1;
        }
        if blocked {
            apply_reflectors_blocked(&mut w[np * nr..], nr, nc - np, &refl, &betas);
        }
        // rejected pivot columns: their residuals (rows accepted..) are E
        for j in accepted..np {
            let col = &mut w[j * nr..(j + 1) * nr];
            self.rejected_sq += col[accepted..].iter().map(|x| x * x).sum::<f64>();
            col[accepted..].iter_mut().for_each(|x| *x = 0.0);
        }
        let base = self.r_rows.len();
        for i in 0..accepted {
            self.pivot_of[cols[perm[i]]] = Some(base + i);
            // exact capacity: R's rows are sparse beyond the front's dense part, and a row's
            // full width (nc − i) would hold half as much again on a lattice
            let len = 1 + (i + 1..nc).filter(|&j| w[j * nr + i] != 0.0).count();
            let mut rc = Vec::with_capacity(len);
            let mut rv = Vec::with_capacity(len);
            for j in i..nc {
                let v = w[j * nr + i];
                if v != 0.0 || j == i {
                    rc.push(cols[perm[j]]);
                    rv.push(v);
                }
            }
            self.r_rows.push(RRow {
                cols: rc,
                vals: rv,
                dep: Vec::new(),
            });
        }
        // the contribution block: rows accepted.., border columns
        let cr = nr - accepted;
        let cb = nc - np;
        let mut data = vec![0.0; cr * cb];
        for j in 0..cb {
            let src = &w[(np + j) * nr + accepted..(np + j + 1) * nr];
            data[j * cr..(j + 1) * cr].copy_from_slice(src);
        }
        let border: Vec<usize> = (np..nc).map(|j| cols[perm[j]]).collect();
        if cr > cb {
            // reduce to cb rows: an unpivoted QR, the rest is zero
            reduce_to_triangle(&mut data, cr, cb);
            let mut reduced = vec![0.0; cb * cb];
            for j in 0..cb {
                reduced[j * cb..j * cb + j + 1].copy_from_slice(&data[j * cr..j * cr + j + 1]);
            }
            return Contribution {
                cols: border,
                rows: cb,
                data: reduced,
            };
        }
        Contribution {
            cols: border,
            rows: cr,
            data,
        }
    }

    /// The rank r: the accepted pivots.
    pub fn rank(&self) -> usize {
        self.r_rows.len()
    }

    /// Rows of B (columns of A).
    pub fn nrows(&self) -> usize {
        self.nrows
    }

    /// Columns of B (rows of A).
    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// The absolute rejection tolerance.
    pub fn tolerance(&self) -> f64 {
        self.tol
    }

    /// Frobenius norm of the rejected residuals: an upper bound of σ_{r+1}(A).
    pub fn rejected_residual(&self) -> f64 {
        self.rejected_sq.sqrt()
    }

    /// Stored entries of R (R_acc and R_dep).
    pub fn stored_entries(&self) -> usize {
        self.r_rows.iter().map(|r| r.vals.len() + r.dep.len()).sum()
    }

    /// The largest front, rows × columns.
    pub fn largest_front(&self) -> (usize, usize) {
        self.largest_front
    }

    /// The columns of B that were rejected (A's rows outside the pivots: one per mechanism).
    pub fn rejected_columns(&self) -> Vec<usize> {
        (0..self.ncols)
            .filter(|&c| self.pivot_of[c].is_none())
            .collect()
    }

    /// The null vectors of B, one per rejected column c: the vector with 1 at c, 0 at the
    /// other rejected columns and −x on the accepted ones, R_acc x = (R_dep)_c (B times it
    /// equals c's rejected residual, of norm ≤ τ); columns in the order of the rejected
    /// columns, B's columns as rows. The back substitution is sparse (a heap of the pivots
    /// reached, entries below 10⁻¹⁴ of the largest dropped), so a dependency that closes
    /// inside a few fronts gives a local vector; `None` as soon as the vectors hold more
    /// than `max_entries` entries (they are not local).
    ///
    /// ```
    /// use tensegrity_linalg::{CscMatrix, FrontalQr};
    /// // B = Aᵀ with A's columns e0, e0 + e1, 2·e0 + e1: B's column 2 = B's column 0 + column 1
    /// let a = CscMatrix::from_triplets(
    ///     3, 2, &[(0, 0, 1.0), (1, 0, 1.0), (1, 1, 1.0), (2, 0, 2.0), (2, 1, 1.0)],
    /// ).unwrap();
    /// let qr = FrontalQr::new(&a, &[vec![0, 1, 2]], &[None], 1e-12).unwrap();
    /// let n = qr.sparse_null_vectors_within(usize::MAX).unwrap().unwrap();
    /// assert_eq!((n.pattern().nrows(), n.pattern().ncols()), (3, 1));
    /// let v: Vec<f64> = (0..3).map(|r| n.pattern().slot(r, 0).map_or(0.0, |s| n.values()[s])).collect();
    /// // v ∝ (1, 1, −1): B v = 0
    /// assert!((v[0] - v[1]).abs() < 1e-12 && (v[0] + v[2]).abs() < 1e-12);
    /// ```
    pub fn sparse_null_vectors_within(&self, max_entries: usize) -> Result<Option<CscMatrix>> {
        let r = self.rank();
        // R_acc by columns (entries above the diagonal) and R_dep by rejected column
        let mut above: Vec<Vec<(usize, f64)>> = vec![Vec::new(); r];
        let mut dep: Vec<Vec<(usize, f64)>> = vec![Vec::new(); self.ncols];
        for (i, row) in self.r_rows.iter().enumerate() {
            for (&j, &v) in row.cols.iter().zip(&row.vals).skip(1) {
                if v != 0.0 {
                    above[j].push((i, v));
                }
            }
            for &(c, v) in &row.dep {
                if v != 0.0 {
                    dep[c].push((i, v));
                }
            }
        }
        let mut col_of = vec![0usize; r];
        for (c, p) in self.pivot_of.iter().enumerate() {
            if let Some(p) = *p {
                col_of[p] = c;
            }
        }
        let mut w = vec![0.0; r];
        let mut queued = vec![false; r];
        let mut heap = std::collections::BinaryHeap::new();
        let mut t: Vec<(usize, usize, f64)> = Vec::new();
        let mut d = 0;
        for c in (0..self.ncols).filter(|&c| self.pivot_of[c].is_none()) {
            t.push((c, d, 1.0));
            for &(i, v) in &dep[c] {
                w[i] += v;
                if !queued[i] {
                    queued[i] = true;
                    heap.push(i);
                }
            }
            let mut largest = 1.0f64;
            while let Some(j) = heap.pop() {
                queued[j] = false;
                let x = w[j] / self.r_rows[j].vals[0];
                w[j] = 0.0;
                if x.is_nan() || x.abs() <= NULL_DROP * largest {
                    continue;
                }
                largest = largest.max(x.abs());
                t.push((col_of[j], d, -x));
                for &(i, v) in &above[j] {
                    w[i] -= v * x;
                    if !queued[i] {
                        queued[i] = true;
                        heap.push(i);
                    }
                }
            }
            if t.len() > max_entries {
                return Ok(None);
            }
            d += 1;
        }
        CscMatrix::from_triplets(self.ncols, d, &t).map(Some)
    }

    /// An estimate of σ_min(R_acc) (≤ σ_r(A) up to the rejected part) by `iterations` steps
    /// of inverse iteration on R_accᵀ R_acc; +∞ at rank 0. Inverse iteration converges from
    /// above: an upper estimate of σ_min(R_acc), accurate to a small factor in a few steps.
    /// R_acc is copied once into contiguous rows for the solves (32-bit indices; a rank of
    /// 2³² or more, which no memory holds, gives 0: uncertified).
    pub fn sigma_min_estimate(&self, iterations: usize) -> f64 {
        if u32::try_from(self.rank()).is_err() {
            return 0.0;
        }
        let r = FlatRows::of(&self.r_rows);
        super::sigma_min::sigma_min_by_inverse_iteration(self.rank(), iterations, |x| {
            r.forward_substitute_transposed(x);
            r.back_substitute(x);
        })
    }
}

/// R_acc in contiguous rows (compressed sparse rows, the diagonal first in each row; 32-bit
/// column indices, a quarter less memory traffic for these memory-bound solves).
struct FlatRows {
    ptr: Vec<usize>,
    cols: Vec<u32>,
    vals: Vec<f64>,
}

impl FlatRows {
    /// The rows of R_acc (pivot indices below 2³²: [`FrontalQr::sigma_min_estimate`]).
    fn of(rows: &[RRow]) -> Self {
        let nnz = rows.iter().map(|r| r.vals.len()).sum();
        let mut flat = Self {
            ptr: Vec::with_capacity(rows.len() + 1),
            cols: Vec::with_capacity(nnz),
            vals: Vec::with_capacity(nnz),
        };
        flat.ptr.push(0);
        for row in rows {
            flat.cols.extend(row.cols.iter().map(|&j| j as u32));
            flat.vals.extend_from_slice(&row.vals);
            flat.ptr.push(flat.vals.len());
        }
        flat
    }

    /// Back substitution R_acc x = c in place (pivot order; entries on rejected columns
    /// skipped). Four partial sums a row: the row's products do not wait on one another.
    fn back_substitute(&self, c: &mut [f64]) {
        for i in (0..c.len()).rev() {
            let (lo, hi) = (self.ptr[i], self.ptr[i + 1]);
            let (cols, vals) = (&self.cols[lo + 1..hi], &self.vals[lo + 1..hi]);
            let mut acc = [0.0; 4];
            let (cc, vc) = (cols.chunks_exact(4), vals.chunks_exact(4));
            let mut tail = 0.0;
            for (&j, &v) in cc.remainder().iter().zip(vc.remainder()) {
                tail += v * c[j as usize];
            }
            for (j, v) in cc.zip(vc) {
                for k in 0..4 {
                    acc[k] += v[k] * c[j[k] as usize];
                }
            }
            let s = c[i] - ((acc[0] + acc[1]) + (acc[2] + acc[3]) + tail);
            c[i] = s / self.vals[lo];
        }
    }

    /// Forward substitution R_accᵀ y = c in place.
    fn forward_substitute_transposed(&self, c: &mut [f64]) {
        for i in 0..c.len() {
            let (lo, hi) = (self.ptr[i], self.ptr[i + 1]);
            let y = c[i] / self.vals[lo];
            c[i] = y;
            for (&j, &v) in self.cols[lo + 1..hi].iter().zip(&self.vals[lo + 1..hi]) {
                c[j as usize] -= v * y;
            }
        }
    }
}

/// One Householder step on the column-major `nr × nc` matrix `w`: the reflector
/// H = I − β v vᵀ that maps column `j`'s entries from row `i` down (norm `norm`) onto row `i`,
/// applied to the columns after `j` (up to `nc`); v is written to `v_out` when given (length
/// `nr`, zero above row `i`) and β returned (0 for a zero column: no reflector).
fn householder_step(
    w: &mut [f64],
    nr: usize,
    nc: usize,
    i: usize,
    j: usize,
    norm: f64,
    mut v_out: Option<&mut [f64]>,
) -> f64 {
    if let Some(out) = v_out.as_deref_mut() {
        out[..nr].iter_mut().for_each(|x| *x = 0.0);
    }
    if norm == 0.0 {
        return 0.0;
    }
    let (head, tail) = w.split_at_mut((j + 1) * nr);
    let v = &mut head[j * nr + i..(j + 1) * nr];
    let alpha = if v[0] > 0.0 { -norm } else { norm };
    v[0] -= alpha;
    let vv = dot(v, v);
    let beta = if vv > 0.0 { 2.0 / vv } else { 0.0 };
    for c in 0..nc.saturating_sub(j + 1) {
        let col = &mut tail[c * nr + i..(c + 1) * nr];
        let s = dot(v, col) * beta;
        if s != 0.0 {
            for (x, a) in col.iter_mut().zip(v.iter()) {
                *x -= s * a;
            }
        }
    }
    if let Some(out) = v_out {
        out[i..nr].copy_from_slice(v);
    }
    v[0] = alpha;
    v[1..].iter_mut().for_each(|x| *x = 0.0);
    beta
}

/// The unpivoted QR of the column-major `nr × nc` block `b` (nr > nc) in place: its upper
/// triangle becomes R (up to the signs of R's rows, which the parent's QR does not see).
/// Level 3 (faer's blocked Householder QR) where the block is large: a separator's
/// contribution block has hundreds of columns, and a reflector at a time is the
/// factorisation's largest cost there.
fn reduce_to_triangle(b: &mut [f64], nr: usize, nc: usize) {
    use faer::dyn_stack::{MemBuffer, MemStack};
    use faer::linalg::qr::no_pivoting::factor;
    use faer::{MatMut, Par};
    if nc < REDUCE_BLOCKED_MIN {
        for i in 0..nc {
            let sq = dot(&b[i * nr + i..(i + 1) * nr], &b[i * nr + i..(i + 1) * nr]);
            householder_step(b, nr, nc, i, i, sq.sqrt(), None);
        }
        return;
    }
    let block = factor::recommended_block_size::<f64>(nr, nc);
    let mut coeff = vec![0.0; block * nc];
    let scratch = factor::qr_in_place_scratch::<f64>(nr, nc, block, Par::Seq, Default::default());
    let mut buf = MemBuffer::new(scratch);
    factor::qr_in_place(
        MatMut::from_column_major_slice_mut(b, nr, nc),
        MatMut::from_column_major_slice_mut(&mut coeff, block, nc),
        Par::Seq,
        MemStack::new(&mut buf),
        Default::default(),
    );
}

/// Contribution blocks with at least this many columns are reduced by the blocked QR
/// ([`reduce_to_triangle`]).
const REDUCE_BLOCKED_MIN: usize = 32;

/// Fronts with at least this many rows and border columns apply their reflectors to the
/// border in blocks ([`apply_reflectors_blocked`]); smaller ones one by one.
const BLOCKED_MIN: usize = 64;

/// Reflectors applied to the border at once in blocks of this many (compact WY).
const REFLECTOR_BLOCK: usize = 32;

/// Applies the reflectors H_k = I − β_k v_k v_kᵀ (`refl`: column k is v_k, of length `nr`,
/// zero above row k), H_0 first, to the column-major `nr × ncols` block `b`. In blocks of
/// [`REFLECTOR_BLOCK`]: H_{r0} ⋯ H_{r1−1} = I − V T Vᵀ with T upper triangular
/// (T_jj = β_j, T[..j, j] = −β_j T[..j, ..j] Vᵀv_j), so the block's product applied to b is
/// b − V Tᵀ (Vᵀ b): two matrix products on rows r0.. instead of one pass over b a reflector.
fn apply_reflectors_blocked(b: &mut [f64], nr: usize, ncols: usize, refl: &[f64], betas: &[f64]) {
    use faer::{Accum, MatMut, MatRef, Par};
    let k = betas.len();
    if ncols == 0 || k == 0 {
        return;
    }
    let mut r0 = 0;
    while r0 < k {
        let r1 = (r0 + REFLECTOR_BLOCK).min(k);
        let nb = r1 - r0;
        let rows = nr - r0;
        // V on rows r0..: column j of the block is v_{r0+j}
        let mut v = vec![0.0; rows * nb];
        for j in 0..nb {
            let src = &refl[(r0 + j) * nr + r0..(r0 + j + 1) * nr];
            v[j * rows..(j + 1) * rows].copy_from_slice(src);
        }
        let mut t = vec![0.0; nb * nb];
        for j in 0..nb {
            let beta = betas[r0 + j];
            t[j * nb + j] = beta;
            let vj = &v[j * rows..(j + 1) * rows];
            let z: Vec<f64> = (0..j)
                .map(|l| dot(&v[l * rows..(l + 1) * rows], vj))
                .collect();
            for row in 0..j {
                let s: f64 = (row..j).map(|l| t[l * nb + row] * z[l]).sum();
                t[j * nb + row] = -beta * s;
            }
        }
        let vm = MatRef::from_column_major_slice(&v, rows, nb);
        let tm = MatRef::from_column_major_slice(&t, nb, nb);
        let mut bm = MatMut::from_column_major_slice_mut(b, nr, ncols);
        let mut sub = bm.as_mut().submatrix_mut(r0, 0, rows, ncols);
        let mut vtb = vec![0.0; nb * ncols];
        let mut vtb_m = MatMut::from_column_major_slice_mut(&mut vtb, nb, ncols);
        faer::linalg::matmul::matmul(
            vtb_m.as_mut(),
            Accum::Replace,
            vm.transpose(),
            sub.as_ref(),
            1.0,
            Par::Seq,
        );
        let mut w2 = vec![0.0; nb * ncols];
        let mut w2_m = MatMut::from_column_major_slice_mut(&mut w2, nb, ncols);
        faer::linalg::matmul::matmul(
            w2_m.as_mut(),
            Accum::Replace,
            tm.transpose(),
            vtb_m.as_ref(),
            1.0,
            Par::Seq,
        );
        faer::linalg::matmul::matmul(sub.as_mut(), Accum::Add, vm, w2_m.as_ref(), -1.0, Par::Seq);
        r0 = r1;
    }
}

/// The dot product with four partial sums (vectorised; the order of the additions differs
/// from a left-to-right sum by rounding only).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let tail: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    acc[0] + acc[1] + acc[2] + acc[3] + tail
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    /// A deterministic entry in [−1, 1).
    fn entry(i: usize, k: usize) -> f64 {
        let x = ((i * 7919 + k * 104_729) as f64 * 0.618_033_988_7).sin() * 43_758.545_3;
        2.0 * (x - x.floor()) - 1.0
    }

    /// The (row, column, value) triplets of the nonzero entries of `d`.
    fn nonzeros(d: &DMatrix<f64>) -> Vec<(usize, usize, f64)> {
        let mut t = Vec::new();
        for k in 0..d.ncols() {
            for i in 0..d.nrows() {
                if d[(i, k)] != 0.0 {
                    t.push((i, k, d[(i, k)]));
                }
            }
        }
        t
    }

    #[test]
    fn rank_and_smallest_singular_value_match_the_svd_on_a_chain_of_fronts() {
        // A: m = 12 rows in 3 fronts (0 and 1 children of 2), n = 20 columns touching one front
        // and its parent; columns 7, 11, … combinations of two others
        let (m, n) = (12, 20);
        let mut dense = DMatrix::<f64>::zeros(m, n);
        let front_rows = [0..4, 4..8, 8..12];
        for k in 0..n {
            if k % 4 == 3 && k >= 7 {
                // columns of the same parity lie in the same front
                let c = dense.column(k - 2) * 0.7 - dense.column(k - 4) * 1.3;
                dense.set_column(k, &c);
                continue;
            }
            let f = k % 2;
            for i in front_rows[f].clone().chain(front_rows[2].clone()) {
                if (i + k) % 3 != 0 {
                    dense[(i, k)] = entry(i, k);
                }
            }
        }
        let a = CscMatrix::from_triplets(m, n, &nonzeros(&dense)).unwrap();
        let fronts: Vec<Vec<usize>> = front_rows.iter().map(|r| r.clone().collect()).collect();
        let qr = FrontalQr::new(&a, &fronts, &[Some(2), Some(2), None], 1e-10).unwrap();
        let svd = crate::svd(&dense).unwrap();
        let rank = svd.rank(1e-10 * svd.s[0]);
        assert_eq!(qr.rank(), rank);
        assert!(qr.rejected_residual() < 1e-12);
        let s_r = svd.s[rank - 1];
        let est = qr.sigma_min_estimate(30);
        assert!(
            est <= 1.5 * s_r * 10.0 && est > 1e-3 * s_r,
            "{est} vs {s_r}"
        );
    }

    #[test]
    fn threshold_pivoting_keeps_the_rank_and_its_null_vectors_annihilate_b() {
        // B = Aᵀ (20 rows × 12 columns in 3 fronts, 0 and 1 children of 2): columns 3, 7 and
        // 11 of B combinations of two earlier ones in their front
        let (m, n) = (12, 20);
        let mut b = DMatrix::<f64>::zeros(n, m);
        let front_cols = [0..4, 4..8, 8..12];
        for r in 0..n {
            let f = r % 2;
            for c in front_cols[f].clone().chain(front_cols[2].clone()) {
                if (r + c) % 3 != 0 {
                    b[(r, c)] = entry(r, c);
                }
            }
        }
        for (c, (x, y)) in [(3, (1, 2)), (7, (5, 4)), (11, (9, 8))] {
            let col = b.column(x) * 0.7 - b.column(y) * 1.3;
            b.set_column(c, &col);
        }
        // a's column r is B's row r
        let a = CscMatrix::from_triplets(m, n, &nonzeros(&b.transpose())).unwrap();
        let fronts: Vec<Vec<usize>> = front_cols.iter().map(|r| r.clone().collect()).collect();
        let rank = crate::svd(&b).unwrap();
        let rank = rank.rank(1e-10 * rank.s[0]);
        for theta in [1.0, 0.1, 1e-3] {
            let qr =
                FrontalQr::with_threshold(&a, &fronts, &[Some(2), Some(2), None], 1e-10, theta)
                    .unwrap();
            assert_eq!(qr.rank(), rank, "θ = {theta}");
            let nv = qr.sparse_null_vectors_within(usize::MAX).unwrap().unwrap();
            assert_eq!(nv.pattern().ncols(), m - rank);
            let rejected = qr.rejected_columns();
            for k in 0..nv.pattern().ncols() {
                let mut v = nalgebra::DVector::<f64>::zeros(m);
                for s in nv.pattern().col_ptr()[k]..nv.pattern().col_ptr()[k + 1] {
                    v[nv.pattern().row_idx()[s]] = nv.values()[s];
                }
                assert!((&b * &v).amax() < 1e-12, "θ = {theta}: B n_{k}");
                // 1 at its own rejected column, 0 at the others
                for (j, &c) in rejected.iter().enumerate() {
                    assert_eq!(v[c], if j == k { 1.0 } else { 0.0 });
                }
            }
        }
        // with θ < 1 the given order decides: the last column of each dependency is rejected
        let qr =
            FrontalQr::with_threshold(&a, &fronts, &[Some(2), Some(2), None], 1e-10, 1e-3).unwrap();
        assert_eq!(qr.rejected_columns(), vec![3, 7, 11]);
    }

    #[test]
    fn a_bad_tree_is_an_error() {
        let a = CscMatrix::from_triplets(2, 1, &[(0, 0, 1.0), (1, 0, 1.0)]).unwrap();
        assert!(FrontalQr::new(&a, &[vec![0]], &[None], 1e-12).is_err());
        assert!(FrontalQr::new(&a, &[vec![0], vec![1]], &[None, None], 1e-12).is_err());
        assert!(FrontalQr::new(&a, &[vec![0, 1]], &[None], 1e-12).is_ok());
    }
}
