//! The toroid's commands as requests ([`tensegrity_core::request::Request`]): one
//! description per field, read by the command line (`tensegrity toroid --sides 12`), the
//! sweeps (`study = "toroid"`, axis `sides`) and Python alike.
//!
//! | request | command / study | library call |
//! |---|---|---|
//! | [`ToroidRequest`] | `toroid` | [`crate::toroid_report`] |
//! | [`TipoverRequest`] | `tipover` | [`crate::tipover_report`] |
//! | [`TipoverDynamicRequest`] | `tipover --dynamic` / `tipover_dynamic` | [`TipoverDynamicRequest::run`] |
//! | [`TipoverRollingRequest`] | `tipover --rolling` / `tipover_rolling` | [`TipoverRollingRequest::run`] |
//!
//! Every one starts from the wheel ([`WheelSpec`], flattened: its parameters come first); the defaults
//! are the named constants of [`crate::defaults`] and of [`DynamicTipover::default`].

use crate::error::Result;
use crate::report::{TipoverRequest, ToroidRequest, WheelSpec};
use crate::rolling_lean::{LeanRolling, LeanRollingReport, LEAN_REFINEMENT};
use crate::tipover_dynamic::{
    beside, coarse_failure, judge, refined_failed, DynamicTipover, DynamicTipoverReport,
    COARSENING, REFINEMENT,
};
use crate::ToroidParams;
use serde::{Deserialize, Serialize};
use tensegrity_core::angle::serde_angle;
use tensegrity_core::request::{InvalidParameter, Request, RunChecks};
use tensegrity_derive::Params;
use tensegrity_dynamics::Convergence;

impl Request for ToroidRequest {
    const NAME: &'static str = "toroid";

    /// The wheel's geometry rules across its parameters, as every request of the wheel.
    fn check(&self) -> std::result::Result<(), InvalidParameter> {
        self.wheel.check()
    }
}

impl Request for TipoverRequest {
    const NAME: &'static str = "tipover";

    /// σ replaces the inner radius and ε the inner tread: each may not come with the length it
    /// sets (a length other than its default).
    fn check(&self) -> std::result::Result<(), InvalidParameter> {
        let g = &self.wheel.params;
        let r = ToroidParams::REFERENCE;
        for (ratio, value, length, set) in [
            (
                "sigma",
                self.sigma,
                "inner_radius",
                g.inner_radius != r.inner_radius,
            ),
            (
                "epsilon",
                self.epsilon,
                "inner_tread",
                g.inner_tread != r.inner_tread,
            ),
        ] {
            if let (Some(x), true) = (value, set) {
                let reason = format!("give `{ratio}` or `{length}`, not both");
                return Err(InvalidParameter::new(ratio, x, reason));
            }
        }
        // the wheel analysed (σ and ε applied), by the rules of every request of the wheel
        self.wheel_spec().check()
    }
}

/// `tipover --dynamic` (study `tipover_dynamic`): the static tip-over threshold checked by the
/// full 3-D dynamics ([`DynamicTipover::run`]) on the wheel.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct TipoverDynamicRequest {
    /// The wheel.
    #[serde(flatten)]
    pub wheel: WheelSpec,
    /// The run (its [`Default`]: a quasi-static ramp on a stiff wheel and ground).
    #[serde(flatten)]
    pub settings: DynamicTipover,
    /// `strict` and `convergence_check` (the ramp again beside it: at twice the step and half
    /// the ground stiffness where that stays inside RK4's stability, else at half the step and
    /// twice the ground stiffness: [`DynamicTipover::coarse_refused`]).
    #[serde(flatten)]
    pub checks: RunChecks,
}

impl TipoverDynamicRequest {
    /// Builds the wheel and runs the ramp ([`TipoverDynamicRequest::report`]); under `strict`
    /// a report that is not valid is an error.
    pub fn run(&self) -> Result<DynamicTipoverReport> {
        let r = self.report()?;
        wheel_rolling::strict_check(self.checks.strict, &r.warnings)?;
        Ok(r)
    }

    /// Builds the wheel and runs the ramp, with `convergence_check` beside the companion ramp
    /// ([`DynamicTipover::coarse`] where [`DynamicTipover::coarse_refused`] allows it, else
    /// [`DynamicTipover::refined`]; a coarse ramp that fails or carries a warning the run does
    /// not is followed by the refined one, its half run added to the cost); the report
    /// whatever its validity.
    pub fn report(&self) -> Result<DynamicTipoverReport> {
        self.report_watched(None)
    }

