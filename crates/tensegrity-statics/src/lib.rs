//! Statics: the equilibrium matrix, its SVD, self-stress and mechanisms, prestressability and
//! load solves.
//!
//! With force densities q (tension positive, bars then strings) nodal equilibrium reads
//! N Cᵀ diag(q) C = W, i.e. column-wise A q = w where column k of A holds −m_k at the rows of
//! the member's start node and +m_k at the rows of its end node (m_k = n_end − n_start). Rows
//! of fixed degrees of freedom are removed from A; their reactions are reported separately.
//!
//! **Clustered strings** ([`tensegrity_core::Cluster`]) add one column each, after the bars
//! and the strings: its unknown is q_c = t_c / L_c (the tension over the cluster's total
//! length), its column Σ_i (L_c / l_i) m_i over its segments, distributed as a string's
//! ([`cluster_columns`]). The dense SVD ([`Statics`]) models them; the sparse, nested and
//! cyclic back-ends refuse them, naming the cluster ([`backend`] takes the dense SVD for a
//! structure with clusters when the method is automatic).
//!
//! **Supports.** A support holds its node along the x, y, z axes it flags and along any
//! further unit directions (`along`, any orientation; [`tensegrity_core::Support`]). With
//! e₁ … e_k an orthonormal basis of the held directions (Gram–Schmidt) and f_1 … f_{3−k} one
//! of their complement, the node's three rows of A are replaced by its rows on the free
//! axes, f_aᵀ(−m_k) and f_aᵀ(+m_k) (the same projection as the free coordinates of
//! `tensegrity-path`): its balance along the held directions is the support's reaction,
//! r = Σ e_h e_hᵀ (A_full q − w)_node, which lies in their span ([`reaction_components`]
//! gives it along each given direction). A node held along coordinate axes keeps x, y, z
//! ([`DofMap`]), so the rows, the rank, the self-stresses, the mechanisms, the prestress
//! test, the load solve, the rigid-body motions (Σ e_hᵀ(a + ω × n) = 0 on the held
//! directions) and the stiffness analyses all see the same held directions.
//!
//! **Elastic supports** (a spring of stiffness k along each held direction d,
//! [`tensegrity_core::Support::elastic`]). The equilibrium analyses — rank, self-stress and
//! mechanism counts, prestressability, the prestress-stability test and the load solve —
//! count a spring as a support, as the classical count of restraints does: it carries a
//! reaction (reported as the support's, the spring's force), members being rigid there, and
//! the minimal-norm load solve of an indeterminate structure is the same with a spring as
//! with a rigid hold (only a compatible solve would differ, and this one is not compatible
//! in either case). The prestress-stability test is scale-free (a self-stress of any level):
//! it is the test at a prestress small against k, where a spring holds like a support. The
//! stiffness analyses, whose numbers have the actual forces and stiffnesses, leave the node
//! free there and add the spring, K += k d dᵀ on the node ([`DofMap::stiffness_of`],
//! [`stiffness::tangent_stiffness`], the modes of [`stiffness::modal_analysis_with`]).
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

pub mod cluster_columns;
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
pub mod reaction;
pub mod report;
pub mod response;
mod select;
pub mod sensitivity;
pub mod sizing;
pub mod sparse;
mod stability;
pub mod stiffness;
pub mod symmetry;

pub use cluster_columns::{column_lengths, column_name, n_columns};
pub use flexes::Flexes;
pub use front::{Certification, Factorization, SelfStressBasis, StaticsBackend};
pub use gap::{SpectralGap, GAP_FACTOR};
pub use load::{reaction_components, LoadSolution, LOAD_RESIDUAL_TOLERANCE};
pub use nested::NestedStatics;
pub use prestress::{solve_lp, MemberSign, Prestressability, PRESTRESS_TOLERANCE};
pub use report::{statics_report, StaticsReport, StaticsRequest};
pub use select::{backend, backend_path, cyclic_backend, ROUNDED_SPARSE_MIN_SIZE};
pub use sparse::{sparse_after_qr, sparse_statics_bytes, SparseStatics, SPARSE_FLOP_RATE};
pub use stability::PrestressStability;

use nalgebra::{DMatrix, DVector};
use nalgebra::{Matrix3, Matrix3xX, Vector3};
use tensegrity_core::error::Result;
use tensegrity_core::structure::Structure;
use tensegrity_linalg::{self as linalg, Svd};

