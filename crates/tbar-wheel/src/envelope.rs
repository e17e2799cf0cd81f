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
//! by the core's dense LP ([`tensegrity_core::statics::solve_lp`]); the reported prestress is
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

use crate::error::{invalid, Result, TbarError};
use nalgebra::{DMatrix, DVector, Vector3};
use serde::Serialize;
use std::f64::consts::PI;
use tensegrity_core::statics::solve_lp;
use tensegrity_core::Statics;

/// Default tip load magnitude w₀ (N).
pub const DEFAULT_LOAD: f64 = 1.0;
/// Default axial stiffness EA (N) of every member (the minimum prestress does not depend on it).
pub const DEFAULT_EA: f64 = 1.0e6;
/// Default number of directions of the slack map.
pub const DEFAULT_DIRECTIONS: usize = 2000;
/// Most directions accepted for a slack map.
pub const MAX_DIRECTIONS: usize = 1_000_000;

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
    /// `g[t][k]`: force in member k (N) per newton of load on tip t, t_k = g·d.
    pub g: Vec<Vec<Vector3<f64>>>,
}

impl LoadResponse {
    /// Assembles K = Â diag(EA/L) Âᵀ from the factored statics and solves for unit loads on
    /// each tip. Fails with [`TbarError::Mechanism`] when K is singular.
    pub fn new(statics: &Statics<'_>, tips: &[usize], ea: f64, what: &'static str) -> Result<Self> {
        if !(ea.is_finite() && ea > 0.0) {
            return Err(invalid(
                "ea",
                ea,
                "the axial stiffness must be finite and > 0",
            ));
        }
        let s = statics.structure();
        let lengths = s.member_lengths();
        let mut a_hat = statics.matrix().clone();
        for (k, mut col) in a_hat.column_iter_mut().enumerate() {
            col /= lengths[k];
        }
        let k_diag = DVector::from_iterator(lengths.len(), lengths.iter().map(|l| ea / l));
        let mut weighted = a_hat.clone();
        for (k, mut col) in weighted.column_iter_mut().enumerate() {
            col *= k_diag[k];
        }
        let stiffness = &weighted * a_hat.transpose();
        let mechanism = || -> Result<TbarError> {
            Ok(TbarError::Mechanism {
                structure: what,
                mechanisms: statics.flexes()?.internal.ncols().max(1),
            })
        };
        if statics.mechanisms() > 0 {
            return Err(mechanism()?);
        }
        let Some(chol) = stiffness.cholesky() else {
            return Err(mechanism()?);
        };
        let dofs = statics.dofs();
        let mut g = Vec::with_capacity(tips.len());
        for &tip in tips {
            let mut e = DMatrix::zeros(dofs.len(), 3);
            for d in 0..3 {
                let row = dofs.row[tip][d].ok_or_else(|| {
                    invalid("tip", tip as f64, "a loaded tip must be a free node")
                })?;
                e[(row, d)] = 1.0;
            }
            let u = chol.solve(&e);
            let forces = weighted.transpose() * u;
            g.push(
                (0..forces.nrows())
                    .map(|k| Vector3::new(forces[(k, 0)], forces[(k, 1)], forces[(k, 2)]))
                    .collect(),
            );
        }
        Ok(Self {
            lengths,
            n_bars: s.n_bars(),
            ends: s.member_nodes(),
            tips: tips.to_vec(),
            g,
        })
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
        (0..self.n_members())
            .map(|k| {
                self.g
                    .iter()
                    .enumerate()
                    .map(|(t, gt)| (gt[k].norm(), t))
                    .fold((0.0, 0), |best, x| if x.0 > best.0 { x } else { best })
            })
            .collect()
    }
}

