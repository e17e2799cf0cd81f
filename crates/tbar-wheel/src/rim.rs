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
//! The rim body has no supports: the structure is a free body (six rigid-body motions). Its
//! bars have no required sign (a rigid body's members carry either sign), so the
//! prestressability of a structure with a rim body asks the tread members only for the right
//! sign ([`prestressability`]).

use crate::error::Result;
use crate::geometry::TbarGeometry;
use crate::params::Layout;
use nalgebra::Vector3;
use std::collections::{BTreeMap, HashSet};
use tensegrity_core::statics::{MemberSign, StaticsBackend};

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

/// Adds the hub nodes and the rim-body bars to `g`, turning its rim supports into rim points.
pub(crate) fn attach(g: &mut TbarGeometry) {
    let rim_points: Vec<usize> = (0..g.nodes.len()).filter(|&i| g.supported[i]).collect();
    let r_q = g.params.rim_radius();
    let (x_min, x_max) = rim_points
        .iter()
        .fold((f64::INFINITY, -f64::INFINITY), |a, &i| {
            (a.0.min(g.nodes[i].x), a.1.max(g.nodes[i].x))
        });
    let hubs = [g.nodes.len(), g.nodes.len() + 1];
    for (label, x) in [("hub_left", x_min - r_q), ("hub_right", x_max + r_q)] {
        g.nodes.push(Vector3::new(x, 0.0, 0.0));
        g.labels.push(label.to_string());
        g.supported.push(false);
    }
    g.supported.iter_mut().for_each(|s| *s = false);
    let mut bars = vec![hubs];
    for &p in &rim_points {
        bars.extend(hubs.map(|h| [p, h]));
    }
    let spokes = bars.len() - 1;
    let ring = ring_bars(g, &rim_points);
    let n_ring = ring.len();
    bars.extend(ring);
    g.rim = Some(RimBody {
        hubs,
        bars,
        rim_points,
        spokes,
        ring: n_ring,
    });
}

/// Every point of an angle group joined to every point of the next group.
fn ring_bars(g: &TbarGeometry, points: &[usize]) -> Vec<[usize; 2]> {
    let phi = g.params.michell.phi;
    let turns = (2.0 * std::f64::consts::PI / phi).round() as i64;
    let mut groups: BTreeMap<i64, Vec<usize>> = BTreeMap::new();
    for &p in points {
        let n = g.nodes[p];
        let k = (n.z.atan2(n.y) / phi).round() as i64;
        let k = if g.params.layout == Layout::Tread {
            k
        } else {
            k.rem_euclid(turns)
        };
        groups.entry(k).or_default().push(p);
    }
    let list: Vec<&Vec<usize>> = groups.values().collect();
    let closed = g.params.layout != Layout::Tread && list.len() > 2;
    let links = if closed {
        list.len()
    } else {
        list.len().saturating_sub(1)
    };
    let mut seen = HashSet::new();
    let mut out = Vec::new();
    for i in 0..links {
        let (a, b) = (list[i], list[(i + 1) % list.len()]);
        for &p in a {
            for &q in b {
                if p != q && seen.insert((p.min(q), p.max(q))) {
                    out.push([p, q]);
                }
            }
        }
    }
    out
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
