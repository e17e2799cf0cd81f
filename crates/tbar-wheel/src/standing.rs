//! The single loop against the extended wheel (issue item 2): the thesis's "this current
//! configuration is unstable in the ι̂₂ι̂₃ plane … resolved by translating a copy of this loop
//! in the ι̂₁ direction such that there are now four contact points with the ground" (§5.1),
//! quantified with the core's statics.
//!
//! Both structures carry a free rim body ([`crate::rim`]). Each is analysed
//!
//! - **free**: no support (a free body: six rigid-body motions);
//! - **vertex**: standing on the tip of tread 0 of each wheel (one contact for the loop, two
//!   for the extended wheel);
//! - **edge**: standing on the tips of treads 0 and 1 of each wheel (two contacts for the
//!   loop, the thesis's four for the extended wheel).
//!
//! A contact is a pinned support (bilateral, no slip): the ground's first-order restraint
//! while standing still. For each case the equilibrium matrix gives the rank r, the
//! self-stress dimension s = members − r and the first-order mechanisms m = free dofs − r.
//! The mechanism space (orthonormal basis M) is projected on the rigid-body motions about the
//! centroid c of the nodes, split into the **in-plane** ones (translations along ι̂₂, ι̂₃ and
//! the rotation about ι̂₁: motions in the wheel's plane, rolling) and the **out-of-plane**
//! ones (translation along ι̂₁, rotations about ι̂₂ and ι̂₃: toppling sideways). Each split is
//! the dimension captured, trace(Mᵀ P M) with P the orthogonal projector on the subspace
//! (restricted to the free dofs): it does not depend on the basis chosen for M, and it is
//! an integer when a mechanism is exactly such a motion. The rest, m − trace(Mᵀ P_rigid M),
//! is internal deformation. The prestressability margin is the rim-body LP
//! ([`crate::rim::prestressability`]) with the case's supports.

use crate::error::Result;
use crate::geometry::TbarGeometry;
use crate::params::{Layout, RimMode, TbarParams};
use nalgebra::{DMatrix, Vector3};
use serde::Serialize;
use tensegrity_core::{Structure, Support};
use tensegrity_statics::Statics;

/// How the structure touches the ground.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Stance {
    /// No contact: a free body.
    Free,
    /// On the tip of tread 0 of each wheel.
    Vertex,
    /// On the tips of treads 0 and 1 of each wheel.
    Edge,
}

impl Stance {
    /// `free`, `vertex` or `edge`.
    pub fn as_str(&self) -> &'static str {
        match self {
            Stance::Free => "free",
            Stance::Vertex => "vertex",
            Stance::Edge => "edge",
        }
    }
}

/// The statics of one structure in one stance.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StandingRow {
    /// `wheel` (the single loop) or `extended wheel`.
    pub structure: &'static str,
    /// The stance.
    pub stance: Stance,
    /// Pinned contact points.
    pub contacts: usize,
    /// Nodes (hub included).
    pub nodes: usize,
    /// Members (treads' bars, rim-body bars, strings).
    pub members: usize,
    /// Free degrees of freedom.
    pub free_dofs: usize,
    /// Rank of the equilibrium matrix.
    pub rank: usize,
    /// Self-stress dimension.
    pub self_stress_dim: usize,
    /// First-order mechanisms (free dofs − rank).
    pub mechanisms: usize,
    /// Dimension of the mechanism space captured by rigid-body motions.
    pub rigid: f64,
    /// … by in-plane rigid motions (ι̂₂, ι̂₃ translations, rotation about ι̂₁).
    pub in_plane: f64,
    /// … by out-of-plane rigid motions (ι̂₁ translation, rotations about ι̂₂, ι̂₃).
    pub out_of_plane: f64,
    /// Internal (deformation) part: mechanisms − rigid.
    pub internal: f64,
    /// The rim-body prestressability margin (treads' members signed, rim bars free).
    pub prestress_margin: f64,
}

/// The six cases: the loop and the extended wheel (copy at `offset` along ι̂₁), each free,
/// on a vertex and on an edge. `params` gives the tread (its layout and rim are replaced).
pub fn loop_study(params: &TbarParams, offset: f64) -> Result<Vec<StandingRow>> {
    let mut rows = Vec::new();
    for layout in [Layout::Wheel, Layout::Extended { offset }] {
        let g = TbarGeometry::new(params.with_layout(layout).with_rim(RimMode::Body))?;
        for stance in [Stance::Free, Stance::Vertex, Stance::Edge] {
            rows.push(standing_row(&g, stance)?);
        }
    }
    Ok(rows)
}

