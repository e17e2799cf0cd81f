//! [`CyclicStatics`]: rank, self-stress and mechanisms of a cyclically symmetric structure
//! from its n Fourier blocks, each classified by representation index k.
//!
//! Block n − k is the complex conjugate of block k (A is real), so only k = 0..⌊n/2⌋ are
//! factored and the others mirrored: O(n·b³) for blocks of size b instead of O(n³b³).
//!
//! Each block has its own rank tolerance, τ_k = max(rows_k, columns_k)·ε·‖A_k‖₂: the
//! rounding of a block (its assembly and its SVD) is of that order, whatever n. The dense
//! rule max(rows, members)·ε·σ_max over the whole matrix grows like n·√n for a wheel (the
//! spokes of the axle scale ‖A‖ by √n) while the smallest genuine singular values of a
//! wheel of n prisms fall like 1/n², so from about n = 3·10⁴ prisms it counted genuine
//! values as zero (a toroid reported 7 internal mechanisms instead of 0). A caller's relative
//! tolerance r is applied as r·σ_max(A) to every block. The decision is certified when every
//! block has a clear gap ([`SpectralGap`]); the narrowest is reported.
//!
//! Rigid-body motions transform like vectors: a translation along, and a rotation about, an
//! eigenvector of R with eigenvalue λ lie in that representation, so they occupy k = 0 (the
//! axis) and k = 1, n − 1 (the transverse plane), two per block; those the supports allow are
//! counted per block as in the dense path.

use super::blocks::{axis_eigenvectors, BlockContext, BlockLayout, BlockRow};
use super::descriptor::CyclicSymmetry;
use crate::front::Factorization;
use crate::front::{Certification, SelfStressBasis, StaticsBackend};
use crate::load::LoadSolution;
use crate::prestress::{MemberSign, Prestressability};
use crate::stability::PrestressStability;
use crate::{SpectralGap, StaticsSettings};
use nalgebra::{Complex, DMatrix, Vector3};
use nalgebra::{DVector, Matrix3xX};
use serde::Serialize;
use tensegrity_core::error::Result;
use tensegrity_core::structure::Structure;
use tensegrity_linalg as linalg;

/// The counts of one irreducible representation k.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct RepCounts {
    /// The representation index k (character e^{2πik/n}).
    pub k: usize,
    /// Free degrees of freedom in this representation (block rows).
    pub rows: usize,
    /// Members in this representation (block columns).
    pub columns: usize,
    /// Rank of the block.
    pub rank: usize,
    /// Self-stress states, columns − rank.
    pub self_stress: usize,
    /// First-order mechanisms, rows − rank (rigid-body motions included).
    pub mechanisms: usize,
    /// Rigid-body motions the supports allow in this representation.
    pub rigid_body: usize,
    /// Mechanisms beyond the rigid-body motions.
    pub internal_mechanisms: usize,
}

/// The symmetry-adapted statics of one structure (see the module docs).
#[derive(Debug, Clone)]
pub struct CyclicStatics<'a> {
    structure: &'a Structure,
    symmetry: &'a CyclicSymmetry,
    settings: StaticsSettings,
    reps: Vec<RepCounts>,
    /// The largest block tolerance.
    tolerance: f64,
    sigma_max: f64,
    /// The smallest singular value of A (0 when the blocks hold fewer than min(m, n)).
    sigma_min: f64,
    /// The narrowest gap over the blocks (certified when it is clear).
    gap: SpectralGap,
    /// Orthonormal self-stress basis of block 0 in member-orbit coordinates (orbits × d₀),
    /// as member values (q_e = entry of e's orbit).
    symmetric_basis: DMatrix<f64>,
}

struct Factored {
    layout: BlockLayout,
    s: Vec<f64>,
}

impl<'a> CyclicStatics<'a> {
    /// Analyses `structure` with default settings; `symmetry` must have been validated
    /// against it ([`CyclicSymmetry::new`]).
    pub fn new(structure: &'a Structure, symmetry: &'a CyclicSymmetry) -> Result<Self> {
        Self::with_settings(structure, symmetry, StaticsSettings::default())
    }

