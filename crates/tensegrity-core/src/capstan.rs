//! Pulley friction on a clustered string: the capstan law's stick and slip ([`slide`]).
//!
//! A cluster with friction carries its material as per-segment rest lengths s_i (Σ s_i =
//! L₀, the cluster's rest length; EA = k L₀ its axial rigidity): segment i of length l_i
//! pulls with
//!
//! > t_i = EA (l_i − s_i)/s_i when l_i > s_i, else 0 (slack).
//!
//! Material passes over the pulley j between segments j−1 and j (a flow f_j from j−1 into
//! j: s_{j−1} −= f_j, s_j += f_j) only at the capstan limit: with the wrap angle θ_j (the
//! angle between the two segments' directions, π where the string turns back over the
//! pulley) and ρ_j = e^{μ_j θ_j},
//!
//! > f_j > 0 ⇒ t_j = ρ_j t_{j−1}, f_j < 0 ⇒ t_{j−1} = ρ_j t_j,
//! > f_j = 0 ⇒ t_j ≤ ρ_j t_{j−1} and t_{j−1} ≤ ρ_j t_j (the pulley sticks).
//!
//! [`slide`] is the return map of this rate-independent law over one increment: at the
//! segments' lengths at the end of the increment and the rest lengths at its start, it
//! finds the flows (backward Euler: the slip direction and the limit are those of the end
//! state). Active set: each pulley sticks or slips one way; the stuck pulleys cut the
//! cluster into runs that keep their material, and along a run of slipping pulleys the
//! tensions are one unknown τ times known ratios, so a run is one monotone scalar equation
//! (Newton from τ = 0); a slipping pulley whose flow turned against its direction sticks, a
//! sticking one outside the cone slips; until the set repeats. With μ = 0 every
//! pulley slips either way at ρ = 1: one tension along the cluster, t = EA (L − L₀)/L₀ =
//! k (L − L₀), the frictionless cluster's.

use thiserror::Error;

/// Why [`slide`] found no answer.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SlideError {
    /// The slices do not fit one another.
    #[error("{segments} segment length(s), {rest} rest length(s) and {pulleys} pulley(s): one rest length per segment, one pulley between two")]
    Sizes {
        /// Segment lengths given.
        segments: usize,
        /// Rest lengths given.
        rest: usize,
        /// Pulleys (μθ values) given.
        pulleys: usize,
    },
    /// Newton on a slipping run's tension did not converge.
    #[error("Newton on the tension of a slipping run of pulleys did not converge in {iterations} iterations")]
    NotConverged {
        /// Iterations done.
        iterations: usize,
    },
    /// The stick/slip set kept changing.
    #[error("the stick and slip states of {pulleys} pulley(s) did not settle")]
    Unsettled {
        /// The number of pulleys.
        pulleys: usize,
    },
    /// A rest length reached zero: the increment asked for more material than a segment has.
    #[error("a segment's rest length left (0, {total:e}) m sliding over the pulleys: the increment is too large")]
    Collapsed {
        /// The cluster's total rest length (m).
        total: f64,
    },
}

/// The largest μθ used: e^600 ≈ 10^260 keeps ρ t finite for any tension below 10^48 N (a
/// wrap that large sticks whatever the load).
pub const MAX_MU_THETA: f64 = 600.0;

/// The state of one pulley after [`slide`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pulley {
    /// No material passed over it.
    Stick,
    /// Material passed forward (from segment j−1 into j): t_j = ρ t_{j−1}.
    SlipForward,
    /// Material passed backward (from segment j into j−1): t_{j−1} = ρ t_j.
    SlipBackward,
}

/// What [`slide`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct Slide {
    /// Each pulley's state, in order along the cluster.
    pub pulleys: Vec<Pulley>,
    /// The largest change of a segment's rest length (m).
    pub moved: f64,
}

/// The tension of a segment of length `l` and rest length `s` in a cluster of rigidity `ea`.
///
/// ```
/// assert_eq!(tensegrity_core::capstan::segment_tension(100.0, 1.1, 1.0), 100.0 * 0.1 / 1.0 * 1.0000000000000009);
/// assert_eq!(tensegrity_core::capstan::segment_tension(100.0, 0.9, 1.0), 0.0);
/// ```
pub fn segment_tension(ea: f64, l: f64, s: f64) -> f64 {
    if l > s {
        ea * (l - s) / s
    } else {
        0.0
    }
}