/// Maps the free degrees of freedom (node, axis) to rows of A (module docs).
///
/// Each node has three orthonormal axes: x, y, z, except a node whose support holds
/// directions spanning no set of coordinate axes (`along` directions of any orientation),
/// whose axes are a frame of its own: first the held directions (orthonormalised in order),
/// then their complement. A row is one free axis of one node, its equation the node's
/// balance projected on that axis; held axes have no row.
///
/// [`DofMap::of`] holds every support, elastic ones included (the equilibrium analyses);
/// [`DofMap::stiffness_of`] holds the rigid supports only and keeps the springs of the
/// elastic ones (the stiffness analyses).
#[derive(Debug, Clone, PartialEq)]
pub struct DofMap {
    /// `(node, axis)` of each free row (axis 0, 1, 2: x, y, z unless the node has a frame,
    /// [`DofMap::axis`]).
    pub free: Vec<(usize, usize)>,
    /// Row of each node's axis, `None` when held.
    pub row: Vec<[Option<usize>; 3]>,
    /// The frame of each node whose axes are not x, y, z (columns: its axes).
    frames: Vec<Option<Box<Matrix3<f64>>>>,
    /// The springs of the elastic supports left free: node and Σ k d dᵀ (N/m, in x, y, z).
    springs: Vec<(usize, Matrix3<f64>)>,
}

/// A projector Σ b bᵀ counts as the projector on coordinate axes when it differs from a
/// diagonal 0/1 matrix by at most this: an `along` direction that is a coordinate axis (to
/// round-off) then gives the same rows as the axis flagged in `fixed`.
const AXIS_ALIGNED_TOLERANCE: f64 = 1e-12;

