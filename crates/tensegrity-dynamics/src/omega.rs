//! Sparse symmetric positive definite constraint systems with a fixed pattern: the Ω system of
//! the class-k closed form and the RATTLE multiplier systems.
//!
//! A system is defined by constraint *rows*; each row touches at most two class-1 nodes with a
//! 3-vector gradient at each. Two rows interact when they touch the same bar, through the
//! bar's 2×2 node block of the (effective) inverse mass:
//!
//! `A_ij = Σ_{p ∈ i, q ∈ j, bar(p) = bar(q)} (1/m) (α_pq u_pᵀ w_q + β_pq (u_pᵀ b̂)(w_qᵀ b̂))`
//!
//! with (α, β) = (4, −3) for p = q and (−2, 3) for the two ends of one bar in the Ω system (the
//! rigid-bar inverse mass C_b M⁻¹ = ½ Ĵ⁻¹ C_b with the λ projection, DESIGN.md), and β = 0 for
//! RATTLE (plain M⁻¹ = [[4, −2], [−2, 4]]/m per bar).
//!
//! The sparsity pattern (lower triangle, CSC) and the fill-reducing symbolic Cholesky
//! factorisation are computed once; each evaluation only refills the values and refactors
//! numerically, without allocating. The factorisations live in [`tensegrity_linalg`]: systems of
//! at most [`DENSE_MAX`] rows (a few class-k joints) use the in-place
//! [`DenseCholesky`](tensegrity_linalg::DenseCholesky), since a sparse factorisation's per-call
//! overhead (permutation, dispatch) is several times the flops of a 12×12 one; larger systems
//! whose rows come in runs of up to three on the same nodes (the Ω system: x, y, z of a tie)
//! use the 3×3 block [`Block3Cholesky`](tensegrity_linalg::Block3Cholesky), the others (RATTLE's
//! single bar rows) the AMD-ordered static-schedule
//! [`StaticCholesky`](tensegrity_linalg::StaticCholesky) (the general
//! [`SparseCholesky`](tensegrity_linalg::SparseCholesky) is cross-checked against both in the
//! tests).
//!
//! Small Ω systems with axis-aligned gradients (all of N P = D) are not factored at all: they
//! are a constant matrix minus one rank-one term per constrained bar, solved by the Woodbury
//! identity in the submodule `woodbury` (see there), with the dense Cholesky of the assembled
//! system as the fallback near singular configurations.

pub(crate) mod joint_space;
mod woodbury;

use nalgebra::Vector3;
use tensegrity_core::error::{CoreError, DynamicsError, FactorizationFailure};
use tensegrity_linalg::{Block3Cholesky, CscPattern, DenseCholesky, LinalgError, StaticCholesky};

/// Largest system solved with the dense Cholesky path.
pub(crate) const DENSE_MAX: usize = 48;

/// One node entry of a constraint row: the class-1 node and the gradient there.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RowEntry {
    pub node: usize,
    pub grad: Vector3<f64>,
}

/// A constraint row with one or two node entries.
#[derive(Debug, Clone)]
pub(crate) struct Row {
    pub entries: [Option<RowEntry>; 2],
}

#[derive(Debug, Clone, Copy)]
struct Contribution {
    slot: usize,
    row_x: usize,
    ent_x: usize,
    row_y: usize,
    ent_y: usize,
    same_node: bool,
    bar: usize,
}

/// A contribution with constant axis-aligned gradients (±e_d, ±e_d'): its value is
/// `c0 + c1 · b̂_d b̂_d'` (the Ω system of N P = D, whose rows are all of this kind).
#[derive(Debug, Clone, Copy)]
struct AxisContribution {
    slot: usize,
    /// Position of the slot in the dense row-major storage (row·n + column).
    dense: usize,
    bar: usize,
    d: usize,
    d2: usize,
    c0: f64,
    c1: f64,
}

/// The axis and sign of a gradient that is ±e_d, if it is one.
pub(crate) fn axis_of(g: &Vector3<f64>) -> Option<(usize, f64)> {
    let nz: Vec<usize> = (0..3).filter(|&d| g[d] != 0.0).collect();
    match nz.as_slice() {
        [d] if g[*d].abs() == 1.0 => Some((*d, g[*d])),
        _ => None,
    }
}

