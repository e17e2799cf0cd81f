//! Tangent stiffness, stress matrix, rigid-body motions and modal analysis.
//!
//! For member k with force density q_k (tension positive), length l_k, unit vector e_k and
//! axial stiffness k_k (k for strings, E·πr²/l for elastic bars), the 3×3 block
//!
//! K_k = k_k e_k e_kᵀ + q_k (I₃ − e_k e_kᵀ)
//!
//! enters the tangent stiffness as [[K_k, −K_k], [−K_k, K_k]] on its two nodes (material plus
//! geometric stiffness). The geometric part alone, Σ q_k (…)⊗I₃, is the stress matrix Ω ⊗ I₃
//! with Ω = Cᵀ diag(q) C.
//!
//! Rigid-body motions δn_i = a + ω × n_i that the supports allow ([`rigid_body_motions`]) are
//! the trivial first-order flexes. The flexes themselves ([`Statics::flexes`]) and the
//! prestress-stability test with the stress matrix ([`Statics::prestress_stability`]) are
//! methods of [`Statics`], in `statics/flexes.rs` and `statics/stability.rs`; their result
//! types are re-exported here.
//!
//! [`Statics`]: crate::Statics
//! [`Statics::flexes`]: crate::Statics::flexes
//! [`Statics::prestress_stability`]: crate::Statics::prestress_stability
//!
//! An elastic support (a spring of stiffness k along each held direction d) adds k d dᵀ on
//! its node, which it leaves free ([`DofMap::stiffness_of`]); a node held along directions
//! of any orientation has the blocks on its free axes, F_iᵀ K_k F_j ([`DofMap::local_block`]).
//!
//! A clustered string adds its own blocks, K_c = k_c g gᵀ + t_c Σ_i (1/l_i) P_i per
//! segment (g = ∂L_c/∂x couples every node of the cluster), and to the stress matrix its
//! geometric part t_c Σ_i (1/l_i) P_i ([`crate::cluster_columns`]); q, the axial stiffnesses
//! and the force densities have one entry per column, the clusters after the members.
//!
//! Modal analysis solves K φ = ω² M φ with the lumped mass M (half of each bar's mass at each
//! of its ends; strings are massless), on the free dofs of [`DofMap::stiffness_of`] (a node
//! on a spring moves, and needs mass).

use crate::cluster_columns::cluster_geometries;
use crate::DofMap;
pub use crate::{Flexes, PrestressStability};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use std::f64::consts::PI;
use tensegrity_core::error::{CoreError, ModelError, NumericsError, Result};
use tensegrity_core::structure::{MemberId, Structure};
use tensegrity_linalg as linalg;

/// Assembles Σ_k blocks into the free-dof matrix, given each member's 3×3 block.
fn assemble(
    structure: &Structure,
    dofs: &DofMap,
    block: impl Fn(usize) -> Matrix3<f64>,
) -> DMatrix<f64> {
    let n = dofs.len();
    let mut k_mat = DMatrix::zeros(n, n);
    for (k, [i, j]) in structure.member_nodes().into_iter().enumerate() {
        let b = block(k);
        for (a, sa) in [(i, 1.0), (j, -1.0)] {
            for (c, sc) in [(i, 1.0), (j, -1.0)] {
                // the block on the two nodes' axes (x, y, z unless a node has a frame)
                let b = dofs.local_block(a, c, &b);
                for d1 in 0..3 {
                    let Some(r) = dofs.row[a][d1] else { continue };
                    for d2 in 0..3 {
                        if let Some(col) = dofs.row[c][d2] {
                            k_mat[(r, col)] += sa * sc * b[(d1, d2)];
                        }
                    }
                }
            }
        }
    }
    k_mat
}

/// Adds 3×3 blocks (row node, column node, block in x, y, z) to the free-dof matrix, on the
/// nodes' axes: the clusters' blocks
/// ([`ClusterGeometry::stiffness_blocks`](crate::cluster_columns::ClusterGeometry::stiffness_blocks)).
fn add_blocks(dofs: &DofMap, k_mat: &mut DMatrix<f64>, blocks: &[(usize, usize, Matrix3<f64>)]) {
    for (a, c, b) in blocks {
        let b = dofs.local_block(*a, *c, b);
        for d1 in 0..3 {
            let Some(r) = dofs.row[*a][d1] else { continue };
            for d2 in 0..3 {
                if let Some(col) = dofs.row[*c][d2] {
                    k_mat[(r, col)] += b[(d1, d2)];
                }
            }
        }
    }
}