    /// Analyses `structure` block by block (the rank tolerance and the LP solver of
    /// `settings` are used; the memory limit is not: the blocks need O(n·b²)).
    pub fn with_settings(
        structure: &'a Structure,
        symmetry: &'a CyclicSymmetry,
        settings: StaticsSettings,
    ) -> Result<Self> {
        crate::cluster_columns::refuse_clusters_in(structure, "cyclic-symmetry block")?;
        if structure.supports().iter().any(|s| !s.along.is_empty()) {
            return Err(Factorization::Cyclic
                .unsupported("supports along directions of any orientation (`along`)"));
        }
        let n = symmetry.order();
        let ctx = BlockContext::new(structure, symmetry);
        let mut factored = Vec::with_capacity(n / 2 + 1);
        let mut v0 = DMatrix::zeros(0, 0);
        for k in 0..=n / 2 {
            let layout = ctx.layout(k);
            let block = ctx.assemble(&layout);
            let s = if k == 0 {
                let real = block.map(|z| z.re);
                let svd = linalg::svd(&real)?;
                v0 = svd.v;
                svd.s
            } else {
                linalg::complex_singular_values(&block)?
            };
            factored.push(Factored { layout, s });
        }
        let sigma_max = factored
            .iter()
            .filter_map(|f| f.s.first().copied())
            .fold(0.0, f64::max);
        let tolerances: Vec<f64> = factored
            .iter()
            .map(|f| block_tolerance(f, sigma_max, settings.rank_tolerance))
            .collect();
        let tolerance = tolerances.iter().copied().fold(0.0, f64::max);
        let gap = factored
            .iter()
            .zip(&tolerances)
            .map(|(f, &t)| SpectralGap::from_values(f.s.iter().copied(), t, Some(f.layout.k)))
            .min_by(|a, b| a.margin().total_cmp(&b.margin()))
            .unwrap_or_default();
        let rigid = rigid_counts(structure, symmetry, &factored)?;
        let reps = (0..n)
            .map(|k| {
                let f = &factored[k.min(n - k)];
                let tol = tolerances[k.min(n - k)];
                let rank = f.s.iter().take_while(|&&s| s > tol).count();
                let (rows, columns) = (f.layout.free_rows(), f.layout.cols.len());
                let rigid_body = match k {
                    0 => rigid[0],
                    k if k == 1 || k == n - 1 => rigid[1],
                    _ => 0,
                };
                RepCounts {
                    k,
                    rows,
                    columns,
                    rank,
                    self_stress: columns - rank,
                    mechanisms: rows - rank,
                    rigid_body,
                    internal_mechanisms: (rows - rank).saturating_sub(rigid_body),
                }
            })
            .collect::<Vec<_>>();
        let (r0, c0) = (reps[0].rank, reps[0].columns);
        let sizes: Vec<f64> = factored[0]
            .layout
            .cols
            .iter()
            .map(|&e| (symmetry.member_orbits()[e].size as f64).sqrt())
            .collect();
        let symmetric_basis =
            DMatrix::from_fn(c0, c0 - r0, |row, col| v0[(row, r0 + col)] / sizes[row]);
        let sigma_min = smallest_value(&factored, &reps);
        Ok(Self {
            structure,
            symmetry,
            settings,
            reps,
            tolerance,
            sigma_max,
            sigma_min,
            gap,
            symmetric_basis,
        })
    }

    /// The analysed structure.
    pub fn structure(&self) -> &Structure {
        self.structure
    }

    /// The symmetry descriptor.
    pub fn symmetry(&self) -> &CyclicSymmetry {
        self.symmetry
    }

    /// The settings.
    pub fn settings(&self) -> &StaticsSettings {
        &self.settings
    }

    /// The counts of every representation k = 0..n−1.
    pub fn representations(&self) -> &[RepCounts] {
        &self.reps
    }

    /// The absolute rank tolerance: the largest block tolerance (see the module docs).
    pub fn tolerance(&self) -> f64 {
        self.tolerance
    }

    /// The largest singular value of A.
    pub fn sigma_max(&self) -> f64 {
        self.sigma_max
    }

    /// The smallest singular value of A (the union of the blocks' singular values; 0 when
    /// the blocks hold fewer than min(free dofs, members) of them).
    pub fn sigma_min(&self) -> f64 {
        self.sigma_min
    }

    /// Whether the rank decision is certified: no singular value of any block lies within a
    /// factor [`CERTIFY_BAND`] of its block's tolerance ([`SpectralGap::is_clear`]), so
    /// rounding (of order the tolerance) cannot move a singular value across it.
    pub fn is_certified(&self) -> bool {
        self.gap.is_clear()
    }

    /// The narrowest gap over the blocks (its `block` is the representation index k).
    pub fn spectral_gap(&self) -> SpectralGap {
        self.gap
    }

