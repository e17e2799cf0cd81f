//! The linear response of a structure at its geometry (small displacements): the node
//! displacements, member force changes and support reactions under the structure's loads
//! and the supports' prescribed displacements.
//!
//! **Stiffness.** With the force state t₀ of the structure (strings: t₀ = k (l − l₀) from
//! their stiffness k and rest length l₀ when taut, 0 when slack or without a rest length;
//! bars: the minimal-norm forces balancing the strings' at every node, A_b q_b = −A_s q_s,
//! held as the equilibrium analyses hold the supports, [`DofMap::of`]) and the axial
//! stiffnesses k_k (EA/l = E π r²/l for bars with a material and a radius, k for taut
//! strings, 0 for slack ones: [`stiffness::axial_stiffness`]), the tangent stiffness is the
//! sum over members of
//!
//! K_k = k_k e_k e_kᵀ + (t₀_k / l_k)(I₃ − e_k e_kᵀ)   (material + geometric)
//!
//! on its two nodes, and for each clustered string K_c = k_c g gᵀ + t₀_c Σ_i (1/l_i)(I₃ −
//! e_i e_iᵀ) over its segments (g = ∂L_c/∂x; t₀_c = k_c (L_c − L₀) when taut:
//! [`crate::cluster_columns`]), plus k d dᵀ for each held direction d of an elastic support, whose node
//! stays free ([`DofMap::stiffness_of`], [`stiffness::tangent_stiffness`]).
//!
//! **Partition.** The coordinates are each node's three axes (x, y, z, or the frame of a node
//! held along directions of any orientation, [`DofMap::axis`]): the free ones (f) and the
//! held directions of the rigid supports (p). A support's prescribed displacement d (m, its
//! `displacement`) gives the held coordinates d_p = e·d on each held axis e of its node (a
//! support `along` directions: d·direction, the component in their span); a component of d
//! outside the held span is refused (as `solve` refuses it). With P the nodal loads (the
//! loads and the bars' weight, as the load solve counts them),
//!
//! K_ff u_f = P_f − K_fp d_p + Σ_s k_s d (d·a_s)
//!
//! where the last sum runs over the elastic supports s whose `displacement` a_s moves their
//! springs' anchor (the spring's force on its node is −k d (d·(u − a)), as in `solve`).
//! K_ff is factored by its symmetric eigendecomposition: eigenvalues within the SVD's
//! tolerance n ε |λ|_max of zero are mechanisms that neither the prestress nor a spring
//! stiffens, and the response is the error [`StaticsError::SingularStiffness`] naming their
//! count and the node the first one moves (never NaN); negative ones (an unstable state) are
//! a warning.
//!
//! **Results.** u = (u_f, d_p) on every node; the member force change
//! Δt_k = k_k e_k·(u_j − u_i) (member from node i to node j), a cluster's Δt_c = k_c gᵀu; the reaction of a rigid support,
//! the force it exerts on the node, (K u − P)_p = K_pf u_f + K_pp d_p − P_p along its held
//! directions (as [`Reaction`], the load solve's shape); of an elastic support, its springs'
//! force k d (d·(a − u)). A string with t₀ + Δt < 0 would go slack: the linear answer is then
//! outside its assumptions (a warning names the strings; `solve` follows them).
//!
//! ```
//! use nalgebra::Vector3;
//! use tensegrity_core::{material::Material, Bar, Structure, Support};
//! use tensegrity_statics::response::linear_response;
//! // a bar along x (EA = 1e4 N, L = 2 m), its far end pushed 1 mm along the bar
//! let ea = 1e4;
//! let e = ea / (std::f64::consts::PI * 1e-4);
//! let s = Structure::builder()
//!     .material("m", Material::new(1000.0, e, 1e6))
//!     .nodes([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]])
//!     .bar(Bar::new(0, 1).material("m").radius(0.01))
//!     .support(Support::pinned(0))
//!     .support(Support::pinned(1))
//!     .build()
//!     .unwrap();
//! let r = linear_response(&s, &[None, Some(Vector3::new(-1e-3, 0.0, 0.0))]).unwrap();
//! assert!((r.member_force_change[0] + ea * 1e-3 / 2.0).abs() < 1e-9);
//! assert!((r.reactions[1].force[0] + 5.0).abs() < 1e-9);
//! ```

