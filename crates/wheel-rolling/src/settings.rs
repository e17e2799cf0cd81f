//! The settings of a rolling run: [`RollSettings`], the serde part every wheel's rolling
//! request shares (`#[serde(flatten)]`: the toroid's `roll` and the T-bar's `tbar_roll`),
//! and [`RunSpec`], the resolved run both models read.
//!
//! [`RollSettings`] holds the fields that mean the same, under the same name, default and
//! rule, in every rolling request: the slope, the step, gravity, the restitution and the
//! contact and string stiffnesses. What the requests spell differently (the toroid's `mu`
//! against the T-bar's `mu_static`/`mu_kinetic`, a fixed or fidelity-dependent `t_end`, the
//! T-bar's optional prestress level) each request resolves into the [`RunSpec`].

use crate::contact_kind::ContactKind;
use crate::defaults;
use crate::fidelity_choice::FidelityChoice;
use serde::{Deserialize, Serialize};
use tensegrity_core::request::InvalidParameter;
use tensegrity_derive::Params;
use tensegrity_dynamics::IntegratorKind;

/// The help texts of the settings that a request spelling them itself shares (the figure of
/// the rolling series).
pub mod help {
    /// `incline`.
    pub const INCLINE: &str = "Slope angle (e.g. `50deg`, `pi/4`, radians)";
    /// `restitution`.
    pub const RESTITUTION: &str = "Normal coefficient of restitution e of an impact, in [0, 1]";
}

/// The first of `values` that is not finite, as an [`InvalidParameter`] of its name.
///
/// ```
/// use wheel_rolling::settings::finite;
/// assert!(finite(&[("t_end", 1.0), ("mu", 0.8)]).is_ok());
/// assert_eq!(finite(&[("t_end", 1.0), ("mu", f64::NAN)]).unwrap_err().name, "mu");
/// ```
pub fn finite(values: &[(&'static str, f64)]) -> Result<(), InvalidParameter> {
    match values.iter().find(|(_, v)| !v.is_finite()) {
        Some(&(name, v)) => Err(InvalidParameter::new(name, v, "must be finite")),
        None => Ok(()),
    }
}

/// The run settings every rolling request shares (module docs); serialised flat inside the
/// request.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Params)]
#[serde(default)]
pub struct RollSettings {
    /// Slope angle φ (rad; reads `50deg`, `pi/4`, …).
    #[serde(with = "tensegrity_core::angle::serde_angle")]
    #[param(
        angle,
        help = help::INCLINE,
        rule = HalfOpen(0.0, std::f64::consts::FRAC_PI_2)
    )]
    pub incline: f64,
    /// Integration step (s): the fixed step of the rigid model and of the full model's
    /// fixed-step integrators, the largest step of the adaptive ones. Unset: each model's
    /// default ([`RunSpec::rigid_dt`], [`RunSpec::full_dt`]).
    #[param(
        number,
        unit = "s",
        help = "Integration step, at most the 1 ms output interval (unset: 1e-4 s; for the full model on a penalty or stick ground 5e-4 s under IMEX and 2.5e-4 s under IMEX-ARK, shorter for strings stiffer than 2e4 N/m)",
        positive,
        optional
    )]
    pub dt: Option<f64>,
    /// Gravity g (m/s²).
    #[param(number, unit = "m/s^2", help = "Gravity", positive)]
    pub gravity: f64,
    /// Normal coefficient of restitution e of an impact, in [0, 1]: the rigid model's impact
    /// law, and the penalty damping unless `ground_damping` is given.
    #[param(
        number,
        help = help::RESTITUTION,
        rule = Closed(0.0, 1.0)
    )]
    pub restitution: f64,
    /// String stiffness of the full model (N/m); it also decides the `auto` fidelity.
    #[param(
        number,
        unit = "N/m",
        help = "String stiffness of the full model",
        positive
    )]
    pub string_stiffness: f64,
    /// Penalty ground stiffness per contact node (N/m).
    #[param(
        number,
        unit = "N/m",
        help = "Penalty ground stiffness per contact node",
        positive
    )]
    pub ground_stiffness: f64,
    /// Ground damping (N·s/m): normal damping per contact node (penalty) or contact-velocity
    /// damping (thesis). Unset: the penalty damping that gives `restitution`
    /// ([`crate::contact::penalty_damping`]), or [`defaults::GROUND_DAMPING`] for the thesis
    /// contact.
    #[param(
        number,
        unit = "N s/m",
        help = "Ground damping per contact node (unset: from the restitution)",
        non_negative,
        optional
    )]
    pub ground_damping: Option<f64>,
}

impl Default for RollSettings {
    /// 50°, each model's default step, g = 9.81 m/s², e = 0, strings 2·10⁴ N/m, ground
    /// 10⁵ N/m per node, the damping from the restitution ([`crate::defaults`]).
    fn default() -> Self {
        Self {
            incline: defaults::INCLINE_DEG.to_radians(),
            dt: None,
            gravity: defaults::GRAVITY,
            restitution: defaults::RESTITUTION,
            string_stiffness: defaults::STRING_STIFFNESS,
            ground_stiffness: defaults::GROUND_STIFFNESS,
            ground_damping: None,
        }
    }
}

