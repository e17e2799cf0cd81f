//! The omnidirectional load envelope (issue item 3, new analysis).
//!
//! **Model.** Every member is linear elastic with axial stiffness EA/L (one EA for all), and
//! displacements are small. With Â = A diag(1/L) the equilibrium matrix in member forces
//! (Â t = w on the free dofs; column k holds ∓e_k at the rows of its two nodes), member
//! elongations are Âᵀu, so the elastic stiffness is K = Â diag(EA/L) Âᵀ, and a load w adds
//! the member forces Δt = diag(EA/L) Âᵀ K⁻¹ w (which satisfy Â Δt = w). The prestress is a
//! self-stress s = S x (S = diag(L) V, V the core's self-stress basis), which loads no node.
//! The geometric stiffness of the prestress is left out (small prestress against EA), which
//! keeps the response linear in the load and independent of the prestress level.
//!
//! **Envelope.** A tip load w₀d (‖d‖ = 1) on tip T gives member k the force
//! t_k = s_k + w₀ g_{k,T}·d with g_{k,T} = row k of diag(EA/L) Âᵀ K⁻¹ E_T (E_T selects T's
//! dofs). Since min over unit d of g·d is −‖g‖ (at d = −g/‖g‖),
//!
//! - a string stays taut for every direction iff s_k − w₀‖g_{k,T}‖ ≥ 0,
//! - a bar stays compressed for every direction iff s_k + w₀‖g_{k,T}‖ ≤ 0,
//!
//! and with a_k = max_T ‖g_{k,T}‖ over the loaded tips (one tip loaded at a time) the
//! minimum prestress is the linear programme
//!
//! ```text
//! min P  over (x, P)  s.t.  S_k x ≥ w₀ a_k (strings),  S_k x ≤ −w₀ a_k (bars),  −S_k x ≤ P (bars)
//! ```
//!
//! i.e. the smallest bar compression P for which some self-stress keeps every string in
//! tension and every bar in compression for every load direction. With one EA, g does not
//! depend on EA, and the LP is homogeneous in w₀ (solved for w₀ = 1 and scaled). It is solved
//! by the core's dense LP ([`tensegrity_statics::solve_lp`]); the reported prestress is
//! then certified: the returned state s is scaled by λ = max(a_k/s_k, a_bar/−s_bar), which
//! makes every constraint hold exactly, and P = max over bars of −λ s_b.
//!
//! **Critical member.** The member with the smallest relative slack at the optimum (0 for the
//! binding ones); its worst direction is −g/‖g‖ for a string (+g/‖g‖ for a bar) on the tip
//! that maximises ‖g‖.
//!
//! **Slack map.** For a prestress P the optimal state is scaled to bar compression P and each
//! direction of a quasi-uniform (Fibonacci) sphere is checked: the direction slackens when
//! some string force is < 0 or some bar force > 0 for a load on some tip. Above the minimum
//! no direction slackens; below it the critical direction does (and nearby sampled ones).
//! The thesis's claims are checked on the same sample: the bar stays in compression, and
//! every load direction is carried by the bar and at least two strings (their forces change).
//! Note that a load need not *tighten* two strings: a radial load towards the hub unloads all
//! four strings of a q = 1 tread and is carried by the prestress drop and the bar.
//!
//! **Wheels through the cyclic path.** The statics back-end ([`StaticsBackend`]) of a wheel is
//! its symmetry-adapted blocks. The response of one tip per tip orbit is solved block by
//! block and rotated to the other tips ([`LoadResponse`]); since every tread's tip is loaded,
//! a_k is constant on member orbits, so the LP above (and its lengths, signs and the bar cap)
//! is invariant under the rotation. Its feasible set is convex, so the average over the group
//! of an optimum is an optimum: the LP restricted to the fully symmetric self-stresses (the
//! back-end's [`SelfStressBasis::Symmetric`], d₀ columns, a few per member orbit) has the same
//! minimum P, and it is what the cyclic path solves, with one row per member orbit (a
//! symmetric state has equal forces over an orbit): its size does not grow with n. With all
//! orbits of n members the reduced LP's log barrier is the full one's divided by n, so both
//! have the same central path and tend to the same point of a non-unique optimal face. The full self-stress basis (dimension 2n for a q = 1
//! wheel) is never needed: the report prints the minimum prestress, the optimal (symmetric)
//! state, the critical member and the mass, all from this LP. The slack map checks every
//! tip, each from a rotated response (O(tips × members) per direction, as on the dense
//! path).
//!
//! [`SelfStressBasis::Symmetric`]: tensegrity_statics::SelfStressBasis::Symmetric