/// The factorisation of a constraint system, chosen by its size.
#[derive(Debug)]
enum Factor {
    /// Dense Cholesky (at most [`DENSE_MAX`] rows).
    Dense(DenseCholesky),
    /// The static-schedule sparse Cholesky (larger systems).
    Static(Box<StaticCholesky>),
    /// The 3×3 block Cholesky (larger systems whose rows come in groups: the Ω system).
    Block(Box<Block3Cholesky>),
    /// The general sparse Cholesky (tests: cross-check of the static schedule).
    #[cfg(test)]
    General(Box<tensegrity_linalg::SparseCholesky>),
}

/// The constraint-system error for a failed factorisation: a non-positive pivot is a singular
/// (redundant or conflicting) constraint set.
/// The groups of the 3×3 block factorisation: runs of at most three consecutive rows that
/// touch the same nodes (the x, y and z rows of one tie of N P = D), or `None` when padding
/// the groups to three rows would cost more than a quarter of the system (the RATTLE system,
/// whose bar rows stand alone).
fn row_groups(rows: &[Row]) -> Option<Vec<usize>> {
    let nodes = |r: &Row| r.entries.map(|e| e.map(|e| e.node));
    let mut groups = Vec::with_capacity(rows.len());
    let (mut group, mut size) = (0, 0);
    for (i, row) in rows.iter().enumerate() {
        if i > 0 && (size == 3 || nodes(row) != nodes(&rows[i - 1])) {
            group += 1;
            size = 0;
        }
        groups.push(group);
        size += 1;
    }
    let padded = 3 * (group + 1);
    (4 * padded <= 5 * rows.len()).then_some(groups)
}

fn constraint_error(e: LinalgError) -> CoreError {
    match e {
        LinalgError {
            reason: FactorizationFailure::NonPositivePivot { pivot, dim },
            ..
        } => CoreError::Dynamics(DynamicsError::SingularConstraint {
            rank: pivot,
            expected: dim,
        }),
        other => other.into(),
    }
}

/// A sparse SPD system over constraint rows with symbolic reuse.
pub(crate) struct ConstraintMatrix {
    pub rows: Vec<Row>,
    /// Lower triangle of the system (column j holds rows i ≥ j).
    pattern: CscPattern,
    values: Vec<f64>,
    contributions: Vec<Contribution>,
    /// Precomputed form of `contributions` when every gradient is ±e_d and the system is
    /// rigid (Ω); empty otherwise.
    axis: Vec<AxisContribution>,
    /// Ω-type (with the b̂ b̂ᵀ rigid-bar projection) or plain M⁻¹ (RATTLE).
    rigid: bool,
    factored: bool,
    factor: Factor,
    /// The Woodbury form of a small Ω system (None: always factor the assembled system).
    low_rank: Option<Box<woodbury::LowRank>>,
    /// Whether the last factorisation was the Woodbury one.
    low_rank_active: bool,
}

impl std::fmt::Debug for ConstraintMatrix {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ConstraintMatrix")
            .field("rows", &self.rows.len())
            .field("nnz", &self.values.len())
            .finish()
    }
}