    /// [`TipoverDynamicRequest::report`], the main run watched
    /// ([`DynamicTipover::run_watched`]: an animation).
    pub fn report_watched(
        &self,
        watch: Option<&mut crate::tipover_dynamic::FrameWatch<'_>>,
    ) -> Result<DynamicTipoverReport> {
        use tensegrity_dynamics::convergence::Companion;
        let wheel = self.wheel.build()?;
        let check = self.checks.convergence_check;
        // the coarse companion (2 dt, k/2) where it serves, else the refined one (dt/2, 2k)
        let refused = if check {
            self.settings.coarse_refused(&wheel)?
        } else {
            None
        };
        let companion = match refused {
            None => self.settings.coarse(),
            Some(_) => self.settings.refined(),
        };
        let (main, first) = beside(
            check,
            || self.settings.run_watched(&wheel, watch),
            || companion.run(&wheel),
        );
        let mut r = main?;
        let Some(first) = first else { return Ok(r) };
        let refined_label = |why: &str| format!("{REFINEMENT} (refined companion: {why})");
        let convergence = match (refused, first) {
            (Some(why), Ok(f)) => r.convergence_with(&f, Convergence::new(refined_label(&why))),
            (Some(why), Err(e)) => refined_failed(format!("{why}; {e}")),
            (None, first) => match (coarse_failure(&r, &first), first) {
                (None, Ok(f)) => {
                    r.convergence_with(&f, Convergence::with(COARSENING, Companion::Coarse, 1.0))
                }
                (why, _) => {
                    let why = why.unwrap_or_default();
                    let label = format!(
                        "{REFINEMENT} (refined companion, run after the coarse one at 2 dt: {why})"
                    );
                    let mut c = match self.settings.refined().run(&wheel) {
                        Ok(f) => r.convergence_with(&f, Convergence::new(label)),
                        Err(e) => {
                            refined_failed(format!("{e} (after the coarse one at 2 dt: {why})"))
                        }
                    };
                    c.cost += Companion::Coarse.cost();
                    c
                }
            },
        };
        r.convergence = judge(convergence, &mut r.warnings);
        r.valid = r.warnings.is_empty();
        Ok(r)
    }
}

impl Request for TipoverDynamicRequest {
    const NAME: &'static str = "tipover_dynamic";

    /// The wheel's geometry rules across its parameters, as `roll` checks them.
    fn check(&self) -> std::result::Result<(), InvalidParameter> {
        self.wheel.check()
    }
}

/// Default incline of `tipover --rolling` (30°).
pub const ROLLING_INCLINE_DEG: f64 = 30.0;
/// Default side slope of `tipover --rolling` (5°).
pub const ROLLING_SIDE_SLOPE_DEG: f64 = 5.0;
/// Default simulated time of `tipover --rolling` (s).
pub const ROLLING_T_END: f64 = 3.0;
/// Default RK4 step of `tipover --rolling` (s): a quarter of the standing wheel's, since the
/// rolling wheel's wobble is damped away by coarser steps ([`crate::rolling_lean`]).
pub const ROLLING_DT: f64 = 2.5e-5;

/// `tipover --rolling` (study `tipover_rolling`, alias `lean`): the wheel rolling down a plane
/// with a side slope, its lean recorded ([`LeanRolling`]); the wheel, ground and integration
/// settings are [`DynamicTipover`]'s.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct TipoverRollingRequest {
    /// The wheel.
    #[serde(flatten)]
    pub wheel: WheelSpec,
    /// Incline φ downhill (rad).
    #[serde(with = "serde_angle")]
    #[param(angle, help = "Incline downhill, e.g. `30deg`", rule = HalfOpen(0.0, std::f64::consts::FRAC_PI_2))]
    pub incline: f64,
    /// Side slope ψ (rad).
    #[serde(with = "serde_angle")]
    #[param(angle, help = "Side slope across, e.g. `5deg`")]
    pub side_slope: f64,
    /// Simulated time (s).
    #[param(number, unit = "s", help = "Simulated time", positive)]
    pub t_end: f64,
    /// Gravity (m/s²).
    #[param(number, unit = "m/s^2", help = "Gravity", positive)]
    pub gravity: f64,
    /// String stiffness of the prestressed wheel (N/m).
    #[param(number, unit = "N/m", help = crate::tipover_dynamic::help::STRING_STIFFNESS, positive)]
    pub string_stiffness: f64,
    /// Smallest string tension of the prestress (N).
    #[param(
        number,
        unit = "N",
        help = "Smallest string tension of the prestress",
        positive
    )]
    pub min_tension: f64,
    /// Axial damping of every string (N·s/m).
    #[param(
        number,
        unit = "N s/m",
        help = "Axial damping of every string",
        non_negative
    )]
    pub string_damping: f64,
    /// Penalty ground stiffness (N/m).
    #[param(number, unit = "N/m", help = "Penalty ground stiffness", positive)]
    pub ground_stiffness: f64,
    /// Penalty ground damping (N·s/m).
    #[param(number, unit = "N s/m", help = "Penalty ground damping", non_negative)]
    pub ground_damping: f64,
    /// Static friction coefficient (kinetic = 0.75 of it).
    #[param(
        number,
        help = "Static friction coefficient of the ground (kinetic = 0.75 μ)",
        non_negative
    )]
    pub mu: f64,
    /// Regularisation velocity of the friction law (m/s).
    #[param(
        number,
        unit = "m/s",
        help = "Regularisation velocity of the friction law",
        positive
    )]
    pub friction_regularization: f64,
    /// RK4 step (s); [`ROLLING_DT`] by default.
    #[param(
        number,
        unit = "s",
        help = crate::tipover_dynamic::help::DT,
        positive
    )]
    pub dt: f64,
    /// Output interval (s).
    #[param(number, unit = "s", help = "Output interval of the history", positive)]
    pub output_dt: f64,
    /// `strict` and `convergence_check` (the run again at half the step and from a start
    /// turned by 10⁻⁶ rad, beside it: [`LeanRollingReport::convergence`]).
    #[serde(flatten)]
    pub checks: RunChecks,
}

