//! Ensemble statistics of a rolling run ([`ensemble`]): where the motion is chaotic (hops on a
//! steep slope), one run's numbers are one draw; K copies from perturbed starting states give
//! the mean and a 95 % interval of every headline quantity.
//!
//! Copy k (k = 0 … K−1) starts from the run's state with the wheel's pose relative to gravity
//! turned by δ_k = (−1)ᵏ ⌊k/2 + 1⌋ · [`PERTURBATION`] (±10⁻⁶ rad, ±2·10⁻⁶ rad, …): the slope and
//! the wheel on it are turned together about the axle, i.e. the incline is φ + δ_k. The copies
//! run in parallel (one scoped thread per core, each taking the next copy), without the
//! convergence check. Per quantity: the mean x̄, the sample standard deviation s and the 95 %
//! prediction interval of one more copy, x̄ ± c_K s with c_K = t_{0.975, K−1} √(1 + 1/K)
//! ([`prediction_factor`]: Student's t, since s is itself estimated from K copies; 3.56 for
//! K = 4, → 1.96 for many copies), and — when the other model's run is given —
//! its value and whether the interval's width exceeds the distance |x̄ − x_other| between the
//! models (then the models cannot be told apart on that quantity by single runs).
//!
//! The spread of the copies is chaotic spread, not the error of the step: the same K copies
//! also run at the refined resolution ([`crate::convergence::refined`]: half the step; the
//! ground is the model's), and the interval of each quantity covers
//! both ensembles and the extrapolation of their means to a vanishing step with order 1,
//! x̄_∞ = 2 x̄_{h/2} − x̄_h:
//!
//! > [low, high] = hull of x̄_h ± c_K s_h, x̄_{h/2} ± c_K s_{h/2}, x̄_∞ ± c_K s_{h/2}
//!
//! `bias` = x̄_{h/2} − x̄_h is reported beside it. The ensemble then costs K runs at the step
//! and K at half of it (3 K runs' work).

use crate::fidelity::Decision;
use crate::run::{roll_decided, Wheel};
use crate::sample::RollingSample;
use crate::settings::RunSpec;
use crate::summary::RunSummary;
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
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
    /// Lower end of the 95 % prediction interval, mean − c_K std, widened to cover the refined
    /// ensemble and the extrapolated mean (module docs).
    pub low: f64,
    /// Upper end, mean + c_K std, widened to cover the refined ensemble and the
    /// extrapolated mean (module docs).
    pub high: f64,
    /// The mean of the copies at the refined resolution.
    pub refined_mean: Option<f64>,
    /// `refined_mean − mean`: the step's bias on the mean, to first order.
    pub bias: Option<f64>,
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
    /// What the refined copies changed (empty when only one resolution ran).
    #[serde(default)]
    pub refinement: String,
    /// The copies that were not valid (their own assumptions, not convergence).
    pub invalid_members: usize,
    /// One entry per headline quantity.
    pub quantities: Vec<EnsembleQuantity>,
    /// The quantities whose spread exceeds the difference between the models, one sentence;
    /// empty when none does or no other model ran.
    pub note: String,
}

/// An ensemble and each copy's sampled history (in copy order).
pub type WithHistories = (Ensemble, Vec<Vec<RollingSample>>);

/// One slot per copy for its summary and samples (or error).
type Slots<E> = Mutex<Vec<Option<Result<(RunSummary, Vec<RollingSample>), E>>>>;

pub use crate::summary::headline;

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
    let (ensemble, _) = copies(wheel, spec, decision, members, threads, other, None)?;
    Ok(ensemble)
}

/// As [`ensemble_with_samples`], every copy stopping at its next sample once `stop` is set
/// (the run's observer's [`Observer::stop_flag`](crate::Observer::stop_flag), e.g. on
/// Ctrl-C): then `None`, no statistics drawn from copies cut short, and no copy started
/// after it.
pub fn ensemble_until<W>(
    wheel: &W,
    spec: &RunSpec,
    decision: &Decision,
    members: usize,
    threads: usize,
    other: Option<&RunSummary>,
    stop: &AtomicBool,
) -> Result<Option<WithHistories>, W::Error>
where
    W: Wheel + Sync,
    W::Error: Send,
{
    let (ensemble, stopped) = copies(wheel, spec, decision, members, threads, other, Some(stop))?;
    Ok((!stopped).then_some(ensemble))
}

/// The ensemble's copies run and gathered, and whether `stop` was set before they all ended.
fn copies<W>(
    wheel: &W,
    spec: &RunSpec,
    decision: &Decision,
    members: usize,
    threads: usize,
    other: Option<&RunSummary>,
    stop: Option<&AtomicBool>,
) -> Result<(WithHistories, bool), W::Error>
where
    W: Wheel + Sync,
    W::Error: Send,
{
    let stopped = || stop.is_some_and(|f| f.load(Ordering::Relaxed));
    let fine = crate::convergence::refined(spec);
    // copies 0..K at the step, K..2K at the refined resolution, the costly ones first
    let specs: Vec<RunSpec> = (0..2 * members)
        .map(|j| {
            let mut copy = if j < members { fine } else { *spec };
            copy.settings.incline += offset(j % members);
            copy
        })
        .collect();
    let next = AtomicUsize::new(0);
    let out: Slots<W::Error> = Mutex::new(specs.iter().map(|_| None).collect());
    std::thread::scope(|s| {
        for _ in 0..threads.clamp(1, specs.len().max(1)) {
            s.spawn(|| loop {
                let j = next.fetch_add(1, Ordering::Relaxed);
                let Some(copy) = specs.get(j).filter(|_| !stopped()) else {
                    break;
                };
                let mut until = stop.map(crate::observer::StopOn);
                let observer = until.as_mut().map(|u| u as &mut dyn crate::Observer);
                let r = roll_decided(wheel, copy, decision, &[], observer).map(|r| {
                    let summary = RunSummary::of(&r.result, spec.t_end);
                    (summary, r.result.samples)
                });
                out.lock().unwrap_or_else(|e| e.into_inner())[j] = Some(r);
            });
        }
    });
    if stopped() {
        return Ok(((statistics(&[], other), Vec::new()), true));
    }
    let (mut runs, mut refined_runs) = (Vec::new(), Vec::new());
    let mut histories = Vec::with_capacity(members);
    let slots = out.into_inner().unwrap_or_else(|e| e.into_inner());
    for (j, r) in slots.into_iter().enumerate() {
        let Some(r) = r else { continue };
        let (summary, samples) = r?;
        if j < members {
            refined_runs.push(summary);
        } else {
            runs.push(summary);
            histories.push(samples);
        }
    }
    let label = crate::convergence::refinement(spec, decision_fidelity(decision));
    let e = statistics(&runs, other).with_refined(&refined_runs, label);
    Ok(((e, histories), false))
}