    /// The singular value that prevents certification (see [`is_certified`](Self::is_certified)).
    pub fn value_near_tolerance(&self) -> Option<f64> {
        if self.is_certified() {
            return None;
        }
        let g = &self.gap;
        let up = g.sigma_above.map_or(f64::INFINITY, |a| a / g.tolerance);
        let down = g.sigma_below.map_or(f64::INFINITY, |b| g.tolerance / b);
        if up <= down {
            g.sigma_above
        } else {
            g.sigma_below
        }
    }

    /// Free degrees of freedom (rows of A).
    pub fn free_dofs(&self) -> usize {
        self.reps.iter().map(|r| r.rows).sum()
    }

    /// Rank of A.
    pub fn rank(&self) -> usize {
        self.reps.iter().map(|r| r.rank).sum()
    }

    /// Dimension of the self-stress space.
    pub fn self_stress_dim(&self) -> usize {
        self.reps.iter().map(|r| r.self_stress).sum()
    }

    /// First-order mechanisms (rigid-body motions included).
    pub fn mechanisms(&self) -> usize {
        self.reps.iter().map(|r| r.mechanisms).sum()
    }

    /// Rigid-body motions the supports allow.
    pub fn rigid_body(&self) -> usize {
        self.reps.iter().map(|r| r.rigid_body).sum()
    }

    /// Mechanisms beyond the rigid-body motions.
    pub fn internal_mechanisms(&self) -> usize {
        self.mechanisms().saturating_sub(self.rigid_body())
    }

    /// The fully symmetric self-stresses (representation 0) in member-orbit coordinates:
    /// column c gives the force density of every member of orbit E in row E (columns
    /// orthonormal in member space).
    pub fn symmetric_basis(&self) -> &DMatrix<f64> {
        &self.symmetric_basis
    }

    /// The fully symmetric self-stresses expanded to members (members × d₀, bars first),
    /// orthonormal.
    pub fn symmetric_self_stress_basis(&self) -> DMatrix<f64> {
        let places = self.symmetry.member_places();
        let b = &self.symmetric_basis;
        DMatrix::from_fn(places.len(), b.ncols(), |e, c| b[(places[e].orbit, c)])
    }
}

/// A block singular value within this factor of its block's rank tolerance makes the cyclic
/// rank decision uncertified ([`CyclicStatics::is_certified`]; the gap rule of
/// [`SpectralGap`]).
pub const CERTIFY_BAND: f64 = crate::GAP_FACTOR;

/// The rank tolerance of one block (see the module docs): max(rows, columns)·ε·‖A_k‖₂, or the
/// caller's relative tolerance times σ_max(A).
fn block_tolerance(f: &Factored, sigma_max: f64, rel: Option<f64>) -> f64 {
    let s_block = f.s.first().copied().unwrap_or(0.0);
    match rel {
        Some(r) => r * sigma_max,
        None => linalg::rank_tolerance(f.layout.free_rows(), f.layout.cols.len(), s_block, None),
    }
}

/// The smallest singular value of A (0 when the n blocks hold fewer than min(m, n) values).
fn smallest_value(factored: &[Factored], reps: &[RepCounts]) -> f64 {
    let slots: usize = reps.iter().map(|r| r.rows.min(r.columns)).sum();
    let rows: usize = reps.iter().map(|r| r.rows).sum();
    let cols: usize = reps.iter().map(|r| r.columns).sum();
    if slots < rows.min(cols) {
        return 0.0;
    }
    let smallest = factored
        .iter()
        .filter_map(|f| f.s.last().copied())
        .fold(f64::INFINITY, f64::min);
    if smallest.is_finite() {
        smallest
    } else {
        0.0
    }
}

/// The rigid-body motions allowed in representation 0 and in representation 1 (= n − 1).
fn rigid_counts(
    structure: &Structure,
    sym: &CyclicSymmetry,
    factored: &[Factored],
) -> Result<[usize; 2]> {
    let eigs = axis_eigenvectors(sym);
    let mut free_blocks = Vec::new();
    let mut fixed_blocks = Vec::new();
    for k in 0..2 {
        let (free, fixed) = rigid_generators(structure, sym, &factored[k].layout, &eigs[k].0);
        free_blocks.push(free);
        fixed_blocks.push(fixed);
    }
    let fixed_rows: usize = fixed_blocks.iter().map(|b| b.nrows()).sum();
    let mut allowed_free = Vec::new();
    for (free, fixed) in free_blocks.iter().zip(&fixed_blocks) {
        let allowed = if fixed.nrows() == 0 {
            DMatrix::identity(2, 2)
        } else {
            let d = linalg::complex_svd(fixed)?;
            let s_max = d.s.first().copied().unwrap_or(0.0);
            let r = d.rank(linalg::rank_tolerance(fixed_rows, 6, s_max, None));
            d.v.columns(r, 2 - r).into_owned()
        };
        allowed_free.push(linalg::complex_singular_values(&(free * allowed))?);
    }
    let s_max = allowed_free
        .iter()
        .filter_map(|s| s.first().copied())
        .fold(0.0, f64::max);
    let count = |s: &Vec<f64>| s.iter().filter(|&&x| x > 1e-10 * s_max).count();
    Ok([count(&allowed_free[0]), count(&allowed_free[1])])
}