mod response;
mod slack;

pub use response::LoadResponse;
pub use slack::{loaded_forces, scaled_state, slack_map, sphere_directions, SlackMap, SlackPoint};

use crate::error::{invalid, Result, TbarError};
use nalgebra::{DMatrix, DVector, Vector3};
use serde::Serialize;
use std::f64::consts::PI;
use tensegrity_derive::Columns;
use tensegrity_statics::{solve_lp, StaticsBackend};

/// Default tip load magnitude w₀ (N).
pub const DEFAULT_LOAD: f64 = 1.0;
/// Default axial stiffness EA (N) of every member (the minimum prestress does not depend on it).
pub const DEFAULT_EA: f64 = 1.0e6;
/// Default number of directions of the slack map.
pub const DEFAULT_DIRECTIONS: usize = 2000;
/// Most directions accepted for a slack map.
pub const MAX_DIRECTIONS: usize = 1_000_000;

/// Whether a member is a bar or a string (serialised as `bar`, `string`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum MemberKind {
    /// A bar.
    Bar,
    /// A string.
    String,
}

impl std::fmt::Display for MemberKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.pad(match self {
            MemberKind::Bar => "bar",
            MemberKind::String => "string",
        })
    }
}

/// The binding member of the minimum-prestress state.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct CriticalMember {
    /// Member index (bars first, then strings).
    pub member: usize,
    /// `bar` or `string`.
    pub kind: MemberKind,
    /// Index among the members of its kind.
    pub index: usize,
    /// Labels of its two nodes (start, end).
    pub nodes: [String; 2],
    /// The loaded tread (index into the tips) of its worst case.
    pub tread: usize,
    /// Worst load direction (unit vector).
    pub direction: [f64; 3],
    /// Azimuth of the direction in the ι̂₁ι̂₂ plane (rad, [0, 2π)).
    #[column(unit = "rad")]
    pub azimuth: f64,
    /// Polar angle of the direction from ι̂₃ (rad).
    #[column(unit = "rad")]
    pub polar: f64,
}

/// The minimum prestress and its state.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EnvelopeSolution {
    /// Tip load magnitude w₀ (N).
    pub load: f64,
    /// Smallest bar compression P (N) that carries w₀ from every direction.
    pub min_prestress: f64,
    /// Member forces (N, tension positive, bars first) of the optimal prestress state.
    pub prestress_force: Vec<f64>,
    /// The binding member and its worst direction.
    pub critical_member: CriticalMember,
    /// Every member whose constraint binds (relative slack below 1e-7).
    pub active_members: Vec<usize>,
}

/// (azimuth ∈ [0, 2π), polar from ι̂₃) of a unit vector.
pub fn angles(d: &Vector3<f64>) -> (f64, f64) {
    let az = d.y.atan2(d.x).rem_euclid(2.0 * PI);
    (az, d.z.clamp(-1.0, 1.0).acos())
}