/// The return map over one increment (module docs): the rest lengths `rest` (the increment's
/// start; overwritten with its end) of the segments of lengths `lengths`, the cluster's
/// rigidity `ea` (N) and the pulleys' `mu_theta` = μ_j θ_j (one per pulley, `lengths.len()
/// − 1`). The total rest length is kept. An error (naming what failed) where Newton does
/// not settle; `rest` is then unchanged.
///
/// ```
/// use tensegrity_core::capstan::{segment_tension, slide, Pulley};
/// // a string over one pulley wrapped by π with μ = 0.1: 3 m pulled, 1 m anchored
/// let (lengths, mut rest) = ([1.003, 1.0], [1.0, 1.0]);
/// let mu_theta = [0.1 * std::f64::consts::PI];
/// let out = slide(&lengths, &mut rest, 1e4, &mu_theta).unwrap();
/// assert_eq!(out.pulleys, vec![Pulley::SlipBackward]);
/// let t = [segment_tension(1e4, lengths[0], rest[0]), segment_tension(1e4, lengths[1], rest[1])];
/// assert!((t[0] / t[1] - mu_theta[0].exp()).abs() < 1e-12);
/// assert!((rest[0] + rest[1] - 2.0).abs() < 1e-15);
/// ```
pub fn slide(
    lengths: &[f64],
    rest: &mut [f64],
    ea: f64,
    mu_theta: &[f64],
) -> Result<Slide, SlideError> {
    let m = lengths.len();
    let p = m.saturating_sub(1);
    if rest.len() != m || mu_theta.len() != p {
        return Err(SlideError::Sizes {
            segments: m,
            rest: rest.len(),
            pulleys: mu_theta.len(),
        });
    }
    let rho: Vec<f64> = mu_theta
        .iter()
        .map(|mt| mt.clamp(0.0, MAX_MU_THETA).exp())
        .collect();
    let start = rest.to_vec();
    let scale = start.iter().sum::<f64>();
    let mut state = vec![Pulley::Stick; p];
    let mut flows;
    // the sets tried: a set that repeats ends the search (a cycle) with its answer
    let mut seen: Vec<Vec<Pulley>> = Vec::new();
    for _ in 0..(4 * p + 8) {
        flows = solve_set(lengths, &start, ea, &rho, &state)?;
        let s = rest_lengths(&start, &flows);
        let t: Vec<f64> = (0..m)
            .map(|i| segment_tension(ea, lengths[i], s[i]))
            .collect();
        let t_max = t.iter().fold(0.0_f64, |a, &b| a.max(b));
        let tol = 1e-12 * t_max;
        let mut next = state.clone();
        for j in 0..p {
            let (before, after) = (t[j], t[j + 1]);
            next[j] = match state[j] {
                Pulley::SlipForward if flows[j] < 0.0 => Pulley::Stick,
                Pulley::SlipBackward if flows[j] > 0.0 => Pulley::Stick,
                Pulley::Stick if after - rho[j] * before > tol => Pulley::SlipForward,
                Pulley::Stick if before - rho[j] * after > tol => Pulley::SlipBackward,
                keep => keep,
            };
            if next[j] == Pulley::Stick {
                flows[j] = 0.0;
            }
        }
        if next == state || seen.contains(&next) {
            let s = rest_lengths(&start, &flows);
            let moved = s
                .iter()
                .zip(&start)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            if s.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
                return Err(SlideError::Collapsed { total: scale });
            }
            rest.copy_from_slice(&s);
            return Ok(Slide {
                pulleys: next,
                moved,
            });
        }
        seen.push(state);
        state = next;
    }
    Err(SlideError::Unsettled { pulleys: p })
}

/// s_i = s⁰_i + f_i − f_{i+1} (f_j the flow over pulley j, into segment j).
fn rest_lengths(start: &[f64], flows: &[f64]) -> Vec<f64> {
    let mut s = start.to_vec();
    for (j, f) in flows.iter().enumerate() {
        s[j] -= f;
        s[j + 1] += f;
    }
    s
}

