//! The sampled history of a rolling run and its summary figures, shared by the rigid and
//! the full model.
//!
//! Samples are kept every output interval (1 ms by default). The summary skips the first
//! second of a run longer than a second (the start from rest): over the samples with
//! t ≥ t_skip (t_skip = 1 s, or 0 for a run of at most 1 s), the axle height oscillation is
//! the RMS deviation √(Σ (h − h̄)² / N) about the mean h̄, and the mean speed
//! (s_last − s_first) / (t_last − t_first). The final speed is the difference quotient of
//! the last two samples; the required friction max |F_t| / N over the samples with N > 0.

use crate::validity::{ImpactRecord, RollValidity};

/// One recorded sample.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RollingSample {
    /// Time (s).
    pub t: f64,
    /// Axle position along the slope (m, downhill positive).
    pub s: f64,
    /// Axle height above the slope (m).
    pub h: f64,
    /// Position of the contact pair along the slope (m); in flight, the last contact's.
    pub pivot: f64,
    /// Angular velocity about the axle (rad/s, positive when rolling downhill).
    pub omega: f64,
    /// Normal contact force (N), 0 in flight.
    pub normal: f64,
    /// Tangential contact force (N, positive downhill).
    pub tangential: f64,
    /// Kinetic plus gravitational energy (J), zero at the start.
    pub energy: f64,
    /// Mean sliding speed of the loaded contact nodes along the slope (m/s); in the rigid model
    /// the contact vertex's sliding speed |w| (0 when pivoting, resting or flying).
    pub slip: f64,
}

/// The result of a rolling run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RollingResult {
    /// Samples at the output interval.
    pub samples: Vec<RollingSample>,
    /// Number of contact-pair impacts.
    pub impacts: usize,
    /// RMS deviation of the axle height about its mean, after the first second (m).
    pub axle_height_oscillation: f64,
    /// Mean downhill speed of the axle after the first second (m/s).
    pub mean_speed: f64,
    /// Largest contact force magnitude (N).
    pub max_reaction: f64,
    /// Smallest normal force (N); negative means the real wheel would lift off.
    pub min_normal: f64,
    /// Sampled time with N < 0 (s).
    pub lift_off_time: f64,
    /// Largest |F_t|/N with N > 0: the friction coefficient rolling without slip needs.
    pub required_friction: f64,
    /// Mean over the samples with contact of the contact nodes' sliding speed (m/s).
    pub mean_slip_speed: f64,
    /// Downhill speed of the axle at the end of the run (m/s).
    pub final_speed: f64,
    /// Every impact of a new contact pair, in time order.
    pub impact_log: Vec<ImpactRecord>,
    /// Admissibility of the run.
    pub validity: RollValidity,
}

impl RollingResult {
    /// Mean axle height above the slope (m) over the samples from 1 s on when `t_end` (the
    /// requested run time) exceeds 1 s, else over every sample.
    pub fn mean_axle_height(&self, t_end: f64) -> f64 {
        let skip = if t_end > 1.0 { 1.0 } else { 0.0 };
        let tail: Vec<f64> = self
            .samples
            .iter()
            .filter(|s| s.t >= skip - 1e-12)
            .map(|s| s.h)
            .collect();
        tail.iter().sum::<f64>() / tail.len().max(1) as f64
    }
}

/// Summary figures of a sampled rolling history (shared by the rigid and the full model).
pub(crate) fn summarise(
    samples: Vec<RollingSample>,
    impacts: usize,
    output_dt: f64,
) -> RollingResult {
    let t_end = samples.last().map_or(0.0, |s| s.t);
    let skip = if t_end > 1.0 { 1.0 } else { 0.0 };
    let tail: Vec<&RollingSample> = samples.iter().filter(|s| s.t >= skip - 1e-12).collect();
    let mean_h = tail.iter().map(|s| s.h).sum::<f64>() / tail.len() as f64;
    let rms = (tail.iter().map(|s| (s.h - mean_h).powi(2)).sum::<f64>() / tail.len() as f64).sqrt();
    let (first, last) = (tail[0], tail[tail.len() - 1]);
    let mean_speed = if last.t > first.t {
        (last.s - first.s) / (last.t - first.t)
    } else {
        0.0
    };
    let with_contact: Vec<f64> = samples
        .iter()
        .filter(|s| s.normal > 0.0)
        .map(|s| s.slip)
        .collect();
    let mean_slip_speed = if with_contact.is_empty() {
        0.0
    } else {
        with_contact.iter().sum::<f64>() / with_contact.len() as f64
    };
    let final_speed = match samples.len() {
        0 | 1 => 0.0,
        n => (samples[n - 1].s - samples[n - 2].s) / (samples[n - 1].t - samples[n - 2].t),
    };
    RollingResult {
        final_speed,
        impact_log: Vec::new(),
        validity: RollValidity::default(),
        mean_slip_speed,
        impacts,
        axle_height_oscillation: rms,
        mean_speed,
        max_reaction: samples
            .iter()
            .map(|s| s.normal.hypot(s.tangential))
            .fold(0.0, f64::max),
        min_normal: samples
            .iter()
            .map(|s| s.normal)
            .fold(f64::INFINITY, f64::min),
        lift_off_time: samples.iter().filter(|s| s.normal < 0.0).count() as f64 * output_dt,
        required_friction: samples
            .iter()
            .filter(|s| s.normal > 0.0)
            .map(|s| s.tangential.abs() / s.normal)
            .fold(0.0, f64::max),
        samples,
    }
}