/// The binding member of the minimum-prestress state.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CriticalMember {
    /// Member index (bars first, then strings).
    pub member: usize,
    /// `bar` or `string`.
    pub kind: michell3d::MemberKind,
    /// Index among the members of its kind.
    pub index: usize,
    /// Labels of its two nodes (start, end).
    pub nodes: [String; 2],
    /// The loaded tread (index into the tips) of its worst case.
    pub tread: usize,
    /// Worst load direction (unit vector).
    pub direction: [f64; 3],
    /// Azimuth of the direction in the ι̂₁ι̂₂ plane (rad, [0, 2π)).
    pub azimuth: f64,
    /// Polar angle of the direction from ι̂₃ (rad).
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
    statics: &Statics<'_>,
    response: &LoadResponse,
    load: f64,
    labels: &[String],
    what: &'static str,
) -> Result<EnvelopeSolution> {
    if !(load.is_finite() && load > 0.0) {
        return Err(invalid("load", load, "the tip load must be finite and > 0"));
    }
    let basis = statics.self_stress_basis();
    let dim = basis.ncols();
    let not_prestressable = || TbarError::NotPrestressable {
        structure: what,
        self_stress_dim: dim,
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
    let nb = response.n_bars;
    let rows = m + nb;
    let mut g = DMatrix::zeros(rows, dim + 1);
    let mut h = DVector::zeros(rows);
    for k in 0..m {
        let sign = if response.is_bar(k) { 1.0 } else { -1.0 };
        for j in 0..dim {
            g[(k, j)] = sign * force_basis[(k, j)];
        }
        h[k] = -gains[k].0;
    }
    for b in 0..nb {
        for j in 0..dim {
            g[(m + b, j)] = -force_basis[(b, j)];
        }
        g[(m + b, dim)] = -1.0;
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
    let gk = response.g[t][k];
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
            michell3d::MemberKind::Bar
        } else {
            michell3d::MemberKind::String
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

/// `n` quasi-uniform unit vectors (Fibonacci sphere): z_i = 1 − (2i+1)/n, azimuth i·π(3 − √5).
///
/// ```
/// let d = tbar_wheel::envelope::sphere_directions(500);
/// assert_eq!(d.len(), 500);
/// let mean: nalgebra::Vector3<f64> = d.iter().sum::<nalgebra::Vector3<f64>>() / 500.0;
/// assert!(mean.norm() < 1e-2 && d.iter().all(|v| (v.norm() - 1.0).abs() < 1e-12));
/// ```
pub fn sphere_directions(n: usize) -> Vec<Vector3<f64>> {
    let golden = PI * (3.0 - 5f64.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - (2 * i + 1) as f64 / n as f64;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let a = i as f64 * golden;
            Vector3::new(r * a.cos(), r * a.sin(), z)
        })
        .collect()
}

/// One direction of the slack map.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SlackPoint {
    /// Azimuth in the ι̂₁ι̂₂ plane (rad).
    pub azimuth: f64,
    /// Polar angle from ι̂₃ (rad).
    pub polar: f64,
    /// Smallest margin over members and tips (N): string tension, or bar compression.
    pub margin: f64,
    /// Whether some string slackens or some bar goes into tension.
    pub slack: bool,
}

/// The slack map of one prestress level.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SlackMap {
    /// Bar compression P of the state (N).
    pub prestress: f64,
    /// Fraction of the sampled directions that slacken a string or put a bar in tension.
    pub slack_fraction: f64,
    /// Whether every bar stays in compression for every sampled direction and tip.
    pub bar_always_compressed: bool,
    /// The fewest strings whose force a load changes (|Δt| above 1e-9 of the largest change),
    /// over the sampled directions and tips (the thesis: a load is carried by the bar and at
    /// least two strings).
    pub min_strings_carrying: usize,
    /// Whether the bar's force changes for every sampled direction (it carries every load).
    pub bar_always_carries: bool,
    /// Every sampled direction.
    pub points: Vec<SlackPoint>,
}

/// Member forces of a state under load `load` in direction `d` on tip `t`.
pub fn loaded_forces(
    response: &LoadResponse,
    state: &[f64],
    load: f64,
    t: usize,
    d: &Vector3<f64>,
) -> Vec<f64> {
    state
        .iter()
        .zip(&response.g[t])
        .map(|(s, g)| s + load * g.dot(d))
        .collect()
}

/// Checks a prestress state (member forces, N) under `load` in every direction of `dirs`,
/// on every tip.
pub fn slack_map(
    response: &LoadResponse,
    state: &[f64],
    load: f64,
    dirs: &[Vector3<f64>],
) -> SlackMap {
    let nb = response.n_bars;
    let prestress = (0..nb).map(|b| -state[b]).fold(0.0f64, f64::max);
    let mut points = Vec::with_capacity(dirs.len());
    let mut bar_ok = true;
    let mut min_tight = usize::MAX;
    let mut bar_carries = true;
    for d in dirs {
        let mut margin = f64::INFINITY;
        for t in 0..response.tips.len() {
            let f = loaded_forces(response, state, load, t, d);
            for (k, v) in f.iter().enumerate() {
                margin = margin.min(if k < nb { -v } else { *v });
                bar_ok &= k >= nb || *v <= 0.0;
            }
            let scale = response.g[t]
                .iter()
                .fold(0.0f64, |m, g| m.max(g.dot(d).abs()));
            let carrying = |g: &Vector3<f64>| g.dot(d).abs() > 1e-9 * scale;
            let tight = response.g[t][nb..].iter().filter(|g| carrying(g)).count();
            min_tight = min_tight.min(tight);
            bar_carries &= response.g[t][..nb].iter().any(carrying);
        }
        let (azimuth, polar) = angles(d);
        points.push(SlackPoint {
            azimuth,
            polar,
            margin,
            slack: margin < 0.0,
        });
    }
    let slack = points.iter().filter(|p| p.slack).count();
    SlackMap {
        prestress,
        slack_fraction: if dirs.is_empty() {
            0.0
        } else {
            slack as f64 / dirs.len() as f64
        },
        bar_always_compressed: bar_ok,
        min_strings_carrying: if min_tight == usize::MAX {
            0
        } else {
            min_tight
        },
        bar_always_carries: bar_carries,
        points,
    }
}

/// The optimal state of `solution` scaled to bar compression `prestress` (N).
pub fn scaled_state(solution: &EnvelopeSolution, prestress: f64) -> Result<Vec<f64>> {
    if !(prestress.is_finite() && prestress > 0.0) {
        return Err(invalid("prestress", prestress, "must be finite and > 0"));
    }
    let f = prestress / solution.min_prestress;
    Ok(solution.prestress_force.iter().map(|v| v * f).collect())
}
