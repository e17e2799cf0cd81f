//! The rim body (issue item 1): the rim as a body of bars instead of rigid supports, for
//! free-body analysis and dynamics.
//!
//! The rim points R are the nodes the rigid rim supports: every level-q lattice node and every
//! bar base (of both copies of an extended wheel). The rim body joins them with bars only
//! (class-k joints: rim bars, the treads' bars and strings share the rim nodes):
//!
//! - **hub**: two hub nodes on the axle, at x_min − r_q and x_max + r_q (x_min, x_max the
//!   extreme ι̂₁ coordinates of the rim points), joined by the axle bar;
//! - **spokes**: every rim point to both hub nodes (2|R| bars). The two spokes of a point span
//!   the plane of the axle and the point, so with the hub fixed a rim point can only move
//!   tangentially;
//! - **ring**: the rim points grouped by their angle about ι̂₁ (all lie at multiples of φ),
//!   every point of a group joined to every point of the next group (Σ_g |G_g||G_{g+1}|
//!   bars); the chain is closed around the wheel, open for a single tread. The ring ties the
//!   tangential motions of consecutive groups, so the rim body is rigid: with it the q = 1
//!   and q = 2 wheels and extended wheels have exactly six first-order mechanisms, the
//!   rigid-body motions (tests/rim.rs, [`crate::standing`]).
//!
//! Counts, with n = π/φ treads per wheel and c copies: a q = 1 wheel has |R| = 3nc rim
//! points in 2n angle groups of 2c (lattice) and c (bar bases) points, hence
//! 1 + 6nc + 2n·2c² = 1 + 6nc + 4nc² rim bars and 2 extra nodes (q = 1, φ = π/8: 81 rim bars
//! for the wheel, 225 for the extended wheel).
//!
//! [`TbarGeometry::new`](crate::geometry::TbarGeometry::new) builds and attaches the rim body
//! ([`RimMode::Body`](crate::params::RimMode::Body)); this module holds what it is
//! ([`RimBody`]) and the prestressability of a structure carrying it.
//!
//! The rim body has no supports: the structure is a free body (six rigid-body motions). Its
//! bars have no required sign (a rigid body's members carry either sign), so the
//! prestressability of a structure with a rim body asks the tread members only for the right
//! sign ([`prestressability`]).

use crate::error::Result;
use tensegrity_statics::{MemberSign, StaticsBackend};

/// The rim body attached to a geometry.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RimBody {
    /// The two hub nodes (x_min side, x_max side).
    pub hubs: [usize; 2],
    /// Every bar of the rim body: axle, spokes, ring (in that order).
    pub bars: Vec<[usize; 2]>,
    /// The rim points.
    pub rim_points: Vec<usize>,
    /// Spoke bars.
    pub spokes: usize,
    /// Ring bars.
    pub ring: usize,
}

/// The prestressability LP of a structure whose first `tread_bars` bars are tread bars and
/// whose next `rim_bars` bars belong to the rim body (sign free): the largest t such that
/// some self-stress with max|q| ≤ 1 has every string q ≥ t and every tread bar q ≤ −t
/// (the core's margin LP with [`MemberSign::Free`] rim bars, through any back-end: on the
/// cyclic one over the fully symmetric self-stresses, the LP being invariant). Returns the
/// certified margin (0 when there is no such state).
pub fn prestressability(
    statics: &dyn StaticsBackend,
    tread_bars: usize,
    rim_bars: usize,
) -> Result<f64> {
    let signs: Vec<MemberSign> = (0..statics.structure().n_members())
        .map(|k| match k {
            k if k < tread_bars => MemberSign::Compression,
            k if k < tread_bars + rim_bars => MemberSign::Free,
            _ => MemberSign::Tension,
        })
        .collect();
    Ok(statics.prestressability_with(&signs)?.margin)
}
