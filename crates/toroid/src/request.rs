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
//! Every one starts from the wheel ([`WheelSpec`], flattened: [`WheelSpec::params`]); the defaults
//! are the named constants of [`crate::defaults`] and of [`DynamicTipover::default`].

use crate::error::Result;
use crate::report::{TipoverRequest, ToroidRequest, WheelSpec};
use crate::rolling_lean::{LeanRolling, LeanRollingReport};
use crate::tipover_dynamic::{beside, judge, refined_failed, DynamicTipover, DynamicTipoverReport};
use crate::ToroidParams;
use serde::{Deserialize, Serialize};
use tensegrity_core::angle::serde_angle;
use tensegrity_core::request::{InvalidParameter, Param, Request, Rule, RunChecks};

impl Request for ToroidRequest {
    const NAME: &'static str = "toroid";

    fn params() -> Vec<Param> {
        let mut p = WheelSpec::params();
        p.extend([
            Param::flag(
                "prism_only",
                "Analyse a single prism (six nodes, K6) instead of the whole wheel",
            ),
            Param::number(
                "min_tension",
                "N",
                "Minimum string tension of the prestress design",
            )
            .positive(),
            Param::flag(
                "rim_window",
                "Also search the rim radii R_m for which a single prism is prestressable",
            ),
            Param::number(
                "string_stiffness",
                "N/m",
                "Give every string of the exported structure this stiffness and the rest \
                 length that realises the prestress design",
            )
            .positive()
            .optional(),
        ]);
        p
    }

    /// The wheel's geometry rules across its parameters, as every request of the wheel.
    fn check(&self) -> std::result::Result<(), InvalidParameter> {
        self.wheel.check()
    }
}

impl Request for TipoverRequest {
    const NAME: &'static str = "tipover";

    fn params() -> Vec<Param> {
        let mut p = WheelSpec::params();
        p.extend([
            Param::number("gravity", "m/s^2", "Gravity").positive(),
            Param::number(
                "sigma",
                "",
                "σ = R_i/R_o: sets inner_radius = σ outer_radius",
            )
            .optional(),
            Param::number("epsilon", "", "ε = t/T: sets inner_tread = ε outer_tread").optional(),
        ]);
        p
    }

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

/// The time ramp of [`DynamicTipover`]'s lateral force.
fn ramp_params() -> Vec<Param> {
    vec![
        Param::number("settle", "s", "Time at rest before the ramp starts").non_negative(),
        Param::number(
            "ramp_time",
            "s",
            "Ramp duration, from 0 to ramp_to × the static threshold",
        )
        .positive(),
        Param::number(
            "ramp_to",
            "",
            "Largest force of the ramp, as a multiple of the static threshold",
        )
        .positive(),
        Param::number("hold", "s", "Time the largest force is held after the ramp").non_negative(),
    ]
}

/// The wheel, ground and integration settings of [`DynamicTipover`] that every timed run of
/// the prestressed wheel uses (in the order of its fields, ramp left out).
fn contact_params() -> Vec<Param> {
    vec![
        Param::number("gravity", "m/s^2", "Gravity").positive(),
        Param::number(
            "string_stiffness",
            "N/m",
            "String stiffness of the wheel: the threshold is the rigid one only for a stiff \
             wheel (a soft one deforms and tips early)",
        )
        .positive(),
        Param::number(
            "min_tension",
            "N",
            "Smallest string tension of the prestress",
        )
        .positive(),
        Param::number("string_damping", "N s/m", "Axial damping of every string").non_negative(),
        Param::number("ground_stiffness", "N/m", "Penalty ground stiffness").positive(),
        Param::number("ground_damping", "N s/m", "Penalty ground damping").non_negative(),
        Param::number(
            "mu",
            "",
            "Static friction coefficient of the ground (kinetic = 0.75 μ)",
        )
        .non_negative(),
        Param::number(
            "friction_regularization",
            "m/s",
            "Regularisation velocity of the friction law",
        )
        .positive(),
        Param::number("dt", "s", "RK4 step; stiffer strings need a smaller one").positive(),
        Param::number("output_dt", "s", "Output interval of the history").positive(),
    ]
}

/// `tipover --dynamic` (study `tipover_dynamic`): the static tip-over threshold checked by the
/// full 3-D dynamics ([`DynamicTipover::run`]) on the wheel.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TipoverDynamicRequest {
    /// The wheel.
    #[serde(flatten)]
    pub wheel: WheelSpec,
    /// The run (its [`Default`]: a quasi-static ramp on a stiff wheel and ground).
    #[serde(flatten)]
    pub settings: DynamicTipover,
    /// `strict` and `convergence_check` (the ramp again at half the step and twice the
    /// ground stiffness, beside it).
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

