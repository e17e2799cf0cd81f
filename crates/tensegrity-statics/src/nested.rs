//! Sparse statics of lattices and long structures: rank, self-stress dimension, mechanisms and
//! the margin of the equilibrium matrix A (free dofs × members) through a nested dissection
//! of the structure.
//!
//! # Why
//!
//! The banded QR of [`SparseStatics`](super::SparseStatics) processes the members along a
//! band; a structure of planar or spatial extent (a double-layer grid of K × K cells) has a
//! band of ∝ K nodes, its null vectors (self-stresses) are not local in the band order and
//! their sparse basis, and the margin LP over it, grow quadratically. Here:
//!
//! - **ordering**: a coordinate nested dissection of the nodes ([`dissection`]): the node set
//!   is split at the median of its longest extent, the separator is the smaller of the two
//!   boundaries (the nodes of one side with a neighbour on the other), and both sides are
//!   dissected again down to [`LEAF_NODES`] nodes; no member joins two sibling sub-domains,
//!   so a member touches one front and its ancestors;
//! - **factorisation**: the rank-revealing multifrontal QR of Aᵀ
//!   ([`tensegrity_linalg::FrontalQr`]) along that tree, with the banded path's
//!   tolerances: τ = max(m, n)·ε·σ_max (σ_max by the power method), rejection at 1000·τ;
//! - **certificate**: as on the banded path, σ_min(R_acc) (inverse iteration) must exceed
//!   100·max(τ, ‖E‖_F), ‖E‖_F the rejected residuals;
//! - **margin**: the LP `max t  s.t.  A q = 0,  σ_k q_k ≥ t,  σ_k q_k ≤ 1` over the force
//!   densities themselves (equality rows A, no self-stress basis), by an interior-point
//!   method on the normal matrix A D⁻¹ Aᵀ (`margin_ipm`: a stiffness
//!   pattern, one sparse Cholesky a step in the order of this dissection; Clarabel on the
//!   same rows should it fail), up to
//!   [`LP_MEMBERS_MAX`] members; beyond, the margin is not computed (the report says so).
//!   Its rows impose A q = 0 exactly, so it runs only where the rank decision rejected
//!   round-off alone ([`NestedStatics::rank_is_exact`]); on coordinates whose rounding the
//!   rank decision discounts, some counted self-stress holds only to their precision, and
//!   the margin is not computed here either (the banded and dense paths compute it over the
//!   counted self-stresses);
//!
//! Not computed here (the report says so, or the banded path answers): the self-stress basis
//! (its dimension is given) and the load solve; prestress stability is "stable" without
//! internal mechanisms (as on the dense path) and otherwise the banded path's test — a loaded structure
//! stays on the banded path ([`prefers_nested`]).
//!
//! # Long structures: the QR of A itself ([`Orientation::Members`])
//!
//! A tower of N prisms has N + 6 mechanisms, one a prism and global (a prism's top turns
//! against its bottom, carrying everything above). Along the band they fill the banded QR's
//! factor quadratically (its pivot lags the rows by the mechanisms met so far: ≈ 4N² stored
//! entries), and in the QR of Aᵀ above they are the rejected columns, whose residuals carry
//! the rounding of a half-tower's conditioning (∝ N²·ε against σ_r ∝ N⁻²): no certificate
//! survives beyond ~2,000 prisms. [`NestedStatics::members_with_settings`] factors A along
//! the same dissection instead, members as columns, so that the rejected columns are the
//! self-stresses, which are local:
//!
//! - **fronts**: leaves of [`MEMBER_LEAF_NODES`] nodes; each member in the front of its
//!   end that lies higher in the tree (a dof row then touches its node's front and the
//!   ancestors only); within a front the members in the banded QR's staircase order (members
//!   to lower fronts last, then by the later end in the reverse Cuthill–McKee order, the
//!   longest span last), so that a dependency closes on a member of its own cell;
//! - **pivots**: threshold pivoting ([`FrontalQr::with_threshold`],
//!   [`MEMBER_PIVOT_THRESHOLD`]) keeps that order where the columns are well conditioned;
//!   rejection and certificate as above;
//! - **self-stresses**: the rejected members' null vectors, e_k − Σ x_j e_acc(j) with
//!   R_acc x = R_dep e_k by a sparse back substitution
//!   ([`FrontalQr::sparse_null_vectors_within`]): a tower's are its prisms' circuits (12
//!   members each), kept up to [`NULL_ENTRIES_PER_MEMBER`] entries a member;
//! - **margin**: the banded path's LP over that sparse basis, q = N c (Clarabel), the
//!   interior point on A D⁻¹ Aᵀ should it fail or the basis not be local;
//! - **stability** with internal mechanisms: the penalised stress matrix
//!   (`penalty`: Ω̄ − σ′I + μAAᵀ positive definite proves the dense test's
//!   "stable", a banded Cholesky, linear), then the banded test where few mechanisms keep its
//!   factor small, else "not tested".
//!
//! The automatic choice ([`prefers_nested_members`]) takes it for an unloaded structure of
//! narrow band with at least [`NESTED_MEMBERS_MIN`] members, unless the report would list
//! the self-stress basis (the banded path builds it). Cost and memory are linear in the
//! tower (docs/notes/PERFORMANCE.md: 12,800 prisms, 115,203 members, in about 4 s and 0.44 GB).

