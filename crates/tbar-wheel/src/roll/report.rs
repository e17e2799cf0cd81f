//! The report of `tbar roll`: one row per number of treads, the T-bar wheel's run beside the
//! toroid's (wheel-rolling's [`WheelRun`]), the full model's structure, and tip-over.

use crate::params::RimMode;
use crate::rolling::{MassProperties, TipOver};
use crate::rolling_full::{FullPrestress, FullWheel};
use serde::Serialize;
use std::f64::consts::PI;
use tensegrity_core::Warning;
use tensegrity_derive::Columns;
use wheel_rolling::{Fidelity, FidelityChoice, WheelRun};

/// What only the full T-bar run has.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FullDetails {
    /// Nodes of the structure (rim body included).
    pub nodes: usize,
    /// Bars (treads' and rim body's).
    pub bars: usize,
    /// Strings.
    pub strings: usize,
    /// Rim-body bars kept (the isostatic rim).
    pub rim_bars: usize,
    /// Of these, spokes (to the two hubs).
    pub rim_spokes: usize,
    /// Rim-body bars left out as redundant (a rigid bar-only self-stress).
    pub redundant_rim_bars: usize,
    /// The prestress it was built with.
    pub prestress: FullPrestress,
    /// Normal ground damping per contact node (N·s/m).
    pub ground_damping: f64,
}

impl FullDetails {
    /// The structure of `w`, run with `ground_damping` (N·s/m).
    pub fn of(w: &FullWheel, ground_damping: f64) -> Self {
        Self {
            nodes: w.structure.n_nodes(),
            bars: w.structure.n_bars(),
            strings: w.structure.n_strings(),
            rim_bars: w.geometry.rim.as_ref().map_or(0, |r| r.bars.len()),
            rim_spokes: w.geometry.rim.as_ref().map_or(0, |r| r.spokes),
            redundant_rim_bars: w.redundant_rim_bars,
            prestress: w.prestress,
            ground_damping,
        }
    }
}

/// One number of treads.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct TbarRollRow {
    /// Treads per wheel n = π/φ (the polygon's sides).
    pub treads: usize,
    /// φ = π/n (rad).
    #[column(unit = "rad")]
    pub phi: f64,
    /// The T-bar wheel's mass properties.
    #[column(skip)]
    pub mass_properties: Option<MassProperties>,
    /// The T-bar wheel's run (of the model asked for).
    #[column(
        nested,
        only = "mass_kg, I1, impact_ratio, valid, impacts, first_impact.t, axle_height_oscillation, mean_speed, final_speed, min_normal_force, airborne_fraction, slip_fraction, max_penetration, energy_balance_error, convergence.converged"
    )]
    pub tbar: Option<WheelRun>,
    /// Full model only: the rigid model of the same polygon, mass and I₁, for the first
    /// contact phase.
    #[column(skip)]
    pub tbar_rigid_reference: Option<WheelRun>,
    /// Full model only: the structure and its prestress.
    #[column(skip)]
    pub full: Option<FullDetails>,
    /// The toroid of equal outer radius and n sides.
    #[column(
        nested,
        only = "mass_kg, I1, valid, impacts, axle_height_oscillation, mean_speed"
    )]
    pub toroid: Option<WheelRun>,
    /// Out-of-plane tip-over of the T-bar structure (its own weight).
    #[column(nested, only = "critical_lateral_force, min_friction_to_tip")]
    pub tipover: Option<TipOver>,
    /// Why a part is missing.
    pub errors: Vec<String>,
}

impl TbarRollRow {
    /// An empty row of `n` treads.
    pub fn new(n: usize) -> Self {
        Self {
            treads: n,
            phi: PI / n as f64,
            mass_properties: None,
            tbar: None,
            tbar_rigid_reference: None,
            full: None,
            toroid: None,
            tipover: None,
            errors: Vec::new(),
        }
    }
}

/// The report of `tbar roll`.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct TbarRollReport {
    /// The rolling model that ran: `rigid` (reduced polygon) or `full` (tensegrity
    /// dynamics); with `auto`, full when any row's T-bar run used it.
    pub model: Fidelity,
    /// The model asked for: `rigid`, `full` or `auto` (each run's choice and its reason are
    /// the row runs' `model` and `fidelity_reason`).
    pub fidelity: FidelityChoice,
    /// Whether the full tensegrity rolling of the T-bar wheel ran (`fidelity = full`).
    pub full_tensegrity_rolling: bool,
    /// `wheel` or `extended wheel`.
    pub structure: &'static str,
    /// `body` (rim body's bars in the mass) or `fixed` (massless rigid rim).
    pub rim: RimMode,
    /// The full model's ground contact (`penalty`, `thesis` or `stick`) when the full model
    /// ran, else `null` (the rigid model has its own unilateral impacts).
    #[column(skip)]
    pub contact: Option<wheel_rolling::ContactKind>,
    /// Slope angle (rad).
    #[column(unit = "rad")]
    pub incline_rad: f64,
    /// Simulated time (s).
    #[column(unit = "s")]
    pub t_end: f64,
    /// Every run of every row (the T-bar's and the toroid's) valid, and no row with an error
    /// ([`TbarRollReport::judged`]).
    pub valid: bool,
    /// Each run's warnings and each row's errors, prefixed by the row and the run.
    pub warnings: Vec<Warning>,
    /// One row per number of treads.
    #[column(first)]
    pub rows: Vec<TbarRollRow>,
}

impl TbarRollReport {
    /// The report with `valid` and `warnings` gathered from its rows: the T-bar's and the
    /// toroid's runs (the full model's rigid reference is a comparison, not the answer) and
    /// the rows' errors.
    pub fn judged(mut self) -> Self {
        let mut warnings = Vec::new();
        for row in &self.rows {
            let n = row.treads;
            for (what, run) in [("T-bar", &row.tbar), ("toroid", &row.toroid)] {
                if let Some(run) = run {
                    let w = &run.summary.warnings;
                    warnings.extend(w.iter().map(|w| w.clone().in_run(n, what)));
                }
            }
            warnings.extend(row.errors.iter().map(|e| Warning::RowFailed {
                sides: n,
                error: e.to_string(),
            }));
        }
        self.valid = warnings.is_empty();
        self.warnings = warnings;
        self
    }
}