impl Default for TipoverRollingRequest {
    /// The reference wheel [`ROLLING_INCLINE_DEG`] down and [`ROLLING_SIDE_SLOPE_DEG`] across
    /// for [`ROLLING_T_END`], with [`DynamicTipover::default`]'s wheel and ground.
    fn default() -> Self {
        let d = DynamicTipover::default();
        Self {
            wheel: WheelSpec::default(),
            incline: ROLLING_INCLINE_DEG.to_radians(),
            side_slope: ROLLING_SIDE_SLOPE_DEG.to_radians(),
            t_end: ROLLING_T_END,
            gravity: d.gravity,
            string_stiffness: d.string_stiffness,
            min_tension: d.min_tension,
            string_damping: d.string_damping,
            ground_stiffness: d.ground_stiffness,
            ground_damping: d.ground_damping,
            mu: d.mu,
            friction_regularization: d.friction_regularization,
            dt: ROLLING_DT,
            output_dt: d.output_dt,
            checks: RunChecks::default(),
        }
    }
}

impl TipoverRollingRequest {
    /// The library's run of this request.
    pub fn lean_rolling(&self) -> LeanRolling {
        LeanRolling {
            incline: self.incline,
            side_slope: self.side_slope,
            t_end: self.t_end,
            wheel: DynamicTipover {
                gravity: self.gravity,
                string_stiffness: self.string_stiffness,
                min_tension: self.min_tension,
                string_damping: self.string_damping,
                ground_stiffness: self.ground_stiffness,
                ground_damping: self.ground_damping,
                mu: self.mu,
                friction_regularization: self.friction_regularization,
                dt: self.dt,
                output_dt: self.output_dt,
                ..DynamicTipover::default()
            },
        }
    }

    /// Builds the wheel and rolls it ([`TipoverRollingRequest::report`]); under `strict` a
    /// report that is not valid is an error.
    pub fn run(&self) -> Result<LeanRollingReport> {
        let r = self.report()?;
        wheel_rolling::strict_check(self.checks.strict, &r.warnings)?;
        Ok(r)
    }

    /// Builds the wheel and rolls it, with `convergence_check` beside the refined run (half
    /// the step) from the twin's start (the incline + 10⁻⁶ rad), and the twin at the run's
    /// step after them only where the refined run moved some quantity by more than τ/8 (the
    /// lazy twin, [`tensegrity_dynamics::convergence`]; [`LeanRollingReport::convergence`]):
    /// cost 2, or 3 with the twin. The report whatever its validity. A failed twin leaves the
    /// quantities judged by the refinement alone, and says so. (RK4 on the default stiff,
    /// damped ground keeps the refined companion: the ground damper's rate, 4·10⁴ 1/s on
    /// the default wheel, puts 2 dt = 5·10⁻⁵ s at 2.0, past ½ × RK4's bound 2.6, as for
    /// `tipover --dynamic` ([`DynamicTipover::coarse_refused`]).)
    pub fn report(&self) -> Result<LeanRollingReport> {
        let wheel = self.wheel.build()?;
        let main = self.lean_rolling();
        let (fine, twin) = (main.refined().twin(), main.twin());
        let (r, first) = beside(
            self.checks.convergence_check,
            || main.run(&wheel),
            || fine.run(&wheel),
        );
        let mut r = r?;
        let turned = format!("{LEAN_REFINEMENT}, from a start turned by 1e-6 rad");
        let convergence = match first {
            Some(Ok(f)) => {
                let mut c = r.convergence(&f, None);
                if c.twin_needed() {
                    let t = twin.run(&wheel).ok();
                    c = r.convergence(&f, t.as_ref());
                    c.refinement = if t.is_none() {
                        c.converged = false;
                        format!("{turned}; the twin run (start turned by 1e-6 rad) failed")
                    } else {
                        format!("{turned}; twin at dt")
                    };
                } else {
                    c.refinement = format!(
                        "{turned}; no quantity moved by an eighth of its tolerance: no twin"
                    );
                }
                c
            }
            Some(Err(e)) => lean_refined_failed(e),
            None => return Ok(r),
        };
        r.convergence = judge(convergence, &mut r.warnings);
        r.valid = r.warnings.is_empty();
        Ok(r)
    }
}

