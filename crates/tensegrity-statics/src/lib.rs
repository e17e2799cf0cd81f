//! Statics: the equilibrium matrix, its SVD, self-stress and mechanisms, prestressability and
//! load solves.
//!
//! With force densities q (tension positive, bars then strings) nodal equilibrium reads
//! N Cᵀ diag(q) C = W, i.e. column-wise A q = w where column k of A holds −m_k at the rows of
//! the member's start node and +m_k at the rows of its end node (m_k = n_end − n_start). Rows
//! of fixed degrees of freedom are removed from A; their reactions are reported separately.
//!
//! From the SVD A = U Σ Vᵀ with the rank r decided by [`rank`] (the arithmetic's tolerance,
//! [`tensegrity_linalg::rank_tolerance`], and the rounding of the data's coordinates):
//! - self-stress states: the last (members − r) columns of V (null space of A);
//! - mechanisms: 3·(free dofs) − r first-order motions (the null space of Aᵀ, i.e. the last
//!   columns of U), rigid-body motions included when the supports allow them.
//!
//! [`Statics`] (dense SVD), [`SparseStatics`] (sparse rank-revealing QR) and
//! [`symmetry::CyclicStatics`] (Fourier blocks of a Cₙ-symmetric structure) are the three
//! back-ends of one front, [`StaticsBackend`] ([`front`]); [`backend`] and [`cyclic_backend`]
//! choose one (`select.rs`), and [`report::report_from`] builds the statics report from any.

mod dense_lp;
mod flexes;
pub mod front;
mod gap;
mod load;
mod margin_ipm;
pub mod nested;
mod penalty;
mod prestress;
pub mod rank;
pub mod report;
mod select;
pub mod sizing;
pub mod sparse;
mod stability;
pub mod stiffness;
pub mod symmetry;

pub use flexes::Flexes;
pub use front::{Certification, Factorization, SelfStressBasis, StaticsBackend};
pub use gap::{SpectralGap, GAP_FACTOR};
pub use load::{LoadSolution, LOAD_RESIDUAL_TOLERANCE};
pub use nested::NestedStatics;
pub use prestress::{solve_lp, MemberSign, Prestressability, PRESTRESS_TOLERANCE};
pub use report::{statics_report, StaticsReport, StaticsRequest};
pub use select::{backend, cyclic_backend};
pub use sparse::{sparse_after_qr, sparse_statics_bytes, SparseStatics, SPARSE_FLOP_RATE};
pub use stability::PrestressStability;

use nalgebra::Matrix3xX;
use nalgebra::{DMatrix, DVector};
use tensegrity_core::error::Result;
use tensegrity_core::structure::Structure;
use tensegrity_linalg::{self as linalg, Svd};

/// Maps the free degrees of freedom (node, direction) to rows of A.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct DofMap {
    /// `(node, direction)` of each free row.
    pub free: Vec<(usize, usize)>,
    /// Row of each node's direction, `None` when fixed.
    pub row: Vec<[Option<usize>; 3]>,
}

impl DofMap {
    /// The free degrees of freedom of `structure` in node-major order.
    pub fn of(structure: &Structure) -> Self {
        let fixed = structure.fixed_dofs();
        let mut free = Vec::new();
        let mut row = vec![[None; 3]; fixed.len()];
        for (i, f) in fixed.iter().enumerate() {
            for d in 0..3 {
                if !f[d] {
                    row[i][d] = Some(free.len());
                    free.push((i, d));
                }
            }
        }
        Self { free, row }
    }

    /// Number of free degrees of freedom.
    pub fn len(&self) -> usize {
        self.free.len()
    }

    /// Whether every degree of freedom is fixed.
    pub fn is_empty(&self) -> bool {
        self.free.is_empty()
    }

    /// Restricts a 3×n nodal matrix to the free rows, as a vector.
    pub fn gather(&self, w: &nalgebra::Matrix3xX<f64>) -> DVector<f64> {
        DVector::from_iterator(self.free.len(), self.free.iter().map(|&(i, d)| w[(d, i)]))
    }
}

/// The full equilibrium matrix (3n × members, no rows removed), node-major rows.
///
/// ```
/// use tensegrity_core::{Bar, Structure};
/// use tensegrity_statics as statics;
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1))
///     .build()
///     .unwrap();
/// let a = statics::equilibrium_matrix_full(&s);
/// assert_eq!((a[(0, 0)], a[(3, 0)]), (-2.0, 2.0));
/// ```
pub fn equilibrium_matrix_full(structure: &Structure) -> DMatrix<f64> {
    let n = structure.n_nodes();
    let mut a = DMatrix::zeros(3 * n, structure.n_members());
    for (k, [i, j]) in structure.member_nodes().into_iter().enumerate() {
        let m = structure.nodes()[j] - structure.nodes()[i];
        for d in 0..3 {
            a[(3 * i + d, k)] = -m[d];
            a[(3 * j + d, k)] = m[d];
        }
    }
    a
}

