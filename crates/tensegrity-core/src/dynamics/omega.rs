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
//! The sparsity pattern and the fill-reducing symbolic Cholesky factorisation are computed once;
//! each evaluation only refills the values and refactors numerically, without allocating.
//!
//! This is the only dynamics file that touches faer; it should move behind `crate::linalg`.

use super::error::DynamicsError;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};
use nalgebra::Vector3;

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

/// A sparse SPD system over constraint rows with symbolic reuse.
pub(crate) struct ConstraintMatrix {
    pub rows: Vec<Row>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    values: Vec<f64>,
    contributions: Vec<Contribution>,
    symbolic: SymbolicCholesky<usize>,
    l_values: Vec<f64>,
    buf: MemBuffer,
    /// Ω-type (with the b̂ b̂ᵀ rigid-bar projection) or plain M⁻¹ (RATTLE).
    rigid: bool,
    factored: bool,
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
    /// Builds the pattern and the symbolic factorisation. `bar_of(node)` gives the bar owning a
    /// class-1 node (node 2k and 2k+1 belong to bar k).
    pub fn new(rows: Vec<Row>, rigid: bool) -> Result<Self, DynamicsError> {
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
        let slot_of = |i: usize, j: usize| -> usize {
            let lo = col_ptr[j];
            let hi = col_ptr[j + 1];
            lo + row_idx[lo..hi].binary_search(&i).expect("slot in pattern")
        };
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
        let values = vec![0.0; row_idx.len()];
        let sym = SymbolicSparseColMatRef::new_checked(n, n, &col_ptr, None, &row_idx);
        let symbolic = factorize_symbolic_cholesky(
            sym,
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        )
        .map_err(|_| DynamicsError::SingularConstraint {
            rank: 0,
            expected: n,
        })?;
        let req = StackReq::any_of(&[
            symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
            symbolic.solve_in_place_scratch::<f64>(1, Par::Seq),
        ]);
        let l_values = vec![0.0; symbolic.len_val()];
        Ok(Self {
            rows,
            col_ptr,
            row_idx,
            values,
            contributions,
            symbolic,
            l_values,
            buf: MemBuffer::new(req),
            rigid,
            factored: false,
        })
    }

    /// Refills the values from the current gradients, bar unit vectors `bhat` (only used for
    /// the rigid Ω form) and inverse bar masses, then refactors numerically.
    pub fn assemble_and_factor(
        &mut self,
        bhat: &[Vector3<f64>],
        inv_mass: &[f64],
    ) -> Result<(), DynamicsError> {
        self.values.iter_mut().for_each(|v| *v = 0.0);
        for c in &self.contributions {
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
        let n = self.rows.len();
        let a = SparseColMatRef::new(
            SymbolicSparseColMatRef::new_checked(n, n, &self.col_ptr, None, &self.row_idx),
            &self.values,
        );
        let stack = MemStack::new(&mut self.buf);
        self.factored = false;
        self.symbolic
            .factorize_numeric_llt(
                &mut self.l_values,
                a,
                Side::Lower,
                LltRegularization::default(),
                Par::Seq,
                stack,
                Default::default(),
            )
            .map_err(|e| {
                let faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index } = e;
                DynamicsError::SingularConstraint {
                    rank: index,
                    expected: n,
                }
            })?;
        self.factored = true;
        Ok(())
    }

    /// Solves A x = rhs in place with the last factorisation.
    pub fn solve_in_place(&mut self, rhs: &mut [f64]) {
        debug_assert!(self.factored);
        let n = self.rows.len();
        let llt = LltRef::<usize, f64>::new(&self.symbolic, &self.l_values);
        let stack = MemStack::new(&mut self.buf);
        let x = MatMut::from_column_major_slice_mut(rhs, n, 1);
        llt.solve_in_place_with_conj(Conj::No, x, Par::Seq, stack);
    }
}
