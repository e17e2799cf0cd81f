//! Sparse statics for large general structures: rank, self-stress, mechanisms and load solves
//! of the equilibrium matrix A (A q = w, free dofs × members) without the SVD's full U and V.
//!
//! # Why this factorisation
//!
//! The dense path ([`Statics`](super::Statics)) takes the full SVD A = U Σ Vᵀ: O(n³) flops and
//! O(n²) memory even when only the rank, a null space of small dimension and a few solves are
//! needed. The factorisation backend has no column-pivoted sparse QR, and the normal equations
//! AᵀA or AAᵀ square the condition number, so a rank decision at max(m, n)·ε·σ_max is
//! impossible there. Structures are meshes: after a reverse Cuthill–McKee ordering of the
//! nodes, A is banded. The factorisation is therefore a Householder QR confined to A's profile
//! ([`tensegrity_linalg::RankRevealingQr`]): the members are processed along the
//! band and a member whose column lies within the rejection tolerance of the span of the
//! members accepted before it is rejected (it carries a self-stress). A member whose
//! acceptance would drop the incremental condition estimate of the accepted set below
//! 10⁻³·σ_max is deferred to the end (restricted pivoting), which keeps the accepted set about
//! as well conditioned as A.
//!
//! Tolerance: τ = max(m, n)·ε·σ_max (or the relative tolerance of the settings times σ_max),
//! the dense path's convention, with σ_max from 40 steps of the power method on AᵀA. A member
//! is rejected when its residual is at most 1000·τ: the residual of an exactly dependent
//! column carries rounding of order κ(A_acc)·ε·‖A‖ (its coefficients on the accepted columns
//! grow with their conditioning), more than the SVD's ε·‖A‖.
//!
//! The rank decision is **certified** when it sits in a clear gap of the spectrum: the
//! Frobenius norm ‖E‖_F of the rejected residuals bounds σ_{r+1}(A) from above, and
//! σ_min(R_acc) ≤ σ_r(A) bounds σ_r from below; the estimate of σ_min(R_acc) must exceed
//! 100 · max(τ, ‖E‖_F). A certified rank is the SVD's at τ unless A has a singular value
//! between τ and ‖E‖_F. An uncertified decision falls back to the dense SVD when it fits the
//! memory budget and the method is automatic, and is flagged in the report otherwise (see
//! [`report`](super::report)).
//!
//! Clustered strings ([`crate::cluster_columns`]) are columns like the members': one per
//! cluster over all its nodes (its segments join the node graph of the ordering), so the
//! counts, the self-stress basis, the LP and the load solve take them as they are; the
//! stress matrix of the dense-mechanism stability test adds each cluster's geometric part
//! q_c L_c Σ_i (1/l_i) P_i segment by segment, and the large-structure tests (the flex QR,
//! the penalised certificate) give no decision with clusters.
//!
//! # What is computed
//!
//! - rank r, self-stress dimension members − r, mechanisms dofs − r;
//! - the self-stress basis: the null vectors e_k − Σ x_j e_{acc(j)} of the rejected members,
//!   kept sparse ([`RankRevealingQr::sparse_null_vectors`]: a sparse back substitution per
//!   vector). The staircase puts, among the members ending at the same row, the longest span
//!   last, so a dependency closes on a member of its own cell and each null vector is a
//!   local circuit (a tower: one prism, 12 members), not a telescoping sum through the members
//!   rejected before. The orthonormal basis (thin QR, O(n·s²), oriented like the dense
//!   path's) is built only when asked for; the report lists it up to
//!   [`SELF_STRESS_LIST_MAX`] numbers;
//! - first-order flexes: Q's last m − r columns (orthonormal); the rigid-body motions the
//!   supports allow are projected out and the internal mechanisms taken from the projected
//!   Gram matrix (its eigenvalues are 1 or 0);
//! - prestressability: the margin LP over the sparse basis N, q = N c
//!   (`max t  s.t.  σ_k (N c)_k ≥ t, σ_k (N c)_k ≤ 1`), solved by Clarabel's sparse interior
//!   point: its rows have N's sparsity. The stress N c lies in the null space by
//!   construction; it is scaled to max|q| = 1 and its margin recomputed, as on the dense
//!   path;
//! - prestress stability: below [`DENSE_MECHANISMS_MAX`] the stress matrix applied member by
//!   member to the internal mechanisms, then a small symmetric eigenproblem; beyond, the
//!   penalised stress matrix, then the sparse flex test
//!   ([`SparseStatics::stable_by_cholesky`]); when neither decides, the report says
//!   stability was not tested;
//! - the minimal-norm load solve: the basic solution R_acc x = (Qᵀw)_{1..r} minus its
//!   projection on the self-stress space (a sparse Cholesky factorisation of NᵀN,
//!   refined twice).

use super::front::Factorization;
use super::load::LoadSolution;
use super::penalty::stable_by_penalty;
use super::prestress::{MemberSign, Prestressability};
use super::stability::PrestressStability;
use super::{orient_self_stress, DofMap, StaticsSettings};
use crate::front::{Certification, SelfStressBasis, StaticsBackend};
use crate::gap::SpectralGap;
use nalgebra::Matrix3xX;
use nalgebra::{DMatrix, DVector, Vector3};
use std::sync::OnceLock;
use tensegrity_core::error::{CoreError, Result};
use tensegrity_core::structure::Structure;
use tensegrity_linalg::{self as linalg, CscMatrix, RankRevealingQr};

/// Largest self-stress basis (members × dimension numbers) the statics report lists; a
/// larger one is left out of the report (its dimension is given), since its
/// orthonormalisation costs O(members·s²) and its listing members·s numbers (written as
/// JSON, about 800 instructions a number). At 2.5·10⁴ numbers both cost a few milliseconds,
/// so the analysis costs about as much on either side of the limit; at 10⁶ it was a step (the
/// grid of 1,420 members cost 0.18 s with its basis listed, that of 1,716 members 0.02 s
/// without), and at 10⁵ still one of 2–3× (grid:5, 360 members × 180 self-stresses: 21 ms
/// listed against grid:6's 8 ms; docs/notes/PERFORMANCE.md, "Statics cost against size").
/// The dense SVD path lists its basis at any size.
pub const SELF_STRESS_LIST_MAX: usize = 25_000;

/// Largest orthonormal self-stress basis (members × dimension numbers) the margin LP falls
/// back on when the LP over the sparse basis stalls (the unclustered Levy dome of 4,080
/// members); above the listing limit [`SELF_STRESS_LIST_MAX`], since the fallback is rare and
/// an answer is worth its O(members·s²).
pub const ORTHONORMAL_LP_MAX: usize = 1_000_000;

/// The sparse flex basis of [`SparseStatics::stable_by_cholesky`] may hold this many entries
/// per kept dof; beyond, the flexes are not local and the test gives no decision.
pub const FLEX_ENTRIES_PER_DOF: usize = 32;

/// The flex test of [`SparseStatics::stable_by_cholesky`] is not attempted when the
/// factor of A already holds more than this many entries per kept dof: the QR of Aᵀ it
/// would run has the same band profile (on the towers its stored entries equal A's to
/// 0.1 %), so it would cost as much again in time and memory, and with that much fill its
/// null vectors were never local (towers: 194 entries per dof at 400 prisms, flexes local;
/// 371 at 800, flexes 90 entries per dof, not local).
pub const FLEX_QR_ENTRIES_PER_DOF: usize = 256;

/// Largest internal-mechanism basis (free dofs × mechanisms numbers) for which prestress
/// stability takes the dense eigenvalue test (O(dofs·d²) flops); larger structures take the
/// sparse Cholesky test ([`SparseStatics::prestress_stability`]).
pub const DENSE_MECHANISMS_MAX: usize = 250_000;