/// The equilibrium matrix restricted to free degrees of freedom.
pub fn equilibrium_matrix(structure: &Structure, dofs: &DofMap) -> DMatrix<f64> {
    let mut a = DMatrix::zeros(dofs.len(), structure.n_members());
    for (k, [i, j]) in structure.member_nodes().into_iter().enumerate() {
        let m = structure.nodes()[j] - structure.nodes()[i];
        for d in 0..3 {
            if let Some(r) = dofs.row[i][d] {
                a[(r, k)] = -m[d];
            }
            if let Some(r) = dofs.row[j][d] {
                a[(r, k)] = m[d];
            }
        }
    }
    a
}

/// Which solver runs the prestressability LP.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum LpSolver {
    /// The built-in dense predictor–corrector interior-point method (fast on the dense LP;
    /// falls back to Clarabel if it fails).
    #[default]
    DenseInteriorPoint,
    /// The Clarabel conic solver (sparse LDL).
    Clarabel,
}

/// Which factorisation answers [`report::statics_report`] (serialised `auto`, `dense`,
/// `sparse`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum StaticsMethod {
    /// The dense SVD below [`SPARSE_MIN_SIZE`] free dofs or members, the sparse
    /// rank-revealing QR ([`SparseStatics`]) from there on, falling back to the SVD when the
    /// sparse rank decision is not certified and the SVD fits the memory budget and a minute
    /// of estimated work.
    #[default]
    Auto,
    /// Always the dense SVD ([`Statics`]).
    Dense,
    /// Always the sparse rank-revealing QR ([`SparseStatics`]), flagged in the report when
    /// its rank decision is not certified.
    Sparse,
}

/// [`StaticsMethod::Auto`] uses the sparse path when both the free dofs and the members
/// number at least this many.
pub const SPARSE_MIN_SIZE: usize = 300;

/// Settings of a statics analysis.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StaticsSettings {
    /// Dense SVD, sparse QR or automatic choice by size (used by
    /// [`report::statics_report`]; [`Statics`] is always dense).
    pub method: StaticsMethod,
    /// Relative rank tolerance (σ counts as zero when σ ≤ tol · σ_max); `None` uses
    /// max(m, n)·ε.
    pub rank_tolerance: Option<f64>,
    /// Relative precision of the node coordinates, as a fraction of the largest coordinate
    /// magnitude (e.g. 5e-10 for data written to nine significant digits); `None` judges it
    /// from the digits of the coordinates, `Some(0.0)` takes them as exact ([`rank`]: the
    /// rank decision discounts the singular values that rounding of this size can create).
    pub input_precision: Option<f64>,
    /// The LP solver for prestressability.
    pub lp_solver: LpSolver,
    /// Memory the dense factorisation may use (bytes); `None` uses
    /// [`DEFAULT_MEMORY_LIMIT`]. A structure needing more is refused before anything is
    /// allocated ([`CoreError::TooLarge`](tensegrity_core::CoreError::TooLarge)).
    pub memory_limit: Option<f64>,
    /// Estimated work the sparse statics may do (s), checked once its rank is known (the
    /// bases, the prestressability LP and the stability test grow with the self-stresses and
    /// mechanisms); `None`: no limit. A structure needing more is refused
    /// ([`CoreError::OverBudget`](tensegrity_core::CoreError::OverBudget)).
    pub work_limit: Option<f64>,
}

/// Default memory budget of the dense statics: 8 GiB.
pub const DEFAULT_MEMORY_LIMIT: f64 = 8.0 * 1024.0 * 1024.0 * 1024.0;

pub use tensegrity_core::budget::dense_statics_bytes;

impl StaticsSettings {
    /// Sets a relative rank tolerance, which must lie in (0, 1).
    ///
    /// ```
    /// use tensegrity_statics::StaticsSettings;
    /// assert!(StaticsSettings::default().rank_tolerance(1e-10).is_ok());
    /// assert!(StaticsSettings::default().rank_tolerance(-1.0).is_err());
    /// ```
    pub fn rank_tolerance(mut self, rel: f64) -> Result<Self> {
        if !(rel > 0.0 && rel < 1.0) {
            return Err(tensegrity_core::CoreError::invalid_parameter(
                "rank_tolerance",
                rel,
                "a relative tolerance must lie strictly between 0 and 1",
            ));
        }
        self.rank_tolerance = Some(rel);
        Ok(self)
    }