impl DofMap {
    /// The free degrees of freedom of `structure` in node-major order, every support held
    /// (elastic ones included: the equilibrium analyses count a spring's reaction as a
    /// support's).
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure, Support};
    /// use tensegrity_statics::DofMap;
    /// // node 1 on a roller held along (0.6, 0.8, 0): its two free axes are normal to it
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    ///     .bar(Bar::new(0, 1))
    ///     .support(Support::pinned(0))
    ///     .support(Support::along(1, [[0.6, 0.8, 0.0]]))
    ///     .build()
    ///     .unwrap();
    /// let dofs = DofMap::of(&s);
    /// assert_eq!(dofs.len(), 2);
    /// for r in 0..2 {
    ///     assert!(dofs.direction(r).dot(&nalgebra::Vector3::new(0.6, 0.8, 0.0)).abs() < 1e-15);
    /// }
    /// ```
    pub fn of(structure: &Structure) -> Self {
        Self::build(structure, true)
    }

    /// The free degrees of freedom of the stiffness analyses: the rigid supports held, the
    /// nodes of elastic supports free, their springs Σ k d dᵀ kept ([`DofMap::springs`]).
    ///
    /// ```
    /// use tensegrity_core::{Bar, Structure, Support};
    /// use tensegrity_statics::DofMap;
    /// let s = Structure::builder()
    ///     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
    ///     .bar(Bar::new(0, 1))
    ///     .support(Support::pinned(0))
    ///     .support(Support::directions(1, [true, false, false]).elastic(1e4))
    ///     .build()
    ///     .unwrap();
    /// assert_eq!((DofMap::of(&s).len(), DofMap::stiffness_of(&s).len()), (2, 3));
    /// assert_eq!(DofMap::stiffness_of(&s).springs()[0].1[(0, 0)], 1e4);
    /// ```
    pub fn stiffness_of(structure: &Structure) -> Self {
        Self::build(structure, false)
    }

    fn build(structure: &Structure, hold_elastic: bool) -> Self {
        let n = structure.n_nodes();
        let mut held = vec![[false; 3]; n];
        let mut frames: Vec<Option<Box<Matrix3<f64>>>> = vec![None; n];
        let mut springs = Vec::new();
        for s in structure.supports() {
            if let (Some(k), false) = (s.stiffness, hold_elastic) {
                let ks = s
                    .held_directions()
                    .iter()
                    .map(|d| {
                        let d = d.normalize();
                        d * d.transpose() * k
                    })
                    .sum();
                springs.push((s.node, ks));
                continue;
            }
            if s.along.is_empty() {
                for d in 0..3 {
                    held[s.node][d] |= s.fixed[d];
                }
                continue;
            }
            // the builder checked the directions: a basis exists
            let basis = s.held_basis().unwrap_or_default();
            let p: Matrix3<f64> = basis.iter().map(|b| b * b.transpose()).sum();
            let diagonal = Matrix3::from_diagonal(&p.diagonal().map(f64::round));
            if (p - diagonal).amax() <= AXIS_ALIGNED_TOLERANCE {
                for d in 0..3 {
                    held[s.node][d] |= diagonal[(d, d)] > 0.5;
                }
                continue;
            }
            let frame = complete_frame(&basis);
            for (a, h) in held[s.node].iter_mut().enumerate() {
                *h = a < basis.len();
            }
            frames[s.node] = Some(Box::new(frame));
        }
        let mut free = Vec::new();
        let mut row = vec![[None; 3]; n];
        for (i, f) in held.iter().enumerate() {
            for d in 0..3 {
                if !f[d] {
                    row[i][d] = Some(free.len());
                    free.push((i, d));
                }
            }
        }
        Self {
            free,
            row,
            frames,
            springs,
        }
    }

    /// Number of free degrees of freedom.
    pub fn len(&self) -> usize {
        self.free.len()
    }

    /// Whether every degree of freedom is fixed.
    pub fn is_empty(&self) -> bool {
        self.free.is_empty()
    }

    /// Whether every node's axes are x, y, z.
    pub fn is_axis_aligned(&self) -> bool {
        self.frames.iter().all(Option::is_none)
    }

    /// The frame of `node` (columns: its axes), `None` when its axes are x, y, z.
    pub fn frame(&self, node: usize) -> Option<&Matrix3<f64>> {
        self.frames.get(node).and_then(|f| f.as_deref())
    }

    /// Axis `a` of `node` (a unit vector).
    pub fn axis(&self, node: usize, a: usize) -> Vector3<f64> {
        match self.frame(node) {
            Some(f) => f.column(a).into_owned(),
            None => Vector3::ith(a, 1.0),
        }
    }

    /// The direction of free row `row` (a unit vector).
    pub fn direction(&self, row: usize) -> Vector3<f64> {
        let (node, a) = self.free[row];
        self.axis(node, a)
    }

    /// The component of `v` along axis `a` of `node`.
    pub fn component(&self, node: usize, a: usize, v: &Vector3<f64>) -> f64 {
        match self.frame(node) {
            Some(f) => f.column(a).dot(v),
            None => v[a],
        }
    }

    /// The components of `v` on the axes of `node` (Fᵀ v).
    pub fn to_local(&self, node: usize, v: &Vector3<f64>) -> Vector3<f64> {
        match self.frame(node) {
            Some(f) => f.transpose() * v,
            None => *v,
        }
    }

    /// A 3×3 block between `i` and `j` (in x, y, z) on their axes: F_iᵀ B F_j.
    pub fn local_block(&self, i: usize, j: usize, b: &Matrix3<f64>) -> Matrix3<f64> {
        match (self.frame(i), self.frame(j)) {
            (None, None) => *b,
            (fi, fj) => {
                let id = Matrix3::identity();
                fi.unwrap_or(&id).transpose() * b * fj.unwrap_or(&id)
            }
        }
    }

    /// The weights e_{i,a} · e_{j,b} of axis `a` of node `i` on the axes b = 0, 1, 2 of node
    /// `j` (for two nodes of axes x, y, z: 1 on b = a, 0 elsewhere).
    pub fn coupling(&self, i: usize, a: usize, j: usize) -> [f64; 3] {
        match (self.frame(i), self.frame(j)) {
            (None, None) => {
                let mut w = [0.0; 3];
                w[a] = 1.0;
                w
            }
            _ => {
                let e = self.axis(i, a);
                [0, 1, 2].map(|b| e.dot(&self.axis(j, b)))
            }
        }
    }

    /// The nodal vectors (3 × nodes) of a vector on the free rows: Σ x_r e_r at each node.
    pub fn expand(&self, x: &[f64]) -> Vec<Vector3<f64>> {
        let mut u = vec![Vector3::zeros(); self.row.len()];
        for (r, &(node, a)) in self.free.iter().enumerate() {
            u[node] += self.axis(node, a) * x[r];
        }
        u
    }

    /// The springs of the elastic supports this map leaves free ([`DofMap::stiffness_of`]):
    /// node and Σ k d dᵀ over its held directions d (N/m, in x, y, z); empty for
    /// [`DofMap::of`].
    pub fn springs(&self) -> &[(usize, Matrix3<f64>)] {
        &self.springs
    }

    /// Restricts a 3×n nodal matrix to the free rows, as a vector (each node's column
    /// projected on its free axes).
    pub fn gather(&self, w: &nalgebra::Matrix3xX<f64>) -> DVector<f64> {
        DVector::from_iterator(
            self.free.len(),
            self.free.iter().map(|&(i, d)| match self.frame(i) {
                Some(f) => f.column(d).dot(&w.column(i)),
                None => w[(d, i)],
            }),
        )
    }
}