use super::front::{Certification, Factorization, SelfStressBasis, StaticsBackend};
use super::load::LoadSolution;
use super::prestress::{MemberSign, Prestressability};
use super::sparse::{equilibrium_matrix_sparse, node_order_rcm, rigid_motions, sigma_max};
use super::stability::PrestressStability;
use super::{DofMap, SpectralGap, StaticsSettings};
use nalgebra::{DMatrix, DVector, Matrix3xX};
use tensegrity_core::error::{CoreError, Result};
use tensegrity_core::structure::Structure;
use tensegrity_linalg::{CscMatrix, FrontalQr};

/// Sub-domains of at most this many nodes are not dissected further (leaf fronts).
pub const LEAF_NODES: usize = 24;

/// The band (in node positions of the reverse Cuthill–McKee order) above which a structure
/// goes to the nested-dissection path ([`prefers_nested`]).
pub const BAND_NODES_MAX: usize = 24;

/// The margin LP over the force densities is solved up to this many members (10⁵ members of
/// a lattice: about 2 s); beyond, the report says it was not computed.
pub const LP_MEMBERS_MAX: usize = 400_000;

/// Rejection (of the arithmetic's tolerance τ₀, [`crate::rank::RankTolerance::reject_level`])
/// and certificate factors, as on the banded path.
const REJECT_FACTOR: f64 = 1e3;
const CERTIFY_FACTOR: f64 = 100.0;
const INVERSE_STEPS: usize = 12;

/// Whether the automatic choice sends `structure` to the nested-dissection path rather than
/// the banded QR: unloaded, with more members × (members − free dofs) — a lower bound of
/// members × self-stresses — than the report lists
/// ([`SELF_STRESS_LIST_MAX`](super::sparse::SELF_STRESS_LIST_MAX): the basis would not be
/// listed on either path), and its reverse Cuthill–McKee band wider than [`BAND_NODES_MAX`]
/// nodes (a lattice; a tower's band is a few rings).
pub fn prefers_nested(structure: &Structure) -> bool {
    let n = structure.n_members();
    let surplus = n.saturating_sub(DofMap::of(structure).len());
    if structure.is_loaded() || n.saturating_mul(surplus) <= super::sparse::SELF_STRESS_LIST_MAX {
        return false;
    }
    let order = node_order_rcm(structure);
    let mut pos = vec![0usize; order.len()];
    for (p, &v) in order.iter().enumerate() {
        pos[v] = p;
    }
    let band = structure
        .member_nodes()
        .into_iter()
        .map(|[i, j]| pos[i].abs_diff(pos[j]))
        .max()
        .unwrap_or(0);
    band > BAND_NODES_MAX
}

/// Flops a second of the multifrontal QR's dense front updates, and the margin LP's cost per
/// member^1.5 (the interior point on A D⁻¹ Aᵀ of a planar lattice), both measured on the
/// double-layer grids of `docs/notes/PERFORMANCE.md` and rounded so that the estimate bounds the
/// time.
const FRONT_FLOP_RATE: f64 = 2.0e9;
const LP_S_PER_MEMBER_1_5: f64 = 1.5e-7;