    /// Sets the relative precision of the node coordinates, in [0, 0.1) ([`rank`]).
    ///
    /// ```
    /// use tensegrity_statics::StaticsSettings;
    /// assert!(StaticsSettings::default().input_precision(5e-10).is_ok());
    /// assert!(StaticsSettings::default().input_precision(0.0).is_ok());
    /// assert!(StaticsSettings::default().input_precision(0.5).is_err());
    /// ```
    pub fn input_precision(mut self, rel: f64) -> Result<Self> {
        if !(0.0..0.1).contains(&rel) {
            return Err(tensegrity_core::CoreError::invalid_parameter(
                "input_precision",
                rel,
                "a relative precision of the coordinates must lie in [0, 0.1)",
            ));
        }
        self.input_precision = Some(rel);
        Ok(self)
    }

    /// The rank tolerance of a back-end that sees no full spectrum (the sparse and nested
    /// QRs) for an m × n equilibrium matrix of `structure` with largest singular value
    /// `sigma_max`: the larger of the arithmetic's tolerance and the coordinates' rounding
    /// ([`rank::RankTolerance::absolute`]).
    pub fn sparse_rank_tolerance(
        &self,
        structure: &Structure,
        (m, n): (usize, usize),
        sigma_max: f64,
    ) -> f64 {
        rank::RankTolerance::of(
            structure,
            (m, n),
            sigma_max,
            self.rank_tolerance,
            self.input_precision,
        )
        .absolute()
    }

    /// Chooses the prestressability LP solver.
    ///
    /// ```
    /// use tensegrity_statics::{LpSolver, StaticsSettings};
    /// let s = StaticsSettings::default().lp_solver(LpSolver::Clarabel);
    /// assert_eq!(s.lp_solver, LpSolver::Clarabel);
    /// ```
    pub fn lp_solver(mut self, solver: LpSolver) -> Self {
        self.lp_solver = solver;
        self
    }

    /// Chooses the factorisation of [`report::statics_report`].
    ///
    /// ```
    /// use tensegrity_statics::{StaticsMethod, StaticsSettings};
    /// let s = StaticsSettings::default().method(StaticsMethod::Sparse);
    /// assert_eq!(s.method, StaticsMethod::Sparse);
    /// ```
    pub fn method(mut self, method: StaticsMethod) -> Self {
        self.method = method;
        self
    }
}

/// The factored equilibrium problem of one structure: A, its SVD and the rank decision.
/// Build it once, then ask for self-stress, prestressability or load solutions.
#[derive(Debug, Clone)]
pub struct Statics<'a> {
    structure: &'a Structure,
    dofs: DofMap,
    a: DMatrix<f64>,
    svd: Svd,
    tolerance: f64,
    rank: usize,
    settings: StaticsSettings,
}

impl<'a> Statics<'a> {
    /// Factors the equilibrium matrix of `structure` with default settings.
    pub fn new(structure: &'a Structure) -> Result<Self> {
        Self::with_settings(structure, StaticsSettings::default())
    }

