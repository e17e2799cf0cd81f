//! [`LoadResponse`]: the member forces per newton of tip load, g_{k,T} = row k of
//! diag(EA/L) Âᵀ K⁻¹ E_T (see [`super`]), from either statics back-end.
//!
//! - **Dense** (a tread, or a wheel without a usable symmetry): K = Â diag(EA/L) Âᵀ is
//!   assembled from the equilibrium matrix and factored once (Cholesky); one solve per tip.
//! - **Cyclic** (the back-end carries a Cₙ descriptor): one tip per tip orbit is solved block
//!   by block ([`elastic_response`], O(n·b³) plus an O(n·members) transform), and every other
//!   tip's response is that one rotated: member πᵖ(k) under the load on σᵖ(T) carries
//!   Rᵖ g_{k,T}. The loaded tips must be whole orbits (every tread of a wheel). The worst
//!   gains a_k = max_T ‖g_{k,T}‖ are then constant on member orbits: a_k is the largest
//!   ‖g_{e,T}‖ over the members e of k's orbit and the computed tips T, found in
//!   O(members) instead of O(tips × members).

use crate::error::{invalid, Result, TbarError};
use nalgebra::{DMatrix, DVector, Vector3};
use std::borrow::Cow;
use tensegrity_core::{CoreError, NumericsError, Structure};
use tensegrity_statics::symmetry::{elastic_response, CyclicSymmetry, MemberRotations};
use tensegrity_statics::{equilibrium_matrix, DofMap, StaticsBackend};

/// The linear response of every member force to a unit tip load, for every loaded tip.
#[derive(Debug, Clone)]
pub struct LoadResponse {
    /// Member lengths (m), bars first.
    pub lengths: Vec<f64>,
    /// Number of bars (members 0..n_bars).
    pub n_bars: usize,
    /// The two nodes (start, end) of every member.
    pub ends: Vec<[usize; 2]>,
    /// The loaded tip nodes.
    pub tips: Vec<usize>,
    /// `g[c][k]`: force in member k (N) per newton of load on computed tip c, t_k = g·d. On
    /// the dense path every tip is computed (c = t); on the cyclic path one tip per tip orbit
    /// (the first of its orbit in `tips`). [`tip_response`](Self::tip_response) gives any
    /// tip's.
    pub g: Vec<Vec<Vector3<f64>>>,
    gains: Vec<(f64, usize)>,
    cyclic: Option<CyclicTips>,
}

/// How the cyclic path derives every tip's response from the computed ones.
#[derive(Debug, Clone)]
struct CyclicTips {
    symmetry: CyclicSymmetry,
    /// For each tip: the computed tip (index into `g`) and the phase p with tip = σᵖ(it).
    source: Vec<(usize, usize)>,
}

impl LoadResponse {
    /// The response of `statics`'s structure to unit loads on each tip, with axial stiffness
    /// `ea` for every member; through the blocks when the back-end is the cyclic one (see the
    /// module docs). Fails with [`TbarError::Mechanism`] when the stiffness is singular.
    pub fn new(
        statics: &dyn StaticsBackend,
        tips: &[usize],
        ea: f64,
        what: &'static str,
    ) -> Result<Self> {
        if !(ea.is_finite() && ea > 0.0) {
            return Err(invalid(
                "ea",
                ea,
                "the axial stiffness must be finite and > 0",
            ));
        }
        let mechanism = || -> Result<TbarError> {
            Ok(TbarError::Mechanism {
                structure: what,
                mechanisms: statics.internal_mechanisms()?.max(1),
            })
        };
        if statics.mechanisms() > 0 {
            return Err(mechanism()?);
        }
        let s = statics.structure();
        let built = match statics.symmetry() {
            Some(sym) => cyclic_response(s, sym, tips, ea),
            None => dense_response(s, tips, ea),
        };
        match built {
            Err(TbarError::Core(CoreError::Numerics(NumericsError::Factorization { .. }))) => {
                Err(mechanism()?)
            }
            other => other,
        }
    }

    /// Number of members.
    pub fn n_members(&self) -> usize {
        self.lengths.len()
    }

    /// Whether member k is a bar.
    pub fn is_bar(&self, k: usize) -> bool {
        k < self.n_bars
    }

    /// a_k = max over tips of ‖g_{k,T}‖ and the tip (index into `tips`) attaining it.
    pub fn worst_gains(&self) -> Vec<(f64, usize)> {
        self.gains.clone()
    }

    /// g_{·,T} for tip `t` (index into `tips`): computed, or rotated from the computed tip of
    /// its orbit (O(members)).
    pub fn tip_response(&self, t: usize) -> Cow<'_, [Vector3<f64>]> {
        match &self.cyclic {
            None => Cow::Borrowed(&self.g[t]),
            Some(c) => {
                let (src, p) = c.source[t];
                if p == 0 {
                    Cow::Borrowed(&self.g[src])
                } else {
                    Cow::Owned(MemberRotations::new(&c.symmetry).rotate(&self.g[src], p))
                }
            }
        }
    }
}

/// The common fields of a response.
fn response(s: &Structure, tips: &[usize], g: Vec<Vec<Vector3<f64>>>) -> LoadResponse {
    LoadResponse {
        lengths: s.member_lengths(),
        n_bars: s.n_bars(),
        ends: s.member_nodes(),
        tips: tips.to_vec(),
        g,
        gains: Vec::new(),
        cyclic: None,
    }
}

