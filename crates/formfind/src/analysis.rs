//! The statics of a found form: residual, self-stress dimension, prestressability and
//! prestress stability.
//!
//! - residual: ‖A q + p‖ / ‖q‖ with A the equilibrium matrix at the found nodes (rows of
//!   fixed nodes removed) and p the loads (zero without), i.e. the out-of-balance force of the
//!   force densities q per unit force density (m);
//! - with loads, the found q balances them rather than being a self-stress: it is no witness
//!   of prestressability (the core's margin LP decides whether the geometry admits a
//!   self-stress with the members' signs; a loaded cable net usually admits none, and needs
//!   none), and the stability certificate below (q balancing the loads with the members'
//!   signs, D_ff positive definite) is that of the loaded form under its dead loads (its
//!   geometric stiffness D_ff ⊗ I₃ alone is positive definite);
//! - self-stress dimension: members − rank A (the rank tolerance relative to σ_max is the
//!   core's default, or 100 × ‖A q‖/(‖q‖ · size) up to 10⁻⁶ for a form in equilibrium only to
//!   an iteration's tolerance). When the form is certified (below) and A Aᵀ,
//!   without the rows of the supports (or of a statically determinate support of a
//!   free-standing form), admits a sparse Cholesky factorisation, the structure has no
//!   first-order mechanism and rank A is that number of rows ([`rigid_rank`]); otherwise
//!   the core's statics back-end decides (dense SVD, or the sparse rank-revealing QR for
//!   large structures);
//! - prestressable: the found q is itself a witness when every string has q > 0, every bar
//!   q < 0 and the relative residual ‖A q‖ / (‖q‖ · size) is below [`WITNESS_TOLERANCE`];
//!   otherwise the core's margin LP decides;
//! - prestress stable: certified by super stability (Connelly): D = Cᵀ diag(q) C positive
//!   semi-definite with nullity exactly d + 1 = 4 (tested sparsely: D with four affinely
//!   independent anchor nodes removed admits a Cholesky factorisation) and the member
//!   directions on no conic at infinity (the members' m mᵀ span all 6 symmetric 3 × 3
//!   matrices); with fixed nodes a positive-definite D_ff suffices. Where the certificate
//!   fails, the core's second-order test (stress matrix on the internal mechanisms) decides
//!   for structures of up to [`STABILITY_MAX_MEMBERS`] members; larger ones are reported not
//!   stable (not certified).
//! - with clustered strings (the `cluster` module), the core's dense statics of the structure
//!   with its clusters decides all three (one column per cluster, q_c = t_c / L_c; the
//!   prestress-stability test takes the cluster's stress matrix t_c ∇²L_c), the residual
//!   counting every segment at its tension t_c.

use crate::fdm::anchors;
use crate::topology::Topology;
use crate::Result;
use nalgebra::{DVector, Matrix6, Vector3, Vector6};
use tensegrity_core::{Bar, Cluster, StringMember, Structure, Support};
use tensegrity_linalg::{CscMatrix, SparseCholesky};
use tensegrity_statics::{backend, StaticsSettings};

/// Relative residual below which the found force densities count as a self-stress.
pub const WITNESS_TOLERANCE: f64 = 1e-8;

/// Largest structure (members) for which the core's prestress-stability test runs when the
/// super-stability certificate fails.
pub const STABILITY_MAX_MEMBERS: usize = 3000;

/// The statics of a found form.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Analysis {
    pub self_stress_dim: usize,
    pub prestressable: bool,
    pub prestress_stable: bool,
    pub residual: f64,
}

/// The members' pull Σ_j q_ij (x_j − x_i) on every node plus its load p_i (`p`: one per
/// node, or empty for none): the out-of-balance force, −r_i at a held node.
pub(crate) fn nodal_balance(
    topology: &Topology,
    nodes: &[Vector3<f64>],
    q: &[f64],
    p: &[Vector3<f64>],
) -> Vec<Vector3<f64>> {
    let mut f = vec![Vector3::zeros(); topology.n_nodes];
    for (&[i, j], &qk) in topology.force_pairs().iter().zip(q) {
        let m = qk * (nodes[j] - nodes[i]);
        f[i] += m;
        f[j] -= m;
    }
    for (fi, pi) in f.iter_mut().zip(p) {
        *fi += pi;
    }
    f
}

/// The unbalanced nodal forces A q + p (one per node; zero at fixed nodes).
pub(crate) fn out_of_balance(
    topology: &Topology,
    nodes: &[Vector3<f64>],
    q: &[f64],
    p: &[Vector3<f64>],
) -> Vec<Vector3<f64>> {
    let mut f = nodal_balance(topology, nodes, q, p);
    for fx in &topology.fixed {
        f[fx.node] = Vector3::zeros();
    }
    f
}