use crate::cluster_columns::cluster_geometries;
use crate::reaction::Reaction;
use crate::stiffness;
use crate::DofMap;
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use serde::Serialize;
use tensegrity_core::error::{CoreError, ModelError, Result, StaticsError};
use tensegrity_core::request::InvalidParameter;
use tensegrity_core::structure::{MemberId, Structure, Support};
use tensegrity_linalg as linalg;

/// A prescribed displacement may leave its support's held span by this fraction of its
/// length (round-off of a direction written to finite digits), as `solve` allows.
const SPAN_TOLERANCE: f64 = 1e-12;

/// The prestress counts as in equilibrium when its residual ‖A q‖ (N, on the free
/// coordinates) is within this fraction of the members' forces ‖t₀‖.
const PRESTRESS_RESIDUAL_TOLERANCE: f64 = 1e-8;

/// The linear response at the structure's geometry (module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LinearResponse {
    /// The displacement u of every node (m, x, y, z); held coordinates carry their prescribed
    /// value.
    pub displacements: Vec<[f64; 3]>,
    /// The change Δt of every member's axial force (N, tension positive; bars, strings, then
    /// clusters, as `member_force`: a cluster's Δt = k_c δL_c).
    pub member_force_change: Vec<f64>,
    /// The force state t₀ the stiffness is taken about (N, tension positive, bars, strings,
    /// then clusters): the strings' and clusters' from their rest lengths, the bars'
    /// balancing them.
    pub initial_force: Vec<f64>,
    /// The reaction of every support (N), the force it exerts on its node, in support order
    /// (an elastic support's: its springs' force).
    pub reactions: Vec<Reaction>,
    /// The largest node displacement ‖u_i‖ (m).
    pub max_displacement: f64,
    /// The strings (their indices among the strings) whose force t₀ + Δt is negative: they
    /// would go slack, and the linear answer is outside its assumptions.
    pub slack: Vec<usize>,
    /// The clusters (their indices among the clusters) that would go slack, as `slack`
    /// (left out of the JSON when none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub slack_clusters: Vec<usize>,
    /// What the numbers need beside them: strings that would go slack, an unstable or
    /// unbalanced force state.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
}

/// The linear response of `structure` to its loads and to the prescribed displacements
/// `displacements` (m; one entry per support, in support order, `None` where a support has
/// none; an empty slice: none at all). Module docs give the equations.
///
/// Errors: a member without an axial stiffness (a bar without a material or a radius, a
/// string without a stiffness), naming it ([`ModelError::MissingProperty`]); a displacement
/// with a component outside its support's held directions, or a list of the wrong length
/// ([`CoreError::InvalidParameter`]); a tangent stiffness singular on the free coordinates
/// ([`StaticsError::SingularStiffness`]).
pub fn linear_response(
    structure: &Structure,
    displacements: &[Option<Vector3<f64>>],
) -> Result<LinearResponse> {
    check_axial_stiffness(structure)?;
    let supports = structure.supports();
    if !displacements.is_empty() && displacements.len() != supports.len() {
        return Err(ModelError::LengthMismatch {
            what: "support displacements".into(),
            expected: supports.len(),
            found: displacements.len(),
        }
        .into());
    }
    let given = |s: usize| displacements.get(s).copied().flatten();
    let dofs = DofMap::stiffness_of(structure);
    let axial = stiffness::axial_stiffness(structure)?;
    let mut warnings = Vec::new();
    let t0 = prestress(structure, &mut warnings)?;
    let lengths = crate::column_lengths(structure);
    let q = DVector::from_iterator(t0.len(), t0.iter().zip(&lengths).map(|(t, l)| t / l));
    let springs = spring_matrices(structure);
    let prescribed = prescribed_motion(structure, &dofs, &given)?;
    // the right-hand side: the loads, the springs' anchors, minus K_fp d_p
    let w = structure.W();
    let mut force: Vec<Vector3<f64>> = (0..structure.n_nodes())
        .map(|i| Vector3::from(w.column(i)))
        .collect();
    for (s, support) in supports.iter().enumerate() {
        if let (Some(ks), Some(a)) = (springs[s], given(s)) {
            force[support.node] += ks * a;
        }
    }
    let resisting = resisting_forces(structure, &q, &axial, &springs, &prescribed);
    let rhs = DVector::from_iterator(
        dofs.len(),
        dofs.free.iter().map(|&(i, a)| {
            let e = dofs.axis(i, a);
            e.dot(&(force[i] - resisting[i]))
        }),
    );
    let k_ff = stiffness::tangent_stiffness(structure, &dofs, &q, &axial);
    let u_f = solve_symmetric(&k_ff, &rhs, &dofs, &mut warnings)?;
    let u: Vec<Vector3<f64>> = dofs
        .expand(u_f.as_slice())
        .into_iter()
        .zip(&prescribed)
        .map(|(free, held)| free + held)
        .collect();
    let nm = structure.n_members();
    let member_force_change: Vec<f64> = (structure.member_nodes().into_iter().enumerate())
        .map(|(k, [i, j])| {
            let e = structure.member_vector(k) / lengths[k];
            axial[k] * e.dot(&(u[j] - u[i]))
        })
        .chain(
            (cluster_geometries(structure).iter().enumerate())
                .map(|(c, g)| axial[nm + c] * g.length_change(&u)),
        )
        .collect();
    let reactions = reactions(structure, &dofs, &q, &axial, &springs, &u, &force, &given);
    let (slack, slack_clusters) =
        slack_strings(structure, &t0, &member_force_change, &mut warnings);
    Ok(LinearResponse {
        max_displacement: u.iter().map(|v| v.norm()).fold(0.0, f64::max),
        displacements: u.iter().map(|v| [v.x, v.y, v.z]).collect(),
        member_force_change,
        initial_force: t0.iter().copied().collect(),
        reactions,
        slack,
        slack_clusters,
        warnings,
    })
}