/// The flows of one stick/slip set. The stuck pulleys cut the cluster into runs that keep
/// their material; along a run every pulley slips, so its tensions are t_i = τ c_i with c
/// the products of ρ^{±1} along it, and s_i = l_i/(1 + τ c_i/EA): one scalar equation
/// Σ s_i(τ) = S_run, decreasing and convex in τ, solved by Newton from τ = 0 (monotone,
/// no overshoot). A run whose segments' lengths add up to no more than its material is
/// slack: nothing pulls its material either way and it keeps it where it was.
fn solve_set(
    lengths: &[f64],
    start: &[f64],
    ea: f64,
    rho: &[f64],
    state: &[Pulley],
) -> Result<Vec<f64>, SlideError> {
    let m = lengths.len();
    let mut flows = vec![0.0; m.saturating_sub(1)];
    let mut first = 0;
    while first < m {
        // the run first..=last: its inner pulleys all slip
        let mut last = first;
        while last + 1 < m && state[last] != Pulley::Stick {
            last += 1;
        }
        if last > first {
            let run = first..last + 1;
            // log c_i along the run, normalised so that the largest c is 1
            let mut log_c = vec![0.0; run.len()];
            for (k, j) in (first..last).enumerate() {
                let step = rho[j].ln();
                log_c[k + 1] = log_c[k]
                    + if state[j] == Pulley::SlipForward {
                        step
                    } else {
                        -step
                    };
            }
            let top = log_c.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b));
            let c: Vec<f64> = log_c.iter().map(|v| (v - top).exp()).collect();
            let material: f64 = start[run.clone()].iter().sum();
            let s = match run_rest_lengths(&lengths[run.clone()], &c, ea, material)? {
                Some(s) => s,
                None => slack_run(&lengths[run.clone()], &start[run]),
            };
            {
                // f_j = f_{j−1} + s⁰_j − s_j along the run (no flow into its first segment)
                let mut f = 0.0;
                for (k, j) in (first..last).enumerate() {
                    f += start[j] - s[k];
                    flows[j] = f;
                }
            }
        }
        first = last + 1;
    }
    Ok(flows)
}

/// A slack run's rest lengths: its taut segments take just enough material to go slack
/// (l_i), from its slack ones in proportion to their slackness (s_i − l_i; enough of it, as
/// Σ l ≤ Σ s), so that every tension is zero with the least material moved on the taut side.
fn slack_run(l: &[f64], start: &[f64]) -> Vec<f64> {
    let need: f64 = l.iter().zip(start).map(|(l, s)| (l - s).max(0.0)).sum();
    let room: f64 = l.iter().zip(start).map(|(l, s)| (s - l).max(0.0)).sum();
    let share = if room > 0.0 { need / room } else { 0.0 };
    l.iter()
        .zip(start)
        .map(|(&l, &s)| if l > s { l } else { s - share * (s - l) })
        .collect()
}

/// The rest lengths of a slipping run of lengths `l` with tension ratios `c` and `material`
/// in all (see [`solve_set`]); `None` when the run is slack.
fn run_rest_lengths(
    l: &[f64],
    c: &[f64],
    ea: f64,
    material: f64,
) -> Result<Option<Vec<f64>>, SlideError> {
    let g = |tau: f64| -> (f64, f64) {
        l.iter()
            .zip(c)
            .fold((-material, 0.0), |(v, d), (&li, &ci)| {
                let den = 1.0 + tau * ci / ea;
                (v + li / den, d - li * ci / (ea * den * den))
            })
    };
    if g(0.0).0 <= 0.0 {
        return Ok(None);
    }
    let mut tau: f64 = 0.0;
    for iteration in 0..200 {
        let (v, d) = g(tau);
        let next = tau - v / d;
        if !next.is_finite() {
            return Err(SlideError::NotConverged {
                iterations: iteration,
            });
        }
        // monotone from below: done when the step no longer moves τ
        if next <= tau * (1.0 + 4.0 * f64::EPSILON) {
            let tau = tau.max(next);
            let s = l
                .iter()
                .zip(c)
                .map(|(&li, &ci)| li / (1.0 + tau * ci / ea))
                .collect();
            return Ok(Some(s));
        }
        tau = next;
    }
    Err(SlideError::NotConverged { iterations: 200 })
}