/// Adds every cluster's tangent stiffness (module docs of [`crate::cluster_columns`]) with
/// force densities `q` and axial stiffnesses `axial` (their entries after the members').
fn add_clusters(
    structure: &Structure,
    dofs: &DofMap,
    q: &DVector<f64>,
    axial: &[f64],
    k_mat: &mut DMatrix<f64>,
) {
    let nm = structure.n_members();
    for (c, g) in cluster_geometries(structure).iter().enumerate() {
        let t = q[nm + c] * g.length;
        add_blocks(dofs, k_mat, &g.stiffness_blocks(axial[nm + c], t));
    }
}

/// Adds the springs of the elastic supports that `dofs` leaves free (Σ k d dᵀ on their
/// nodes' axes, [`DofMap::stiffness_of`]) to `k_mat`.
fn add_springs(dofs: &DofMap, k_mat: &mut DMatrix<f64>) {
    for (node, ks) in dofs.springs() {
        let b = dofs.local_block(*node, *node, ks);
        for d1 in 0..3 {
            let Some(r) = dofs.row[*node][d1] else {
                continue;
            };
            for d2 in 0..3 {
                if let Some(c) = dofs.row[*node][d2] {
                    k_mat[(r, c)] += b[(d1, d2)];
                }
            }
        }
    }
}

/// The stress (geometric stiffness) matrix Ω ⊗ I₃ on the free degrees of freedom for force
/// densities `q` (bars then strings).
///
/// ```
/// use nalgebra::DVector;
/// use tensegrity_core::{StringMember, Structure};
/// use tensegrity_statics::{DofMap, stiffness};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .string(StringMember::new(0, 1))
///     .build()
///     .unwrap();
/// let k = stiffness::stress_matrix(&s, &DofMap::of(&s), &DVector::from_element(1, 2.0));
/// assert_eq!((k[(0, 0)], k[(0, 3)]), (2.0, -2.0));
/// ```
pub fn stress_matrix(structure: &Structure, dofs: &DofMap, q: &DVector<f64>) -> DMatrix<f64> {
    let mut omega = assemble(structure, dofs, |k| Matrix3::identity() * q[k]);
    let zero = vec![0.0; q.len()];
    add_clusters(structure, dofs, q, &zero, &mut omega);
    omega
}

/// The tangent stiffness (material + geometric) on the free degrees of freedom for force
/// densities `q` and axial stiffnesses `axial` (N/m, one per member), plus the springs of
/// the elastic supports that `dofs` leaves free (k d dᵀ per held direction d: with
/// [`DofMap::stiffness_of`]; [`DofMap::of`] holds them instead).
///
/// ```
/// use nalgebra::DVector;
/// use tensegrity_core::{StringMember, Structure, Support};
/// use tensegrity_statics::{stiffness, DofMap};
/// // a string along x from a pinned node to a node on a spring of 300 N/m along x
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
///     .string(StringMember::new(0, 1).stiffness(100.0))
///     .support(Support::pinned(0))
///     .support(Support::directions(1, [true, false, false]).elastic(300.0))
///     .build()
///     .unwrap();
/// let dofs = DofMap::stiffness_of(&s);
/// let k = stiffness::tangent_stiffness(&s, &dofs, &DVector::zeros(1), &[100.0]);
/// assert_eq!(k[(0, 0)], 400.0); // string and spring in parallel on the node's x
/// ```
pub fn tangent_stiffness(
    structure: &Structure,
    dofs: &DofMap,
    q: &DVector<f64>,
    axial: &[f64],
) -> DMatrix<f64> {
    let mut k_mat = assemble(structure, dofs, |k| {
        let e: Vector3<f64> = structure.member_vector(k).normalize();
        let eet = e * e.transpose();
        eet * axial[k] + (Matrix3::identity() - eet) * q[k]
    });
    add_clusters(structure, dofs, q, axial, &mut k_mat);
    add_springs(dofs, &mut k_mat);
    k_mat
}