/// Memory of the dissection, the DOF map and the report's member vectors, per member, and
/// the fixed part of a run (measured on the lattices K = 20…86: the rest of the estimate
/// alone fell 12 % short of the peak at K = 20).
const REPORT_BYTES_PER_MEMBER: f64 = 256.0;
const FIXED_BYTES: f64 = 4.0 * 1024.0 * 1024.0;

/// The resource estimate of the nested-dissection statics of `structure` before it runs:
/// memory 16 bytes a stored R entry (E = Σ pivots × front columns, every pivot accepted)
/// plus the largest dense front, and on top of R the larger of the σ_min(R) iteration's
/// contiguous copy (12 bytes an entry) and, for the margin LP (up to [`LP_MEMBERS_MAX`]
/// members), its Cholesky factor with the factor's symbolic structure and workspace (≤ 12 bytes
/// for each of E entries: 10.4 M entries of L against E = 14.1 M at K = 86), the normal
/// matrix's member contributions (24 bytes each) and its vectors; then the dissection and
/// the report (`REPORT_BYTES_PER_MEMBER`, `FIXED_BYTES`); work
/// the fronts' 2·rows·columns·pivots flops and the LP.
pub fn nested_estimate(
    structure: &Structure,
    parameter: String,
) -> Result<tensegrity_core::budget::Estimate> {
    crate::cluster_columns::refuse_clusters_in(structure, "nested-dissection QR")?;
    let dofs = DofMap::of(structure);
    let a = equilibrium_matrix_sparse(structure, &dofs)?;
    let (fronts, parent) = dof_fronts(structure, &dofs);
    let (entries, largest, flops) = front_totals(&FrontalQr::symbolic(&a, &fronts, &parent));
    let n = structure.n_members();
    let lp = if n <= LP_MEMBERS_MAX { 1.0 } else { 0.0 };
    let contributions: f64 = (0..n)
        .map(|k| {
            let c = a.pattern().col_ptr()[k + 1] - a.pattern().col_ptr()[k];
            (c * (c + 1) / 2) as f64
        })
        .sum();
    let lp_memory = lp * (12.0 * entries + 24.0 * contributions + 48.0 * 8.0 * n as f64);
    Ok(tensegrity_core::budget::Estimate::new(
        format!(
            "the sparse statics (nested-dissection QR of the {} × {n} equilibrium matrix)",
            dofs.len()
        ),
        parameter,
    )
    .memory(
        16.0 * entries
            + 8.0 * largest
            + f64::max(12.0 * entries, lp_memory)
            + REPORT_BYTES_PER_MEMBER * n as f64
            + FIXED_BYTES,
    )
    .work(flops / FRONT_FLOP_RATE + lp * LP_S_PER_MEMBER_1_5 * (n as f64).powf(1.5)))
}

/// Leaf size of the dissection in the members orientation: a tower's stage has 3 nodes, so
/// leaves of 4 stages; smaller dense fronts than [`LEAF_NODES`] where the band is narrow.
pub const MEMBER_LEAF_NODES: usize = 12;

/// The sparse self-stress basis of the members orientation is kept up to this many entries
/// per member (a tower: 12 entries a self-stress, 9 members a prism); beyond, its vectors are
/// not local and the margin LP takes the equilibrium rows.
pub const NULL_ENTRIES_PER_MEMBER: usize = 16;

/// The smallest structure (members) that the automatic choice sends to the members
/// orientation ([`prefers_nested_members`]).
pub const NESTED_MEMBERS_MIN: usize = 5_000;

/// Whether the automatic choice first factors `structure` in the members orientation
/// ([`Orientation::Members`]): unloaded (the load solve is the banded path's), at least
/// [`NESTED_MEMBERS_MIN`] members and not a lattice ([`prefers_nested`]). The banded QR's
/// factor grows with the mechanisms met along the band (quadratically on a tower, whose
/// mechanisms are one a prism); the choice keeps this factorisation unless the banded one
/// would list the self-stress basis ([`crate::backend`]).
pub fn prefers_nested_members(structure: &Structure) -> bool {
    !structure.is_loaded()
        && structure.n_members() >= NESTED_MEMBERS_MIN
        && !prefers_nested(structure)
}

