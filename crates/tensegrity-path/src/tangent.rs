//! The tangent stiffness K = dR/dx on the free coordinates (crate docs): per taut member
//! K_k = (EA/L₀) n nᵀ + (t/L)(I − n nᵀ) on [[K_k, −K_k], [−K_k, K_k]], projected onto each
//! node's free directions, the clusters' k g gᵀ + Σ (t/l_i)(I − e_i e_iᵀ)
//! ([`crate::clusters`]), and k d dᵀ per spring of an elastic support ([`crate::dofs::Spring`]):
//! [`tangent_stiffness`] dense, [`tangent_triplets`] as triplets for the sparse
//! factorisations of large structures ([`crate::factor`]).

use crate::dofs::Dofs;
use crate::forces::MemberState;
use crate::model::ElasticModel;
use nalgebra::{DMatrix, Matrix3};

/// The tangent stiffness on the free coordinates of `dofs` at the member `states`.
///
/// ```
/// use nalgebra::Vector3;
/// use tensegrity_path::{dofs::Dofs, forces::member_states, tangent::tangent_stiffness};
/// use tensegrity_path::{ElasticMember, ElasticModel, MemberKind, Support};
/// // a bar along x, node 0 pinned: EA/L₀ along x, t/L across
/// let bar = ElasticMember { nodes: [0, 1], kind: MemberKind::Bar, ea: 100.0, rest_length: 1.0 };
/// let m = ElasticModel { nodes: vec![Vector3::zeros(), Vector3::x()], members: vec![bar],
///     clusters: Vec::new(),
///     supports: vec![Support::pinned(0)], load: vec![Vector3::zeros(); 2], drivers: Default::default() };
/// let x = [Vector3::zeros(), Vector3::new(1.1, 0.0, 0.0)];
/// let k = tangent_stiffness(&m, &Dofs::of(&m).unwrap(), &member_states(&m, &x, 0.0));
/// let t = 100.0 * 0.1;
/// assert!((k.trace() - (100.0 + 2.0 * t / 1.1)).abs() < 1e-12);
/// ```
pub fn tangent_stiffness(
    model: &ElasticModel,
    dofs: &Dofs,
    states: &[MemberState],
) -> DMatrix<f64> {
    let mut k = DMatrix::zeros(dofs.len(), dofs.len());
    for (r, c, v) in tangent_triplets(model, dofs, states) {
        k[(r, c)] += v;
    }
    k
}

/// The tangent's entries as (row, column, value) triplets on the free coordinates, both
/// triangles, repeated entries to be summed (sparse assembly, [`crate::factor`]).
pub fn tangent_triplets(
    model: &ElasticModel,
    dofs: &Dofs,
    states: &[MemberState],
) -> Vec<(usize, usize, f64)> {
    let mut t = member_block_triplets(
        model,
        dofs,
        |k, s| {
            let m = &model.members[k];
            (!s.slack).then(|| {
                let nn = s.direction * s.direction.transpose();
                nn * (m.ea / s.rest_length) + (Matrix3::identity() - nn) * (s.tension / s.length)
            })
        },
        states,
    );
    t.extend(spring_triplets(dofs));
    t.extend(crate::clusters::cluster_triplets(model, dofs, states));
    t
}

/// The springs of the elastic supports ([`crate::dofs::Spring`]): k d dᵀ on each spring's
/// node, projected onto its free directions, as triplets (part of [`tangent_triplets`]).
pub fn spring_triplets(dofs: &Dofs) -> Vec<(usize, usize, f64)> {
    let mut t = Vec::new();
    for s in &dofs.springs {
        let (p0, pc) = dofs.of_node[s.node];
        for r in 0..pc {
            let dr = s.direction.dot(&dofs.free[p0 + r].1);
            for c in 0..pc {
                let dc = s.direction.dot(&dofs.free[p0 + c].1);
                t.push((p0 + r, p0 + c, s.stiffness * dr * dc));
            }
        }
    }
    t
}

/// Assembles per-member 3 × 3 blocks B_k (from `block`, given the member's index and state;
/// `None`: nothing) as [[B_k, −B_k], [−B_k, B_k]] on its two nodes, projected onto their
/// free directions, as triplets (both triangles, repeated entries to be summed): the
/// tangent's pattern, also the dashpots' c n nᵀ of the implicit dynamics.
pub fn member_block_triplets(
    model: &ElasticModel,
    dofs: &Dofs,
    block: impl Fn(usize, &MemberState) -> Option<Matrix3<f64>>,
    states: &[MemberState],
) -> Vec<(usize, usize, f64)> {
    let mut t = Vec::with_capacity(36 * model.members.len());
    for (k, (m, s)) in model.members.iter().zip(states).enumerate() {
        let Some(local) = block(k, s) else {
            continue;
        };
        let [a, b] = m.nodes;
        for (p, sp) in [(a, 1.0), (b, -1.0)] {
            let (p0, pc) = dofs.of_node[p];
            for (q, sq) in [(a, 1.0), (b, -1.0)] {
                let (q0, qc) = dofs.of_node[q];
                for r in 0..pc {
                    let er = dofs.free[p0 + r].1;
                    let kr = local * er;
                    for c in 0..qc {
                        let ec = dofs.free[q0 + c].1;
                        t.push((p0 + r, q0 + c, sp * sq * ec.dot(&kr)));
                    }
                }
            }
        }
    }
    t
}