/// The reactions r_i = (D X)_i − p_i at the held nodes (in `topology.fixed` order) and the
/// relative equilibrium residual of the free nodes, ‖(D X)_f − P_f‖ / ‖F_f‖ with
/// F_i = Σ_k∋i |q_k| L_k + ‖p_i‖ the size of the forces meeting at node i (0 when no force
/// meets a free node).
pub(crate) fn reactions(
    topology: &Topology,
    nodes: &[Vector3<f64>],
    q: &[f64],
    p: &[Vector3<f64>],
) -> (Vec<Vector3<f64>>, f64) {
    let f = nodal_balance(topology, nodes, q, p);
    let r = topology.fixed.iter().map(|fx| -f[fx.node]).collect();
    let mut magnitude: Vec<f64> = (0..topology.n_nodes)
        .map(|i| p.get(i).map_or(0.0, |x| x.norm()))
        .collect();
    for (&[i, j], &qk) in topology.force_pairs().iter().zip(q) {
        let t = qk.abs() * (nodes[j] - nodes[i]).norm();
        magnitude[i] += t;
        magnitude[j] += t;
    }
    let mut held = vec![false; topology.n_nodes];
    for fx in &topology.fixed {
        held[fx.node] = true;
    }
    let (mut num, mut den) = (0.0, 0.0);
    for i in (0..topology.n_nodes).filter(|&i| !held[i]) {
        num += f[i].norm_squared();
        den += magnitude[i] * magnitude[i];
    }
    let relative = if den > 0.0 { (num / den).sqrt() } else { 0.0 };
    (r, relative)
}

/// ‖A q + p‖ / ‖q‖ at the free nodes (`p` empty: no loads).
pub(crate) fn residual(
    topology: &Topology,
    nodes: &[Vector3<f64>],
    q: &[f64],
    p: &[Vector3<f64>],
) -> f64 {
    let f = out_of_balance(topology, nodes, q, p);
    let num = f.iter().map(|v| v.norm_squared()).sum::<f64>().sqrt();
    let den = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    if den > 0.0 {
        num / den
    } else {
        0.0
    }
}

