//! Validity of a rolling run: the figures that say whether the model was used inside its
//! assumptions (a ground that only pushes, a wheel that stays above the slope, an energy
//! budget that closes), shared by the rigid and the full model.
//!
//! A run is `valid` when it has no warning. The warnings are plain sentences naming the
//! violated assumption and its size; the front ends print them (the command line on stderr
//! as well).

use serde::{Deserialize, Serialize};
use tensegrity_core::Warning;
use tensegrity_dynamics::Convergence;

/// One contact impact (a new contact pair touching the slope).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ImpactRecord {
    /// Time of the impact (s).
    pub t: f64,
    /// Angular velocity about the axle just before (rad/s, positive rolling downhill).
    pub omega_before: f64,
    /// Angular velocity about the axle just after (rad/s).
    pub omega_after: f64,
    /// Normal impulse of the ground on the wheel (N·s).
    pub normal_impulse: f64,
    /// Tangential impulse of the ground on the wheel (N·s, positive downhill).
    pub tangential_impulse: f64,
}

/// The admissibility figures of a rolling run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct RollValidity {
    /// Smallest normal contact force over the run (N); negative means the ground pulled.
    pub min_normal_force: f64,
    /// Fraction of the simulated time with no contact (flight).
    pub airborne_fraction: f64,
    /// Fraction of the simulated time in contact with sliding.
    pub slip_fraction: f64,
    /// Deepest penetration of a contact node below the slope (m, ≥ 0).
    pub max_penetration: f64,
    /// Residual of the energy budget (ΔE − impact losses − friction work − damping work)
    /// over the largest energy term of the run: dimensionless.
    pub energy_balance_error: f64,
    /// What the run violated, one warning each; empty when the run is valid.
    pub warnings: Vec<Warning>,
    /// When the integration failed before the end time, or the run's observer stopped it:
    /// the time (s) of the last state kept. The figures cover [0, stopped_at] only, and a
    /// warning says why it stopped.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped_at: Option<f64>,
    /// The headline quantities at a refined resolution ([`crate::convergence`]); `None` when
    /// not checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub convergence: Option<Convergence>,
}

impl RollValidity {
    /// A run is valid when nothing was flagged.
    pub fn valid(&self) -> bool {
        self.warnings.is_empty()
    }
}