/// The dense path: K assembled and factored once, one solve per tip.
fn dense_response(s: &Structure, tips: &[usize], ea: f64) -> Result<LoadResponse> {
    let dofs = DofMap::of(s);
    let lengths = s.member_lengths();
    let mut a_hat = equilibrium_matrix(s, &dofs);
    for (k, mut col) in a_hat.column_iter_mut().enumerate() {
        col /= lengths[k];
    }
    let k_diag = DVector::from_iterator(lengths.len(), lengths.iter().map(|l| ea / l));
    let mut weighted = a_hat.clone();
    for (k, mut col) in weighted.column_iter_mut().enumerate() {
        col *= k_diag[k];
    }
    let stiffness = &weighted * a_hat.transpose();
    let chol = stiffness
        .cholesky()
        .ok_or(CoreError::from(NumericsError::Factorization {
            operation: "Cholesky of the T-bar stiffness",
            reason: tensegrity_core::error::FactorizationFailure::NonPositivePivot {
                pivot: 0,
                dim: dofs.len(),
            },
        }))?;
    let mut g = Vec::with_capacity(tips.len());
    for &tip in tips {
        let mut e = DMatrix::zeros(dofs.len(), 3);
        for d in 0..3 {
            let row = dofs.row[tip][d]
                .ok_or_else(|| invalid("tip", tip as f64, "a loaded tip must be a free node"))?;
            e[(row, d)] = 1.0;
        }
        let forces = weighted.transpose() * chol.solve(&e);
        g.push(
            (0..forces.nrows())
                .map(|k| Vector3::new(forces[(k, 0)], forces[(k, 1)], forces[(k, 2)]))
                .collect(),
        );
    }
    let mut r = response(s, tips, g);
    r.gains = (0..r.n_members())
        .map(|k| {
            r.g.iter()
                .enumerate()
                .map(|(t, gt)| (gt[k].norm(), t))
                .fold((0.0, 0), |best, x| if x.0 > best.0 { x } else { best })
        })
        .collect();
    Ok(r)
}

/// The cyclic path (see the module docs).
fn cyclic_response(
    s: &Structure,
    sym: &CyclicSymmetry,
    tips: &[usize],
    ea: f64,
) -> Result<LoadResponse> {
    let source = tip_sources(sym, tips)?;
    let lengths = s.member_lengths();
    let stiffness: Vec<f64> = lengths.iter().map(|l| ea / l).collect();
    let mut g = Vec::new();
    for (t, &(src, p)) in source.iter().enumerate() {
        if src == g.len() && p == 0 {
            let forces = elastic_response(s, sym, &stiffness, tips[t])?;
            g.push(
                forces
                    .row_iter()
                    .map(|r| Vector3::new(r[0], r[1], r[2]))
                    .collect(),
            );
        }
    }
    let gains = cyclic_gains(sym, &source, &g);
    let mut r = response(s, tips, g);
    r.gains = gains;
    r.cyclic = Some(CyclicTips {
        symmetry: sym.clone(),
        source,
    });
    Ok(r)
}

/// For each tip, the computed tip of its orbit (the first in `tips`) and the phase from it;
/// every tip orbit must be whole.
fn tip_sources(sym: &CyclicSymmetry, tips: &[usize]) -> Result<Vec<(usize, usize)>> {
    let n = sym.order();
    let places = sym.node_places();
    let mut first: Vec<(usize, usize)> = Vec::new(); // (orbit, phase) of each computed tip
    let mut count = Vec::new();
    let mut source = Vec::with_capacity(tips.len());
    for &tip in tips {
        let place = places[tip];
        let c = match first.iter().position(|f| f.0 == place.orbit) {
            Some(c) => c,
            None => {
                first.push((place.orbit, place.phase));
                count.push(0);
                first.len() - 1
            }
        };
        count[c] += 1;
        source.push((c, (place.phase + n - first[c].1) % n));
    }
    let orbit_size = |o: usize| if sym.node_orbits()[o].on_axis { 1 } else { n };
    if let Some(c) = (0..first.len()).find(|&c| count[c] != orbit_size(first[c].0)) {
        return Err(invalid(
            "tips",
            tips.len() as f64,
            format!(
                "the loaded tips must be whole orbits of the symmetry: {} of the {} nodes of one orbit are loaded",
                count[c],
                orbit_size(first[c].0)
            ),
        ));
    }
    Ok(source)
}

/// a_k and its tip from the computed responses (see the module docs): per member orbit the
/// largest ‖g‖ over its members and the computed tips (the first maximum), carried to every
/// member by the rotation that maps the maximising member onto it.
fn cyclic_gains(
    sym: &CyclicSymmetry,
    source: &[(usize, usize)],
    g: &[Vec<Vector3<f64>>],
) -> Vec<(f64, usize)> {
    let rot = MemberRotations::new(sym);
    let places = sym.member_places();
    let mut tip_of = std::collections::HashMap::new();
    for (t, &(c, p)) in source.iter().enumerate() {
        tip_of.insert((c, p), t);
    }
    let m = places.len();
    let mut gains = vec![(0.0, 0); m];
    let mut done = vec![false; m];
    for k in 0..m {
        if done[k] {
            continue;
        }
        let orbit = rot.orbit_of(k);
        let d = orbit.len();
        let (mut best, mut best_c, mut best_s) = (0.0, 0, 0);
        for (c, gc) in g.iter().enumerate() {
            for (s, &e) in orbit.iter().enumerate() {
                if gc[e].norm() > best {
                    (best, best_c, best_s) = (gc[e].norm(), c, s);
                }
            }
        }
        for (s, &e) in orbit.iter().enumerate() {
            // member e = π^{s − s*}(maximising member) under the load on σ^{s − s*}(tip c)
            let p = (s + d - best_s) % d;
            let t = tip_of.get(&(best_c, p)).copied().unwrap_or(0);
            gains[e] = (best, t);
            done[e] = true;
        }
    }
    gains
}