    /// Factors the equilibrium matrix of `structure`.
    pub fn with_settings(structure: &'a Structure, settings: StaticsSettings) -> Result<Self> {
        let dofs = DofMap::of(structure);
        let (m, n) = (dofs.len(), structure.n_members());
        let bytes = dense_statics_bytes(m, n);
        let limit = settings.memory_limit.unwrap_or(DEFAULT_MEMORY_LIMIT);
        if bytes > limit {
            return Err(tensegrity_core::CoreError::TooLarge {
                what: "the dense SVD of the equilibrium matrix",
                rows: m,
                cols: n,
                bytes,
                limit,
            });
        }
        let a = equilibrium_matrix(structure, &dofs);
        let svd = linalg::svd(&a)?;
        let s_max = svd.s.first().copied().unwrap_or(0.0);
        let (rank, tolerance) = rank::RankTolerance::of(
            structure,
            (m, n),
            s_max,
            settings.rank_tolerance,
            settings.input_precision,
        )
        .decide(&svd.s);
        Ok(Self {
            structure,
            dofs,
            a,
            svd,
            tolerance,
            rank,
            settings,
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

    /// The equilibrium matrix A (free dofs × members).
    pub fn matrix(&self) -> &DMatrix<f64> {
        &self.a
    }

    /// Singular values of A, non-increasing.
    pub fn singular_values(&self) -> &[f64] {
        &self.svd.s
    }

    /// The absolute tolerance below which a singular value counts as zero.
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// Rank of A.
    pub fn rank(&self) -> usize {
        self.rank
    }

    /// The singular values on either side of the tolerance ([`SpectralGap`]).
    pub fn spectral_gap(&self) -> SpectralGap {
        SpectralGap::from_values(self.svd.s.iter().copied(), self.tolerance, None)
    }

    /// Dimension of the self-stress space, members − rank.
    pub fn self_stress_dim(&self) -> usize {
        self.a.ncols() - self.rank
    }

    /// Number of first-order mechanisms, free dofs − rank (rigid-body motions included when
    /// the supports allow them).
    pub fn mechanisms(&self) -> usize {
        self.a.nrows() - self.rank
    }

    /// An orthonormal basis of the self-stress space (one column per state, members bars first).
    ///
    /// Each state is oriented so that its strings sum to a positive value (when they sum to
    /// zero, its first significant entry is positive), which makes a one-dimensional basis
    /// unique.
    pub fn self_stress_basis(&self) -> DMatrix<f64> {
        let m = self.a.ncols();
        let nb = self.structure.n_bars();
        orient_self_stress(
            self.svd.v.columns(self.rank, m - self.rank).into_owned(),
            nb,
        )
    }

    /// An orthonormal basis of the first-order motions δn of the free dofs that keep every
    /// member length to first order (null space of Aᵀ), rigid-body motions included.
    pub fn motion_basis(&self) -> DMatrix<f64> {
        let rows = self.a.nrows();
        self.svd.u.columns(self.rank, rows - self.rank).into_owned()
    }

    /// Minimal-norm least-squares solution of A q = w on the free rows.
    pub fn solve_min_norm(&self, w: &DVector<f64>) -> DVector<f64> {
        self.svd.solve_min_norm(w, self.rank)
    }
}

/// Orients every self-stress column so that its strings (rows `nb..`) sum to a positive value
/// (when they sum to zero, its first entry above 1e-9 is positive): the convention shared by
/// the dense and the sparse path, which makes a one-dimensional basis unique.
pub(crate) fn orient_self_stress(mut basis: DMatrix<f64>, nb: usize) -> DMatrix<f64> {
    let m = basis.nrows();
    for mut col in basis.column_iter_mut() {
        let string_sum: f64 = col.rows(nb, m - nb).sum();
        let sign = if string_sum.abs() > 1e-9 {
            string_sum.signum()
        } else {
            col.iter()
                .find(|x| x.abs() > 1e-9)
                .map_or(1.0, |x| x.signum())
        };
        col *= sign;
    }
    basis
}

/// The dense SVD as one back-end of the statics front.
impl StaticsBackend for Statics<'_> {
    fn kind(&self) -> Factorization {
        Factorization::Svd
    }
    fn structure(&self) -> &Structure {
        Statics::structure(self)
    }
    fn free_dofs(&self) -> usize {
        self.dofs().len()
    }
    fn rank(&self) -> usize {
        Statics::rank(self)
    }
    fn rigid_body_motions(&self) -> Result<usize> {
        Ok(stiffness::rigid_body_motions(Statics::structure(self), self.dofs())?.ncols())
    }
    fn tolerance(&self) -> f64 {
        Statics::tolerance(self)
    }
    fn smallest_singular_value(&self) -> f64 {
        self.singular_values().last().copied().unwrap_or(0.0)
    }
    fn spectral_gap(&self) -> SpectralGap {
        Statics::spectral_gap(self)
    }
    fn certification(&self) -> Certification {
        let gap = Statics::spectral_gap(self);
        if gap.is_clear() {
            return match rank::near_deficiency(&self.svd.s, self.rank) {
                None => Certification::Certified,
                Some((sigma, factor)) => Certification::NotCertified {
                    reason: format!(
                        "the smallest singular value counted non-zero, {sigma:.3e}, lies {factor:.1e} times below the next one up: the coordinates hold one more self-stress to about {:.1e} relative, as rounded data do (set `input_precision` to the coordinates' precision to count it)",
                        sigma / self.svd.s[0]
                    ),
                },
            };
        }
        Certification::NotCertified {
            reason: gap.warning("dense SVD"),
        }
    }
    fn self_stress(&self) -> SelfStressBasis {
        SelfStressBasis::Full(self.self_stress_basis())
    }
    fn prestressability_with(&self, signs: &[MemberSign]) -> Result<Prestressability> {
        Statics::prestressability_with(self, signs)
    }
    fn prestress_stability(&self, q: &DVector<f64>) -> Result<PrestressStability> {
        Statics::prestress_stability(self, q)
    }
    fn solve_nodal_forces(&self, w_nodes: &Matrix3xX<f64>) -> Result<LoadSolution> {
        Ok(Statics::solve_nodal_forces(self, w_nodes))
    }
}

/// The README's examples, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