/// Refuses a member without an axial stiffness, naming it: a bar needs a material and a
/// radius (EA = E π r²), a string its stiffness.
fn check_axial_stiffness(structure: &Structure) -> Result<()> {
    let missing = |member, property| {
        CoreError::Model(ModelError::MissingProperty {
            member,
            analysis: "the linear response (an axial stiffness)",
            property,
        })
    };
    for (i, b) in structure.bars().iter().enumerate() {
        let id = MemberId::Bar(i);
        if structure.member_material(id).is_none() {
            return Err(missing(id, "material"));
        }
        if b.radius.is_none() {
            return Err(missing(id, "radius"));
        }
    }
    for (i, s) in structure.strings().iter().enumerate() {
        if s.stiffness.is_none() {
            return Err(missing(MemberId::String(i), "stiffness"));
        }
    }
    for (c, cluster) in structure.clusters().iter().enumerate() {
        if cluster.stiffness.is_none() {
            return Err(stiffness::missing_cluster_property(
                c,
                "the linear response (an axial stiffness)",
                "stiffness",
            ));
        }
    }
    Ok(())
}

/// The force state t₀ (N, module docs): the strings' from their rest lengths, the bars'
/// minimal-norm forces balancing them; a balance that fails (the rest lengths realise no
/// self-stress) is a warning.
fn prestress(structure: &Structure, warnings: &mut Vec<String>) -> Result<DVector<f64>> {
    let lengths = crate::column_lengths(structure);
    let nb = structure.n_bars();
    let nm = structure.n_members();
    let mut q = DVector::zeros(lengths.len());
    for (i, s) in structure.strings().iter().enumerate() {
        let l = lengths[nb + i];
        if let (Some(k), Some(l0)) = (s.stiffness, s.rest_length) {
            q[nb + i] = if l > l0 { k * (l - l0) / l } else { 0.0 };
        }
    }
    for (c, cluster) in structure.clusters().iter().enumerate() {
        let l = lengths[nm + c];
        if let (Some(k), Some(l0)) = (cluster.stiffness, cluster.rest_length) {
            q[nm + c] = if l > l0 { k * (l - l0) / l } else { 0.0 };
        }
    }
    if q.iter().all(|&v| v == 0.0) {
        return Ok(q);
    }
    let dofs = DofMap::of(structure);
    let a = crate::equilibrium_matrix(structure, &dofs);
    let strings_force = &a * &q;
    if nb > 0 {
        let q_b = crate::stiffness::bars_balancing(&a, nb, &(-&strings_force))?;
        q.rows_mut(0, nb).copy_from(&q_b);
    }
    let residual = (&a * &q).norm();
    let forces = DVector::from_iterator(q.len(), q.iter().zip(&lengths).map(|(q, l)| q * l));
    if residual > PRESTRESS_RESIDUAL_TOLERANCE * forces.norm() {
        warnings.push(format!(
            "the strings' prestress (from their rest lengths) is not in equilibrium at this geometry (residual {residual:.3e} N with the bars' balancing forces): the linear response is taken about a state that is not an equilibrium; `solve` finds the equilibrium first"
        ));
    }
    Ok(forces)
}