/// Threshold of the members orientation's pivot choice
/// ([`FrontalQr::with_threshold`]): a member is taken in the staircase order of its front
/// while its residual is within this factor of the largest.
pub const MEMBER_PIVOT_THRESHOLD: f64 = 0.1;

/// The members orientation's fronts: the dissection of the nodes (leaves of
/// [`MEMBER_LEAF_NODES`]), each member in the front of its higher end, and the parents.
/// Within a front the members are in the banded QR's staircase order (the members whose
/// other end lies in a lower front last, then by the later of their ends in the reverse
/// Cuthill–McKee order of the nodes, the longest span last), so that, as on the band, a
/// dependency closes on a member of its own cell and the self-stresses come out as local
/// circuits.
fn member_fronts(structure: &Structure) -> (Vec<Vec<usize>>, Vec<Option<usize>>) {
    let (node_fronts, parent) = dissection_with_leaves(structure, MEMBER_LEAF_NODES);
    let mut front_of = vec![0usize; structure.n_nodes()];
    for (f, nodes) in node_fronts.iter().enumerate() {
        for &v in nodes {
            front_of[v] = f;
        }
    }
    let order = node_order_rcm(structure);
    let mut pos = vec![0usize; order.len()];
    for (p, &v) in order.iter().enumerate() {
        pos[v] = p;
    }
    let members = structure.member_nodes();
    let mut fronts = vec![Vec::new(); node_fronts.len()];
    for (k, &[i, j]) in members.iter().enumerate() {
        // post order: an ancestor has the larger index
        fronts[front_of[i].max(front_of[j])].push(k);
    }
    for front in &mut fronts {
        front.sort_by_key(|&k| {
            let [i, j] = members[k];
            let (a, b) = (pos[i], pos[j]);
            let below = front_of[i].min(front_of[j]);
            (
                std::cmp::Reverse(below),
                a.max(b),
                std::cmp::Reverse(a.min(b)),
            )
        });
    }
    (fronts, parent)
}

/// Aᵀ of a sparse matrix.
fn transpose(a: &CscMatrix) -> Result<CscMatrix> {
    let (cp, ri, v) = (a.pattern().col_ptr(), a.pattern().row_idx(), a.values());
    let mut t = Vec::with_capacity(v.len());
    for c in 0..a.pattern().ncols() {
        for s in cp[c]..cp[c + 1] {
            t.push((c, ri[s], v[s]));
        }
    }
    Ok(CscMatrix::from_triplets(
        a.pattern().ncols(),
        a.pattern().nrows(),
        &t,
    )?)
}

/// The resource estimate of the members orientation ([`Orientation::Members`]) of
/// `structure` before it runs: memory 16 bytes a stored R entry (every pivot accepted), the
/// largest dense front, the sparse self-stress basis and the margin LP over it (at most
/// [`NULL_ENTRIES_PER_MEMBER`] entries a member, about ten times that for Clarabel's
/// factor) and the penalised stress matrix of the stability test (36 triplets a member);
/// work the fronts' 2·rows·columns·pivots flops, the LP (30 interior-point steps over the
/// basis) and five banded Cholesky factorisations.
pub fn nested_members_estimate(
    structure: &Structure,
    parameter: String,
) -> Result<tensegrity_core::budget::Estimate> {
    crate::cluster_columns::refuse_clusters_in(structure, "nested-dissection QR")?;
    let dofs = DofMap::of(structure);
    let at = transpose(&equilibrium_matrix_sparse(structure, &dofs)?)?;
    let (fronts, parent) = member_fronts(structure);
    let (entries, largest, flops) = front_totals(&FrontalQr::symbolic(&at, &fronts, &parent));
    let n = structure.n_members() as f64;
    let basis = (NULL_ENTRIES_PER_MEMBER as f64) * n;
    let penalty = 36.0 * n;
    Ok(tensegrity_core::budget::Estimate::new(
        format!(
            "the sparse statics (nested-dissection QR of the {} × {} equilibrium matrix)",
            dofs.len(),
            structure.n_members()
        ),
        parameter,
    )
    .memory(16.0 * entries + 8.0 * largest + 16.0 * 11.0 * basis + 3.0 * 24.0 * penalty)
    .work((flops + 30.0 * 20.0 * basis + 5.0 * 50.0 * penalty) / FRONT_FLOP_RATE))
}