/// Up to this many numbers of the internal-mechanism basis (free dofs × mechanisms) the
/// dense eigenvalue test runs first; above, the sparse Cholesky test
/// ([`SparseStatics::stable_by_cholesky`]) runs first and the dense one (up to
/// [`DENSE_MECHANISMS_MAX`]) only where it gives no decision. The dense test's O(dofs·d²) made
/// a tower of 100 prisms (909 dofs × 106 mechanisms) cost more than one of 200, which took
/// the sparse test (docs/notes/PERFORMANCE.md, "Statics cost against size").
pub const DENSE_MECHANISMS_FIRST: usize = 25_000;

/// [`DENSE_MECHANISMS_MAX`] for a structure with clusters, whose large-structure tests (the
/// flex QR, the penalised certificate) give no decision: the dense test up to 32 MB of basis
/// (a clustered Levy dome of 4,080 members, 4,032 free dofs × 611 mechanisms, 2.5·10⁶
/// numbers: about 1 s) rather than no answer.
pub const DENSE_MECHANISMS_MAX_CLUSTERED: usize = 4_000_000;

/// The largest dense mechanism basis (free dofs × mechanisms) the stability test of
/// `structure` takes.
fn dense_mechanisms_max(structure: &Structure) -> usize {
    if structure.has_clusters() {
        DENSE_MECHANISMS_MAX_CLUSTERED
    } else {
        DENSE_MECHANISMS_MAX
    }
}

/// Power-method steps for σ_max of the equilibrium matrix.
const POWER_STEPS: usize = 40;
/// Inverse-iteration steps for the σ_min(R_acc) estimate.
const INVERSE_STEPS: usize = 12;
/// The σ_min(R_acc) estimate must exceed this multiple of max(τ, ‖E‖_F) for a certified rank.
const CERTIFY_FACTOR: f64 = 100.0;
/// A member whose acceptance would drop the condition estimate of R_acc below this fraction
/// of σ_max is deferred to the end of the factorisation; another level for larger structures ([`defer_level`]).
const DEFER_BELOW: f64 = 1e-3;

/// The deferral level of an m × n matrix whose columns are rejected at `reject`
/// ([`crate::rank::RankTolerance::reject_level`]): 10⁻³·σ_max up to 1000 rows and columns
/// (a condition estimate of R_acc within 10³ of A's scale), and beyond that ten times the
/// rejection level. A long structure's own σ_r falls
/// with its size (a tower of N prisms: σ_r ∝ 1/N²), so a fixed fraction of σ_max would defer
/// most of its members, and a deferred member spans the whole band (quadratic work and
/// global null vectors); the certificate (σ_min(R_acc) against the rejected residuals)
/// still catches an accepted set that went bad.
fn defer_level(m: usize, n: usize, sigma_max: f64, reject: f64) -> f64 {
    if m.max(n) <= 1000 {
        DEFER_BELOW * sigma_max
    } else {
        10.0 * reject
    }
}
/// Columns are rejected when their residual is at most this multiple of the arithmetic's
/// tolerance τ₀ (or [`crate::rank::DATA_REJECT_FACTOR`] times the coordinates' rounding e,
/// whichever is larger: [`crate::rank::RankTolerance::reject_level`]): the residual of an
/// exactly dependent column carries rounding of order κ(A_acc)·ε·‖A‖, larger than the SVD's
/// ε·‖A‖, so τ₀ itself would accept some dependent columns of ill-conditioned structures.
const REJECT_FACTOR: f64 = 1e3;

/// The sparse equilibrium matrix A (free dofs × columns: members, then one per cluster,
/// [`crate::cluster_columns`]), rows as [`DofMap`] numbers them.
pub fn equilibrium_matrix_sparse(structure: &Structure, dofs: &DofMap) -> Result<CscMatrix> {
    let mut t = Vec::with_capacity(6 * structure.n_members());
    for (k, [i, j]) in structure.member_nodes().into_iter().enumerate() {
        let m = structure.nodes()[j] - structure.nodes()[i];
        for d in 0..3 {
            if let Some(r) = dofs.row[i][d] {
                t.push((r, k, -dofs.component(i, d, &m)));
            }
            if let Some(r) = dofs.row[j][d] {
                t.push((r, k, dofs.component(j, d, &m)));
            }
        }
    }
    let nm = structure.n_members();
    for (c, geometry) in crate::cluster_columns::cluster_geometries(structure)
        .iter()
        .enumerate()
    {
        for (node, v) in geometry.column() {
            for d in 0..3 {
                if let Some(r) = dofs.row[node][d] {
                    // a pulley's two entries add in the triplets
                    t.push((r, nm + c, dofs.component(node, d, &v)));
                }
            }
        }
    }
    Ok(CscMatrix::from_triplets(
        dofs.len(),
        crate::n_columns(structure),
        &t,
    )?)
}

/// A reverse Cuthill–McKee order of the nodes (by the member graph): breadth-first from a
/// pseudo-peripheral node of each connected part, neighbours by increasing degree, reversed.
/// It makes the equilibrium matrix banded.
pub fn node_order_rcm(structure: &Structure) -> Vec<usize> {
    let n = structure.n_nodes();
    let mut adj = vec![Vec::new(); n];
    let segments = structure.clusters().iter().flat_map(|c| c.segments());
    for [i, j] in structure.member_nodes().into_iter().chain(segments) {
        adj[i].push(j);
        adj[j].push(i);
    }
    for a in &mut adj {
        a.sort_unstable();
        a.dedup();
    }
    let degree: Vec<usize> = adj.iter().map(Vec::len).collect();
    for a in &mut adj {
        a.sort_by_key(|&v| (degree[v], v));
    }
    let mut order = Vec::with_capacity(n);
    let mut seen = vec![false; n];
    while order.len() < n {
        let start = (0..n).filter(|&v| !seen[v]).min_by_key(|&v| (degree[v], v));
        let Some(mut start) = start else { break };
        // two sweeps towards a pseudo-peripheral node
        for _ in 0..2 {
            let level = bfs(&adj, start, &seen);
            start = *level.last().expect("the start is reached");
        }
        for v in bfs(&adj, start, &seen) {
            seen[v] = true;
            order.push(v);
        }
    }
    order.reverse();
    order
}

/// Breadth-first order from `start` over the nodes not `excluded`.
fn bfs(adj: &[Vec<usize>], start: usize, excluded: &[bool]) -> Vec<usize> {
    let mut mark = excluded.to_vec();
    mark[start] = true;
    let mut out = vec![start];
    let mut head = 0;
    while head < out.len() {
        let v = out[head];
        head += 1;
        for &w in &adj[v] {
            if !mark[w] {
                mark[w] = true;
                out.push(w);
            }
        }
    }
    out
}

/// The rows of A in the reverse Cuthill–McKee order of the nodes, and each row's position.
fn row_ordering(structure: &Structure, dofs: &DofMap) -> (Vec<usize>, Vec<usize>) {
    let row_order: Vec<usize> = node_order_rcm(structure)
        .into_iter()
        .flat_map(|i| dofs.row[i].into_iter().flatten())
        .collect();
    let mut pos_of_row = vec![0; dofs.len()];
    for (p, &r) in row_order.iter().enumerate() {
        pos_of_row[r] = p;
    }
    (row_order, pos_of_row)
}

/// The bytes the sparse QR of `structure` holds (the bound [`SparseStatics::with_settings`]
/// checks against its memory budget), computed without factoring: for a front end's
/// estimate. The dense output bases come on top.
pub fn sparse_statics_bytes(structure: &Structure) -> Result<f64> {
    let dofs = DofMap::of(structure);
    let a = equilibrium_matrix_sparse(structure, &dofs)?;
    let (_, pos_of_row) = row_ordering(structure, &dofs);
    Ok(sparse_bytes_bound(&a, &pos_of_row))
}