/// An orthonormal frame whose first columns are the orthonormal `basis` (one or two
/// vectors) and whose others span its complement (for one vector: the coordinate axis least
/// aligned with it, orthogonalised, then the cross product).
fn complete_frame(basis: &[Vector3<f64>]) -> Matrix3<f64> {
    let b0 = basis[0];
    let (e1, e2) = match basis.get(1) {
        Some(&b1) => (b1, b0.cross(&b1).normalize()),
        None => {
            let least = (0..3)
                .min_by(|&a, &b| b0[a].abs().total_cmp(&b0[b].abs()))
                .unwrap_or(0);
            let a = Vector3::ith(least, 1.0);
            let e1 = (a - b0 * b0.dot(&a)).normalize();
            (e1, b0.cross(&e1))
        }
    };
    Matrix3::from_columns(&[b0, e1, e2])
}

/// The full equilibrium matrix (3n × columns: members, then clusters; no rows removed),
/// node-major rows.
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
    let mut a = DMatrix::zeros(3 * n, n_columns(structure));
    for (k, [i, j]) in structure.member_nodes().into_iter().enumerate() {
        let m = structure.nodes()[j] - structure.nodes()[i];
        for d in 0..3 {
            a[(3 * i + d, k)] = -m[d];
            a[(3 * j + d, k)] = m[d];
        }
    }
    let nm = structure.n_members();
    for (c, geometry) in cluster_columns::cluster_geometries(structure)
        .iter()
        .enumerate()
    {
        for (node, v) in geometry.column() {
            for d in 0..3 {
                a[(3 * node + d, nm + c)] += v[d];
            }
        }
    }
    a
}

/// The equilibrium matrix restricted to free degrees of freedom.
pub fn equilibrium_matrix(structure: &Structure, dofs: &DofMap) -> DMatrix<f64> {
    let mut a = DMatrix::zeros(dofs.len(), n_columns(structure));
    for (k, [i, j]) in structure.member_nodes().into_iter().enumerate() {
        let m = structure.nodes()[j] - structure.nodes()[i];
        for d in 0..3 {
            if let Some(r) = dofs.row[i][d] {
                a[(r, k)] = -dofs.component(i, d, &m);
            }
            if let Some(r) = dofs.row[j][d] {
                a[(r, k)] = dofs.component(j, d, &m);
            }
        }
    }
    let nm = structure.n_members();
    for (c, geometry) in cluster_columns::cluster_geometries(structure)
        .iter()
        .enumerate()
    {
        for (node, v) in geometry.column() {
            for d in 0..3 {
                if let Some(r) = dofs.row[node][d] {
                    a[(r, nm + c)] += dofs.component(node, d, &v);
                }
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
/// number at least this many. The two paths cost the same (the process start, 3.5 ms) up to
/// about 50 members and the sparse one less from there on (whole process, release, best of
/// 11: free towers of 5…11 prisms, 48…102 members, 3.3–4.4 ms sparse against 3.5–5.8 ms
/// dense; a double-layer grid of 132 members, 6.0 ms sparse against 8.9 ms dense; a tower of
/// 25 prisms, 7.4 against 17.4 ms; docs/notes/PERFORMANCE.md "Statics cost against size"), so that with
/// the limit at 50 the cost rises with size across the switch. At 100 a tower of 10 prisms
/// (93 members, dense) cost 5.2 ms and one of 11 (sparse) 4.4 ms; at 300 the dense path's
/// O(members·s²) margin LP made mid-size lattices cost more than larger ones.
pub const SPARSE_MIN_SIZE: usize = 50;

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
        self.rank_scales(structure, (m, n), sigma_max).absolute()
    }

    /// The scales of the rank decision of an m × n equilibrium matrix of `structure` with
    /// largest singular value `sigma_max` under these settings ([`rank::RankTolerance::of`]).
    pub fn rank_scales(
        &self,
        structure: &Structure,
        (m, n): (usize, usize),
        sigma_max: f64,
    ) -> rank::RankTolerance {
        rank::RankTolerance::of(
            structure,
            (m, n),
            sigma_max,
            self.rank_tolerance,
            self.input_precision,
        )
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
        let (m, n) = (dofs.len(), n_columns(structure));
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

    /// An orthonormal basis of the self-stress space (one column per state; rows: bars,
    /// strings, then clusters).
    ///
    /// Each state is oriented so that its strings (and clusters) sum to a positive value (when they sum to
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
