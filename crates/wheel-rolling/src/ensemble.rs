//! Ensemble statistics of a rolling run ([`ensemble`]): where the motion is chaotic (hops on a
//! steep slope), one run's numbers are one draw; K copies from perturbed starting states give
//! the mean and a 95 % interval of every headline quantity.
//!
//! Copy k (k = 0 … K−1) starts from the run's state with the wheel's pose relative to gravity
//! turned by δ_k = (−1)ᵏ ⌊k/2 + 1⌋ · [`PERTURBATION`] (±10⁻⁶ rad, ±2·10⁻⁶ rad, …): the slope and
//! the wheel on it are turned together about the axle, i.e. the incline is φ + δ_k. The copies
//! run in parallel (one scoped thread per core, each taking the next copy), without the
//! convergence check. Per quantity: the mean x̄, the sample standard deviation s and the
//! interval x̄ ± 1.96 s (95 % of a normal spread), and — when the other model's run is given —
//! its value and whether the interval's width exceeds the distance |x̄ − x_other| between the
//! models (then the models cannot be told apart on that quantity by single runs).

use crate::fidelity::Decision;
use crate::run::{roll_decided, Wheel};
use crate::sample::RollingSample;
use crate::settings::RunSpec;
use crate::summary::RunSummary;
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// The size of the first perturbation of the starting pose (rad).
pub const PERTURBATION: f64 = 1e-6;

/// One headline quantity over the copies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EnsembleQuantity {
    /// The report key.
    pub name: String,
    /// Mean over the copies that have it.
    pub mean: f64,
    /// Sample standard deviation.
    pub std: f64,
    /// Lower end of the 95 % interval, mean − 1.96 std.
    pub low: f64,
    /// Upper end, mean + 1.96 std.
    pub high: f64,
    /// The other model's value (one unperturbed run), when it ran.
    pub other_model: Option<f64>,
    /// Whether the interval is wider than |mean − other model|.
    pub spread_exceeds_model_difference: Option<bool>,
}

/// The statistics of an ensemble (module docs).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Ensemble {
    /// Number of copies K.
    pub members: usize,
    /// How the copies were perturbed.
    pub perturbation: String,
    /// The copies that were not valid (their own assumptions, not convergence).
    pub invalid_members: usize,
    /// One entry per headline quantity.
    pub quantities: Vec<EnsembleQuantity>,
    /// The quantities whose spread exceeds the difference between the models, one sentence;
    /// empty when none does or no other model ran.
    pub note: String,
}

/// One slot per copy for its summary and samples (or error).
type Slots<E> = Mutex<Vec<Option<Result<(RunSummary, Vec<RollingSample>), E>>>>;

/// The headline quantities of a summary, by key (those it has).
pub fn headline(s: &RunSummary) -> Vec<(&'static str, Option<f64>)> {
    let first = s.first_impact;
    vec![
        ("first_impact.t", first.map(|i| i.t)),
        ("first_impact.omega_before", first.map(|i| i.omega_before)),
        ("impacts", Some(s.impacts as f64)),
        ("mean_axle_height", Some(s.mean_axle_height)),
        ("axle_height_oscillation", Some(s.axle_height_oscillation)),
        ("mean_speed", Some(s.mean_speed)),
        ("final_speed", Some(s.final_speed)),
        ("airborne_fraction", Some(s.airborne_fraction)),
        ("slip_fraction", Some(s.slip_fraction)),
    ]
}

/// The incline offset of copy k (module docs).
pub fn offset(k: usize) -> f64 {
    let sign = if k.is_multiple_of(2) { 1.0 } else { -1.0 };
    sign * (k / 2 + 1) as f64 * PERTURBATION
}

/// Runs `members` perturbed copies of `spec` under `decision` on `threads` threads and
/// gathers their statistics; `other` is the other model's summary, for the comparison.
pub fn ensemble<W>(
    wheel: &W,
    spec: &RunSpec,
    decision: &Decision,
    members: usize,
    threads: usize,
    other: Option<&RunSummary>,
) -> Result<Ensemble, W::Error>
where
    W: Wheel + Sync,
    W::Error: Send,
{
    ensemble_with_samples(wheel, spec, decision, members, threads, other).map(|(e, _)| e)
}

/// As [`ensemble`], also returning each copy's sampled history (in copy order), for bands
/// over time ([`band`]).
pub fn ensemble_with_samples<W>(
    wheel: &W,
    spec: &RunSpec,
    decision: &Decision,
    members: usize,
    threads: usize,
    other: Option<&RunSummary>,
) -> Result<(Ensemble, Vec<Vec<RollingSample>>), W::Error>
where
    W: Wheel + Sync,
    W::Error: Send,
{
    let next = AtomicUsize::new(0);
    let out: Slots<W::Error> = Mutex::new((0..members).map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads.clamp(1, members.max(1)) {
            s.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                if k >= members {
                    break;
                }
                let mut copy = *spec;
                copy.settings.incline += offset(k);
                let r = roll_decided(wheel, &copy, decision, &[], None).map(|r| {
                    let summary = RunSummary::of(&r.result, spec.t_end);
                    (summary, r.result.samples)
                });
                out.lock().unwrap_or_else(|e| e.into_inner())[k] = Some(r);
            });
        }
    });
    let mut runs = Vec::with_capacity(members);
    let mut histories = Vec::with_capacity(members);
    for r in out
        .into_inner()
        .unwrap_or_else(|e| e.into_inner())
        .into_iter()
        .flatten()
    {
        let (summary, samples) = r?;
        runs.push(summary);
        histories.push(samples);
    }
    Ok((statistics(&runs, other), histories))
}