/// Flops a second of the sparse statics' stages (the QR's column updates, the back
/// substitutions, the small dense products and eigenproblems of the bases), calibrated on the
/// measured runs of `crates/tensegrity-engine/tests/statics_estimate.rs` (towers and chains,
/// 2.6·10⁹ measured in the test profile; rounded down so the estimate bounds the time).
pub const SPARSE_FLOP_RATE: f64 = 1.5e9;

/// The estimate of the sparse statics of an m × n equilibrium matrix once its QR (`entries`
/// stored numbers, [`RankRevealingQr::stored_entries`]) has found rank r — s = n − r
/// self-stresses, d = m − r mechanisms: what is still to come and what is held at its peak.
///
/// - memory: the factorisation (16·entries: each column's window is allocated whole, then
///   shrunk to its entries, and the allocator keeps the tails), the orthonormal self-stress
///   basis n × s about four times when the report lists it (n·s ≤ [`SELF_STRESS_LIST_MAX`])
///   and, when there is a self-stress, the LP's sparse rows and interior-point factor
///   (~3 × 16·entries) and either the dense mechanisms m × d about four times (m·d ≤
///   [`DENSE_MECHANISMS_MAX`]) or the flex QR (~2 × 16·entries);
/// - work: the local sparse null vectors (64 flops each), the thin QR of a listed basis
///   (2ns²) and, with a self-stress, the LP (20·entries per interior-point step, 30 steps)
///   and either the dense mechanism test (d·entries + 2md² + 10d³) or the flex QR and the
///   sparse test (200·entries).
///
/// ```
/// use tensegrity_statics::sparse_after_qr;
/// // a chain without self-stress: the factorisation and nothing to add
/// let e = sparse_after_qr(9000, 5997, 5997, 1_000_000);
/// assert_eq!(e.memory_bytes, 16e6);
/// assert!(sparse_after_qr(4509, 4503, 4003, 2_000_000).work_s > 0.5);
/// ```
pub fn sparse_after_qr(
    m: usize,
    n: usize,
    r: usize,
    entries: usize,
) -> tensegrity_core::budget::Estimate {
    after_qr(m, n, r, entries, DENSE_MECHANISMS_MAX)
}

fn after_qr(
    m: usize,
    n: usize,
    r: usize,
    entries: usize,
    dense_max: usize,
) -> tensegrity_core::budget::Estimate {
    let (mf, nf, e) = (m as f64, n as f64, entries as f64);
    let s = n.saturating_sub(r) as f64;
    let d = m.saturating_sub(r) as f64;
    let stressed = if s > 0.0 { 1.0 } else { 0.0 };
    // the orthonormal basis only when the report lists it
    let listed = if nf * s <= SELF_STRESS_LIST_MAX as f64 {
        1.0
    } else {
        0.0
    };
    // the dense mechanism test below its size, else the flex QR and the sparse test
    let dense_mech = if mf * d <= dense_max as f64 { 1.0 } else { 0.0 };
    let memory = 16.0 * e
        + listed * 32.0 * nf * s
        + stressed * (48.0 * e + dense_mech * 32.0 * mf * d + (1.0 - dense_mech) * 32.0 * e);
    let flops = s * 64.0
        + listed * 2.0 * nf * s * s
        + stressed
            * (600.0 * e
                + dense_mech * (d * e + 2.0 * mf * d * d + 10.0 * d * d * d)
                + (1.0 - dense_mech) * 200.0 * e);
    let (s_dim, d_dim) = (n.saturating_sub(r), m.saturating_sub(r));
    tensegrity_core::budget::Estimate::new(
        format!("the sparse statics of the {m} × {n} equilibrium matrix after its QR"),
        format!("the scene's {s_dim} self-stresses and {d_dim} mechanisms"),
    )
    .memory(memory)
    .work(flops / SPARSE_FLOP_RATE)
}

/// A bound of the bytes the sparse factorisation holds: the profile of A in the ordering (each
/// column's reflector and R entries lie within its positions 0..=l, l its last row: one f64
/// each, two allocations a column). The dense output bases (members × self-stress dimension,
/// dofs × mechanisms) come on top; they are the size of the report itself.
fn sparse_bytes_bound(a: &CscMatrix, pos_of_row: &[usize]) -> f64 {
    let (cp, ri) = (a.pattern().col_ptr(), a.pattern().row_idx());
    let profile: f64 = (0..a.pattern().ncols())
        .map(|k| {
            ri[cp[k]..cp[k + 1]]
                .iter()
                .map(|&r| pos_of_row[r] + 1)
                .max()
                .unwrap_or(0) as f64
        })
        .sum();
    8.0 * profile + 64.0 * a.pattern().ncols() as f64
}

/// σ_max of A by the power method on AᵀA (a lower estimate, accurate to a few digits).
pub(super) fn sigma_max(a: &CscMatrix) -> f64 {
    let (m, n) = (a.pattern().nrows(), a.pattern().ncols());
    if m == 0 || n == 0 {
        return 0.0;
    }
    let mut x: Vec<f64> = (0..n).map(|k| 1.0 + ((k * 37) % 11) as f64 * 0.1).collect();
    let mut sigma = 0.0;
    for _ in 0..POWER_STEPS {
        let norm = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        if norm == 0.0 {
            return 0.0;
        }
        x.iter_mut().for_each(|v| *v /= norm);
        let y = a.mul_vec(&x);
        sigma = y.iter().map(|v| v * v).sum::<f64>().sqrt();
        x = transpose_mul(a, &y);
    }
    sigma
}

/// Aᵀ y for a CSC matrix.
fn transpose_mul(a: &CscMatrix, y: &[f64]) -> Vec<f64> {
    let (cp, ri, v) = (a.pattern().col_ptr(), a.pattern().row_idx(), a.values());
    (0..a.pattern().ncols())
        .map(|k| (cp[k]..cp[k + 1]).map(|s| v[s] * y[ri[s]]).sum())
        .collect()
}

/// The lower triangle of NᵀN for a sparse N, from the rows of N (each row's pairs).
fn gram_lower(n: &CscMatrix) -> Result<CscMatrix> {
    let (rows, cols) = (n.pattern().nrows(), n.pattern().ncols());
    let (cp, ri, v) = (n.pattern().col_ptr(), n.pattern().row_idx(), n.values());
    let mut by_row: Vec<Vec<(usize, f64)>> = vec![Vec::new(); rows];
    for c in 0..cols {
        for s in cp[c]..cp[c + 1] {
            by_row[ri[s]].push((c, v[s]));
        }
    }
    let mut t = Vec::new();
    for row in &by_row {
        for &(a, va) in row {
            for &(b, vb) in row {
                if a >= b {
                    t.push((a, b, va * vb));
                }
            }
        }
    }
    Ok(CscMatrix::from_triplets(cols, cols, &t)?)
}

/// The factored equilibrium problem of a large structure (see the module documentation).
#[derive(Debug, Clone)]
pub struct SparseStatics<'a> {
    structure: &'a Structure,
    dofs: DofMap,
    a: CscMatrix,
    qr: RankRevealingQr,
    tolerance: f64,
    /// The residual at or below which a column is rejected
    /// ([`crate::rank::RankTolerance::reject_level`]).
    reject: f64,
    sigma_max: f64,
    sigma_min_estimate: f64,
    null_basis: CscMatrix,
    self_stress: OnceLock<DMatrix<f64>>,
}

