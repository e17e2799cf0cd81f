//! Lateral stability while rolling (the thesis's conclusion: "higher complexity and a wider
//! tread improve rolling stability"), with the full 3-D dynamics.
//!
//! The prestressed wheel starts at rest on a side of its polygon (as in
//! [`crate::tipover_dynamic`]) on a plane that slopes by the incline φ downhill (+ι̂₂) and by
//! the side slope ψ across (+ι̂₁): in the plane's frame gravity is
//!
//! > g (sin ψ, cos ψ sin φ, −cos ψ cos φ).
//!
//! The side slope pulls the wheel over as it rolls; the lean angle (the tilt of the wheel's
//! axis out of the plane, [`crate::tipover_dynamic`]'s definition) is recorded. A wheel that
//! leans past [`crate::tipover_dynamic::TIPPED_LEAN`] has fallen. The statically expected
//! critical side slope of a wheel resting on a side is tan ψ = T / (2h), h = R_o cos(π/n)
//! (the weight's line leaves the tread), so a wider tread and — through the hub height only
//! weakly — more sides raise it; the run shows what rolling adds.

use crate::analysis::analyse;
use crate::builder::Toroid;
use crate::error::Result;
use crate::tipover_dynamic::{lean_and_hub, DynamicTipover, RunValidity, TIPPED_LEAN};
use serde::Serialize;
use std::f64::consts::PI;
use tensegrity_core::dynamics::{IntegratorKind, Quantities, Simulation, SimulationSettings};

/// A lean-while-rolling run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeanRolling {
    /// Incline φ downhill (rad).
    pub incline: f64,
    /// Side slope ψ (rad).
    pub side_slope: f64,
    /// Simulated time (s).
    pub t_end: f64,
    /// Wheel, ground and integration settings (its ramp fields are unused).
    pub wheel: DynamicTipover,
}

impl Default for LeanRolling {
    /// 15° down, 5° across, 3 s, with [`DynamicTipover`]'s stiff wheel and ground.
    fn default() -> Self {
        Self {
            incline: 15f64.to_radians(),
            side_slope: 5f64.to_radians(),
            t_end: 3.0,
            wheel: DynamicTipover::default(),
        }
    }
}

/// One sample of a lean-while-rolling run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RollingLeanSample {
    /// Time (s).
    pub t: f64,
    /// Lean angle (rad).
    pub lean: f64,
    /// Hub travel downhill (m).
    pub downhill: f64,
    /// Hub drift across the slope (m).
    pub across: f64,
}

/// The result of [`LeanRolling::run`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LeanRollingReport {
    /// Number of sides n.
    pub sides: usize,
    /// Outer tread width T (m).
    pub outer_tread: f64,
    /// Incline (rad).
    pub incline: f64,
    /// Side slope (rad).
    pub side_slope: f64,
    /// Wheel mass (kg).
    pub mass_kg: f64,
    /// Static critical side slope atan(T / 2h) of the wheel at rest on a side (rad).
    pub static_critical_side_slope: f64,
    /// Largest |lean| (rad).
    pub max_lean: f64,
    /// Lean at the end (rad).
    pub final_lean: f64,
    /// Whether it fell (|lean| > the tipped threshold).
    pub fell: bool,
    /// Time at which it fell (s).
    pub fall_time: Option<f64>,
    /// Hub travel downhill at the end (m).
    pub downhill: f64,
    /// Deepest contact node below the plane (m).
    pub max_penetration: f64,
    /// No warning: the run stayed inside its model.
    pub valid: bool,
    /// What the run violated (penetration past 1 % of R_o, integrator drift).
    pub warnings: Vec<String>,
    /// The history (not serialised).
    #[serde(skip)]
    pub samples: Vec<RollingLeanSample>,
}

impl LeanRolling {
    /// Rolls `toroid` down the cross-sloped plane.
    pub fn run(&self, toroid: &Toroid) -> Result<LeanRollingReport> {
        use tensegrity_core::validate::{finite, non_negative, positive};
        self.wheel.validate()?;
        positive("t_end", self.t_end)?;
        non_negative("incline", self.incline)?;
        finite("side_slope", self.side_slope)?;
        if self.incline >= PI / 2.0 || self.side_slope.abs() >= PI / 2.0 {
            return Err(tensegrity_core::CoreError::invalid_parameter(
                "side_slope",
                self.side_slope,
                "the incline and the side slope must lie in (−π/2, π/2)",
            )
            .into());
        }
        let g = self.wheel.gravity;
        let (sp, cp) = self.incline.sin_cos();
        let (ss, cs) = self.side_slope.sin_cos();
        let (structure, ground) = self
            .wheel
            .standing_model(toroid, [g * ss, g * cs * sp, -g * cs * cp])?;
        let settings = SimulationSettings {
            t_end: self.t_end,
            integrator: IntegratorKind::Rk4,
            dt: self.wheel.dt,
            output_interval: Some(self.wheel.output_dt),
            // keep the bar lengths and joints exact (RK4 alone drifts on this stiff wheel)
            project: true,
            quantities: Quantities {
                nodes: true,
                velocities: false,
                contact_forces: false,
                energy: false,
                member_forces: false,
            },
            ..SimulationSettings::default()
        };
        let mut sim = Simulation::new(&structure, settings)?;
        sim.model.set_ground(ground)?;
        let result = sim.run()?;
        let h = toroid.params.outer_radius * (PI / toroid.params.sides as f64).cos();
        let validity = RunValidity::of(toroid, &result, h);
        let n = toroid.params.sides;
        let rim: Vec<usize> = (0..n).map(|k| 5 * k + 2).collect();
        let mut start = None;
        let samples: Vec<RollingLeanSample> = result
            .samples
            .iter()
            .filter_map(|s| {
                let (lean, hub) = lean_and_hub(s.nodes.as_ref()?, &rim);
                let origin = *start.get_or_insert(hub);
                Some(RollingLeanSample {
                    t: s.t,
                    lean,
                    downhill: hub.y - origin.y,
                    across: hub.x - origin.x,
                })
            })
            .collect();
        let last = samples.last().copied();
        let max_lean = samples.iter().map(|s| s.lean.abs()).fold(0.0, f64::max);
        Ok(LeanRollingReport {
            sides: n,
            outer_tread: toroid.params.outer_tread,
            incline: self.incline,
            side_slope: self.side_slope,
            mass_kg: analyse(toroid)?.mass_kg,
            static_critical_side_slope: (toroid.params.outer_tread / (2.0 * h)).atan(),
            max_lean,
            final_lean: last.map_or(0.0, |s| s.lean),
            fell: max_lean > TIPPED_LEAN,
            fall_time: samples
                .iter()
                .find(|s| s.lean.abs() > TIPPED_LEAN)
                .map(|s| s.t),
            downhill: last.map_or(0.0, |s| s.downhill),
            max_penetration: validity.max_penetration,
            valid: validity.warnings.is_empty(),
            warnings: validity.warnings,
            samples,
        })
    }
}