/// The extent of the nodes: the diagonal of their bounding box.
pub(crate) fn size(nodes: &[Vector3<f64>]) -> f64 {
    if nodes.is_empty() {
        return 0.0;
    }
    let mut lo = nodes[0];
    let mut hi = nodes[0];
    for p in nodes {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    (hi - lo).norm()
}

/// A core structure of the topology at `nodes` (no properties; fixed nodes pinned).
pub(crate) fn bare_structure(topology: &Topology, nodes: &[Vector3<f64>]) -> Result<Structure> {
    let mut b = Structure::builder()
        .allow_isolated_nodes(!topology.fixed.is_empty())
        .nodes(nodes.iter().map(|p| [p.x, p.y, p.z]));
    for m in &topology.bars {
        b = b.bar(Bar::new(m.nodes[0], m.nodes[1]));
    }
    for m in &topology.strings {
        b = b.string(StringMember::new(m.nodes[0], m.nodes[1]));
    }
    for c in &topology.clusters {
        b = b.cluster(Cluster::new(c.nodes.iter().copied()));
    }
    for f in &topology.fixed {
        b = b.support(Support::pinned(f.node));
    }
    Ok(b.build()?)
}

/// The statics of force densities `q` at `nodes` under the loads `p` (one per node, in the
/// units of `q`; empty: none; see the module docs).
pub(crate) fn analyse(
    topology: &Topology,
    nodes: &[Vector3<f64>],
    q: &[f64],
    p: &[Vector3<f64>],
) -> Result<Analysis> {
    let residual = residual(topology, nodes, q, p);
    let signs_ok = (0..q.len()).all(|k| crate::topology::member_kind_ok(topology.is_bar(k), q[k]));
    let scale = size(nodes).max(f64::MIN_POSITIVE);
    let witness = signs_ok && residual <= WITNESS_TOLERANCE * scale;
    // Under loads q balances them, so it witnesses no self-stress: prestressability is the
    // core's decision for the geometry.
    let loaded = p.iter().any(|x| *x != Vector3::zeros());
    if !topology.clusters.is_empty() {
        return clustered(topology, nodes, q, (residual, witness, loaded));
    }
    let certified = witness && super_stable(topology, nodes, q);
    // The sparse shortcut: a witness, a super-stability certificate and no first-order
    // mechanism settle everything without the core's statics.
    if certified && !loaded {
        if let Some(rank) = rigid_rank(topology, nodes) {
            return Ok(Analysis {
                self_stress_dim: q.len() - rank,
                prestressable: true,
                prestress_stable: true,
                residual,
            });
        }
    }
    let structure = bare_structure(topology, nodes)?;
    // A form found iteratively (dynamic relaxation) is in equilibrium to its tolerance, not
    // to round-off: the rank decision takes a relative tolerance of 100 × its relative
    // residual (at most 10⁻⁶) when that exceeds the default.
    let mut settings = StaticsSettings::default();
    let relative = residual / scale;
    if witness && relative > 1e-14 {
        settings = settings.rank_tolerance((100.0 * relative).min(1e-6))?;
    }
    let statics = backend(&structure, settings)?;
    let self_stress_dim = statics.self_stress_dim();
    let prestressable = (witness && !loaded) || statics.prestressability()?.prestressable;
    let prestress_stable = if certified {
        true
    } else if witness && q.len() <= STABILITY_MAX_MEMBERS {
        statics
            .prestress_stability(&DVector::from_column_slice(q))
            .map(|s| s.stable)
            .unwrap_or(false)
    } else {
        false
    };
    Ok(Analysis {
        self_stress_dim,
        prestressable,
        prestress_stable,
        residual,
    })
}

/// [`analyse`] of a topology with clusters (module docs): the core's dense statics of the
/// structure with its clusters, one column per cluster with q_c = t_c / L_c (`q`: the
/// members' force densities, then t_c / l_i of every segment).
fn clustered(
    topology: &Topology,
    nodes: &[Vector3<f64>],
    q: &[f64],
    (residual, witness, loaded): (f64, bool, bool),
) -> Result<Analysis> {
    let structure = bare_structure(topology, nodes)?;
    let nm = topology.n_members();
    let mut columns = q[..nm].to_vec();
    let mut s = nm;
    for c in &topology.clusters {
        let l: Vec<f64> = c
            .segments()
            .map(|[a, b]| (nodes[b] - nodes[a]).norm())
            .collect();
        let length: f64 = l.iter().sum();
        // t_c = q_i l_i on any segment (the same on all): the first one's
        columns.push(q[s] * l[0] / length);
        s += l.len();
    }
    let mut settings = StaticsSettings::default();
    let relative = residual / size(nodes).max(f64::MIN_POSITIVE);
    if witness && relative > 1e-14 {
        settings = settings.rank_tolerance((100.0 * relative).min(1e-6))?;
    }
    let statics = backend(&structure, settings)?;
    let prestressable = (witness && !loaded) || statics.prestressability()?.prestressable;
    let prestress_stable = witness
        && columns.len() <= STABILITY_MAX_MEMBERS
        && statics
            .prestress_stability(&DVector::from_column_slice(&columns))
            .map(|s| s.stable)
            .unwrap_or(false);
    Ok(Analysis {
        self_stress_dim: statics.self_stress_dim(),
        prestressable,
        prestress_stable,
        residual,
    })
}

/// The super-stability certificate (module docs).
pub(crate) fn super_stable(topology: &Topology, nodes: &[Vector3<f64>], q: &[f64]) -> bool {
    let free_standing = topology.fixed.is_empty();
    let removed: Vec<usize> = if free_standing {
        match anchors(nodes) {
            Some(a) => a.to_vec(),
            None => return false,
        }
    } else {
        topology.fixed.iter().map(|f| f.node).collect()
    };
    if free_standing && !no_conic_at_infinity(topology, nodes) {
        return false;
    }
    positive_definite_without(topology, q, &removed)
}

/// Whether D with the rows and columns of `removed` deleted is positive definite.
pub(crate) fn positive_definite_without(topology: &Topology, q: &[f64], removed: &[usize]) -> bool {
    let n = topology.n_nodes;
    let mut index = vec![usize::MAX; n];
    let mut nf = 0;
    for (i, slot) in index.iter_mut().enumerate() {
        if !removed.contains(&i) {
            *slot = nf;
            nf += 1;
        }
    }
    if nf == 0 {
        return true;
    }
    let mut t = Vec::with_capacity(3 * q.len());
    for (&[i, j], &qk) in topology.member_nodes().iter().zip(q) {
        let (a, b) = (index[i], index[j]);
        if a != usize::MAX {
            t.push((a, a, qk));
        }
        if b != usize::MAX {
            t.push((b, b, qk));
        }
        if a != usize::MAX && b != usize::MAX {
            t.push((a.max(b), a.min(b), -qk));
        }
    }
    let Ok(lower) = CscMatrix::from_triplets(nf, nf, &t) else {
        return false;
    };
    let Ok(mut chol) = SparseCholesky::new(lower.pattern()) else {
        return false;
    };
    // A relative margin: the factorisation must survive a small negative shift.
    let qmax = q.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let mut values = lower.values().to_vec();
    let p = lower.pattern();
    for c in 0..nf {
        for s in p.col_ptr()[c]..p.col_ptr()[c + 1] {
            if p.row_idx()[s] == c {
                values[s] -= 1e-12 * qmax;
            }
        }
    }
    chol.factor(&values).is_ok()
}

/// Whether the member directions lie on no conic at infinity: the symmetric matrices
/// m mᵀ of the members span all six dimensions.
fn no_conic_at_infinity(topology: &Topology, nodes: &[Vector3<f64>]) -> bool {
    let mut g = Matrix6::zeros();
    for &[i, j] in &topology.member_nodes() {
        let m = (nodes[j] - nodes[i]).normalize();
        let r = Vector6::new(
            m.x * m.x,
            m.y * m.y,
            m.z * m.z,
            2f64.sqrt() * m.x * m.y,
            2f64.sqrt() * m.x * m.z,
            2f64.sqrt() * m.y * m.z,
        );
        g += r * r.transpose();
    }
    let e = g.symmetric_eigenvalues();
    e.min() > 1e-10 * e.max()
}

/// The rank of the equilibrium matrix A when the structure has no first-order mechanism
/// beyond the rigid-body motions its supports allow, else `None`.
///
/// The rows of the fixed nodes are removed; a free-standing structure also loses six rows
/// of a statically determinate support (three at one anchor node, the two coordinate
/// directions least aligned with the first anchor edge at a second, the direction most
/// aligned with the anchors' plane normal at a third). A Aᵀ on the remaining rows is then
/// positive definite (sparse Cholesky, with a shift of 10⁻¹⁰ of its largest diagonal entry
/// as margin, i.e. σ_min(A) > 10⁻⁵ σ-scale) exactly when those rows are independent: rank A
/// is their number.
pub(crate) fn rigid_rank(topology: &Topology, nodes: &[Vector3<f64>]) -> Option<usize> {
    let n = topology.n_nodes;
    let mut removed = vec![[false; 3]; n];
    for f in &topology.fixed {
        removed[f.node] = [true; 3];
    }
    if topology.fixed.is_empty() {
        let [a0, a1, a2, _] = anchors(nodes)?;
        removed[a0] = [true; 3];
        let d1 = nodes[a1] - nodes[a0];
        let along = d1.iamax();
        for (axis, r) in removed[a1].iter_mut().enumerate() {
            *r = axis != along;
        }
        let normal = d1.cross(&(nodes[a2] - nodes[a0]));
        removed[a2][normal.iamax()] = true;
    }
    let mut row = vec![[usize::MAX; 3]; n];
    let mut rows = 0;
    for i in 0..n {
        for d in 0..3 {
            if !removed[i][d] {
                row[i][d] = rows;
                rows += 1;
            }
        }
    }
    if rows == 0 {
        return Some(0);
    }
    if rows > topology.n_members() {
        return None;
    }
    let mut t = Vec::with_capacity(topology.n_members() * 21);
    let mut diag_max = 0.0f64;
    for &[i, j] in &topology.member_nodes() {
        let m = nodes[j] - nodes[i];
        // a_k: −m at node i, +m at node j; a_k a_kᵀ blocks ±m mᵀ.
        for (a, sa) in [(i, -1.0), (j, 1.0)] {
            for (b, sb) in [(i, -1.0), (j, 1.0)] {
                for da in 0..3 {
                    for db in 0..3 {
                        let (r, c) = (row[a][da], row[b][db]);
                        if r == usize::MAX || c == usize::MAX || r < c {
                            continue;
                        }
                        let v = sa * sb * m[da] * m[db];
                        if r == c {
                            diag_max = diag_max.max(v);
                        }
                        t.push((r, c, v));
                    }
                }
            }
        }
    }
    for r in 0..rows {
        t.push((r, r, 0.0));
    }
    let lower = CscMatrix::from_triplets(rows, rows, &t).ok()?;
    let mut chol = SparseCholesky::new(lower.pattern()).ok()?;
    let mut values = lower.values().to_vec();
    let p = lower.pattern();
    for c in 0..rows {
        for s in p.col_ptr()[c]..p.col_ptr()[c + 1] {
            if p.row_idx()[s] == c {
                values[s] -= 1e-10 * diag_max;
            }
        }
    }
    chol.factor(&values).ok()?;
    Some(rows)
}