/// From the fronts' sizes of [`FrontalQr::symbolic`] (rows, pivots, columns): the stored R
/// entries (Σ pivots × columns, every pivot accepted), the largest dense front (rows ×
/// columns) and the flops (Σ 2·rows·columns·pivots).
fn front_totals(sizes: &[(usize, usize, usize)]) -> (f64, f64, f64) {
    sizes.iter().fold(
        (0.0, 0.0, 0.0),
        |(entries, largest, flops), &(nr, np, nc)| {
            (
                entries + (np * nc) as f64,
                f64::max(largest, (nr * nc) as f64),
                flops + 2.0 * (nr * nc * np) as f64,
            )
        },
    )
}

/// The dissection's fronts as lists of free dofs (rows of A), and their parents.
pub(crate) fn dof_fronts(
    structure: &Structure,
    dofs: &DofMap,
) -> (Vec<Vec<usize>>, Vec<Option<usize>>) {
    let (node_fronts, parent) = dissection(structure);
    let fronts = node_fronts
        .iter()
        .map(|nodes| {
            nodes
                .iter()
                .flat_map(|&v| dofs.row[v].into_iter().flatten())
                .collect()
        })
        .collect();
    (fronts, parent)
}

/// A nested dissection of the nodes by coordinates: the fronts (node lists, post order:
/// children before their parent) and each front's parent.
pub fn dissection(structure: &Structure) -> (Vec<Vec<usize>>, Vec<Option<usize>>) {
    dissection_with_leaves(structure, LEAF_NODES)
}

/// [`dissection`] down to sub-domains of at most `leaf` nodes.
pub fn dissection_with_leaves(
    structure: &Structure,
    leaf: usize,
) -> (Vec<Vec<usize>>, Vec<Option<usize>>) {
    let n = structure.n_nodes();
    let mut adj = vec![Vec::new(); n];
    for [i, j] in structure.member_nodes() {
        if i != j {
            adj[i].push(j);
            adj[j].push(i);
        }
    }
    let mut d = Dissector {
        pos: structure.nodes().iter().map(|p| [p.x, p.y, p.z]).collect(),
        adj,
        side: vec![0; n],
        leaf: leaf.max(1),
        fronts: Vec::new(),
        parent: Vec::new(),
    };
    d.split((0..n).collect());
    (d.fronts, d.parent)
}

struct Dissector {
    pos: Vec<[f64; 3]>,
    adj: Vec<Vec<usize>>,
    side: Vec<u8>,
    leaf: usize,
    fronts: Vec<Vec<usize>>,
    parent: Vec<Option<usize>>,
}

impl Dissector {
    fn push(&mut self, nodes: Vec<usize>, children: &[usize]) -> usize {
        let f = self.fronts.len();
        self.fronts.push(nodes);
        self.parent.push(None);
        for &c in children {
            self.parent[c] = Some(f);
        }
        f
    }

    /// Dissects `set`; returns the index of its top front.
    fn split(&mut self, mut set: Vec<usize>) -> usize {
        if set.len() <= self.leaf {
            return self.push(set, &[]);
        }
        let extent = |a: usize| {
            let (lo, hi) = set
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
                    (l.min(self.pos[v][a]), h.max(self.pos[v][a]))
                });
            hi - lo
        };
        let axis = (0..3)
            .max_by(|&a, &b| extent(a).total_cmp(&extent(b)))
            .unwrap_or(0);
        let key = |v: usize| self.pos[v][axis];
        set.sort_by(|&a, &b| key(a).total_cmp(&key(b)).then(a.cmp(&b)));
        // cut between distinct coordinates next to the median
        let c = key(set[set.len() / 2]);
        let mut cut = set.partition_point(|&v| key(v) < c);
        if cut == 0 {
            cut = set.partition_point(|&v| key(v) <= c);
        }
        if cut == 0 || cut == set.len() {
            return self.push(set, &[]);
        }
        for (i, &v) in set.iter().enumerate() {
            self.side[v] = if i < cut { 1 } else { 2 };
        }
        let boundary = |s: u8, d: &Self| -> Vec<usize> {
            set.iter()
                .copied()
                .filter(|&v| d.side[v] == s && d.adj[v].iter().any(|&w| d.side[w] == 3 - s))
                .collect()
        };
        let (bl, br) = (boundary(1, self), boundary(2, self));
        let sep = if bl.len() <= br.len() { bl } else { br };
        for &v in &sep {
            self.side[v] = 3;
        }
        let left: Vec<usize> = set.iter().copied().filter(|&v| self.side[v] == 1).collect();
        let right: Vec<usize> = set.iter().copied().filter(|&v| self.side[v] == 2).collect();
        for &v in &set {
            self.side[v] = 0;
        }
        if 2 * sep.len() >= set.len() {
            return self.push(set, &[]);
        }
        let mut kids = Vec::new();
        for part in [left, right] {
            if !part.is_empty() {
                kids.push(self.split(part));
            }
        }
        self.push(sep, &kids)
    }
}