/// Axial stiffness of every column: k for strings (0 when slack at the current length), E·πr²/l
/// for bars with a material and a radius, then k of each cluster (of its whole length; 0 when
/// slack, L_c ≤ L₀).
pub fn axial_stiffness(structure: &Structure) -> Result<Vec<f64>> {
    let lengths = structure.member_lengths();
    let mut axial = (0..structure.n_members())
        .map(|k| match structure.member_id(k) {
            MemberId::Bar(i) => {
                let bar = &structure.bars()[i];
                let missing = |property| {
                    CoreError::Model(ModelError::MissingProperty {
                        member: MemberId::Bar(i),
                        analysis: "tangent stiffness",
                        property,
                    })
                };
                let mat = structure
                    .member_material(MemberId::Bar(i))
                    .ok_or(missing("material"))?;
                let r = bar.radius.ok_or(missing("radius"))?;
                Ok(mat.youngs_modulus * PI * r * r / lengths[k])
            }
            MemberId::String(i) => {
                let s = &structure.strings()[i];
                let k_s = s.stiffness.ok_or(ModelError::MissingProperty {
                    member: MemberId::String(i),
                    analysis: "tangent stiffness",
                    property: "stiffness",
                })?;
                let taut = s.rest_length.is_none_or(|s0| lengths[k] > s0);
                Ok(if taut { k_s } else { 0.0 })
            }
        })
        .collect::<Result<Vec<f64>>>()?;
    for (c, cluster) in structure.clusters().iter().enumerate() {
        let k_c = cluster
            .stiffness
            .ok_or_else(|| missing_cluster_property(c, "tangent stiffness", "stiffness"))?;
        let length = cluster.length(structure.nodes());
        let taut = cluster.rest_length.is_none_or(|l0| length > l0);
        axial.push(if taut { k_c } else { 0.0 });
    }
    Ok(axial)
}

/// The error of cluster `c` without a `property` that `analysis` needs.
pub(crate) fn missing_cluster_property(c: usize, analysis: &str, property: &str) -> CoreError {
    ModelError::InvalidCluster {
        cluster: c,
        reason: format!("{analysis} needs its {property}, which is not given"),
    }
    .into()
}

/// Force densities of the strings from their rest lengths, q = k(1 − s0/l) when taut, else 0
/// (bars get 0: their forces follow from equilibrium), then of the clusters, q_c = t_c / L_c
/// = k(1 − L₀/L_c) when taut, else 0.
pub fn string_force_densities(structure: &Structure) -> Result<DVector<f64>> {
    let lengths = structure.member_lengths();
    let nb = structure.n_bars();
    let nm = structure.n_members();
    let mut q = DVector::zeros(crate::n_columns(structure));
    for (c, cluster) in structure.clusters().iter().enumerate() {
        let missing = |property| missing_cluster_property(c, "the string tension", property);
        let k = cluster.stiffness.ok_or_else(|| missing("stiffness"))?;
        let l0 = cluster.rest_length.ok_or_else(|| missing("rest_length"))?;
        let l = cluster.length(structure.nodes());
        q[nm + c] = if l > l0 { k * (1.0 - l0 / l) } else { 0.0 };
    }
    for (i, s) in structure.strings().iter().enumerate() {
        let missing = |property| {
            CoreError::Model(ModelError::MissingProperty {
                member: MemberId::String(i),
                analysis: "string tension",
                property,
            })
        };
        let k = s.stiffness.ok_or(missing("stiffness"))?;
        let s0 = s.rest_length.ok_or(missing("rest_length"))?;
        let l = lengths[nb + i];
        q[nb + i] = if l > s0 { k * (1.0 - s0 / l) } else { 0.0 };
    }
    Ok(q)
}

/// The force densities of the current state: strings from their rest lengths
/// ([`string_force_densities`]), bars from equilibrium with them and the external loads,
/// A_b q_b = w − A_s q_s in the least-squares, minimal-norm sense. Returns q and the equilibrium
/// residual ‖A q − w‖ (N), which is zero when the rest lengths realise a self-stress.
///
/// ```
/// use tensegrity_core::{Bar, StringMember, Structure};
/// use tensegrity_statics::stiffness;
/// // a bar held in compression by a string along it: the bar force balances the string
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 2))
///     .string(StringMember::new(0, 1).stiffness(100.0).rest_length(0.9))
///     .string(StringMember::new(1, 2).stiffness(100.0).rest_length(0.9))
///     .build()
///     .unwrap();
/// let (q, residual) = stiffness::equilibrium_force_densities(&s).unwrap();
/// assert!((q[1] - 10.0).abs() < 1e-12 && (q[0] + 5.0).abs() < 1e-12 && residual < 1e-12);
/// ```
pub fn equilibrium_force_densities(structure: &Structure) -> Result<(DVector<f64>, f64)> {
    let mut q = string_force_densities(structure)?;
    let dofs = DofMap::of(structure);
    let a = crate::equilibrium_matrix(structure, &dofs);
    let w = dofs.gather(&structure.W());
    let nb = structure.n_bars();
    let q_b = bars_balancing(&a, nb, &(&w - &a * &q))?;
    q.rows_mut(0, nb).copy_from(&q_b);
    let residual = (&a * &q - &w).norm();
    Ok((q, residual))
}

