//! The statics of a found form: residual, self-stress dimension, prestressability and
//! prestress stability.
//!
//! - residual: ‖A q‖ / ‖q‖ with A the equilibrium matrix at the found nodes (rows of fixed
//!   nodes removed), i.e. the out-of-balance force of the force densities q per unit force
//!   density (m);
//! - self-stress dimension: members − rank A, from the core's statics back-end (dense SVD, or
//!   the sparse rank-revealing QR for large structures);
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

use crate::fdm::anchors;
use crate::topology::Topology;
use crate::Result;
use nalgebra::{DVector, Matrix6, Vector3, Vector6};
use tensegrity_core::linalg::{CscMatrix, SparseCholesky};
use tensegrity_core::statics::{backend, StaticsSettings};
use tensegrity_core::{Bar, StringMember, Structure, Support};

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

/// The unbalanced nodal forces A q (one per node; zero at fixed nodes).
pub(crate) fn out_of_balance(
    topology: &Topology,
    nodes: &[Vector3<f64>],
    q: &[f64],
) -> Vec<Vector3<f64>> {
    let mut f = vec![Vector3::zeros(); topology.n_nodes];
    for (&[i, j], &qk) in topology.member_nodes().iter().zip(q) {
        let m = qk * (nodes[j] - nodes[i]);
        f[i] += m;
        f[j] -= m;
    }
    for fx in &topology.fixed {
        f[fx.node] = Vector3::zeros();
    }
    f
}

/// ‖A q‖ / ‖q‖.
pub(crate) fn residual(topology: &Topology, nodes: &[Vector3<f64>], q: &[f64]) -> f64 {
    let f = out_of_balance(topology, nodes, q);
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
    let mut b = Structure::builder().nodes(nodes.iter().map(|p| [p.x, p.y, p.z]));
    for m in &topology.bars {
        b = b.bar(Bar::new(m.nodes[0], m.nodes[1]));
    }
    for m in &topology.strings {
        b = b.string(StringMember::new(m.nodes[0], m.nodes[1]));
    }
    for f in &topology.fixed {
        b = b.support(Support::pinned(f.node));
    }
    Ok(b.build()?)
}

/// The statics of force densities `q` at `nodes` (see the module docs).
pub(crate) fn analyse(topology: &Topology, nodes: &[Vector3<f64>], q: &[f64]) -> Result<Analysis> {
    let residual = residual(topology, nodes, q);
    let structure = bare_structure(topology, nodes)?;
    let statics = backend(&structure, StaticsSettings::default())?;
    let self_stress_dim = statics.self_stress_dim();
    let signs_ok = (0..q.len()).all(|k| crate::topology::member_kind_ok(topology.is_bar(k), q[k]));
    let scale = size(nodes).max(f64::MIN_POSITIVE);
    let witness = signs_ok && residual <= WITNESS_TOLERANCE * scale;
    let prestressable = witness || statics.prestressability()?.prestressable;
    let prestress_stable = if witness && super_stable(topology, nodes, q) {
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