/// Σ k d dᵀ over the held directions d of each elastic support (None for a rigid one), in
/// support order.
fn spring_matrices(structure: &Structure) -> Vec<Option<Matrix3<f64>>> {
    structure
        .supports()
        .iter()
        .map(|s| {
            s.stiffness.map(|k| {
                s.held_directions()
                    .iter()
                    .map(|d| {
                        let d = d.normalize();
                        d * d.transpose() * k
                    })
                    .sum()
            })
        })
        .collect()
}

/// The prescribed motion of every node (m): the displacements of its rigid supports on its
/// held axes (zero elsewhere), each displacement checked to lie in its support's held span.
fn prescribed_motion(
    structure: &Structure,
    dofs: &DofMap,
    given: &dyn Fn(usize) -> Option<Vector3<f64>>,
) -> Result<Vec<Vector3<f64>>> {
    let mut motion = vec![Vector3::zeros(); structure.n_nodes()];
    for (s, support) in structure.supports().iter().enumerate() {
        let Some(d) = given(s) else { continue };
        check_in_span(s, support, &d)?;
        if !support.is_elastic() {
            motion[support.node] += d;
        }
    }
    Ok(motion
        .iter()
        .enumerate()
        .map(|(i, d)| {
            (0..3)
                .filter(|&a| dofs.row[i][a].is_none())
                .map(|a| dofs.axis(i, a) * dofs.component(i, a, d))
                .sum()
        })
        .collect())
}

/// Refuses a displacement that is not finite or has a component outside the span of its
/// support's held directions (the node's free directions follow from equilibrium).
fn check_in_span(s: usize, support: &Support, d: &Vector3<f64>) -> Result<()> {
    let shown = format!("[{:?}, {:?}, {:?}]", d.x, d.y, d.z);
    let refuse = |reason: String| {
        Err(CoreError::InvalidParameter(InvalidParameter::text(
            "displacement",
            format!("support {s}: {shown}"),
            reason,
        )))
    };
    if !d.iter().all(|v| v.is_finite()) {
        return refuse(format!("support {s}: a displacement must be finite"));
    }
    let basis = support.held_basis().unwrap_or_default();
    let inside: Vector3<f64> = basis.iter().map(|b| b * b.dot(d)).sum();
    if (d - inside).norm() > SPAN_TOLERANCE * d.norm() {
        return refuse(format!(
            "support {s} (node {}): a prescribed displacement moves a node along its held directions only (an elastic support: its springs' anchor along theirs); the component {:.6e} m off them would be ignored: hold the node along it, or remove it",
            support.node,
            (d - inside).norm()
        ));
    }
    Ok(())
}

/// K u on every node (in x, y, z): the members' K_k (u_i − u_j) at i and its opposite at j,
/// and the springs' Σ k d dᵀ u at their nodes.
fn resisting_forces(
    structure: &Structure,
    q: &DVector<f64>,
    axial: &[f64],
    springs: &[Option<Matrix3<f64>>],
    u: &[Vector3<f64>],
) -> Vec<Vector3<f64>> {
    let mut f = vec![Vector3::zeros(); structure.n_nodes()];
    for (k, [i, j]) in structure.member_nodes().into_iter().enumerate() {
        let e: Vector3<f64> = structure.member_vector(k).normalize();
        let eet = e * e.transpose();
        let block = eet * axial[k] + (Matrix3::identity() - eet) * q[k];
        let g = block * (u[i] - u[j]);
        f[i] += g;
        f[j] -= g;
    }
    let nm = structure.n_members();
    for (c, geometry) in cluster_geometries(structure).iter().enumerate() {
        let t = q[nm + c] * geometry.length;
        for (a, b, block) in geometry.stiffness_blocks(axial[nm + c], t) {
            f[a] += block * u[b];
        }
    }
    for (support, ks) in structure.supports().iter().zip(springs) {
        if let Some(ks) = ks {
            f[support.node] += ks * u[support.node];
        }
    }
    f
}

