//! The cyclic symmetry of the toroid: prism k is prism 0 rotated by 2πk/n about ι₁ (the x
//! axis through the wheel centre), so the rotation by 2π/n maps prism k onto prism k + 1 and
//! leaves the two axle ends (on the axis) and the axle bar fixed.
//!
//! With the builder's numbering ([`crate::build`]): node 5k + j ↦ 5(k+1 mod n) + j, axle ends
//! fixed; bar 3k + b ↦ 3(k+1 mod n) + b, the axle bar fixed; the 12 prism strings 12k + s,
//! then each ring or spoke set of 2n strings 2k + j, shift by one prism likewise. The core
//! validates the descriptor against the structure ([`CyclicSymmetry::new`]).

use crate::builder::Toroid;
use crate::error::Result;
use nalgebra::Vector3;
use tensegrity_statics::symmetry::CyclicSymmetry;

/// The Cₙ descriptor of a built toroid (n = sides), validated against its structure.
///
/// ```
/// use toroid::{build, toroid_symmetry, ToroidParams};
/// let t = build(&ToroidParams::default(), "spokes,inner".parse().unwrap(), 1.0).unwrap();
/// let sym = toroid_symmetry(&t).unwrap();
/// // five node orbits of n prism nodes and the two axle ends on the axis
/// assert_eq!(sym.node_orbits().len(), 7);
/// ```
pub fn toroid_symmetry(toroid: &Toroid) -> Result<CyclicSymmetry> {
    let s = &toroid.structure;
    let n = toroid.params.sides;
    let next = |k: usize| (k + 1) % n;
    let mut nodes: Vec<usize> = (0..5 * n).map(|i| 5 * next(i / 5) + i % 5).collect();
    nodes.extend(5 * n..s.n_nodes());
    let mut members: Vec<usize> = (0..3 * n).map(|e| 3 * next(e / 3) + e % 3).collect();
    members.extend(3 * n..s.n_bars());
    let nb = s.n_bars();
    members.extend((0..12 * n).map(|e| nb + 12 * next(e / 12) + e % 12));
    let mut offset = nb + 12 * n;
    while offset < s.n_members() {
        members.extend((0..2 * n).map(|e| offset + 2 * next(e / 2) + e % 2));
        offset += 2 * n;
    }
    Ok(CyclicSymmetry::new(
        s,
        n,
        Vector3::x(),
        Vector3::zeros(),
        nodes,
        members,
    )?)
}

/// The self-stress states and internal mechanisms each irreducible representation k of Cₙ
/// carries (k = 0..n−1; representation k has character e^{2πik/n}, k = 0 the fully symmetric
/// states); serialised as the `symmetry` object of `tensegrity toroid --json` (arrays only,
/// so the sweep studies' scalar columns stay the report's scalars; n is their length).
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct SymmetryCounts {
    /// Self-stress states per representation k.
    pub self_stress_by_representation: Vec<usize>,
    /// Internal mechanisms (first-order, rigid-body motions removed) per representation k.
    pub internal_mechanisms_by_representation: Vec<usize>,
}

impl SymmetryCounts {
    /// The counts of a symmetric analysis; `None` when `reps` is empty (the dense path).
    pub fn of(reps: &[tensegrity_statics::symmetry::RepCounts]) -> Option<Self> {
        (!reps.is_empty()).then(|| Self {
            self_stress_by_representation: reps.iter().map(|r| r.self_stress).collect(),
            internal_mechanisms_by_representation: reps
                .iter()
                .map(|r| r.internal_mechanisms)
                .collect(),
        })
    }
}