impl ConstraintMatrix {
    /// Builds the pattern and the symbolic factorisation (class-1 nodes 2k and 2k+1 belong to
    /// bar k). `rigid` selects the Ω form (with the b̂b̂ᵀ projection) instead of plain M⁻¹.
    pub fn new(rows: Vec<Row>, rigid: bool) -> Result<Self, CoreError> {
        let n = rows.len();
        // bar -> list of (row, entry)
        let mut by_bar: std::collections::BTreeMap<usize, Vec<(usize, usize, usize)>> =
            Default::default();
        for (r, row) in rows.iter().enumerate() {
            for (e, ent) in row.entries.iter().enumerate() {
                if let Some(ent) = ent {
                    by_bar
                        .entry(ent.node / 2)
                        .or_default()
                        .push((r, e, ent.node));
                }
            }
        }
        let mut pairs: Vec<(usize, usize)> = (0..n).map(|i| (i, i)).collect();
        let mut raw: Vec<(usize, usize, usize, usize, bool, usize)> = Vec::new();
        for (&bar, list) in &by_bar {
            for &(rx, ex, px) in list {
                for &(ry, ey, py) in list {
                    if rx >= ry {
                        pairs.push((rx, ry));
                        raw.push((rx, ex, ry, ey, px == py, bar));
                    }
                }
            }
        }
        // CSC, lower triangle: column j holds rows i >= j.
        pairs.sort_by_key(|&(i, j)| (j, i));
        pairs.dedup();
        let mut col_ptr = vec![0usize; n + 1];
        for &(_, j) in &pairs {
            col_ptr[j + 1] += 1;
        }
        for j in 0..n {
            col_ptr[j + 1] += col_ptr[j];
        }
        let row_idx: Vec<usize> = pairs.iter().map(|&(i, _)| i).collect();
        let pattern = CscPattern::new(n, col_ptr, row_idx).map_err(constraint_error)?;
        let slot_of =
            |i: usize, j: usize| -> usize { pattern.slot(i, j).expect("slot in pattern") };
        let contributions = raw
            .into_iter()
            .map(|(rx, ex, ry, ey, same, bar)| Contribution {
                slot: slot_of(rx, ry),
                row_x: rx,
                ent_x: ex,
                row_y: ry,
                ent_y: ey,
                same_node: same,
                bar,
            })
            .collect();
        let contributions: Vec<Contribution> = contributions;
        let axis = if rigid {
            Self::axis_form(&rows, &contributions).unwrap_or_default()
        } else {
            Vec::new()
        };
        let values = vec![0.0; pattern.nnz()];
        let factor = if n <= DENSE_MAX {
            Factor::Dense(DenseCholesky::new(n))
        } else if let Some(block) =
            row_groups(&rows).and_then(|groups| Block3Cholesky::new(&pattern, &groups))
        {
            Factor::Block(Box::new(block))
        } else {
            Factor::Static(Box::new(
                StaticCholesky::new(&pattern).map_err(constraint_error)?,
            ))
        };
        // the Woodbury form pays when the bars are few against the rows (β ≤ n/2)
        let low_rank = if matches!(factor, Factor::Dense(_)) && !axis.is_empty() {
            woodbury::LowRank::new(&rows, &axis)
                .filter(|lr| 2 * lr.rank() <= n)
                .map(Box::new)
        } else {
            None
        };
        Ok(Self {
            rows,
            pattern,
            values,
            contributions,
            axis,
            rigid,
            factored: false,
            factor,
            low_rank,
            low_rank_active: false,
        })
    }

    /// The constant-gradient form of the contributions (None if a gradient is not ±e_d). The
    /// inverse masses enter at assembly, so only signs and the (α, β) weights are stored.
    fn axis_form(rows: &[Row], contributions: &[Contribution]) -> Option<Vec<AxisContribution>> {
        contributions
            .iter()
            .map(|c| {
                let u = rows[c.row_x].entries[c.ent_x].as_ref()?.grad;
                let w = rows[c.row_y].entries[c.ent_y].as_ref()?.grad;
                let (d, su) = axis_of(&u)?;
                let (d2, sw) = axis_of(&w)?;
                let (alpha, beta) = if c.same_node {
                    (4.0, -3.0)
                } else {
                    (-2.0, 3.0)
                };
                let s = su * sw;
                Some(AxisContribution {
                    slot: c.slot,
                    dense: c.row_x * rows.len() + c.row_y,
                    bar: c.bar,
                    d,
                    d2,
                    c0: if d == d2 { s * alpha } else { 0.0 },
                    c1: s * beta,
                })
            })
            .collect()
    }

    /// Whether the last [`Self::assemble_and_factor`] succeeded (its factor is usable).
    pub(crate) fn is_factored(&self) -> bool {
        self.factored
    }