/// A band over time: at each time t of the first history, the mean x̄(t) of `value` over
/// the histories (each interpolated linearly at t; a history that ended before t is left
/// out) and the interval x̄ ± 1.96 s(t) (the sample standard deviation), as
/// `(t, mean, low, high)`.
///
/// ```
/// use wheel_rolling::ensemble::band;
/// use wheel_rolling::RollingSample;
/// let at = |t: f64, h: f64| RollingSample { t, h, ..RollingSample::default() };
/// let copies = vec![vec![at(0.0, 1.0), at(1.0, 3.0)], vec![at(0.0, 3.0), at(1.0, 5.0)]];
/// let b = band(&copies, |s| s.h);
/// assert_eq!(b[0].1, 2.0);
/// assert_eq!(b[1].1, 4.0);
/// // s = √2 at each time
/// assert!((b[1].3 - b[1].2 - 2.0 * 1.96 * 2f64.sqrt()).abs() < 1e-12);
/// ```
pub fn band(
    histories: &[Vec<RollingSample>],
    value: impl Fn(&RollingSample) -> f64,
) -> Vec<(f64, f64, f64, f64)> {
    let Some(first) = histories.first() else {
        return Vec::new();
    };
    let at = |h: &[RollingSample], t: f64| -> Option<f64> {
        let i = h.partition_point(|s| s.t < t);
        match (i.checked_sub(1).and_then(|j| h.get(j)), h.get(i)) {
            (_, Some(b)) if b.t == t => Some(value(b)),
            (Some(a), Some(b)) => {
                let w = (t - a.t) / (b.t - a.t);
                Some(value(a) + w * (value(b) - value(a)))
            }
            _ => None,
        }
    };
    first
        .iter()
        .filter_map(|s| {
            let xs: Vec<f64> = histories.iter().filter_map(|h| at(h, s.t)).collect();
            if xs.is_empty() {
                return None;
            }
            let n = xs.len() as f64;
            let mean = xs.iter().sum::<f64>() / n;
            let var = if xs.len() > 1 {
                xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)
            } else {
                0.0
            };
            let half = 1.96 * var.sqrt();
            Some((s.t, mean, mean - half, mean + half))
        })
        .collect()
}

/// The statistics of `runs` (module docs) against `other`.
pub fn statistics(runs: &[RunSummary], other: Option<&RunSummary>) -> Ensemble {
    let names: Vec<&str> = RunSummary::headline_names().to_vec();
    let other_values = other.map(headline);
    let mut quantities = Vec::new();
    for (i, name) in names.iter().enumerate() {
        let xs: Vec<f64> = runs.iter().filter_map(|r| headline(r)[i].1).collect();
        if xs.is_empty() {
            continue;
        }
        let n = xs.len() as f64;
        let mean = xs.iter().sum::<f64>() / n;
        let var = if xs.len() > 1 {
            xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)
        } else {
            0.0
        };
        let std = var.sqrt();
        let other_model = other_values.as_ref().and_then(|o| o[i].1);
        quantities.push(EnsembleQuantity {
            name: name.to_string(),
            mean,
            std,
            low: mean - 1.96 * std,
            high: mean + 1.96 * std,
            other_model,
            spread_exceeds_model_difference: other_model
                .map(|o| 2.0 * 1.96 * std > (mean - o).abs()),
        });
    }
    let wide: Vec<&str> = quantities
        .iter()
        .filter(|q| q.spread_exceeds_model_difference == Some(true))
        .map(|q| q.name.as_str())
        .collect();
    let note = if wide.is_empty() {
        String::new()
    } else {
        format!(
            "the spread of the copies exceeds the difference between the models for {}: single runs cannot tell the models apart on these",
            wide.join(", ")
        )
    };
    Ensemble {
        members: runs.len(),
        perturbation: format!(
            "copy k on the incline φ + δ_k, δ_k = ±{PERTURBATION:.0e}, ±{:.0e}, … rad (the starting pose turned relative to gravity)",
            2.0 * PERTURBATION
        ),
        invalid_members: runs.iter().filter(|r| !r.valid).count(),
        quantities,
        note,
    }
}

impl RunSummary {
    /// The keys of [`headline`], in its order.
    pub fn headline_names() -> [&'static str; 9] {
        [
            "first_impact.t",
            "first_impact.omega_before",
            "impacts",
            "mean_axle_height",
            "axle_height_oscillation",
            "mean_speed",
            "final_speed",
            "airborne_fraction",
            "slip_fraction",
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offsets_alternate_and_grow_and_statistics_are_the_sample_ones() {
        assert_eq!(
            (0..4).map(offset).collect::<Vec<_>>(),
            [1e-6, -1e-6, 2e-6, -2e-6]
        );
        let base = crate::summary::RunSummary::of(&crate::sample::RollingResult::default(), 1.0);
        let runs: Vec<RunSummary> = [1.0, 2.0, 3.0]
            .iter()
            .map(|&v| RunSummary {
                mean_speed: v,
                ..base.clone()
            })
            .collect();
        let other = RunSummary {
            mean_speed: 2.5,
            ..base.clone()
        };
        let e = statistics(&runs, Some(&other));
        let q = e
            .quantities
            .iter()
            .find(|q| q.name == "mean_speed")
            .unwrap();
        assert_eq!((q.mean, q.std), (2.0, 1.0));
        assert!((q.high - q.low - 2.0 * 1.96).abs() < 1e-12);
        assert_eq!(q.spread_exceeds_model_difference, Some(true));
        assert!(e.note.contains("mean_speed"), "{}", e.note);
    }
}