/// The bars' force densities of least norm that balance `rhs` (A_b q_b = rhs in the least
/// squares sense; A_b the first `nb` columns of `a`): the bars' forces under a given force
/// state of the other members.
pub(crate) fn bars_balancing(
    a: &DMatrix<f64>,
    nb: usize,
    rhs: &DVector<f64>,
) -> Result<DVector<f64>> {
    let a_b = a.columns(0, nb).into_owned();
    let d = linalg::svd(&a_b)?;
    let tol = linalg::rank_tolerance(
        a_b.nrows(),
        a_b.ncols(),
        d.s.first().copied().unwrap_or(0.0),
        None,
    );
    Ok(d.solve_min_norm(rhs, d.rank(tol)))
}

/// Rigid-body motions on the free degrees of freedom that the supports allow: an orthonormal
/// basis (free dofs × count).
pub fn rigid_body_motions(structure: &Structure, dofs: &DofMap) -> Result<DMatrix<f64>> {
    let n = structure.n_nodes();
    let centre = structure.nodes().iter().sum::<Vector3<f64>>() / n as f64;
    // T: 3n × 6, columns = three translations and three rotations about the centroid.
    // (rows on each node's axes: x, y, z unless it has a frame)
    let mut t = DMatrix::zeros(3 * n, 6);
    for (i, p) in structure.nodes().iter().enumerate() {
        let r = p - centre;
        for d in 0..3 {
            let a = dofs.to_local(i, &Vector3::ith(d, 1.0));
            let w = dofs.to_local(i, &Vector3::ith(d, 1.0).cross(&r));
            for c in 0..3 {
                t[(3 * i + c, d)] = a[c];
                t[(3 * i + c, 3 + d)] = w[c];
            }
        }
    }
    let fixed_rows: Vec<usize> = (0..3 * n)
        .filter(|&r| dofs.row[r / 3][r % 3].is_none())
        .collect();
    let allowed = if fixed_rows.is_empty() {
        DMatrix::identity(6, 6)
    } else {
        let t_fixed = t.select_rows(fixed_rows.iter());
        let d = linalg::svd(&t_fixed)?;
        let tol = linalg::rank_tolerance(
            t_fixed.nrows(),
            6,
            d.s.first().copied().unwrap_or(0.0),
            None,
        );
        let r = d.rank(tol);
        d.v.columns(r, 6 - r).into_owned()
    };
    let free_rows: Vec<usize> = dofs.free.iter().map(|&(i, d)| 3 * i + d).collect();
    let t_free = t.select_rows(free_rows.iter()) * allowed;
    Ok(linalg::orthonormal_basis(&t_free, Some(1e-10))?)
}

/// Lumped nodal masses: half of each bar's mass at each of its ends (strings massless).
pub fn lumped_masses(structure: &Structure) -> Vec<f64> {
    let mut m = vec![0.0; structure.n_nodes()];
    for b in structure.bars() {
        if let Some(mass) = b.mass {
            m[b.nodes[0]] += 0.5 * mass;
            m[b.nodes[1]] += 0.5 * mass;
        }
    }
    m
}

/// Natural modes of small vibration about the current configuration.
#[derive(Debug, Clone)]
pub struct Modes {
    /// ω² (rad²/s²), ascending.
    pub eigenvalues: Vec<f64>,
    /// Natural frequencies f = √max(ω², 0) / 2π (Hz).
    pub frequencies_hz: Vec<f64>,
    /// Mode shapes on the free degrees of freedom (M-orthonormal columns).
    pub shapes: DMatrix<f64>,
}

/// The size, relative to the largest |ω²|, at or below which a mode's ω² counts as zero: a
/// rigid-body motion the supports allow, or a mechanism the prestress does not stiffen.
pub const ZERO_MODE_TOLERANCE: f64 = 1e-9;