/// The block coordinates of a translation along `v` and a rotation about `v` (through the
/// centre), split into the free and the fixed rows of `layout`.
fn rigid_generators(
    structure: &Structure,
    sym: &CyclicSymmetry,
    layout: &BlockLayout,
    v: &Vector3<Complex<f64>>,
) -> (DMatrix<Complex<f64>>, DMatrix<Complex<f64>>) {
    let eigs = axis_eigenvectors(sym);
    let sqrt_n = Complex::new((sym.order() as f64).sqrt(), 0.0);
    let x = structure.nodes();
    let motion = |node: usize, which: usize| -> Vector3<Complex<f64>> {
        if which == 0 {
            *v
        } else {
            let r = (x[node] - sym.centre()).map(|t| Complex::new(t, 0.0));
            v.cross(&r)
        }
    };
    let coordinate = |row: &BlockRow, which: usize| -> Complex<f64> {
        match *row {
            BlockRow::Orbit { orbit, dir } => {
                motion(sym.node_orbits()[orbit].rep, which)[dir] * sqrt_n
            }
            BlockRow::Axis { node, eig } => {
                let u = motion(node, which);
                (0..3).map(|t| eigs[eig].0[t].conj() * u[t]).sum()
            }
        }
    };
    let pick = |want_free: bool| {
        let rows: Vec<&BlockRow> = layout
            .rows
            .iter()
            .filter(|r| r.1 == want_free)
            .map(|r| &r.0)
            .collect();
        DMatrix::from_fn(rows.len(), 2, |i, c| coordinate(rows[i], c))
    };
    (pick(true), pick(false))
}

/// The symmetry-adapted blocks as one back-end of the statics front.
impl StaticsBackend for CyclicStatics<'_> {
    fn kind(&self) -> Factorization {
        Factorization::Cyclic
    }
    fn structure(&self) -> &Structure {
        CyclicStatics::structure(self)
    }
    fn symmetry(&self) -> Option<&CyclicSymmetry> {
        Some(CyclicStatics::symmetry(self))
    }
    fn free_dofs(&self) -> usize {
        CyclicStatics::free_dofs(self)
    }
    fn rank(&self) -> usize {
        CyclicStatics::rank(self)
    }
    fn rigid_body_motions(&self) -> Result<usize> {
        Ok(self.rigid_body())
    }
    fn tolerance(&self) -> f64 {
        CyclicStatics::tolerance(self)
    }
    fn smallest_singular_value(&self) -> f64 {
        self.sigma_min()
    }
    fn spectral_gap(&self) -> SpectralGap {
        CyclicStatics::spectral_gap(self)
    }
    fn certification(&self) -> Certification {
        let gap = CyclicStatics::spectral_gap(self);
        if gap.is_clear() {
            return Certification::Certified;
        }
        Certification::NotCertified {
            reason: gap.warning("cyclic (per-block)"),
        }
    }
    fn self_stress(&self) -> SelfStressBasis {
        let nb = CyclicStatics::structure(self).n_bars();
        SelfStressBasis::Symmetric {
            basis: crate::orient_self_stress(self.symmetric_self_stress_basis(), nb),
            dim: CyclicStatics::self_stress_dim(self),
        }
    }
    fn prestressability_with(&self, signs: &[MemberSign]) -> Result<Prestressability> {
        CyclicStatics::prestressability_with(self, signs)
    }
    fn prestress_stability(&self, _q: &DVector<f64>) -> Result<PrestressStability> {
        Err(Factorization::Cyclic.unsupported("prestress stability"))
    }
    fn solve_nodal_forces(&self, _w_nodes: &Matrix3xX<f64>) -> Result<LoadSolution> {
        Err(Factorization::Cyclic.unsupported("the load solve"))
    }
}