/// The factored equilibrium problem of a lattice (see the module documentation).
#[derive(Debug, Clone)]
pub struct NestedStatics<'a> {
    structure: &'a Structure,
    dofs: DofMap,
    a: CscMatrix,
    qr: FrontalQr,
    orientation: Orientation,
    tolerance: f64,
    /// The residual at or below which a column is rejected
    /// ([`crate::rank::RankTolerance::reject_level`]).
    reject: f64,
    sigma_max: f64,
    sigma_min_estimate: f64,
    /// The sparse self-stress basis (members orientation, when its vectors are local).
    null_basis: Option<CscMatrix>,
    settings: StaticsSettings,
}

/// Which matrix the multifrontal QR factors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Orientation {
    /// Aᵀ (members × dofs), dofs as columns: the rejected columns are mechanisms. For
    /// lattices, which have few (their self-stresses are many and not listed).
    Dofs,
    /// A itself, members as columns: the rejected columns are self-stresses, local circuits
    /// on a long structure, whose sparse basis carries the margin LP. For towers, whose
    /// mechanisms are many and global: in the QR of Aᵀ their rejected residuals carry the
    /// rounding of a half-tower's conditioning (∝ N²·ε, against σ_r ∝ N⁻²), which no
    /// certificate survives beyond ~2,000 prisms, and on the band they fill R quadratically.
    Members,
}

impl<'a> NestedStatics<'a> {
    /// Orders, factors and estimates σ_min(R_acc).
    pub fn with_settings(structure: &'a Structure, settings: StaticsSettings) -> Result<Self> {
        crate::cluster_columns::refuse_clusters_in(structure, "nested-dissection QR")?;
        let dofs = DofMap::of(structure);
        let a = equilibrium_matrix_sparse(structure, &dofs)?;
        let (m, n) = (dofs.len(), structure.n_members());
        let (fronts, parent) = dof_fronts(structure, &dofs);
        let sigma = sigma_max(&a);
        let scales = settings.rank_scales(structure, (m, n), sigma);
        let (tolerance, reject) = (scales.absolute(), scales.reject_level(REJECT_FACTOR));
        let qr = FrontalQr::new(&a, &fronts, &parent, reject)?;
        let sigma_min_estimate = qr.sigma_min_estimate(INVERSE_STEPS);
        Ok(Self {
            structure,
            dofs,
            a,
            qr,
            orientation: Orientation::Dofs,
            tolerance,
            reject,
            sigma_max: sigma,
            sigma_min_estimate,
            null_basis: None,
            settings,
        })
    }