impl<'a> SparseStatics<'a> {
    /// Orders, bounds the memory against the budget of `settings`, factors and builds the
    /// orthonormal self-stress basis.
    pub fn with_settings(structure: &'a Structure, settings: StaticsSettings) -> Result<Self> {
        let dofs = DofMap::of(structure);
        let a = equilibrium_matrix_sparse(structure, &dofs)?;
        let (row_order, pos_of_row) = row_ordering(structure, &dofs);
        let bytes = sparse_bytes_bound(&a, &pos_of_row);
        let limit = settings.memory_limit.unwrap_or(super::DEFAULT_MEMORY_LIMIT);
        if bytes > limit {
            return Err(CoreError::TooLarge {
                what: "the sparse QR of the equilibrium matrix",
                rows: dofs.len(),
                cols: crate::n_columns(structure),
                bytes,
                limit,
            });
        }
        let (m, n) = (dofs.len(), crate::n_columns(structure));
        let sigma = sigma_max(&a);
        let scales = settings.rank_scales(structure, (m, n), sigma);
        let (tolerance, reject) = (scales.absolute(), scales.reject_level(REJECT_FACTOR));
        let qr = RankRevealingQr::with_deferral(
            &a,
            &row_order,
            reject,
            defer_level(m, n, sigma, reject),
        )?;
        // the rank is known: the bases, the LP and the stability test are estimated and
        // checked before they are allocated
        let after = after_qr(
            m,
            n,
            qr.rank(),
            qr.stored_entries(),
            dense_mechanisms_max(structure),
        );
        let limits = tensegrity_core::budget::Limits {
            memory_bytes: limit,
            work_s: settings.work_limit.unwrap_or(f64::INFINITY),
            output_bytes: f64::INFINITY,
        };
        limits
            .check(&after)
            .map_err(|over| CoreError::OverBudget(Box::new(over)))?;
        let sigma_min_estimate = qr.sigma_min_estimate(INVERSE_STEPS);
        let null_basis = qr.sparse_null_vectors()?;
        Ok(Self {
            structure,
            dofs,
            a,
            qr,
            tolerance,
            reject,
            sigma_max: sigma,
            sigma_min_estimate,
            null_basis,
            self_stress: OnceLock::new(),
        })
    }

    /// The analysed structure.
    pub fn structure(&self) -> &Structure {
        self.structure
    }

    /// The free degrees of freedom (rows of A).
    pub fn dofs(&self) -> &DofMap {
        &self.dofs
    }

    /// The sparse equilibrium matrix.
    pub fn matrix(&self) -> &CscMatrix {
        &self.a
    }

    /// The factorisation.
    pub fn factorization(&self) -> &RankRevealingQr {
        &self.qr
    }

    /// The absolute rank tolerance τ.
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// Rank of A.
    pub fn rank(&self) -> usize {
        self.qr.rank()
    }

    /// Dimension of the self-stress space.
    pub fn self_stress_dim(&self) -> usize {
        crate::n_columns(self.structure) - self.rank()
    }

    /// First-order mechanisms, rigid-body motions included.
    pub fn mechanisms(&self) -> usize {
        self.dofs.len() - self.rank()
    }

    /// Whether the rank decision is certified (see the module documentation); a rank of 0
    /// only where all of A is below the rejection level (σ_max ≤ it), since no accepted
    /// column then bounds the gap.
    pub fn is_certified(&self) -> bool {
        if self.rank() == 0 {
            return self.sigma_max <= self.reject;
        }
        let noise = self.qr.rejected_residual().max(self.tolerance);
        self.sigma_min_estimate > CERTIFY_FACTOR * noise
    }

    /// The estimate of σ_min(R_acc), a lower bound of σ_r(A) (+∞ at rank 0).
    pub fn sigma_min_r_estimate(&self) -> f64 {
        self.sigma_min_estimate
    }

    /// An estimate of the smallest singular value of A: the rejected residual norm (an upper
    /// bound, ≤ τ) when A is rank deficient, else the σ_min(R_acc) estimate.
    pub fn smallest_singular_value_estimate(&self) -> f64 {
        let (m, n) = (self.dofs.len(), crate::n_columns(self.structure));
        if self.rank() < m.min(n) {
            self.qr.rejected_residual()
        } else {
            self.sigma_min_estimate
        }
    }

    /// The orthonormal self-stress basis (members × dimension), oriented like the dense
    /// path's: the sparse basis orthonormalised by a thin QR on first use, O(members·s²)
    /// flops and members·s numbers (the statics report lists it only up to
    /// [`SELF_STRESS_LIST_MAX`] numbers).
    pub fn self_stress_basis(&self) -> &DMatrix<f64> {
        self.self_stress.get_or_init(|| {
            let n = &self.null_basis;
            let (rows, cols) = (n.pattern().nrows(), n.pattern().ncols());
            if cols == 0 {
                return DMatrix::zeros(rows, 0);
            }
            let mut f = DMatrix::<f64>::zeros(rows, cols);
            let (cp, ri, v) = (n.pattern().col_ptr(), n.pattern().row_idx(), n.values());
            for c in 0..cols {
                for s in cp[c]..cp[c + 1] {
                    f[(ri[s], c)] = v[s];
                }
            }
            let q = tensegrity_linalg::dense::thin_q(&f);
            orient_self_stress(q, self.structure.n_bars())
        })
    }

    /// The sparse self-stress basis N (members × dimension, not orthonormal): one null
    /// vector per rejected member, 1 at that member and 0 at the other rejected ones
    /// ([`RankRevealingQr::sparse_null_vectors`]).
    pub fn sparse_self_stress_basis(&self) -> &CscMatrix {
        &self.null_basis
    }

    /// The orthogonal projection of `x` (members) on the self-stress space,
    /// N (NᵀN)⁻¹ Nᵀ x, by a sparse Cholesky factorisation of NᵀN (s × s, sparse when the
    /// null vectors are local; NᵀN ⪰ I since each null vector has a unit entry where the
    /// others vanish). The normal equations lose accuracy with N's conditioning, so the
    /// component is removed again from the remainder twice (iterative refinement).
    pub fn project_on_self_stress(&self, x: &[f64]) -> Result<Vec<f64>> {
        let n = &self.null_basis;
        let members = n.pattern().nrows();
        if n.pattern().ncols() == 0 {
            return Ok(vec![0.0; members]);
        }
        let gram = gram_lower(n)?;
        let mut chol = linalg::SparseCholesky::new(gram.pattern())?;
        chol.factor(gram.values())?;
        let mut rest = x.to_vec();
        for _ in 0..3 {
            let mut c = transpose_mul(n, &rest);
            chol.solve_in_place(&mut c);
            for (r, v) in rest.iter_mut().zip(n.mul_vec(&c)) {
                *r -= v;
            }
        }
        Ok(x.iter().zip(&rest).map(|(a, b)| a - b).collect())
    }
}

/// How many times A's entries the sparse self-stress basis N may hold before the margin LP
/// runs on A (the interior point on A D⁻¹ Aᵀ) instead of on N: N's LP (Clarabel) costs
/// about a factorisation of N's pattern, A's about one of a stiffness matrix's. Measured by
/// `tensegrity-statics`' `lp_scaling` example (the LP alone, release): a tower's N is
/// local (0.22 × A), where the LP over N costs 6.9 ms at 200 prisms against 15 ms on A; a
/// lattice's N fills in (0.82 × A at K = 3, 1.5 × at K = 4, 8–13 × at K = 8…10), where the
/// LP on A costs 0.19 and 0.52 ms against 0.79 and 2.4 ms over N. At the earlier limit of 4
/// the LP of the lattice K = 4 cost three times that of K = 5 (on the nested path).
pub const NULL_BASIS_FILL_MAX: f64 = 0.5;