/// Solves K_ff u_f = rhs by the symmetric eigendecomposition (module docs): a zero
/// eigenvalue is the error naming the mechanisms, negative ones a warning.
fn solve_symmetric(
    k: &DMatrix<f64>,
    rhs: &DVector<f64>,
    dofs: &DofMap,
    warnings: &mut Vec<String>,
) -> Result<DVector<f64>> {
    let n = k.nrows();
    if n == 0 {
        return Ok(DVector::zeros(0));
    }
    let sym = (k + k.transpose()) * 0.5;
    let (w, v) = linalg::symmetric_eigen(&sym)?;
    let largest = w.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let tol = linalg::rank_tolerance(n, n, largest, None);
    let zero: Vec<usize> = (0..n).filter(|&i| w[i].abs() <= tol).collect();
    if let Some(&first) = zero.first() {
        let mode = v.column(first);
        let nodal = dofs.expand(mode.as_slice());
        let (node, motion) = nodal
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.norm().total_cmp(&b.1.norm()))
            .map(|(i, m)| (i, m.normalize()))
            .unwrap_or((0, Vector3::zeros()));
        return Err(StaticsError::SingularStiffness {
            mechanisms: zero.len(),
            node,
            direction: [motion.x, motion.y, motion.z],
        }
        .into());
    }
    let negative = w.iter().filter(|&&x| x < 0.0).count();
    if negative > 0 {
        warnings.push(format!(
            "the tangent stiffness has {negative} negative eigenvalue(s): the force state is unstable, the linear response is not a stable equilibrium's; `solve` follows the structure"
        ));
    }
    let projected = v.transpose() * rhs;
    let scaled = DVector::from_iterator(n, projected.iter().zip(&w).map(|(p, l)| p / l));
    Ok(&v * scaled)
}

/// The reaction of every support (module docs): a rigid one's (K u − P) on its node's held
/// axes (the springs on the node counted in K u, their anchors' pull in `force`), an elastic
/// one's springs' force k d (d·(a − u)).
#[allow(clippy::too_many_arguments)]
fn reactions(
    structure: &Structure,
    dofs: &DofMap,
    q: &DVector<f64>,
    axial: &[f64],
    springs: &[Option<Matrix3<f64>>],
    u: &[Vector3<f64>],
    force: &[Vector3<f64>],
    given: &dyn Fn(usize) -> Option<Vector3<f64>>,
) -> Vec<Reaction> {
    let resisting = resisting_forces(structure, q, axial, springs, u);
    structure
        .supports()
        .iter()
        .enumerate()
        .map(|(s, support)| {
            let i = support.node;
            let r: Vector3<f64> = match springs[s] {
                Some(ks) => ks * (given(s).unwrap_or_else(Vector3::zeros) - u[i]),
                None => {
                    let unbalanced = resisting[i] - force[i];
                    (0..3)
                        .filter(|&a| dofs.row[i][a].is_none())
                        .map(|a| dofs.axis(i, a) * dofs.component(i, a, &unbalanced))
                        .sum()
                }
            };
            Reaction::of(support, &r)
        })
        .collect()
}

/// The strings and the clusters (indices among their kind) whose force t₀ + Δt is
/// negative, with a warning naming them.
fn slack_strings(
    structure: &Structure,
    t0: &DVector<f64>,
    change: &[f64],
    warnings: &mut Vec<String>,
) -> (Vec<usize>, Vec<usize>) {
    let nb = structure.n_bars();
    let nm = structure.n_members();
    let slack: Vec<usize> = (0..structure.n_strings())
        .filter(|&i| t0[nb + i] + change[nb + i] < 0.0)
        .collect();
    let clusters: Vec<usize> = (0..structure.clusters().len())
        .filter(|&c| t0[nm + c] + change[nm + c] < 0.0)
        .collect();
    let names: Vec<String> = (slack.iter().map(|i| format!("string {i}")))
        .chain(clusters.iter().map(|c| format!("cluster {c}")))
        .collect();
    if !names.is_empty() {
        warnings.push(format!(
            "{} would go slack (t + Δt < 0): the linear response is outside its assumptions (strings carry no compression); `solve` follows the slack strings",
            names.join(", ")
        ));
    }
    (slack, clusters)
}