/// The convergence of a lean-while-rolling run whose refined run failed (its error named).
fn lean_refined_failed(why: impl std::fmt::Display) -> Convergence {
    let mut c = Convergence::new(format!("{LEAN_REFINEMENT}: the refined run failed: {why}"));
    c.converged = false;
    c
}

impl Request for TipoverRollingRequest {
    const NAME: &'static str = "tipover_rolling";

    /// The wheel's geometry rules (as `roll` checks them) and the side slope within
    /// (−π/2, π/2), before anything is built.
    fn check(&self) -> std::result::Result<(), InvalidParameter> {
        self.wheel.check()?;
        if self.side_slope.is_nan() || self.side_slope.abs() >= std::f64::consts::FRAC_PI_2 {
            return Err(InvalidParameter::new(
                "side_slope",
                self.side_slope,
                "must lie in (−π/2, π/2)",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;
    use tensegrity_core::request::check_description;

    #[test]
    fn every_request_describes_its_fields() {
        check_description::<ToroidRequest>().unwrap();
        check_description::<TipoverRequest>().unwrap();
        check_description::<TipoverDynamicRequest>().unwrap();
        check_description::<TipoverRollingRequest>().unwrap();
    }

    #[test]
    fn the_serde_form_is_flat_and_reads_the_flag_values() {
        let v = serde_json::to_value(ToroidRequest::default()).unwrap();
        assert_eq!(v["sides"], 8);
        assert_eq!(v["stabilize"], "spokes,inner");
        assert!(v.get("wheel").is_none());
        let r = ToroidRequest::from_values([
            ("sides", json!("12")),
            ("stabilize", json!("spokes,outer")),
            ("string_stiffness", json!(1e4)),
        ])
        .unwrap();
        assert_eq!(r.wheel.params.sides, 12);
        assert!(r.wheel.stabilize.outer && !r.wheel.stabilize.inner);
        assert_eq!(r.string_stiffness, Some(1e4));
        let e = ToroidRequest::from_values([("stabilize", json!("wheels"))]).unwrap_err();
        assert_eq!(e.name, "stabilize");
        assert!(e.to_string().contains("wheels"), "{e}");
        let e = ToroidRequest::from_values([("outer_tread", json!(-1))]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "outer_tread = -1: must be finite and positive"
        );
    }

    #[test]
    fn sigma_and_epsilon_set_the_inner_radius_and_tread() {
        let r = TipoverRequest::from_values([
            ("sigma", json!(0.5)),
            ("epsilon", json!(0.25)),
            ("outer_radius", json!(2.0)),
        ])
        .unwrap();
        let p = r.wheel_spec().params;
        assert_eq!((p.inner_radius, p.inner_tread), (1.0, 0.25 * 0.4));
        let report = crate::tipover_report(&r).unwrap();
        assert_eq!((report.sigma, report.epsilon), (0.5, 0.25));
        // eq. 3.29: F_f' = −(σ + ε)/(1 − σ)
        assert!((report.normalized_friction + 0.75 / 0.5).abs() < 1e-12);
        let both =
            TipoverRequest::from_values([("sigma", json!(0.5)), ("inner_radius", json!(0.5))]);
        assert!(both.unwrap_err().to_string().contains("not both"));
    }

    #[test]
    fn the_rolling_request_is_the_library_run_of_the_cli_defaults() {
        let r = TipoverRollingRequest::from_values([("incline", json!("20deg"))]).unwrap();
        let lean = r.lean_rolling();
        assert!((lean.incline - 20f64.to_radians()).abs() < 1e-15);
        assert_eq!(lean.side_slope, 5f64.to_radians());
        // the standing wheel's settings, at the rolling wheel's own default step
        let standing = DynamicTipover::default();
        assert_eq!(lean.wheel.dt, ROLLING_DT);
        assert_eq!(
            lean.wheel,
            DynamicTipover {
                dt: ROLLING_DT,
                ..standing
            }
        );
        let d = TipoverDynamicRequest::from_values([("ramp_to", json!(1.1))]).unwrap();
        assert_eq!(d.settings.ramp_to, 1.1);
        assert!(TipoverDynamicRequest::from_values([("incline", json!(0.1))]).is_err());
    }
}