/// Largest ‖A n‖∞ / (σ_max(A)·‖n‖∞) over the columns n of the sparse self-stress basis for
/// which the self-stresses count as exact ([`prefers_equilibrium_lp`]): round-off is
/// 10⁻¹⁵–10⁻¹³, a self-stress that rounded coordinates hold only to their precision
/// (10⁻⁴–10⁻⁸) is far above.
pub(crate) const EXACT_SELF_STRESS_RESIDUAL: f64 = 1e-10;

/// Whether the margin LP should run on the equilibrium rows of `a` rather than on the basis
/// `null_basis`: where N holds more than [`NULL_BASIS_FILL_MAX`] times A's entries, and
/// only if its columns are exact self-stresses (A n = 0 to round-off,
/// [`EXACT_SELF_STRESS_RESIDUAL`]). The interior point imposes A q = 0 exactly, so on
/// coordinates rounded to a few digits, whose self-stresses the rank decision counts at
/// the coordinates' precision, it would find none: measured on rounded forms of the
/// gallery (`--input-precision 1e-4`), margin 0 or a different one where the LP over N
/// gives the dense path's.
fn prefers_equilibrium_lp(null_basis: &CscMatrix, a: &CscMatrix, sigma_max: f64) -> bool {
    let fill = null_basis.values().len() as f64 / a.values().len().max(1) as f64;
    if fill <= NULL_BASIS_FILL_MAX {
        return false;
    }
    let (cp, ri, vals) = (
        null_basis.pattern().col_ptr(),
        null_basis.pattern().row_idx(),
        null_basis.values(),
    );
    let (acp, ari, avals) = (a.pattern().col_ptr(), a.pattern().row_idx(), a.values());
    // A n from the columns of A that n touches (its members), in a scatter vector
    let (mut y, mut touched) = (vec![0.0; a.pattern().nrows()], Vec::new());
    for c in 0..null_basis.pattern().ncols() {
        let mut norm = 0.0f64;
        for slot in cp[c]..cp[c + 1] {
            let (k, v) = (ri[slot], vals[slot]);
            norm = norm.max(v.abs());
            for s in acp[k]..acp[k + 1] {
                y[ari[s]] += avals[s] * v;
                touched.push(ari[s]);
            }
        }
        let mut residual = 0.0f64;
        for &r in &touched {
            residual = residual.max(y[r].abs());
            y[r] = 0.0;
        }
        touched.clear();
        // (a NaN residual is not exact either)
        let exact = residual <= EXACT_SELF_STRESS_RESIDUAL * sigma_max * norm;
        if !exact {
            return false;
        }
    }
    true
}

