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
//! axis out of the plane, [`crate::tipover_dynamic`]'s definition) is recorded. The statically
//! expected critical side slope of a wheel resting on a side is tan ψ = T / (2h),
//! h = R_o cos(π/n) (the weight's line leaves the tread), so a wider tread and — through the
//! hub height only weakly — more sides raise it; the run shows what rolling adds.
//!
//! **Fell**: on the side slope the weight's line leaves the tread edge when the lean passes
//! α₊ = atan(T/2h) − ψ (over the downhill-side edge) or −α₋ = −(atan(T/2h) + ψ) (over the
//! other one) — [`crate::tipover_dynamic::tip_angle`] with the lateral component g sin ψ. The
//! wheel has `fell` when it **ends** leaning beyond one of them (on its side, or past the point
//! where its weight turns it over); `fall_time` is when that last excursion began. A wheel
//! that passed the angle and came back (rolling can right it) has not fallen.
//!
//! **A wobble is chaotic.** Rolling fast, the wheel rocks from one tread edge to the other
//! with a growing amplitude (on 30°: ±0.03 rad after 1.5 s, ±0.4 rad at 3 s, past both tip
//! angles and held up by the rolling); the phase of that wobble at any instant, and so the
//! largest and the final lean, move by 5–50 % under a start turned by 10⁻⁶ rad. The
//! root-mean-square lean over the run, `rms_lean`, is the time statistic of the wobble; the
//! convergence check ([`LeanRollingReport::convergence`]) runs the step halved (the ground's
//! stiffness is the model's, as in `roll`) and a twin from the incline + 10⁻⁶ rad, reports a
//! quantity the twin moves as `chaotic` with the 95 % interval of another run, and judges
//! the others. Whether it `fell` is decided by the final lean: when that is chaotic and its
//! interval reaches past a tip angle while part of it stays inside, `fell` and `fall_time`
//! are chaotic too (on 30°, 3 s the default run ends past α₋, a run at a quarter of its step
//! does not). RK4 must resolve the wobble: at 10⁻⁴ s it damps it (RMS lean 0.045 rad against
//! 0.155–0.169 rad at 2.5·10⁻⁵ and 1.25·10⁻⁵ s), hence the finer default step of
//! [`crate::request::ROLLING_DT`].

use crate::analysis::analyse;
use crate::builder::Toroid;
use crate::error::Result;
use crate::tipover_dynamic::{lean_and_hub, tip_angle, DynamicTipover, RunValidity};
use serde::Serialize;
use std::f64::consts::PI;
use tensegrity_core::Warning;
use tensegrity_derive::Columns;
use tensegrity_dynamics::convergence::TWIN_PERTURBATION;
use tensegrity_dynamics::{
    Convergence, IntegratorKind, Quantities, Simulation, SimulationSettings,
};

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
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct LeanRollingReport {
    /// Number of sides n.
    #[column(skip)]
    pub sides: usize,
    /// Outer tread width T (m).
    #[column(skip)]
    pub outer_tread: f64,
    /// Incline (rad).
    #[column(skip)]
    pub incline: f64,
    /// Side slope (rad).
    #[column(skip)]
    pub side_slope: f64,
    /// Wheel mass (kg).
    #[column(unit = "kg")]
    pub mass_kg: f64,
    /// Static critical side slope atan(T / 2h) of the wheel at rest on a side (rad).
    #[column(unit = "rad")]
    pub static_critical_side_slope: f64,
    /// Largest |lean| (rad).
    #[column(unit = "rad")]
    pub max_lean: f64,
    /// Root-mean-square lean over the run's samples (rad): the wobble's time statistic.
    #[column(unit = "rad")]
    pub rms_lean: f64,
    /// Lean at the end (rad).
    #[column(unit = "rad")]
    pub final_lean: f64,
    /// The static tip angle atan(T/2h) on a level plane (rad).
    #[column(unit = "rad")]
    pub static_tip_angle: f64,
    /// The tip angles on the side slope, α₊ (over the downhill-side edge, a positive lean)
    /// and α₋ (over the other, a lean below −α₋) (rad; module docs).
    #[column(skip)]
    pub tip_angles: [f64; 2],
    /// Whether it fell: it ends leaning past the tip angle of the side slope, α₊ or −α₋
    /// (module docs).
    pub fell: bool,
    /// When its last excursion past that angle began (s); null when it did not fall.
    #[column(unit = "s")]
    pub fall_time: Option<f64>,
    /// Hub travel downhill at the end (m).
    #[column(unit = "m")]
    pub downhill: f64,
    /// Deepest contact node below the plane (m).
    #[column(unit = "m")]
    pub max_penetration: f64,
    /// No warning: the run stayed inside its model.
    pub valid: bool,
    /// What the run violated (penetration past 1 % of R_o, integrator drift, an unconverged
    /// quantity).
    pub warnings: Vec<Warning>,
    /// The headline quantities re-run at half the step from a start turned by 10⁻⁶ rad, and
    /// by the twin at the step where that moved one by more than τ/8
    /// ([`LeanRollingReport::convergence`], [`crate::TipoverRollingRequest::report`]); null
    /// when not checked.
    #[column(nested)]
    pub convergence: Option<Convergence>,
    /// The history (not serialised).
    #[serde(skip)]
    pub samples: Vec<RollingLeanSample>,
}

/// What the convergence check of a lean-while-rolling run changes: the step only (the
/// ground's penalty stiffness is part of the model, as in `roll`).
pub const LEAN_REFINEMENT: &str = "dt/2 (the ground's stiffness is the model's)";