    /// The members orientation ([`Orientation::Members`]): the multifrontal QR of A itself
    /// along the same dissection (leaves of [`MEMBER_LEAF_NODES`] nodes), each member in
    /// the front of whichever of its ends lies higher in the tree (no member joins two
    /// siblings, so every dof row touches one front and its ancestors); the rejected
    /// members' null vectors form a sparse self-stress basis, kept when it holds at most
    /// [`NULL_ENTRIES_PER_MEMBER`] entries per member.
    ///
    /// ```
    /// use tensegrity_statics::{NestedStatics, StaticsBackend, StaticsSettings};
    /// use tensegrity_core::test_models::snelson_tower_free;
    /// let tower = snelson_tower_free(12).unwrap();
    /// let nd = NestedStatics::members_with_settings(&tower, StaticsSettings::default()).unwrap();
    /// // one self-stress a prism; 12 internal mechanisms and the 6 rigid motions
    /// assert_eq!((nd.self_stress_dim(), nd.mechanisms()), (12, 18));
    /// assert!(nd.is_certified());
    /// ```
    pub fn members_with_settings(
        structure: &'a Structure,
        settings: StaticsSettings,
    ) -> Result<Self> {
        crate::cluster_columns::refuse_clusters_in(structure, "nested-dissection QR")?;
        let dofs = DofMap::of(structure);
        let a = equilibrium_matrix_sparse(structure, &dofs)?;
        let (m, n) = (dofs.len(), structure.n_members());
        let at = transpose(&a)?;
        let (fronts, parent) = member_fronts(structure);
        let sigma = sigma_max(&a);
        let scales = settings.rank_scales(structure, (m, n), sigma);
        let (tolerance, reject) = (scales.absolute(), scales.reject_level(REJECT_FACTOR));
        let qr = FrontalQr::with_threshold(&at, &fronts, &parent, reject, MEMBER_PIVOT_THRESHOLD)?;
        let sigma_min_estimate = qr.sigma_min_estimate(INVERSE_STEPS);
        let null_basis =
            qr.sparse_null_vectors_within(NULL_ENTRIES_PER_MEMBER.saturating_mul(n))?;
        Ok(Self {
            structure,
            dofs,
            a,
            qr,
            orientation: Orientation::Members,
            tolerance,
            reject,
            sigma_max: sigma,
            sigma_min_estimate,
            null_basis,
            settings,
        })
    }

    /// Which matrix was factored.
    pub fn orientation(&self) -> Orientation {
        self.orientation
    }

    /// The sparse self-stress basis N (members × dimension, not orthonormal) of the members
    /// orientation, when its vectors are local; `None` otherwise.
    pub fn sparse_self_stress_basis(&self) -> Option<&CscMatrix> {
        self.null_basis.as_ref()
    }

    /// The factorisation.
    pub fn factorization(&self) -> &FrontalQr {
        &self.qr
    }

    /// The estimate of σ_min(R_acc), a lower bound of σ_r(A) (+∞ at rank 0).
    pub fn sigma_min_r_estimate(&self) -> f64 {
        self.sigma_min_estimate
    }

    /// Whether the rejected part is round-off: ‖E‖_F ≤ 10⁻¹⁰·σ_max(A), so that every
    /// counted self-stress (and mechanism) is exact. Rounded coordinates whose rank
    /// decision discounts their rounding leave more.
    pub fn rank_is_exact(&self) -> bool {
        self.qr.rejected_residual() <= super::sparse::EXACT_SELF_STRESS_RESIDUAL * self.sigma_max
    }

    /// Whether the rank decision is certified: σ_min(R_acc) > 100·max(τ, ‖E‖_F); a rank of
    /// 0 only where σ_max(A) is within the rejection level.
    pub fn is_certified(&self) -> bool {
        if self.rank() == 0 {
            return self.sigma_max <= self.reject;
        }
        let noise = self.qr.rejected_residual().max(self.tolerance);
        self.sigma_min_estimate > CERTIFY_FACTOR * noise
    }
}