    /// Builds the wheel and runs the ramp, with `convergence_check` beside the refined ramp
    /// ([`DynamicTipover::refined`]); the report whatever its validity.
    pub fn report(&self) -> Result<DynamicTipoverReport> {
        self.report_watched(None)
    }

    /// [`TipoverDynamicRequest::report`], the main run watched
    /// ([`DynamicTipover::run_watched`]: an animation).
    pub fn report_watched(
        &self,
        watch: Option<&mut crate::tipover_dynamic::FrameWatch<'_>>,
    ) -> Result<DynamicTipoverReport> {
        let wheel = self.wheel.build()?;
        let fine = self.settings.refined();
        let (main, refined) = beside(
            self.checks.convergence_check,
            || self.settings.run_watched(&wheel, watch),
            || fine.run(&wheel),
        );
        let mut r = main?;
        let convergence = match refined {
            Some(Ok(f)) => r.convergence(&f),
            Some(Err(e)) => refined_failed(e),
            None => return Ok(r),
        };
        r.convergence = judge(convergence, &mut r.warnings);
        r.valid = r.warnings.is_empty();
        Ok(r)
    }
}

impl Request for TipoverDynamicRequest {
    const NAME: &'static str = "tipover_dynamic";

    fn params() -> Vec<Param> {
        let mut p = WheelSpec::params();
        p.extend(contact_params());
        p.extend(ramp_params());
        p.extend(RunChecks::params());
        p
    }

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

/// `tipover --rolling` (study `tipover_rolling`, alias `lean`): the wheel rolling down a plane
/// with a side slope, its lean recorded ([`LeanRolling`]); the wheel, ground and integration
/// settings are [`DynamicTipover`]'s.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct TipoverRollingRequest {
    /// The wheel.
    #[serde(flatten)]
    pub wheel: WheelSpec,
    /// Incline φ downhill (rad).
    #[serde(with = "serde_angle")]
    pub incline: f64,
    /// Side slope ψ (rad).
    #[serde(with = "serde_angle")]
    pub side_slope: f64,
    /// Simulated time (s).
    pub t_end: f64,
    /// Gravity (m/s²).
    pub gravity: f64,
    /// String stiffness of the prestressed wheel (N/m).
    pub string_stiffness: f64,
    /// Smallest string tension of the prestress (N).
    pub min_tension: f64,
    /// Axial damping of every string (N·s/m).
    pub string_damping: f64,
    /// Penalty ground stiffness (N/m).
    pub ground_stiffness: f64,
    /// Penalty ground damping (N·s/m).
    pub ground_damping: f64,
    /// Static friction coefficient (kinetic = 0.75 of it).
    pub mu: f64,
    /// Regularisation velocity of the friction law (m/s).
    pub friction_regularization: f64,
    /// RK4 step (s).
    pub dt: f64,
    /// Output interval (s).
    pub output_dt: f64,
    /// `strict` and `convergence_check` (the run again at half the step and twice the ground
    /// stiffness, beside it).
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
            dt: d.dt,
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
    /// the step, twice the ground stiffness); the report whatever its validity.
    pub fn report(&self) -> Result<LeanRollingReport> {
        let wheel = self.wheel.build()?;
        let main = self.lean_rolling();
        let fine = LeanRolling {
            wheel: main.wheel.refined(),
            ..main
        };
        let (r, refined) = beside(
            self.checks.convergence_check,
            || main.run(&wheel),
            || fine.run(&wheel),
        );
        let mut r = r?;
        let convergence = match refined {
            Some(Ok(f)) => r.convergence(&f),
            Some(Err(e)) => refined_failed(e),
            None => return Ok(r),
        };
        r.convergence = judge(convergence, &mut r.warnings);
        r.valid = r.warnings.is_empty();
        Ok(r)
    }
}

impl Request for TipoverRollingRequest {
    const NAME: &'static str = "tipover_rolling";

    fn params() -> Vec<Param> {
        let mut p = WheelSpec::params();
        p.extend([
            Param::angle("incline", "Incline downhill, e.g. `30deg`")
                .rule(Rule::HalfOpen(0.0, std::f64::consts::FRAC_PI_2)),
            Param::angle("side_slope", "Side slope across, e.g. `5deg`"),
            Param::number("t_end", "s", "Simulated time").positive(),
        ]);
        p.extend(contact_params());
        p.extend(RunChecks::params());
        p
    }

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
        assert_eq!(lean.wheel, DynamicTipover::default());
        let d = TipoverDynamicRequest::from_values([("ramp_to", json!(1.1))]).unwrap();
        assert_eq!(d.settings.ramp_to, 1.1);
        assert!(TipoverDynamicRequest::from_values([("incline", json!(0.1))]).is_err());
    }
}