/// The model a decision runs (the full one when it may run both: the costlier refinement).
fn decision_fidelity(decision: &Decision) -> crate::fidelity::Fidelity {
    match decision.plan {
        crate::fidelity::Plan::Rigid => crate::fidelity::Fidelity::Rigid,
        _ => crate::fidelity::Fidelity::Full,
    }
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
            low: mean - prediction_factor(xs.len()) * std,
            high: mean + prediction_factor(xs.len()) * std,
            refined_mean: None,
            bias: None,
            other_model,
            spread_exceeds_model_difference: other_model
                .map(|o| 2.0 * prediction_factor(xs.len()) * std > (mean - o).abs()),
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
        refinement: String::new(),
        invalid_members: runs.iter().filter(|r| !r.valid).count(),
        quantities,
        note,
    }
}

impl Ensemble {
    /// The statistics widened by the same copies at the refined resolution, `refined`
    /// (`refinement`: what it changed), as the module docs say.
    pub fn with_refined(mut self, refined: &[RunSummary], refinement: &str) -> Self {
        let fine = statistics(refined, None);
        for q in &mut self.quantities {
            let Some(f) = fine.quantities.iter().find(|f| f.name == q.name) else {
                continue;
            };
            let limit = 2.0 * f.mean - q.mean;
            let half = (f.high - f.low) / 2.0;
            q.low = q.low.min(f.low).min(limit - half);
            q.high = q.high.max(f.high).max(limit + half);
            q.refined_mean = Some(f.mean);
            q.bias = Some(f.mean - q.mean);
        }
        self.refinement = refinement.to_string();
        self.invalid_members += fine.invalid_members;
        self
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

/// Student's t quantile t_{0.975, ν} for ν = 1 … 30 degrees of freedom.
const T_975: [f64; 30] = [
    12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
    2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
    2.052, 2.048, 2.045, 2.042,
];

/// c_K = t_{0.975, K−1} √(1 + 1/K): the half-width of the 95 % prediction interval of one more
/// draw in units of the sample standard deviation of K draws (1.96 beyond 30 degrees of
/// freedom; 0 for K < 2, where no spread is known).
///
/// ```
/// use wheel_rolling::ensemble::prediction_factor;
/// assert!((prediction_factor(4) - 3.182 * 1.25f64.sqrt()).abs() < 1e-12);
/// assert_eq!(prediction_factor(1), 0.0);
/// ```
pub fn prediction_factor(k: usize) -> f64 {
    if k < 2 {
        return 0.0;
    }
    let t = T_975.get(k - 2).copied().unwrap_or(1.96);
    t * (1.0 + 1.0 / k as f64).sqrt()
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
        // K = 3: t_{0.975, 2} = 4.303, √(1 + 1/3)
        let c = 4.303 * (4.0f64 / 3.0).sqrt();
        assert!((q.high - q.low - 2.0 * c).abs() < 1e-12);
        assert!((prediction_factor(1000) - 1.96).abs() < 0.01);
        assert_eq!(q.spread_exceeds_model_difference, Some(true));
        assert!(e.note.contains("mean_speed"), "{}", e.note);
    }

    #[test]
    fn the_refined_ensemble_and_its_extrapolation_widen_the_interval() {
        let base = crate::summary::RunSummary::of(&crate::sample::RollingResult::default(), 1.0);
        let at = |v: f64| RunSummary {
            mean_speed: v,
            ..base.clone()
        };
        let coarse: Vec<RunSummary> = [10.0, 10.2, 10.4].iter().map(|&v| at(v)).collect();
        // the refined copies sit 1 higher: the step's bias; the extrapolated mean 12.2
        let fine: Vec<RunSummary> = [11.0, 11.2, 11.4].iter().map(|&v| at(v)).collect();
        let e = statistics(&coarse, None).with_refined(&fine, "dt/2");
        let q = e
            .quantities
            .iter()
            .find(|q| q.name == "mean_speed")
            .unwrap();
        assert_eq!(e.refinement, "dt/2");
        assert!((q.bias.unwrap() - 1.0).abs() < 1e-12);
        assert!((q.refined_mean.unwrap() - 11.2).abs() < 1e-12);
        let half = prediction_factor(3) * 0.2;
        // from the coarse ensemble's lower end to the extrapolation's upper end
        assert!((q.low - (10.2 - half)).abs() < 1e-12, "{q:?}");
        assert!((q.high - (12.2 + half)).abs() < 1e-12, "{q:?}");
        assert!((q.mean - 10.2).abs() < 1e-12);
    }
}