impl StaticsBackend for NestedStatics<'_> {
    fn kind(&self) -> Factorization {
        Factorization::SparseQr
    }
    fn structure(&self) -> &Structure {
        self.structure
    }
    fn free_dofs(&self) -> usize {
        self.dofs.len()
    }
    fn rank(&self) -> usize {
        self.qr.rank()
    }
    fn rigid_body_motions(&self) -> Result<usize> {
        Ok(rigid_motions(self.structure, &self.dofs)?.ncols())
    }
    fn tolerance(&self) -> f64 {
        self.tolerance
    }
    fn smallest_singular_value(&self) -> f64 {
        let (m, n) = (self.dofs.len(), self.structure.n_members());
        if self.qr.rank() < m.min(n) {
            self.qr.rejected_residual()
        } else {
            self.sigma_min_estimate
        }
    }
    fn spectral_gap(&self) -> SpectralGap {
        let (m, n) = (self.dofs.len(), self.structure.n_members());
        let below = (self.qr.rank() < m.min(n)).then_some(self.qr.rejected_residual());
        let mut gap = SpectralGap::from_values(below, self.tolerance, None);
        let above = self.sigma_min_estimate;
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
                "the sparse rank decision (nested dissection) is not certified (rejected residual {:.3e}, σ_min(R) estimate {:.3e}, tolerance {:.3e}): rank and self-stress dimension may differ from the SVD's",
                self.qr.rejected_residual(),
                self.sigma_min_estimate,
                self.tolerance
            ),
        }
    }
    fn self_stress(&self) -> SelfStressBasis {
        SelfStressBasis::Omitted {
            basis: DMatrix::zeros(self.structure.n_members(), 0),
            dim: self.self_stress_dim(),
        }
    }
    fn prestressability_with(&self, signs: &[MemberSign]) -> Result<Prestressability> {
        let n = self.structure.n_members();
        super::prestress::check_signs(signs, n)?;
        if self.self_stress_dim() == 0 {
            return Ok(Prestressability::none(n));
        }
        if n > LP_MEMBERS_MAX {
            return Err(Factorization::SparseQr.unsupported(
                "the prestressability margin of a lattice this large (nested dissection)",
            ));
        }
        if let Some(basis) = &self.null_basis {
            // the LP over the sparse basis, q = N c (the banded path's LP)
            if let Ok(c) = super::prestress::solve_null_space_lp(basis, signs) {
                let q = DVector::from_vec(basis.mul_vec(&c));
                return Ok(Prestressability::from_signed(q, signs));
            }
        }
        // the interior point imposes A q = 0 exactly: where the rank decision rejected more
        // than round-off (coordinates rounded to their precision), some self-stress it counts
        // holds only to that precision, and the margin over the exact ones would not be this
        // structure's (a rounded prism beside a lattice: 1.5·10⁻¹¹ against 0.577)
        if !self.rank_is_exact() {
            return Err(Factorization::SparseQr.unsupported(
                "the prestressability margin where some self-stress holds only to the coordinates' precision (rejected residual above round-off; the interior point on A needs exact ones): the banded sparse QR or the dense SVD computes it over the counted self-stresses",
            ));
        }
        // the interior point on A D⁻¹ Aᵀ; Clarabel on the same rows should it fail
        // the normal matrix A D⁻¹ Aᵀ has the pattern of a stiffness matrix: the structure's
        // own nested dissection orders it with less fill than AMD (lattice K = 86: 10.4 M
        // against 13.9 M entries of L, 0.31 against 0.53 s a factorisation)
        let order = dof_fronts(self.structure, &self.dofs).0.concat();
        let q = super::margin_ipm::solve(&self.a, signs, Some(&order))
            .or_else(|_| super::prestress::solve_equilibrium_lp(&self.a, signs))?;
        Ok(Prestressability::from_signed(DVector::from_vec(q), signs))
    }
    fn prestress_stability(&self, q: &DVector<f64>) -> Result<PrestressStability> {
        // without internal mechanisms the structure is stable for any stress (the dense
        // path's answer); with some, the test is not available here
        let internal = self.internal_mechanisms()?;
        if internal == 0 {
            return Ok(PrestressStability::rigid());
        }
        if self.orientation == Orientation::Members {
            // the penalised stress matrix (linear: no flex basis), which only proves
            // stability; then the banded test where few mechanisms keep its factor banded
            let certificate = super::sparse::stable_by_penalty_certificate(
                self.structure,
                &self.dofs,
                q,
                self.sigma_max,
            )?;
            if certificate == Some(true) {
                return Ok(PrestressStability {
                    internal_mechanisms: internal,
                    eigenvalues: Vec::new(),
                    stable: true,
                });
            }
            let (m, d) = (self.dofs.len(), self.mechanisms());
            if m.saturating_mul(d) > super::sparse::DENSE_MECHANISMS_MAX {
                return Err(Factorization::SparseQr.unsupported(
                    "prestress stability of a long structure with this many mechanisms (the penalised stress matrix gives no decision)",
                ));
            }
        }
        // with internal mechanisms: the banded path's test (its flexes)
        super::SparseStatics::with_settings(self.structure, self.settings)?.prestress_stability(q)
    }
    fn solve_nodal_forces(&self, _w_nodes: &Matrix3xX<f64>) -> Result<LoadSolution> {
        Err(CoreError::Unsupported {
            analysis: "the load solve",
            backend: "sparse rank-revealing QR (nested dissection)",
        })
    }
}