impl SparseStatics<'_> {
    /// The prestressability LP over the member force densities (see the module
    /// documentation).
    pub fn prestressability(&self) -> Result<Prestressability> {
        self.prestressability_with(&MemberSign::standard(self.structure))
    }

    /// The margin LP with the given member signs ([`MemberSign`]) over the member force
    /// densities.
    pub fn prestressability_with(&self, signs: &[MemberSign]) -> Result<Prestressability> {
        let n = crate::n_columns(self.structure);
        super::prestress::check_signs(signs, n)?;
        if self.self_stress_dim() == 0 {
            return Ok(Prestressability::none(n));
        }
        // the method by the sizes of the two formulations: the LP over the sparse basis
        // (Clarabel's LDL on N's pattern) where N is local, the interior point on A D⁻¹ Aᵀ
        // (a stiffness pattern) where N has filled in (a lattice's basis: grid:10, 1,420
        // members, N 107,160 entries against A's 8,520, took 0.49 s by the first and 0.01 s
        // by the second); the other one should the chosen one fail
        if prefers_equilibrium_lp(&self.null_basis, &self.a, self.sigma_max) {
            if let Ok(q) = super::margin_ipm::solve(&self.a, signs, None) {
                return Ok(Prestressability::from_signed(DVector::from_vec(q), signs));
            }
        }
        let q = match super::prestress::solve_null_space_lp(&self.null_basis, signs) {
            Ok(c) => DVector::from_vec(self.null_basis.mul_vec(&c)),
            // the sparse basis is not orthonormal, and its LP can stall (a Levy dome of 4,080
            // members: NumericalError); where the orthonormal basis is small enough to hold,
            // the same LP over it (same optimum: the rows constrain q = N c alike)
            Err(e) if n.saturating_mul(self.self_stress_dim()) > ORTHONORMAL_LP_MAX => {
                return Err(e)
            }
            Err(_) => {
                let basis = self.self_stress_basis();
                let x = super::prestress::margin_lp(
                    basis,
                    signs,
                    super::LpSolver::default(),
                    "prestressability LP (orthonormal self-stress basis, after the sparse one failed)",
                )?;
                basis * x
            }
        };
        Ok(Prestressability::from_signed(q, signs))
    }

    /// An orthonormal basis of the internal mechanisms (free dofs × count): the flexes with
    /// the rigid-body motions the supports allow projected out; and the rigid-body count.
    pub fn internal_mechanisms(&self) -> Result<(DMatrix<f64>, usize)> {
        let motions = self.qr.left_null_vectors();
        let rigid = rigid_motions(self.structure, &self.dofs)?;
        let n_rigid = rigid.ncols();
        let d = motions.ncols();
        let internal_dim = d.saturating_sub(n_rigid);
        if internal_dim == 0 {
            return Ok((DMatrix::zeros(motions.nrows(), 0), n_rigid));
        }
        let projected = &motions - &rigid * (rigid.transpose() * &motions);
        let gram = projected.transpose() * &projected;
        let gram = (&gram + gram.transpose()) * 0.5;
        let (w, v) = linalg::symmetric_eigen(&gram)?;
        // the largest `internal_dim` eigenvalues (ascending order: the last ones), ≈ 1
        let mut phi = &projected * v.columns(d - internal_dim, internal_dim);
        for (c, k) in (d - internal_dim..d).enumerate() {
            phi.column_mut(c)
                .scale_mut(1.0 / w[k].max(f64::MIN_POSITIVE).sqrt());
        }
        Ok((phi, n_rigid))
    }

    /// The rigid-body motions the supports allow.
    pub fn rigid_body_motions(&self) -> Result<usize> {
        Ok(rigid_motions(self.structure, &self.dofs)?.ncols())
    }

    /// Prestress stability with force densities `q` (normally a self-stress).
    ///
    /// While the internal-mechanism basis is small (free dofs × mechanisms ≤
    /// [`DENSE_MECHANISMS_MAX`]) this is the dense path's test and tolerance (the eigenvalues
    /// of the stress matrix projected on an orthonormal basis of the internal mechanisms must
    /// exceed 10⁻⁹·max|q|). Beyond, the sparse test [`stable_by_cholesky`](Self::stable_by_cholesky)
    /// decides; when it cannot certify stability the answer is the error
    /// [`CoreError::Unsupported`] (the report then says that stability was not tested).
    pub fn prestress_stability(&self, q: &DVector<f64>) -> Result<PrestressStability> {
        let (m, d) = (self.dofs.len(), self.mechanisms());
        let basis = m.saturating_mul(d);
        let dense_fits = basis <= dense_mechanisms_max(self.structure);
        // the dense test first where it is cheap, or where the sparse one cannot answer (a
        // structure with clusters); the sparse test first from DENSE_MECHANISMS_FIRST on, the
        // dense one then only where the sparse one gives no decision
        if dense_fits && (basis <= DENSE_MECHANISMS_FIRST || self.structure.has_clusters()) {
            let (phi, _) = self.internal_mechanisms()?;
            return self.prestress_stability_on(&phi, q);
        }
        let internal = d.saturating_sub(self.rigid_body_motions()?);
        if internal == 0 {
            return Ok(PrestressStability::rigid());
        }
        match self.stable_by_cholesky(q)? {
            Some(stable) => Ok(PrestressStability {
                internal_mechanisms: internal,
                eigenvalues: Vec::new(),
                stable,
            }),
            None if dense_fits => {
                let (phi, _) = self.internal_mechanisms()?;
                self.prestress_stability_on(&phi, q)
            }
            None => Err(Factorization::SparseQr.unsupported(
                "prestress stability of a structure this large whose flexes are not local (or disagree with the rank)",
            )),
        }
    }

    /// The sparse prestress-stability test: `Some(stable)` with the dense path's decision
    /// (the stress matrix Ω̄ = Ω ⊗ I₃ on the internal mechanisms, Rayleigh quotients above
    /// σ = 10⁻⁹·max|q|) but in a borderline case; `None` (no decision) when neither of its
    /// two tests decides.
    ///
    /// First the penalised stress matrix (`statics/penalty.rs`, a banded sparse Cholesky of
    /// Ω̄ − σ′I + μAAᵀ on the kept dofs, linear in the size): it certifies `Some(true)` or
    /// gives no decision, never "unstable". It goes first because the flex test's product
    /// Mᵀ Ω̄ M grows faster than linearly as a tower's flexes lengthen: with the flex test
    /// first a tower of 475 prisms cost 119 ms and one of 575, whose flexes are past the
    /// locality limit, 75 ms (`docs/notes/PERFORMANCE.md`, "Statics cost against size").
    ///
    /// Where it gives no decision (an unstable structure, or a μ ladder too short), the
    /// flex test [`stable_by_flexes`](Self::stable_by_flexes) decides.
    pub fn stable_by_cholesky(&self, q: &DVector<f64>) -> Result<Option<bool>> {
        let q_max = q.amax();
        if !self.member_by_member(q) {
            return Ok(None);
        }
        let rigid = rigid_motions(self.structure, &self.dofs)?;
        let (index, kept) = kept_dofs(self.dofs.len(), &pinned_rows(&rigid));
        let certificate = stable_by_penalty(
            self.structure,
            &self.dofs,
            &index,
            kept,
            q,
            1e-9 * q_max,
            self.sigma_max,
        )?;
        if certificate.is_some() {
            return Ok(certificate);
        }
        self.stable_by_flexes(q)
    }

    /// Whether the stability tests that assemble the stress matrix member by member apply
    /// to `q`: a cluster's stress matrix (its geometric part over all its segments) is not
    /// in them, so they give no decision for a structure with clusters.
    fn member_by_member(&self, q: &DVector<f64>) -> bool {
        let q_max = q.amax();
        q.len() == self.structure.n_members()
            && !self.structure.has_clusters()
            && q_max > 0.0
            && q_max.is_finite()
    }

    /// The flex test alone: `Some(stable)` with the dense path's decision (as
    /// [`stable_by_cholesky`](Self::stable_by_cholesky)) but in a borderline case; `None`
    /// (no decision) when the sparse flexes do not match the rank of A, or are not local
    /// (more than [`FLEX_ENTRIES_PER_DOF`] entries per kept dof: the product Mᵀ Ω̄ M would
    /// then grow quadratically; a long tower's flexes span a growing part of it), or,
    /// without trying, when the factor of A holds more than [`FLEX_QR_ENTRIES_PER_DOF`]
    /// entries per kept dof.
    ///
    /// A few free dofs are pinned (the rows of the rigid-body basis T with the largest
    /// pivots, one per rigid motion the supports allow), so that every internal mechanism
    /// has exactly one representative vanishing there: the null space of Aᵀ without the
    /// pinned rows. Its sparse basis M (kept dofs × internal mechanisms) comes from a second
    /// rank-revealing QR, of Aᵀ (members along the band, dofs as columns), whose null
    /// vectors are local flexes ([`RankRevealingQr::sparse_null_vectors`]). Then
    /// K = Mᵀ Ω̄ M − σ MᵀM (sparse: member by member, Σ q_k (Δ_k M)ᵀ(Δ_k M)) is positive
    /// definite exactly when every pinned internal mechanism w has wᵀΩ̄w > σ‖w‖², tested by a
    /// sparse Cholesky factorisation. Ω̄ annihilates the rigid motions (q a self-stress) and
    /// the orthogonal representative is the shortest of its class, so K positive definite
    /// implies the dense test's "stable"; the converse holds unless the smallest Rayleigh
    /// quotient lies within the pinning's conditioning of σ.
    pub fn stable_by_flexes(&self, q: &DVector<f64>) -> Result<Option<bool>> {
        let q_max = q.amax();
        if !self.member_by_member(q) {
            return Ok(None);
        }
        let rigid = rigid_motions(self.structure, &self.dofs)?;
        let internal = self.mechanisms().saturating_sub(rigid.ncols());
        let (index, kept) = kept_dofs(self.dofs.len(), &pinned_rows(&rigid));
        if self.qr.stored_entries() > FLEX_QR_ENTRIES_PER_DOF.saturating_mul(kept) {
            return Ok(None);
        }
        // Aᵀ on the kept dofs: members × kept dofs, members in the band order of the nodes
        let n = self.structure.n_members();
        let member_nodes = self.structure.member_nodes();
        let mut t = Vec::with_capacity(6 * n);
        for (k, &[i, j]) in member_nodes.iter().enumerate() {
            let e = self.structure.nodes()[j] - self.structure.nodes()[i];
            for d in 0..3 {
                for (node, sign) in [(i, -1.0), (j, 1.0)] {
                    if let Some(c) = self.dofs.row[node][d].and_then(|r| index[r]) {
                        t.push((k, c, sign * self.dofs.component(node, d, &e)));
                    }
                }
            }
        }
        let at = CscMatrix::from_triplets(n, kept, &t)?;
        let node_pos = inverse(&node_order_rcm(self.structure));
        let mut member_order: Vec<usize> = (0..n).collect();
        member_order.sort_by_key(|&k| {
            let [i, j] = member_nodes[k];
            let (a, b) = (node_pos[i], node_pos[j]);
            (a.max(b), a.min(b))
        });
        let flexes = RankRevealingQr::with_deferral(
            &at,
            &member_order,
            self.reject,
            defer_level(n, kept, self.sigma_max, self.reject),
        )?;
        if flexes.rank() != self.rank() || kept - flexes.rank() != internal {
            return Ok(None);
        }
        let Some(m) = flexes.sparse_null_vectors_within(FLEX_ENTRIES_PER_DOF * kept)? else {
            return Ok(None);
        };
        let kmat = self.projected_stress_lower(&m, q, &index, 1e-9 * q_max)?;
        let mut chol = linalg::SparseCholesky::new(kmat.pattern())?;
        Ok(Some(chol.factor(kmat.values()).is_ok()))
    }

    /// The lower triangle of K = Mᵀ (Ω̄ − σ I) M for a sparse M (kept dofs × d, `index`
    /// numbering the kept dofs among the free ones), column by column: Y = (Ω̄ − σ I) M_c
    /// member by member from the nodes M_c touches, then Mᵀ Y through the rows of M, both
    /// accumulated in scatter vectors (cost ≈ nnz(M) × the rows' lengths).
    fn projected_stress_lower(
        &self,
        m: &CscMatrix,
        q: &DVector<f64>,
        index: &[Option<usize>],
        sigma: f64,
    ) -> Result<CscMatrix> {
        let kept = m.pattern().nrows();
        let d = m.pattern().ncols();
        let mut dof_of = vec![(0usize, 0usize); kept];
        for (node, rows) in self.dofs.row.iter().enumerate() {
            for (dir, r) in rows.iter().enumerate() {
                if let Some(k) = r.and_then(|r| index[r]) {
                    dof_of[k] = (node, dir);
                }
            }
        }
        let mut adjacent = vec![Vec::new(); self.structure.n_nodes()];
        for (k, [i, j]) in self.structure.member_nodes().into_iter().enumerate() {
            adjacent[i].push((j, q[k]));
            adjacent[j].push((i, q[k]));
        }
        let kept_at = |node: usize, dir: usize| self.dofs.row[node][dir].and_then(|r| index[r]);
        let rows = csc_rows(m);
        let (cp, ri, vals) = (m.pattern().col_ptr(), m.pattern().row_idx(), m.values());
        let (mut y, mut y_touched, mut y_seen) = (vec![0.0; kept], Vec::new(), vec![false; kept]);
        let (mut acc, mut acc_touched, mut acc_seen) = (vec![0.0; d], Vec::new(), vec![false; d]);
        let mut t = Vec::new();
        for c in 0..d {
            let mut add = |r: usize, v: f64, y: &mut [f64]| {
                y[r] += v;
                if !y_seen[r] {
                    y_seen[r] = true;
                    y_touched.push(r);
                }
            };
            for s in cp[c]..cp[c + 1] {
                let (r, v) = (ri[s], vals[s]);
                let (node, dir) = dof_of[r];
                add(r, -sigma * v, &mut y);
                for &(other, qk) in &adjacent[node] {
                    add(r, qk * v, &mut y);
                    // the other node's axes weighted by their alignment with this one's
                    // (the same axis, weight 1, unless a node has a frame)
                    for (b, w) in self.dofs.coupling(node, dir, other).into_iter().enumerate() {
                        if let (Some(r2), true) = (kept_at(other, b), w != 0.0) {
                            add(r2, -qk * v * w, &mut y);
                        }
                    }
                }
            }
            for &r in &y_touched {
                let yr = y[r];
                y[r] = 0.0;
                y_seen[r] = false;
                for &(a, mv) in &rows[r] {
                    if a >= c {
                        acc[a] += mv * yr;
                        if !acc_seen[a] {
                            acc_seen[a] = true;
                            acc_touched.push(a);
                        }
                    }
                }
            }
            y_touched.clear();
            t.push((c, c, 0.0));
            for &a in &acc_touched {
                t.push((a, c, acc[a]));
                acc[a] = 0.0;
                acc_seen[a] = false;
            }
            acc_touched.clear();
        }
        Ok(CscMatrix::from_triplets(d, d, &t)?)
    }

    /// Prestress stability with force densities `q` on a given orthonormal basis `phi` of the
    /// internal mechanisms ([`internal_mechanisms`](Self::internal_mechanisms)).
    pub fn prestress_stability_on(
        &self,
        phi: &DMatrix<f64>,
        q: &DVector<f64>,
    ) -> Result<PrestressStability> {
        if phi.ncols() == 0 {
            return Ok(PrestressStability::rigid());
        }
        let omega_phi = self.stress_matrix_times(q, phi);
        PrestressStability::from_projected(&(phi.transpose() * omega_phi), q.amax())
    }

    /// (Ω ⊗ I₃) X on the free dofs, member by member: Ω = Cᵀ diag(q) C; a cluster's
    /// column q_c adds its geometric part q_c L_c Σ_i (1/l_i) [[P_i, −P_i], [−P_i, P_i]]
    /// (P_i = I − e_i e_iᵀ, [`crate::cluster_columns`]), as the dense path's stress matrix.
    fn stress_matrix_times(&self, q: &DVector<f64>, x: &DMatrix<f64>) -> DMatrix<f64> {
        if !self.dofs.is_axis_aligned() || self.structure.has_clusters() {
            return stress_matrix_times_framed(self.structure, &self.dofs, q, x);
        }
        let mut y = DMatrix::zeros(x.nrows(), x.ncols());
        let pairs: Vec<(f64, Option<usize>, Option<usize>)> = self
            .structure
            .member_nodes()
            .into_iter()
            .enumerate()
            .flat_map(|(k, [i, j])| (0..3).map(move |d| (k, i, j, d)))
            .map(|(k, i, j, d)| (q[k], self.dofs.row[i][d], self.dofs.row[j][d]))
            .collect();
        for (xc, mut yc) in x.column_iter().zip(y.column_iter_mut()) {
            for &(qk, ri, rj) in &pairs {
                let xi = ri.map_or(0.0, |r| xc[r]);
                let xj = rj.map_or(0.0, |r| xc[r]);
                let f = qk * (xi - xj);
                if let Some(r) = ri {
                    yc[r] += f;
                }
                if let Some(r) = rj {
                    yc[r] -= f;
                }
            }
        }
        y
    }

    /// Solves for the structure's own loads (nodal loads plus gravity on bar masses).
    pub fn solve_loads(&self) -> LoadSolution {
        self.solve_nodal_forces(&self.structure.W())
    }

    /// The minimal-norm solution of A q = w for a 3×n nodal force matrix.
    pub fn solve_nodal_forces(&self, w_nodes: &nalgebra::Matrix3xX<f64>) -> LoadSolution {
        let w = self.dofs.gather(w_nodes);
        let (basic, _) = self.qr.solve_basic(w.as_slice());
        let q = match self.project_on_self_stress(basic.as_slice()) {
            Ok(p) => &basic - DVector::from_vec(p),
            // NᵀN is positive definite in exact arithmetic; should its factorisation fail,
            // the orthonormal basis projects instead
            Err(_) => {
                let basis = self.self_stress_basis();
                &basic - basis * (basis.transpose() * &basic)
            }
        };
        let aq = DVector::from_vec(self.a.mul_vec(q.as_slice()));
        super::load::assemble_solution(self.structure, &self.dofs, w_nodes, q, &aq - &w)
    }
}