impl RollSettings {
    /// Checks that every number is finite (a non-finite number serialises as `null`, which
    /// the per-field rules of a request do not see): the first one that is not, by name.
    pub fn check_finite(&self) -> Result<(), InvalidParameter> {
        finite(&[
            ("incline", self.incline),
            ("dt", self.dt.unwrap_or(1.0)),
            ("gravity", self.gravity),
            ("restitution", self.restitution),
            ("string_stiffness", self.string_stiffness),
            ("ground_stiffness", self.ground_stiffness),
            ("ground_damping", self.ground_damping.unwrap_or(0.0)),
        ])
    }

    /// The shared rules across fields: every number finite ([`RollSettings::check_finite`]),
    /// and an explicit `dt` no longer than the output interval
    /// [`defaults::ROLL_OUTPUT_DT`]: both models cut their steps at the sample times, so a
    /// longer step would not be the step that runs, and the convergence check's half step
    /// would refine nothing.
    ///
    /// ```
    /// use wheel_rolling::RollSettings;
    /// let step = |dt| RollSettings { dt: Some(dt), ..RollSettings::default() }.check();
    /// assert!(step(1e-3).is_ok());
    /// let err = step(2e-3).unwrap_err();
    /// assert_eq!(err.name, "dt");
    /// assert!(err.to_string().contains("output interval"), "{err}");
    /// ```
    pub fn check(&self) -> Result<(), InvalidParameter> {
        self.check_finite()?;
        match self.dt {
            Some(dt) if dt > defaults::ROLL_OUTPUT_DT => Err(InvalidParameter::new(
                "dt",
                dt,
                format!(
                    "must not exceed the output interval {} s (the steps are cut at the sample times)",
                    defaults::ROLL_OUTPUT_DT
                ),
            )),
            _ => Ok(()),
        }
    }
}

/// A rolling run resolved from a request: what the rigid and the full model read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RunSpec {
    /// The shared settings.
    pub settings: RollSettings,
    /// Simulated time (s).
    pub t_end: f64,
    /// The model asked for.
    pub fidelity: FidelityChoice,
    /// The full model's ground contact.
    pub contact: ContactKind,
    /// Static friction coefficient μ_s.
    pub mu_static: f64,
    /// Kinetic friction coefficient μ_k ≤ μ_s.
    pub mu_kinetic: f64,
    /// Integrator of the full model ([`RunSpec::full_dt`] is its step, or its largest step).
    pub integrator: IntegratorKind,
    /// Output (sampling) interval of both models (s).
    pub output_dt: f64,
    /// Factor on both models' steps: 1, and ½ for the refined run of the convergence check
    /// ([`crate::convergence::refined`]).
    pub step_scale: f64,
}

impl RunSpec {
    /// The rigid model's step (s): `settings.dt`, or [`defaults::ROLL_DT`], times
    /// `step_scale`.
    ///
    /// ```
    /// let spec = wheel_rolling::RunSpec::default();
    /// assert_eq!(spec.rigid_dt(), 1e-4);
    /// ```
    pub fn rigid_dt(&self) -> f64 {
        self.step_scale * self.settings.dt.unwrap_or(defaults::ROLL_DT)
    }

    /// The full model's step (s): `settings.dt`, or the default of its integrator and
    /// contact and strings ([`defaults::full_dt`]), times `step_scale`.
    ///
    /// ```
    /// use tensegrity_dynamics::IntegratorKind;
    /// use wheel_rolling::{RollSettings, RunSpec};
    /// let imex = RunSpec { integrator: IntegratorKind::Imex, ..RunSpec::default() };
    /// assert_eq!(imex.full_dt(), 5e-4);
    /// let given = RunSpec { settings: RollSettings { dt: Some(2e-4), ..imex.settings }, ..imex };
    /// assert_eq!((given.full_dt(), given.rigid_dt()), (2e-4, 2e-4));
    /// ```
    pub fn full_dt(&self) -> f64 {
        self.step_scale
            * self.settings.dt.unwrap_or_else(|| {
                defaults::full_dt(
                    self.integrator,
                    self.contact,
                    self.settings.string_stiffness,
                )
            })
    }
}

impl Default for RunSpec {
    /// [`RollSettings::default`] for 10 s, `auto`, penalty contact, μ_s = 0.8, μ_k = 0.6,
    /// RK4, 1 ms samples.
    fn default() -> Self {
        Self {
            settings: RollSettings::default(),
            t_end: defaults::ROLL_T_END,
            fidelity: FidelityChoice::Auto,
            contact: ContactKind::Penalty,
            mu_static: defaults::STATIC_FRICTION,
            mu_kinetic: defaults::KINETIC_FRICTION_RATIO * defaults::STATIC_FRICTION,
            integrator: IntegratorKind::Rk4,
            output_dt: defaults::ROLL_OUTPUT_DT,
            step_scale: 1.0,
        }
    }
}