    /// Refills the values from the current gradients, bar unit vectors `bhat` (only used for
    /// the rigid Ω form) and inverse bar masses, then refactors numerically.
    pub fn assemble_and_factor(
        &mut self,
        bhat: &[Vector3<f64>],
        inv_mass: &[f64],
    ) -> Result<(), CoreError> {
        self.factored = false;
        self.low_rank_active = false;
        if let Some(lr) = self.low_rank.as_mut() {
            if lr.factor(bhat, inv_mass) {
                self.low_rank_active = true;
                self.factored = true;
                return Ok(());
            }
        }
        if let (false, Factor::Dense(chol)) = (self.axis.is_empty(), &mut self.factor) {
            // straight into the dense factor's storage: no CSC values, no scatter
            let a = chol.zeroed();
            for c in &self.axis {
                let b = &bhat[c.bar];
                a[c.dense] += inv_mass[c.bar] * (c.c0 + c.c1 * b[c.d] * b[c.d2]);
            }
            self.factored = false;
            chol.factor_filled().map_err(constraint_error)?;
            self.factored = true;
            return Ok(());
        }
        self.values.fill(0.0);
        for c in &self.axis {
            let b = &bhat[c.bar];
            self.values[c.slot] += inv_mass[c.bar] * (c.c0 + c.c1 * b[c.d] * b[c.d2]);
        }
        // the general form only when the axis form is not available (not a filter over the
        // contributions on every evaluation)
        let general: &[Contribution] = if self.axis.is_empty() {
            &self.contributions
        } else {
            &[]
        };
        for c in general {
            let u = self.rows[c.row_x].entries[c.ent_x]
                .as_ref()
                .map(|e| e.grad)
                .unwrap_or_default();
            let w = self.rows[c.row_y].entries[c.ent_y]
                .as_ref()
                .map(|e| e.grad)
                .unwrap_or_default();
            let (alpha, beta) = match (self.rigid, c.same_node) {
                (true, true) => (4.0, -3.0),
                (true, false) => (-2.0, 3.0),
                (false, true) => (4.0, 0.0),
                (false, false) => (-2.0, 0.0),
            };
            let mut v = alpha * u.dot(&w);
            if beta != 0.0 {
                let b = &bhat[c.bar];
                v += beta * u.dot(b) * w.dot(b);
            }
            self.values[c.slot] += inv_mass[c.bar] * v;
        }
        self.factored = false;
        match &mut self.factor {
            Factor::Dense(c) => c.factor(&self.pattern, &self.values),
            Factor::Static(c) => c.factor(&self.values),
            Factor::Block(c) => c.factor(&self.values),
            #[cfg(test)]
            Factor::General(c) => c.factor(&self.values),
        }
        .map_err(constraint_error)?;
        self.factored = true;
        Ok(())
    }