/// `inv[v] = position` of a permutation `order[position] = v`.
fn inverse(order: &[usize]) -> Vec<usize> {
    let mut inv = vec![0; order.len()];
    for (p, &v) in order.iter().enumerate() {
        inv[v] = p;
    }
    inv
}

/// The rows of a CSC matrix as (column, value) lists.
fn csc_rows(m: &CscMatrix) -> Vec<Vec<(usize, f64)>> {
    let (cp, ri, v) = (m.pattern().col_ptr(), m.pattern().row_idx(), m.values());
    let mut rows = vec![Vec::new(); m.pattern().nrows()];
    for c in 0..m.pattern().ncols() {
        for s in cp[c]..cp[c + 1] {
            rows[ri[s]].push((c, v[s]));
        }
    }
    rows
}

/// (Ω ⊗ I₃) X on the free dofs of a map with node frames: each column expanded to the nodes'
/// vectors, Σ_k q_k (u_i − u_j) at i (minus at j), projected back on the free axes.
fn stress_matrix_times_framed(
    structure: &Structure,
    dofs: &DofMap,
    q: &DVector<f64>,
    x: &DMatrix<f64>,
) -> DMatrix<f64> {
    let mut y = DMatrix::zeros(x.nrows(), x.ncols());
    let members = structure.member_nodes();
    let clusters = crate::cluster_columns::cluster_geometries(structure);
    for (xc, mut yc) in x.column_iter().zip(y.column_iter_mut()) {
        let xs: Vec<f64> = xc.iter().copied().collect();
        let u = dofs.expand(&xs);
        let mut f = vec![Vector3::zeros(); u.len()];
        for (k, &[i, j]) in members.iter().enumerate() {
            let t = (u[i] - u[j]) * q[k];
            f[i] += t;
            f[j] -= t;
        }
        for (c, g) in clusters.iter().enumerate() {
            let w = q[members.len() + c] * g.length;
            for s in &g.segments {
                let [i, j] = s.nodes;
                let du = u[i] - u[j];
                let t = (du - s.unit * s.unit.dot(&du)) * (w / s.length);
                f[i] += t;
                f[j] -= t;
            }
        }
        for (r, &(node, a)) in dofs.free.iter().enumerate() {
            yc[r] = dofs.component(node, a, &f[node]);
        }
    }
    y
}