impl LeanRolling {
    /// The same run at half the step ([`LEAN_REFINEMENT`]).
    pub fn refined(&self) -> Self {
        let mut r = *self;
        r.wheel.dt *= 0.5;
        r
    }

    /// The twin of the convergence check: the same run from a start turned by
    /// [`TWIN_PERTURBATION`] rad relative to gravity (the incline + 10⁻⁶).
    pub fn twin(&self) -> Self {
        Self {
            incline: self.incline + TWIN_PERTURBATION,
            ..*self
        }
    }

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
        let rms_lean = if samples.is_empty() {
            0.0
        } else {
            (samples.iter().map(|s| s.lean * s.lean).sum::<f64>() / samples.len() as f64).sqrt()
        };
        let tread = toroid.params.outer_tread;
        let (plus, minus) = (tip_angle(tread, h, ss, cs), tip_angle(tread, h, -ss, cs));
        let beyond = |s: &RollingLeanSample| s.lean > plus || s.lean < -minus;
        let fell = last.as_ref().is_some_and(beyond);
        let fall_time = fell.then(|| {
            let upright = samples.iter().rposition(|s| !beyond(s));
            samples[upright.map_or(0, |i| i + 1)].t
        });
        Ok(LeanRollingReport {
            sides: n,
            outer_tread: toroid.params.outer_tread,
            incline: self.incline,
            side_slope: self.side_slope,
            mass_kg: analyse(toroid)?.mass_kg,
            static_critical_side_slope: (toroid.params.outer_tread / (2.0 * h)).atan(),
            max_lean,
            rms_lean,
            final_lean: last.map_or(0.0, |s| s.lean),
            static_tip_angle: tip_angle(tread, h, 0.0, 1.0),
            tip_angles: [plus, minus],
            fell,
            fall_time,
            downhill: last.map_or(0.0, |s| s.downhill),
            max_penetration: validity.max_penetration,
            valid: validity.warnings.is_empty(),
            warnings: validity.warnings,
            convergence: None,
            samples,
        })
    }
}

impl LeanRollingReport {
    /// The convergence of this report's headline quantities against the `refined` run's
    /// (half the step, [`LEAN_REFINEMENT`]), order 1 (the contacts' events), told chaotic
    /// against the `twin` run's when there is one (module docs): the largest, the RMS and the
    /// final lean within 5 % (on a scale of at least 0.01 rad), the travel downhill within
    /// 2 % (at least 1 cm), the fall time within 2 %, and whether it fell.
    ///
    /// ```no_run
    /// use toroid::{rolling_lean::LeanRolling, WheelSpec};
    /// let wheel = WheelSpec::default().build().unwrap();
    /// let run = LeanRolling::default();
    /// let (a, b, t) = (run.run(&wheel), run.refined().run(&wheel), run.twin().run(&wheel));
    /// let c = a.unwrap().convergence(&b.unwrap(), Some(&t.unwrap()));
    /// assert_eq!(c.cost, 3.0);
    /// ```
    pub fn convergence(&self, refined: &Self, twin: Option<&Self>) -> Convergence {
        let mut c = Convergence::new(LEAN_REFINEMENT);
        for (name, value, fine, tolerance, scale) in self.headline(refined) {
            c.compare(name, value, fine, tolerance, scale);
        }
        if let Some(twin) = twin {
            let values = twin.headline(twin);
            c.twin(|name| values.iter().find(|q| q.0 == name).and_then(|q| q.1));
            c.bound(&["max_lean", "rms_lean"], [0.0, f64::INFINITY])
                .bound(&["fell"], [0.0, 1.0]);
            if self.fall_undecided(&c) {
                c.mark_chaotic("fell").mark_chaotic("fall_time");
            }
        }
        c
    }

    /// Whether the final lean is chaotic with an interval that reaches past a tip angle
    /// while another part of it does not: whether the wheel ends fallen is then the phase of
    /// its wobble at the last instant, a draw.
    fn fall_undecided(&self, c: &Convergence) -> bool {
        use tensegrity_dynamics::convergence::Status;
        let [plus, minus] = self.tip_angles;
        let final_lean = c.quantities.iter().find(|q| q.name == "final_lean");
        let Some([lo, hi]) = final_lean
            .filter(|q| q.status == Status::Chaotic)
            .map(|q| q.interval.unwrap_or([f64::NEG_INFINITY, f64::INFINITY]))
        else {
            return false;
        };
        let beyond = |x: f64| x > plus || x < -minus;
        // some of [lo, hi] beyond, some inside: the interval meets an edge of (−α₋, α₊)
        let inside = hi > -minus && lo < plus;
        let outside = beyond(lo) || beyond(hi);
        inside && outside
    }

    /// The headline quantities of this run and of `other`, with their tolerance and scale.
    #[allow(clippy::type_complexity)]
    fn headline(&self, other: &Self) -> Vec<(&'static str, Option<f64>, Option<f64>, f64, f64)> {
        let fell = |r: &Self| Some(f64::from(u8::from(r.fell)));
        vec![
            (
                "max_lean",
                Some(self.max_lean),
                Some(other.max_lean),
                0.05,
                0.01,
            ),
            (
                "rms_lean",
                Some(self.rms_lean),
                Some(other.rms_lean),
                0.05,
                0.01,
            ),
            (
                "final_lean",
                Some(self.final_lean),
                Some(other.final_lean),
                0.05,
                0.01,
            ),
            (
                "downhill",
                Some(self.downhill),
                Some(other.downhill),
                0.02,
                0.01,
            ),
            ("fall_time", self.fall_time, other.fall_time, 0.02, 0.0),
            ("fell", fell(self), fell(other), 0.5, 1.0),
        ]
    }
}