/// The wrap angle θ (rad) at a pulley between the unit directions `before` and `after` of
/// its two segments (both along the string): 0 straight through, π turned back.
///
/// ```
/// use nalgebra::Vector3;
/// let theta = tensegrity_core::capstan::wrap_angle(&Vector3::z(), &(-Vector3::z()));
/// assert!((theta - std::f64::consts::PI).abs() < 1e-15);
/// ```
pub fn wrap_angle(before: &nalgebra::Vector3<f64>, after: &nalgebra::Vector3<f64>) -> f64 {
    // atan2 of the cross and dot products: accurate near 0 and π, unlike acos
    before.cross(after).norm().atan2(before.dot(after))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tensions(ea: f64, l: &[f64], s: &[f64]) -> Vec<f64> {
        l.iter()
            .zip(s)
            .map(|(&l, &s)| segment_tension(ea, l, s))
            .collect()
    }

    #[test]
    fn frictionless_pulleys_carry_the_cluster_tension() {
        // μ = 0: one tension k (L − L₀) along the cluster, whatever the start's distribution
        let l = [1.2, 0.7, 2.05, 0.4];
        let mut s = [1.0, 1.0, 1.0, 1.0];
        let ea = 5e3;
        slide(&l, &mut s, ea, &[0.0; 3]).unwrap();
        let k = ea / 4.0;
        let t = k * (l.iter().sum::<f64>() - 4.0);
        for ti in tensions(ea, &l, &s) {
            assert!((ti - t).abs() < 1e-11 * t, "{ti} vs {t}");
        }
        assert!((s.iter().sum::<f64>() - 4.0).abs() < 1e-14);
    }

    #[test]
    fn a_chain_slips_at_the_capstan_limit_at_every_pulley() {
        // one end pulled hard, all pulleys slip: t_{j+1} = e^{μθ} t_j down the chain
        let l = [1.0, 1.0, 1.0, 1.05];
        let mut s = [1.0; 4];
        let mt = [0.3, 0.2, 0.5];
        let out = slide(&l, &mut s, 1e4, &mt).unwrap();
        assert_eq!(out.pulleys, vec![Pulley::SlipForward; 3]);
        let t = tensions(1e4, &l, &s);
        for j in 0..3 {
            assert!((t[j + 1] / t[j] - f64::exp(mt[j])).abs() < 1e-12);
        }
    }

    #[test]
    fn inside_the_cone_nothing_slides() {
        let l = [1.001, 1.0011];
        let mut s = [1.0, 1.0];
        let out = slide(&l, &mut s, 1e4, &[0.2]).unwrap();
        assert_eq!(out.pulleys, vec![Pulley::Stick]);
        assert_eq!((s, out.moved), ([1.0, 1.0], 0.0));
    }

    #[test]
    fn a_slack_side_draws_the_other_to_zero() {
        // segment 0 slack, segment 1 taut: material flows into 1 until it is slack too
        let l = [0.5, 1.01];
        let mut s = [1.0, 1.0];
        slide(&l, &mut s, 1e4, &[0.3]).unwrap();
        let t = tensions(1e4, &l, &s);
        assert_eq!(t, vec![0.0, 0.0]);
        assert_eq!(s, [0.99, 1.01]);
    }

    #[test]
    fn a_stretched_middle_draws_material_from_both_sides() {
        let l = [1.0, 1.02, 1.0];
        let mut s = [1.0; 3];
        let mt = [0.05, 0.05];
        let out = slide(&l, &mut s, 1e4, &mt).unwrap();
        let t = tensions(1e4, &l, &s);
        assert_eq!(out.pulleys, vec![Pulley::SlipForward, Pulley::SlipBackward]);
        assert!((t[1] / t[0] - mt[0].exp()).abs() < 1e-12);
        assert!((t[1] / t[2] - mt[1].exp()).abs() < 1e-12);
    }

    #[test]
    fn mixed_stick_and_slip() {
        // a rough second pulley holds while the first slips to its limit: the first two
        // segments share their material, the third keeps its own
        let l = [1.0, 1.02, 1.01];
        let mut s = [1.0; 3];
        let mt = [0.05, 5.0];
        let out = slide(&l, &mut s, 1e4, &mt).unwrap();
        let t = tensions(1e4, &l, &s);
        assert_eq!(out.pulleys, vec![Pulley::SlipForward, Pulley::Stick]);
        assert!((t[1] / t[0] - mt[0].exp()).abs() < 1e-12);
        assert_eq!(s[2], 1.0);
        assert!((s[0] + s[1] - 2.0).abs() < 1e-15);
    }

    #[test]
    fn wrong_sizes_are_refused() {
        let e = slide(&[1.0, 1.0], &mut [1.0], 1.0, &[0.1])
            .unwrap_err()
            .to_string();
        assert!(e.contains("one rest length per segment"), "{e}");
    }
}