/// The penalised stress-matrix certificate (`statics/penalty.rs`) for `structure` on its
/// free dofs `dofs`, with the pins of [`SparseStatics::stable_by_cholesky`] (one free dof per
/// rigid motion the supports allow) and the dense test's threshold σ = 10⁻⁹·max|q|:
/// `Some(true)` when it proves the stress `q` stable, `None` when it cannot decide.
/// `sigma_a` is σ_max(A). Linear in the members (a banded sparse Cholesky).
pub(super) fn stable_by_penalty_certificate(
    structure: &Structure,
    dofs: &DofMap,
    q: &DVector<f64>,
    sigma_a: f64,
) -> Result<Option<bool>> {
    let q_max = q.amax();
    if q.len() != structure.n_members() || !(q_max > 0.0 && q_max.is_finite()) {
        return Ok(None);
    }
    let rigid = rigid_motions(structure, dofs)?;
    let (index, kept) = kept_dofs(dofs.len(), &pinned_rows(&rigid));
    stable_by_penalty(structure, dofs, &index, kept, q, 1e-9 * q_max, sigma_a)
}

/// One free-dof row per column of the rigid-body basis `t` (m × k): greedy pivoting on the
/// rows (the row of largest residual norm, then the others orthogonalised against it), so
/// that the k × k submatrix is well conditioned.
fn pinned_rows(t: &DMatrix<f64>) -> Vec<usize> {
    let mut res = t.clone();
    let mut chosen = Vec::with_capacity(t.ncols());
    for _ in 0..t.ncols() {
        let best = (0..res.nrows())
            .filter(|r| !chosen.contains(r))
            .max_by(|&a, &b| {
                res.row(a)
                    .norm_squared()
                    .total_cmp(&res.row(b).norm_squared())
            });
        let Some(best) = best else { break };
        let norm = res.row(best).norm();
        if norm <= 0.0 {
            break;
        }
        let v = res.row(best).transpose() / norm;
        let proj = &res * &v;
        res -= proj * v.transpose();
        chosen.push(best);
    }
    chosen
}

/// The new index of every free dof without the `pinned` ones, and their count.
fn kept_dofs(m: usize, pinned: &[usize]) -> (Vec<Option<usize>>, usize) {
    let mut index = vec![None; m];
    let mut next = 0;
    for (r, slot) in index.iter_mut().enumerate() {
        if !pinned.contains(&r) {
            *slot = Some(next);
            next += 1;
        }
    }
    (index, next)
}

/// Rigid-body motions on the free dofs that the supports allow, orthonormal (free dofs ×
/// count), from 6×6 Gram matrices (no m × m factor).
pub(super) fn rigid_motions(structure: &Structure, dofs: &DofMap) -> Result<DMatrix<f64>> {
    let n = structure.n_nodes();
    let centre = structure.nodes().iter().sum::<Vector3<f64>>() / n.max(1) as f64;
    let mut t_free = DMatrix::zeros(dofs.len(), 6);
    let mut g_fixed = DMatrix::<f64>::zeros(6, 6);
    for (i, p) in structure.nodes().iter().enumerate() {
        let r = p - centre;
        for c in 0..3 {
            // row (i, c) of T on the node's axis c: translations and rotations (e_d × r)
            // along it
            let axis = dofs.axis(i, c);
            let mut row = [0.0; 6];
            for d in 0..3 {
                row[d] = axis[d];
                row[3 + d] = Vector3::ith(d, 1.0).cross(&r).dot(&axis);
            }
            match dofs.row[i][c] {
                Some(fr) => (0..6).for_each(|j| t_free[(fr, j)] = row[j]),
                None => {
                    for a in 0..6 {
                        for b in 0..6 {
                            g_fixed[(a, b)] += row[a] * row[b];
                        }
                    }
                }
            }
        }
    }
    // motions the supports allow: the null space of T_fixed, from its Gram matrix
    let (w, v) = linalg::symmetric_eigen(&g_fixed)?;
    let w_max = w.last().copied().unwrap_or(0.0);
    let allowed: Vec<usize> = (0..6).filter(|&k| w[k] <= 1e-12 * w_max.max(0.0)).collect();
    let t = &t_free * v.select_columns(allowed.iter());
    let g = t.transpose() * &t;
    let (w, v) = linalg::symmetric_eigen(&((&g + g.transpose()) * 0.5))?;
    let w_max = w.last().copied().unwrap_or(0.0);
    let keep: Vec<usize> = (0..w.len()).filter(|&k| w[k] > 1e-12 * w_max).collect();
    let mut basis = &t * v.select_columns(keep.iter());
    for (c, &k) in keep.iter().enumerate() {
        basis.column_mut(c).scale_mut(1.0 / w[k].sqrt());
    }
    Ok(basis)
}

/// The sparse QR as one back-end of the statics front.
impl StaticsBackend for SparseStatics<'_> {
    fn kind(&self) -> Factorization {
        Factorization::SparseQr
    }
    fn structure(&self) -> &Structure {
        SparseStatics::structure(self)
    }
    fn free_dofs(&self) -> usize {
        self.dofs().len()
    }
    fn rank(&self) -> usize {
        SparseStatics::rank(self)
    }
    fn rigid_body_motions(&self) -> Result<usize> {
        SparseStatics::rigid_body_motions(self)
    }
    fn tolerance(&self) -> f64 {
        SparseStatics::tolerance(self)
    }
    fn smallest_singular_value(&self) -> f64 {
        self.smallest_singular_value_estimate()
    }
    fn spectral_gap(&self) -> SpectralGap {
        let (m, n) = (
            self.dofs().len(),
            crate::n_columns(SparseStatics::structure(self)),
        );
        let above = self.sigma_min_r_estimate();
        let below = SparseStatics::factorization(self).rejected_residual();
        let below = (SparseStatics::rank(self) < m.min(n)).then_some(below);
        let mut gap = SpectralGap::from_values(below, SparseStatics::tolerance(self), None);
        gap.sigma_above = above.is_finite().then_some(above);
        gap.ratio = match (gap.sigma_above, gap.sigma_below) {
            (Some(a), Some(b)) if b > 0.0 => Some(a / b),
            _ => None,
        };
        gap
    }
    fn certification(&self) -> Certification {
        if self.is_certified() {
            return Certification::Certified;
        }
        Certification::NotCertified {
            reason: format!(
                "the sparse rank decision is not certified (rejected residual {:.3e}, σ_min(R) estimate {:.3e}, tolerance {:.3e}): rank and self-stress dimension may differ from the SVD's",
                SparseStatics::factorization(self).rejected_residual(),
                self.sigma_min_r_estimate(),
                SparseStatics::tolerance(self)
            ),
        }
    }
    fn self_stress(&self) -> SelfStressBasis {
        let (n, dim) = (
            crate::n_columns(SparseStatics::structure(self)),
            SparseStatics::self_stress_dim(self),
        );
        if n.saturating_mul(dim) > SELF_STRESS_LIST_MAX {
            return SelfStressBasis::Omitted {
                basis: DMatrix::zeros(n, 0),
                dim,
            };
        }
        SelfStressBasis::Full(self.self_stress_basis().clone())
    }
    fn prestressability_with(&self, signs: &[MemberSign]) -> Result<Prestressability> {
        SparseStatics::prestressability_with(self, signs)
    }
    fn prestress_stability(&self, q: &DVector<f64>) -> Result<PrestressStability> {
        SparseStatics::prestress_stability(self, q)
    }
    fn solve_nodal_forces(&self, w_nodes: &Matrix3xX<f64>) -> Result<LoadSolution> {
        Ok(SparseStatics::solve_nodal_forces(self, w_nodes))
    }
}