/// Solves the minimum-prestress LP for a tip load of magnitude `load` (see the module docs).
/// `labels` names the nodes (for the critical member).
pub fn min_prestress(
    statics: &dyn StaticsBackend,
    response: &LoadResponse,
    load: f64,
    labels: &[String],
    what: &'static str,
) -> Result<EnvelopeSolution> {
    if !(load.is_finite() && load > 0.0) {
        return Err(invalid("load", load, "the tip load must be finite and > 0"));
    }
    // the whole self-stress space, or its fully symmetric part on the cyclic path: the LP
    // is invariant (a_k constant on member orbits), so it has a symmetric optimum
    let basis = statics.self_stress().matrix().clone();
    let dim = basis.ncols();
    let not_prestressable = || TbarError::NotPrestressable {
        structure: what,
        self_stress_dim: statics.self_stress_dim(),
    };
    if dim == 0 {
        return Err(not_prestressable());
    }
    let m = response.n_members();
    let mut force_basis = basis;
    for (k, mut row) in force_basis.row_iter_mut().enumerate() {
        row *= response.lengths[k];
    }
    let gains = response.worst_gains();
    // the members whose constraints enter: all of them, or one per member orbit on the cyclic
    // path (a symmetric state has equal forces, lengths and gains over an orbit)
    let members: Vec<usize> = match statics.symmetry() {
        Some(sym) => sym.member_orbits().iter().map(|o| o.rep).collect(),
        None => (0..m).collect(),
    };
    let bars: Vec<usize> = members
        .iter()
        .copied()
        .filter(|&k| response.is_bar(k))
        .collect();
    let rows = members.len() + bars.len();
    let mut g = DMatrix::zeros(rows, dim + 1);
    let mut h = DVector::zeros(rows);
    for (r, &k) in members.iter().enumerate() {
        let sign = if response.is_bar(k) { 1.0 } else { -1.0 };
        for j in 0..dim {
            g[(r, j)] = sign * force_basis[(k, j)];
        }
        h[r] = -gains[k].0;
    }
    for (r, &b) in bars.iter().enumerate() {
        let r = members.len() + r;
        for j in 0..dim {
            g[(r, j)] = -force_basis[(b, j)];
        }
        g[(r, dim)] = -1.0;
    }
    let mut c = DVector::zeros(dim + 1);
    c[dim] = 1.0;
    let z = solve_lp(&g, &h, &c, "T-bar minimum-prestress LP").map_err(|_| not_prestressable())?;
    let s = &force_basis * z.rows(0, dim);
    certify(response, &gains, s.as_slice(), load, labels).ok_or_else(not_prestressable)
}

/// Scales the LP state so that every constraint holds exactly, and finds the critical member.
fn certify(
    response: &LoadResponse,
    gains: &[(f64, usize)],
    s: &[f64],
    load: f64,
    labels: &[String],
) -> Option<EnvelopeSolution> {
    let m = response.n_members();
    // signed forces: positive when the member has the right sign
    let signed = |k: usize| if response.is_bar(k) { -s[k] } else { s[k] };
    let mut lambda: f64 = 0.0;
    for k in 0..m {
        if signed(k) <= 0.0 {
            return None;
        }
        lambda = lambda.max(gains[k].0 / signed(k));
    }
    if !(lambda > 0.0 && lambda.is_finite()) {
        return None;
    }
    let force: Vec<f64> = s.iter().map(|v| v * lambda * load).collect();
    let min_prestress = (0..response.n_bars)
        .map(|b| -force[b])
        .fold(0.0f64, f64::max);
    let slack: Vec<f64> = (0..m)
        .map(|k| {
            let need = gains[k].0 * load;
            let have = if response.is_bar(k) {
                -force[k]
            } else {
                force[k]
            };
            if need > 0.0 {
                (have - need) / need
            } else {
                f64::INFINITY
            }
        })
        .collect();
    let least = slack.iter().copied().fold(f64::INFINITY, f64::min);
    // ties (symmetric members bind together): the lowest index
    let best = (0..m).find(|&k| slack[k] <= least + 1e-9)?;
    let active = (0..m).filter(|&k| slack[k] <= 1e-7).collect();
    let critical = critical_member(response, gains, best, labels);
    Some(EnvelopeSolution {
        load,
        min_prestress,
        prestress_force: force,
        critical_member: critical,
        active_members: active,
    })
}

/// The worst direction of member k: −g/‖g‖ for a string, +g/‖g‖ for a bar.
fn critical_member(
    response: &LoadResponse,
    gains: &[(f64, usize)],
    k: usize,
    labels: &[String],
) -> CriticalMember {
    let (norm, t) = gains[k];
    let gk = response.tip_response(t)[k];
    let sign = if response.is_bar(k) { 1.0 } else { -1.0 };
    let d = if norm > 0.0 {
        sign * gk / norm
    } else {
        Vector3::z()
    };
    let (azimuth, polar) = angles(&d);
    let ends = member_ends(response, k, labels);
    CriticalMember {
        member: k,
        kind: if response.is_bar(k) {
            MemberKind::Bar
        } else {
            MemberKind::String
        },
        index: if response.is_bar(k) {
            k
        } else {
            k - response.n_bars
        },
        nodes: ends,
        tread: t,
        direction: [d.x, d.y, d.z],
        azimuth,
        polar,
    }
}

fn member_ends(response: &LoadResponse, k: usize, labels: &[String]) -> [String; 2] {
    let [a, b] = response.ends[k];
    let name = |i: usize| labels.get(i).cloned().unwrap_or_else(|| i.to_string());
    [name(a), name(b)]
}