impl Modes {
    /// The indices of the modes of nonzero ω² (|ω²| > [`ZERO_MODE_TOLERANCE`] · max |ω²|),
    /// ascending: the modes a report lists and a figure draws, the zero modes skipped in both.
    /// A negative ω² (an unstable mode) is kept.
    ///
    /// ```
    /// use nalgebra::DMatrix;
    /// use tensegrity_statics::stiffness::Modes;
    /// let modes = Modes {
    ///     eigenvalues: vec![-1e-12, 3e-11, 4.0, 9.0],
    ///     frequencies_hz: vec![0.0, 0.0, 1.0 / std::f64::consts::PI, 1.5 / std::f64::consts::PI],
    ///     shapes: DMatrix::identity(4, 4),
    /// };
    /// assert_eq!(modes.nonzero(), vec![2, 3]);
    /// ```
    pub fn nonzero(&self) -> Vec<usize> {
        let top = self.eigenvalues.iter().fold(0.0f64, |a, &w| a.max(w.abs()));
        (0..self.eigenvalues.len())
            .filter(|&i| self.eigenvalues[i].abs() > ZERO_MODE_TOLERANCE * top)
            .collect()
    }
}

/// How bar mass enters modal analysis (serialised `lumped`, `consistent`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MassModel {
    /// Half of each bar's mass at each end (diagonal M).
    #[default]
    Lumped,
    /// The rigid-bar mass matrix of the dynamics, m [[1/3, 1/6], [1/6, 1/3]] ⊗ I₃ per bar
    /// (J = m/12 about the centre plus m at the centre), so the frequencies are those of small
    /// oscillations of `tensegrity_dynamics` with very stiff bars.
    Consistent,
}

/// Solves K φ = ω² M φ with the tangent stiffness for force densities `q` and the lumped mass.
/// Every free node needs mass; bars need a material and a radius (axial stiffness), strings a
/// stiffness.
pub fn modal_analysis(structure: &Structure, q: &DVector<f64>) -> Result<Modes> {
    modal_analysis_with(structure, q, MassModel::Lumped)
}

/// [`modal_analysis`] with a choice of mass matrix. With M = L Lᵀ (diagonal for the lumped
/// model, Cholesky for the consistent one) the symmetric problem L⁻¹ K L⁻ᵀ ψ = ω² ψ is solved
/// and φ = L⁻ᵀ ψ (M-orthonormal shapes).
pub fn modal_analysis_with(
    structure: &Structure,
    q: &DVector<f64>,
    mass: MassModel,
) -> Result<Modes> {
    let dofs = DofMap::stiffness_of(structure);
    let axial = axial_stiffness(structure)?;
    let k_t = tangent_stiffness(structure, &dofs, q, &axial);
    let masses = lumped_masses(structure);
    for &(node, _) in &dofs.free {
        if masses[node] <= 0.0 {
            return Err(ModelError::NoLumpedMass { node }.into());
        }
    }
    let n = dofs.len();
    let m = match mass {
        MassModel::Lumped => DMatrix::from_diagonal(&DVector::from_iterator(
            n,
            dofs.free.iter().map(|&(node, _)| masses[node]),
        )),
        MassModel::Consistent => {
            let mut m = DMatrix::zeros(n, n);
            for b in structure.bars() {
                let mb = b.mass.unwrap_or(0.0);
                for (x, y, c) in [
                    (0, 0, 1.0 / 3.0),
                    (1, 1, 1.0 / 3.0),
                    (0, 1, 1.0 / 6.0),
                    (1, 0, 1.0 / 6.0),
                ] {
                    let (i, j) = (b.nodes[x], b.nodes[y]);
                    for d in 0..3 {
                        let Some(r) = dofs.row[i][d] else { continue };
                        for (e, w) in dofs.coupling(i, d, j).into_iter().enumerate() {
                            if let (Some(col), true) = (dofs.row[j][e], w != 0.0) {
                                m[(r, col)] += c * mb * w;
                            }
                        }
                    }
                }
            }
            m
        }
    };
    let l = m
        .clone()
        .cholesky()
        .ok_or(NumericsError::NoConvergence {
            operation: "Cholesky factorisation of the mass matrix",
        })?
        .unpack();
    let l_inv = l
        .clone()
        .try_inverse()
        .ok_or(NumericsError::NoConvergence {
            operation: "inverse of the mass matrix factor",
        })?;
    let scaled = &l_inv * &k_t * l_inv.transpose();
    let sym = (&scaled + scaled.transpose()) * 0.5;
    let (w, v) = linalg::symmetric_eigen(&sym)?;
    let shapes = l_inv.transpose() * v;
    let frequencies_hz = w.iter().map(|&x| x.max(0.0).sqrt() / (2.0 * PI)).collect();
    Ok(Modes {
        eigenvalues: w,
        frequencies_hz,
        shapes,
    })
}