/// The contact tips of a stance (tread 0, and 1 on an edge, of every wheel).
pub fn contact_tips(g: &TbarGeometry, stance: Stance) -> Vec<usize> {
    let copies = g.params.copies();
    let per_wheel = g.tips.len() / copies;
    let treads: &[usize] = match stance {
        Stance::Free => &[],
        Stance::Vertex => &[0],
        Stance::Edge => &[0, 1],
    };
    (0..copies)
        .flat_map(|c| treads.iter().map(move |t| c * per_wheel + t))
        .filter(|&t| t < g.tips.len())
        .map(|t| g.tips[t])
        .collect()
}

/// The statics of `g` (with its rim body) in one stance.
pub fn standing_row(g: &TbarGeometry, stance: Stance) -> Result<StandingRow> {
    let contacts = contact_tips(g, stance);
    let mut b = g.structure()?.to_builder();
    for &c in &contacts {
        b = b.support(Support::pinned(c));
    }
    let s = b.build()?;
    crate::statics::check_size(&s)?;
    let statics = Statics::new(&s)?;
    let split = split_mechanisms(&s, &statics);
    let rim_bars = g.rim.as_ref().map_or(0, |r| r.bars.len());
    let mechanisms = statics.mechanisms();
    Ok(StandingRow {
        structure: g.params.layout.name(),
        stance,
        contacts: contacts.len(),
        nodes: s.n_nodes(),
        members: s.n_members(),
        free_dofs: statics.dofs().len(),
        rank: statics.rank(),
        self_stress_dim: statics.self_stress_dim(),
        mechanisms,
        rigid: split[2],
        in_plane: split[0],
        out_of_plane: split[1],
        internal: (mechanisms as f64 - split[2]).max(0.0),
        prestress_margin: crate::rim::prestressability(&statics, g.bars.len(), rim_bars)?,
    })
}

/// trace(Mᵀ P M) for the in-plane, out-of-plane and all rigid motions.
fn split_mechanisms(s: &Structure, statics: &Statics<'_>) -> [f64; 3] {
    let m = statics.motion_basis();
    if m.ncols() == 0 {
        return [0.0; 3];
    }
    let n = s.n_nodes();
    let c = s.nodes().iter().sum::<Vector3<f64>>() / n as f64;
    // columns: translation ι̂₂, ι̂₃, rotation ι̂₁ | translation ι̂₁, rotation ι̂₂, ι̂₃
    let motion = |k: usize, p: &Vector3<f64>| -> Vector3<f64> {
        let r = p - c;
        match k {
            0 => Vector3::y(),
            1 => Vector3::z(),
            2 => Vector3::x().cross(&r),
            3 => Vector3::x(),
            4 => Vector3::y().cross(&r),
            _ => Vector3::z().cross(&r),
        }
    };
    let dofs = statics.dofs();
    let free: Vec<(usize, usize)> = dofs.free.clone();
    let rigid = DMatrix::from_fn(free.len(), 6, |row, k| {
        let (i, d) = free[row];
        motion(k, &s.nodes()[i])[d]
    });
    let captured = |cols: &[usize]| -> f64 {
        let t = rigid.select_columns(cols.iter());
        let q = orthonormal_columns(&t);
        (q.transpose() * &m).norm_squared()
    };
    [
        captured(&[0, 1, 2]),
        captured(&[3, 4, 5]),
        captured(&[0, 1, 2, 3, 4, 5]),
    ]
}

/// An orthonormal basis of the column space of `t` (SVD, relative tolerance 1e-10).
fn orthonormal_columns(t: &DMatrix<f64>) -> DMatrix<f64> {
    let svd = t.clone().svd(true, false);
    let Some(u) = svd.u else {
        return DMatrix::zeros(t.nrows(), 0);
    };
    let smax = svd.singular_values.iter().copied().fold(0.0, f64::max);
    let keep: Vec<usize> = (0..svd.singular_values.len())
        .filter(|&i| svd.singular_values[i] > 1e-10 * smax.max(f64::MIN_POSITIVE))
        .collect();
    u.select_columns(keep.iter())
}