    /// Solves A x = rhs in place with the last factorisation.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        debug_assert!(self.factored);
        if self.low_rank_active {
            if let Some(lr) = self.low_rank.as_mut() {
                lr.solve_in_place(rhs);
                return;
            }
        }
        match &mut self.factor {
            Factor::Dense(c) => c.solve_in_place(rhs),
            Factor::Static(c) => c.solve_in_place(rhs),
            Factor::Block(c) => c.solve_in_place(rhs),
            #[cfg(test)]
            Factor::General(c) => c.solve_in_place(rhs),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Model;
    use tensegrity_core::structure::{Bar, StringMember, Structure};
    use tensegrity_linalg::SparseCholesky;

    /// `n` D-bars in a row sharing their end joints: 6 + 9(n−1) + 6n constraint rows.
    fn dbar_chain(n: usize) -> Structure {
        let (l, h) = (2.0, 0.5);
        let mut b = Structure::builder();
        for k in 0..=n {
            b = b.node([k as f64 * l, 0.0, 0.1 * k as f64]);
        }
        for k in 0..n {
            let x = k as f64 * l;
            b = b.node([x + l / 2.0, h / 2.0, 0.0]);
            b = b.node([x + l / 2.0, -h / 2.0, 0.05]);
        }
        for k in 0..n {
            let (a, d) = (k, k + 1);
            let (up, dn) = (n + 1 + 2 * k, n + 2 + 2 * k);
            b = b
                .bar(Bar::new(a, up).mass(1.0 + k as f64))
                .bar(Bar::new(a, dn).mass(1.0))
                .bar(Bar::new(up, d).mass(2.0))
                .bar(Bar::new(dn, d).mass(1.0))
                .string(StringMember::new(a, d).stiffness(1000.0))
                .string(StringMember::new(up, dn).stiffness(1000.0));
        }
        b.build().unwrap()
    }

    #[test]
    fn sparse_and_dense_paths_agree() {
        let s = dbar_chain(6);
        let model = Model::new(&s, None).unwrap();
        let rows: Vec<Row> = model.linear_rows.iter().map(|r| r.row.clone()).collect();
        assert!(rows.len() > DENSE_MAX, "{} rows", rows.len());
        let bhat: Vec<Vector3<f64>> = (0..model.bars.len())
            .map(|k| {
                (crate::model::vec3(&model.x0, 2 * k + 1) - crate::model::vec3(&model.x0, 2 * k))
                    .normalize()
            })
            .collect();
        let mut sparse = ConstraintMatrix::new(rows.clone(), true).unwrap();
        sparse.assemble_and_factor(&bhat, &model.inv_mass).unwrap();
        // the Ω rows come in ties of three: the block factorisation
        assert!(matches!(sparse.factor, Factor::Block(_)));
        // the scalar static schedule on the same pattern
        let mut scalar = ConstraintMatrix::new(rows.clone(), true).unwrap();
        scalar.factor = Factor::Static(Box::new(StaticCholesky::new(&scalar.pattern).unwrap()));
        scalar.assemble_and_factor(&bhat, &model.inv_mass).unwrap();
        // the general sparse Cholesky on the same pattern
        let mut general = ConstraintMatrix::new(rows.clone(), true).unwrap();
        general.factor = Factor::General(Box::new(SparseCholesky::new(&general.pattern).unwrap()));
        general.assemble_and_factor(&bhat, &model.inv_mass).unwrap();
        // the dense path on the same values: a copy with the dense factorisation forced on
        let mut dense = ConstraintMatrix::new(rows.clone(), true).unwrap();
        dense.factor = Factor::Dense(DenseCholesky::new(rows.len()));
        dense.assemble_and_factor(&bhat, &model.inv_mass).unwrap();
        // and the generic (non-precomputed) assembly on the dense path
        let mut generic = ConstraintMatrix::new(rows.clone(), true).unwrap();
        assert!(!generic.axis.is_empty());
        generic.axis.clear();
        generic.factor = Factor::Dense(DenseCholesky::new(rows.len()));
        generic.assemble_and_factor(&bhat, &model.inv_mass).unwrap();
        let rhs: Vec<f64> = (0..rows.len()).map(|i| (i as f64 * 0.37).sin()).collect();
        let (mut x1, mut x2, mut x3) = (rhs.clone(), rhs.clone(), rhs.clone());
        sparse.solve_in_place(&mut x1);
        dense.solve_in_place(&mut x2);
        let mut x4 = rhs.clone();
        general.solve_in_place(&mut x4);
        let mut x5 = rhs.clone();
        scalar.solve_in_place(&mut x5);
        let diff5 = x1
            .iter()
            .zip(&x5)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(diff5 <= 1e-12 * x1.iter().map(|a| a.abs()).fold(0.0, f64::max));
        let diff4 = x1
            .iter()
            .zip(&x4)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(diff4 <= 1e-10 * x1.iter().map(|a| a.abs()).fold(0.0, f64::max));
        generic.solve_in_place(&mut x3);
        let diff3 = x2
            .iter()
            .zip(&x3)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(diff3 <= 1e-12 * x2.iter().map(|a| a.abs()).fold(0.0, f64::max));
        let diff = x1
            .iter()
            .zip(&x2)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        let scale = x1.iter().map(|a| a.abs()).fold(0.0, f64::max);
        assert!(diff <= 1e-10 * scale, "diff {diff:e}, scale {scale:e}");
        assert!(scale > 1e-3);
    }
}
