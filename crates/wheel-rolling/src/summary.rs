//! The per-run summary every rolling report shows ([`RunSummary`]), and one wheel's run as a
//! comparison table shows it ([`WheelRun`]: the model, the wheel's m and I₁, its plastic
//! impact ratio and the summary). The toroid's `RollReport` and the T-bar's `tbar roll`
//! rows are built from these.

use crate::fidelity::Fidelity;
use crate::rigid::Polygon;
use crate::sample::RollingResult;
use crate::validity::ImpactRecord;
use serde::{Deserialize, Serialize};
use tensegrity_core::Warning;
use tensegrity_derive::Columns;
use tensegrity_dynamics::Convergence;

/// The first impact of a run (the JSON's `first_impact`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Columns, Deserialize)]
pub struct FirstImpact {
    /// Time (s).
    #[column(unit = "s")]
    pub t: f64,
    /// Angular velocity about the axle before the impact (rad/s).
    #[column(unit = "rad/s")]
    pub omega_before: f64,
    /// Angular velocity about the axle after it (rad/s).
    #[column(unit = "rad/s")]
    pub omega_after: f64,
}

impl From<&ImpactRecord> for FirstImpact {
    fn from(i: &ImpactRecord) -> Self {
        Self {
            t: i.t,
            omega_before: i.omega_before,
            omega_after: i.omega_after,
        }
    }
}

/// The summary figures of one rolling run (either model), with its validity.
#[derive(Debug, Clone, PartialEq, Serialize, Columns, Deserialize)]
pub struct RunSummary {
    /// Whether the run stayed inside its model's assumptions (no warning).
    pub valid: bool,
    /// What the run violated, one sentence each.
    pub warnings: Vec<Warning>,
    /// Set when the run stopped before `t_end` (an integration failure or its observer): the
    /// time (s) of the last state kept; every figure covers [0, stopped_at] only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    #[column(skip)]
    pub stopped_at: Option<f64>,
    /// Number of contact-pair impacts.
    pub impacts: usize,
    /// The first impact (null if none).
    #[column(nested)]
    pub first_impact: Option<FirstImpact>,
    /// RMS deviation of the axle height about its mean, after the first second (m; over the
    /// whole run if shorter).
    #[column(unit = "m")]
    pub axle_height_oscillation: f64,
    /// Mean axle height above the slope after the first second (m).
    #[column(unit = "m")]
    pub mean_axle_height: f64,
    /// Mean downhill speed of the axle after the first second (m/s).
    #[column(unit = "m/s")]
    pub mean_speed: f64,
    /// Downhill speed of the axle at the end (m/s).
    #[column(unit = "m/s")]
    pub final_speed: f64,
    /// Largest contact force magnitude (N).
    #[column(unit = "N")]
    pub max_reaction: f64,
    /// Smallest normal force (N); negative means the ground pulled.
    #[column(unit = "N")]
    pub min_normal_force: f64,
    /// Fraction of the time with no contact.
    pub airborne_fraction: f64,
    /// Fraction of the time in contact and sliding.
    pub slip_fraction: f64,
    /// Deepest penetration of a contact node below the slope (m).
    #[column(unit = "m")]
    pub max_penetration: f64,
    /// Energy-budget residual over the budget's largest term (dimensionless).
    pub energy_balance_error: f64,
    /// Sampled time with a negative normal force (s).
    #[column(unit = "s")]
    pub lift_off_time: f64,
    /// Largest |F_t|/N: the friction coefficient rolling without slip needs.
    pub required_friction: f64,
    /// Mean sliding speed of the loaded contact nodes (m/s).
    #[column(unit = "m/s")]
    pub mean_slip_speed: f64,
    /// The headline quantities re-estimated at a refined resolution
    /// ([`crate::convergence`]); null when the check was skipped or the run stopped early.
    #[column(nested)]
    pub convergence: Option<Convergence>,
}

impl RunSummary {
    /// Whether the run is not valid only because headline quantities did not converge (it
    /// finished, and every warning is `not_converged`): a finer step is its remedy.
    pub fn only_unconverged(&self) -> bool {
        !self.valid
            && self.stopped_at.is_none()
            && self.warnings.iter().all(|w| w.kind() == "not_converged")
    }

    /// The summary of `r`, a run asked for `t_end` seconds (the mean axle height skips the
    /// first second when `t_end` > 1 s).
    pub fn of(r: &RollingResult, t_end: f64) -> Self {
        let v = &r.validity;
        let mut warnings = v.warnings.clone();
        // a run that left double precision says so: its numbers are no answer
        let headline = [
            ("mean_speed", r.mean_speed),
            ("final_speed", r.final_speed),
            ("mean_axle_height", r.mean_axle_height(t_end)),
            ("axle_height_oscillation", r.axle_height_oscillation),
            ("max_reaction", r.max_reaction),
        ];
        for (quantity, x) in headline {
            if !x.is_finite() {
                let quantity = quantity.to_string();
                warnings.push(Warning::NonFinite { quantity });
            }
        }
        Self {
            valid: warnings.is_empty(),
            warnings,
            stopped_at: v.stopped_at,
            impacts: r.impacts,
            first_impact: r.impact_log.first().map(FirstImpact::from),
            axle_height_oscillation: r.axle_height_oscillation,
            mean_axle_height: r.mean_axle_height(t_end),
            mean_speed: r.mean_speed,
            final_speed: r.final_speed,
            max_reaction: r.max_reaction,
            min_normal_force: v.min_normal_force,
            airborne_fraction: v.airborne_fraction,
            slip_fraction: v.slip_fraction,
            max_penetration: v.max_penetration,
            energy_balance_error: v.energy_balance_error,
            lift_off_time: r.lift_off_time,
            required_friction: r.required_friction,
            mean_slip_speed: r.mean_slip_speed,
            convergence: v.convergence.clone(),
        }
    }
}

/// One wheel's run in a comparison: the model, the wheel and the summary.
#[derive(Debug, Clone, PartialEq, Serialize, Columns, Deserialize)]
pub struct WheelRun {
    /// The model that ran.
    pub model: Fidelity,
    /// Why that model ran: "requested", or the `auto` decision's reasoning
    /// ([`crate::fidelity::Decision::reason`]); empty when not given.
    #[serde(default)]
    pub fidelity_reason: String,
    /// Mass m (kg).
    #[column(unit = "kg")]
    pub mass_kg: f64,
    /// I₁ about the axle (kg m²).
    #[serde(rename = "I1")]
    #[column(unit = "kg m^2")]
    pub i1: f64,
    /// ω⁺/ω⁻ of a plastic pivot-to-pivot impact of its polygon.
    pub impact_ratio: f64,
    /// The run's figures.
    #[serde(flatten)]
    pub summary: RunSummary,
}

impl WheelRun {
    /// The run `r` (asked for `t_end` s) of the wheel `polygon` with `model`.
    pub fn of(model: Fidelity, polygon: &Polygon, r: &RollingResult, t_end: f64) -> Self {
        Self {
            model,
            fidelity_reason: String::new(),
            mass_kg: polygon.mass,
            i1: polygon.i1,
            impact_ratio: polygon.impact_ratio(),
            summary: RunSummary::of(r, t_end),
        }
    }

    /// The run with `reason` as its `fidelity_reason`.
    pub fn because(self, reason: impl Into<String>) -> Self {
        Self {
            fidelity_reason: reason.into(),
            ..self
        }
    }
}

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
