//! The T-bar side of `tbar roll`: the request ([`TbarRollRequest`]), its documented
//! fidelity-dependent defaults, and the T-bar columns of each row ([`TbarRollRequest::tbar_row`]).
//!
//! For each number of treads n = π/φ the T-bar wheel (or extended wheel) rolls down the
//! incline with wheel-rolling's models, on its own wheel description:
//!
//! - **rigid** (default): the rolling polygon of the geometry ([`crate::rolling::MassProperties::polygon`]:
//!   n sides on the tip radius r₀, m and I₁ of its bars at `bar_density` — the rim body's at
//!   `rim_density` with `rim = body` — strings massless) in the reduced rigid model;
//! - **full**: the prestressed wheel with its free rim body ([`crate::rolling_full::full_wheel`],
//!   a [`wheel_rolling::Wheel`]) in the full tensegrity model with a penalty ground at the
//!   tips, by default with friction that sticks ([`DEFAULT_CONTACT`]; `contact` chooses);
//!   the row also carries the rigid polygon of the same m and I₁
//!   (`tbar_rigid_reference`) for the first contact phase. The full model needs the rim body
//!   (a free body): `rim = fixed` is refused.
//!
//! Each row has the structure's out-of-plane tip-over ([`crate::rolling::tipover`]). The
//! toroid column (the reference toroid scaled to r₀ with n sides) is composed by the engine
//! crate, since topology crates do not depend on each other.

mod drawn;
mod report;

use crate::error::Result;
use crate::geometry::TbarGeometry;
use crate::params::{BarBase, Layout, RimMode, TbarParams};
use crate::rolling::{mass_properties_with, tipover, MassProperties};
use crate::rolling_full::{full_wheel, FullWheelRequest, PrestressLevel, DEFAULT_CAPACITY_FACTOR};
pub use drawn::Watch;
use michell3d::MichellParams;
pub use report::{FullDetails, TbarRollReport, TbarRollRow};
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use tensegrity_core::request::{InvalidParameter, Request};
use tensegrity_derive::Params;
use wheel_rolling::defaults as roll_defaults;
use wheel_rolling::{
    roll_checked, ContactKind, Decision, Fidelity, FidelityChoice, RollSettings, RunChecks,
    RunSpec, WheelRun,
};

/// Default simulated time of the full model (s): the full model costs far more a second.
pub const FULL_T_END: f64 = 1.0;

/// Default number of treads of the full model (its cost grows steeply with n).
pub const FULL_TREADS: [usize; 1] = [8];

/// Default slope of `tbar roll` (degrees): 30°, below the friction angle atan μ_s = 38.7° of
/// the default μ_s = 0.8, so that the wheel rolls on its tips rather than slides and hops
/// (on 50° the full wheel's uphill tips chatter and its 1 s statistics do not converge; see
/// docs/notes/ROLLING.md, "The T-bar wheel in the full model").
pub const DEFAULT_INCLINE_DEG: f64 = 30.0;

/// Default ground stiffness of `tbar roll` (N/m per contact node): 10⁶, ten times `roll`'s,
/// so that the full model's tips barely enter the ground (0.05 mm for the default wheel) and
/// the first pivot does not depend on it (with the stick contact the default full roll is
/// then converged at twice the stiffness; at 10⁵ N/m its mean speed moves by 2 %). The rigid
/// model does not read it.
pub const DEFAULT_GROUND_STIFFNESS: f64 = 1e6;

/// Default density of the rim body's bars in the full model (and `auto`) (kg/m): a light
/// rim, so that the rim body is not most of the wheel's mass (2.49 of the n = 8 loop's
/// 5.44 kg) and its tips do not sink into the default ground (with the 1 kg/m of the treads'
/// bars the rim body is 49.7 of 52.7 kg and its tips sink 2.3 cm, more than 1 % of r₀).
pub const FULL_RIM_DENSITY: f64 = 0.05;

/// Default ground contact of `tbar roll`'s full model (T-bar and toroid columns): `stick`,
/// the penalty ground with an elastic–plastic tangential spring per contact node, which
/// holds a stick up to μ_s N. The regularised Coulomb law of `penalty` is a viscous law of
/// slope μ N / v_s below the Stribeck velocity v_s: a tip under a static tangential load
/// creeps, and at the default step its stiff viscous stick is near the explicit step's
/// stability limit, so whether a tip counts as slipping depends on the step and the ground
/// stiffness (default scene: the T-bar's `slip_fraction` 0.153 at 0.1 ms and 10⁶ N/m, 0.009
/// at half the step and twice the stiffness; the toroid's 0.695 and 0.160). With the stick
/// contact the T-bar's run is converged (0.012 and 0.007) and its energy budget closes to
/// 10⁻⁷ (2.5·10⁻³ with `penalty`); see docs/notes/ROLLING.md, "The T-bar wheel in the full model".
pub const DEFAULT_CONTACT: ContactKind = ContactKind::Stick;

/// Default departure angle β (rad): π/6, the measured cases of docs/notes/ROLLING.md.
pub const DEFAULT_BETA: f64 = PI / 6.0;

/// Default cylindrical offset δ (m) when neither parameterisation is given.
pub const DEFAULT_CYLINDRICAL: f64 = 0.25;

/// What `tbar roll` runs; every field is named as the `tbar roll` flag in snake_case. The
/// fields left unset (`null`) take the documented defaults of their methods, some of which
/// depend on the fidelity ([`TbarRollRequest::t_end`], [`TbarRollRequest::treads`],
/// [`TbarRollRequest::rim`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[params(
    order = "incline, t_end, dt, gravity, bar_density, mu_static, mu_kinetic, restitution, rim_density, string_stiffness, min_tension, contact, ground_stiffness, ground_damping"
)]
#[serde(default, deny_unknown_fields)]
pub struct TbarRollRequest {
    /// Complexity q of the treads.
    #[param(count, help = "Complexity q", rule = AtLeast(1.0))]
    pub complexity: usize,
    /// Departure angle β (rad).
    #[serde(with = "tensegrity_core::angle::serde_angle")]
    #[param(angle, help = "Departure angle β")]
    pub beta: f64,
    /// Cylindrical parameterisation with offset δ (m); exclusive with `spherical`; neither
    /// given: δ = [`DEFAULT_CYLINDRICAL`].
    #[param(
        number,
        help = "Cylindrical parameterisation with offset δ (neither given: δ = 0.25)",
        optional
    )]
    pub cylindrical: Option<f64>,
    /// Spherical parameterisation with angle ε (rad); exclusive with `cylindrical`.
    #[serde(with = "tensegrity_core::angle::serde_angle_option")]
    #[param(angle, help = "Spherical parameterisation with angle ε", optional)]
    pub spherical: Option<f64>,
    /// Tip radius r₀ (m): the rolling polygon's circumradius.
    #[param(
        number,
        unit = "m",
        help = "Tip radius r₀: the rolling polygon's circumradius",
        positive
    )]
    pub r0: f64,
    /// Roll the extended wheel with its copy at this offset (m) along ι̂₁; unset: the single
    /// loop.
    #[param(
        number,
        unit = "m",
        help = "Roll the extended wheel with its copy at this offset",
        optional
    )]
    pub extended: Option<f64>,
    /// Base of the radial bar.
    #[param(choice = ["rim", "chord"], help = "Base of the radial bar")]
    pub bar_base: BarBase,
    /// Rim mass: `fixed` (massless rigid rim) or `body` (the rim body's bars); unset: see
    /// [`TbarRollRequest::rim`].
    #[param(choice = ["fixed", "body"], help = "Rim mass: fixed (massless rigid rim; rigid default) or body (full: only choice)", optional)]
    pub rim: Option<RimMode>,
    /// Rolling model: `rigid`, `full` or `auto` (the fidelity policy of
    /// [`wheel_rolling::fidelity`]: rigid only where the two models agree within their
    /// uncertainty on the scene's class, else full). `auto` takes the full model's defaults
    /// (it may run the full model).
    #[param(choice = FidelityChoice::NAMES, help = "Rolling model (auto: rigid only where rigid and full agree within their uncertainty on this scene class, else full; takes the full model's defaults)")]
    pub fidelity: FidelityChoice,
    /// Numbers of treads n = π/φ to roll; unset: see [`TbarRollRequest::treads`].
    #[param(counts, help = "Numbers of treads n = π/φ, each at least 3 (default 8,12,16,24 rigid, 8 full)", rule = AtLeast(3.0), optional)]
    pub treads: Option<Vec<usize>>,
    /// Slope, step, gravity, restitution, string and ground stiffness, ground damping.
    #[serde(flatten)]
    pub settings: RollSettings,
    /// Simulated time (s); unset: see [`TbarRollRequest::t_end`].
    #[param(
        number,
        unit = "s",
        help = "Simulated time (default 10 s rigid, 1 s full)",
        positive,
        optional
    )]
    pub t_end: Option<f64>,
    /// Bar density of both wheels (kg/m); strings are massless.
    #[param(number, unit = "kg/m", help = "Bar density of both wheels", positive)]
    pub bar_density: f64,
    /// Static friction coefficient of the slope.
    #[param(number, help = "Static friction coefficient", non_negative)]
    pub mu_static: f64,
    /// Kinetic friction coefficient; unset: 0.75 μ_s.
    #[param(
        number,
        help = "Kinetic friction coefficient (default 0.75 μ_s)",
        non_negative,
        optional
    )]
    pub mu_kinetic: Option<f64>,
    /// Density of the rim body's bars (kg/m); unset: see [`TbarRollRequest::rim_density`].
    #[param(
        number,
        unit = "kg/m",
        help = "Density of the rim body's bars (default: bar_density for the rigid model, 0.05 kg/m for full and auto)",
        positive,
        optional
    )]
    pub rim_density: Option<f64>,
    /// Full model: smallest string tension of the prestress (N); unset: the prestress that
    /// carries twice the wheel's weight on one tip of each copy from every direction.
    #[param(
        number,
        unit = "N",
        help = "Full model: smallest string tension of the prestress (default: twice the weight per tip)",
        positive,
        optional
    )]
    pub min_tension: Option<f64>,
    /// Ground contact of the full model (T-bar and toroid columns): `penalty`, `thesis` or
    /// `stick`; default [`DEFAULT_CONTACT`].
    #[param(choice = ContactKind::NAMES, help = "Ground contact of the full model, T-bar and toroid (default stick: friction that holds a stick)")]
    pub contact: ContactKind,
    /// `strict` (an invalid report is an error) and `convergence_check` (every run repeated
    /// at a refined resolution, [`wheel_rolling::convergence`]).
    #[serde(flatten)]
    pub checks: RunChecks,
}

impl Default for TbarRollRequest {
    /// q = 1, β = π/6, cylindrical δ = 0.25 (unset: the default of neither parameterisation
    /// given, so that `spherical` alone is a complete request), r₀ = 1, the single loop on rim bar bases, the
    /// rigid model, the rolling defaults of wheel-rolling on [`DEFAULT_INCLINE_DEG`] (30°)
    /// and [`DEFAULT_GROUND_STIFFNESS`] (10⁶ N/m) (0.1 ms, g = 9.81, e = 0, strings
    /// 2·10⁴ N/m), 1 kg/m bars, μ_s = 0.8, the full model's [`DEFAULT_CONTACT`] (stick); the
    /// rest unset.
    fn default() -> Self {
        Self {
            complexity: 1,
            beta: DEFAULT_BETA,
            cylindrical: None,
            spherical: None,
            r0: 1.0,
            extended: None,
            bar_base: BarBase::Rim,
            rim: None,
            fidelity: FidelityChoice::Rigid,
            treads: None,
            settings: RollSettings {
                incline: DEFAULT_INCLINE_DEG.to_radians(),
                ground_stiffness: DEFAULT_GROUND_STIFFNESS,
                ..RollSettings::default()
            },
            t_end: None,
            bar_density: crate::rolling::DEFAULT_BAR_DENSITY,
            mu_static: roll_defaults::STATIC_FRICTION,
            mu_kinetic: None,
            rim_density: None,
            min_tension: None,
            contact: DEFAULT_CONTACT,
            checks: RunChecks::default(),
        }
    }
}

impl Request for TbarRollRequest {
    const NAME: &'static str = "tbar_roll";

    /// Finite numbers and `dt` within the output interval ([`RollSettings::check`]); the full
    /// model needs the rim body; μ_k ≤ μ_s ([`TbarRollRequest::check_friction`]); one
    /// parameterisation; the treads given, at most
    /// [`crate::params::MAX_TREADS`].
    fn check(&self) -> std::result::Result<(), InvalidParameter> {
        self.settings.check()?;
        wheel_rolling::settings::finite(&[
            ("beta", self.beta),
            ("cylindrical", self.cylindrical.unwrap_or(0.0)),
            ("spherical", self.spherical.unwrap_or(0.0)),
            ("r0", self.r0),
            ("extended", self.extended.unwrap_or(0.0)),
            ("t_end", self.t_end.unwrap_or(1.0)),
            ("bar_density", self.bar_density),
            ("mu_static", self.mu_static),
            ("mu_kinetic", self.mu_kinetic.unwrap_or(0.0)),
            ("rim_density", self.rim_density.unwrap_or(1.0)),
            ("min_tension", self.min_tension.unwrap_or(1.0)),
        ])?;
        self.rim()?;
        self.check_friction()?;
        if self.cylindrical.is_some() && self.spherical.is_some() {
            return Err(InvalidParameter::raw(
                "spherical",
                format!("{:?}", self.spherical.unwrap_or_default()),
                "give either cylindrical or spherical, not both",
            ));
        }
        if self.treads.as_ref().is_some_and(Vec::is_empty) {
            return Err(InvalidParameter::raw("treads", "[]", "give at least one"));
        }
        let max = crate::params::MAX_TREADS;
        if let Some(&n) = self.treads().iter().find(|&&n| n > max) {
            return Err(InvalidParameter::new(
                "treads",
                n as f64,
                format!("must be at most {max} (the T-bar wheel's limit of treads per wheel)"),
            ));
        }
        Ok(())
    }
}

impl TbarRollRequest {
    /// μ_k ≤ μ_s, the rule of a scene's ground: a kinetic friction above the static one is
    /// refused before any run (each run would refuse it, leaving every row empty).
    ///
    /// ```
    /// use tbar_wheel::roll::TbarRollRequest;
    /// let r = TbarRollRequest { mu_static: 0.8, mu_kinetic: Some(0.9), ..Default::default() };
    /// let e = r.check_friction().unwrap_err();
    /// assert_eq!(e.name, "mu_kinetic");
    /// assert_eq!(
    ///     e.reason,
    ///     "mu_kinetic (0.9) exceeds mu_static (0.8); kinetic friction must not exceed static friction"
    /// );
    /// assert!(TbarRollRequest { mu_kinetic: Some(0.8), ..r }.check_friction().is_ok());
    /// ```
    pub fn check_friction(&self) -> std::result::Result<(), InvalidParameter> {
        let short = tensegrity_core::number::short_number;
        match self.mu_kinetic {
            Some(mu_k) if mu_k > self.mu_static => Err(InvalidParameter::new(
                "mu_kinetic",
                mu_k,
                format!(
                    "mu_kinetic ({}) exceeds mu_static ({}); kinetic friction must not exceed static friction",
                    short(mu_k),
                    short(self.mu_static)
                ),
            )),
            _ => Ok(()),
        }
    }

    /// The simulated time: `t_end`, else 10 s for the rigid model
    /// ([`wheel_rolling::defaults::ROLL_T_END`]) or 1 s for the full model ([`FULL_T_END`]).
    pub fn t_end(&self) -> f64 {
        self.t_end.unwrap_or(match self.fidelity {
            FidelityChoice::Rigid => roll_defaults::ROLL_T_END,
            FidelityChoice::Full | FidelityChoice::Auto => FULL_T_END,
        })
    }

    /// The rim: `rim`, else `fixed` for the rigid model or `body` for the full model (and
    /// `auto`, which may run it); the full model refuses `fixed` (it needs a free body).
    ///
    /// ```
    /// use tbar_wheel::roll::TbarRollRequest;
    /// use tbar_wheel::RimMode;
    /// use wheel_rolling::FidelityChoice;
    /// let full = TbarRollRequest { fidelity: FidelityChoice::Full, ..Default::default() };
    /// assert_eq!(full.rim().unwrap(), RimMode::Body);
    /// let fixed = TbarRollRequest { rim: Some(RimMode::Fixed), ..full };
    /// assert_eq!(fixed.rim().unwrap_err().name, "rim");
    /// ```
    pub fn rim(&self) -> std::result::Result<RimMode, InvalidParameter> {
        match (self.fidelity, self.rim) {
            (FidelityChoice::Full | FidelityChoice::Auto, Some(RimMode::Fixed)) => {
                Err(InvalidParameter::text(
                    "rim",
                    "fixed",
                    "the full model (which `auto` may run) needs a free body: the rim body (rim = body), not the fixed rim",
                ))
            }
            (FidelityChoice::Full | FidelityChoice::Auto, _) => Ok(RimMode::Body),
            (FidelityChoice::Rigid, r) => Ok(r.unwrap_or(RimMode::Fixed)),
        }
    }

    /// The numbers of treads: `treads`, else 8, 12, 16, 24 for the rigid model
    /// ([`wheel_rolling::defaults::FIG_3_10_SIDES`]) or 8 for the full model and `auto`
    /// ([`FULL_TREADS`]).
    pub fn treads(&self) -> Vec<usize> {
        self.treads.clone().unwrap_or_else(|| match self.fidelity {
            FidelityChoice::Rigid => roll_defaults::FIG_3_10_SIDES.to_vec(),
            FidelityChoice::Full | FidelityChoice::Auto => FULL_TREADS.to_vec(),
        })
    }

    /// The rim body's bar density: `rim_density`, else `bar_density` for the rigid model or
    /// [`FULL_RIM_DENSITY`] for the full model and `auto`.
    pub fn rim_density(&self) -> f64 {
        self.rim_density.unwrap_or(match self.fidelity {
            FidelityChoice::Rigid => self.bar_density,
            FidelityChoice::Full | FidelityChoice::Auto => FULL_RIM_DENSITY,
        })
    }

    /// μ_k: `mu_kinetic`, else 0.75 μ_s ([`wheel_rolling::defaults::KINETIC_FRICTION_RATIO`]).
    pub fn mu_kinetic(&self) -> f64 {
        self.mu_kinetic
            .unwrap_or(roll_defaults::KINETIC_FRICTION_RATIO * self.mu_static)
    }

    /// The single loop, or the extended wheel with its copy at `extended`.
    pub fn layout(&self) -> Layout {
        match self.extended {
            Some(offset) => Layout::Extended { offset },
            None => Layout::Wheel,
        }
    }

    /// The T-bar parameters of the wheel with `n` treads (φ = π/n) and the rim `rim`.
    pub fn tbar_params(&self, n: usize, rim: RimMode) -> TbarParams {
        let phi = PI / n as f64;
        let (q, r0, beta) = (self.complexity, self.r0, self.beta);
        let m = match (self.cylindrical, self.spherical) {
            (_, Some(e)) => MichellParams::spherical(q, r0, beta, phi, e),
            (d, None) => {
                MichellParams::cylindrical(q, r0, beta, phi, d.unwrap_or(DEFAULT_CYLINDRICAL))
            }
        };
        TbarParams::tread(m)
            .with_layout(self.layout())
            .with_bar_base(self.bar_base)
            .with_rim(rim)
    }

    /// The run both models read: the full model's ground contact `contact` (the rigid model
    /// has its own), μ_s and [`TbarRollRequest::mu_kinetic`], RK4, 1 ms samples, for
    /// [`TbarRollRequest::t_end`] s with the model choice `fidelity`.
    pub fn spec(&self, fidelity: FidelityChoice) -> RunSpec {
        RunSpec {
            settings: self.settings,
            t_end: self.t_end(),
            fidelity,
            contact: self.contact,
            mu_static: self.mu_static,
            mu_kinetic: self.mu_kinetic(),
            ..RunSpec::default()
        }
    }

    /// What the full model's structure is built with: the densities, the string stiffness,
    /// and the prestress from `min_tension`, else a capacity of twice the weight per tip.
    pub fn full_wheel_request(&self) -> FullWheelRequest {
        FullWheelRequest {
            bar_density: self.bar_density,
            rim_density: self.rim_density(),
            string_stiffness: self.settings.string_stiffness,
            prestress: match self.min_tension {
                Some(t) => PrestressLevel::MinTension(t),
                None => PrestressLevel::Weight {
                    factor: DEFAULT_CAPACITY_FACTOR,
                    gravity: self.settings.gravity,
                },
            },
        }
    }

    /// The rigid run of `polygon` in the settings of this request.
    pub fn rigid_run(&self, polygon: &wheel_rolling::Polygon) -> Result<WheelRun> {
        let r = self.checked_run(polygon, FidelityChoice::Rigid, None)?;
        Ok(WheelRun::of(Fidelity::Rigid, polygon, &r.result, self.t_end()).because(r.reason))
    }

    /// The T-bar columns of the row of `n` treads (module docs): mass properties, the run of
    /// the model asked for (and for the full model its rigid reference and structure),
    /// tip-over. What fails is named in the row's `errors`; the toroid column is left empty.
    pub fn tbar_row(&self, n: usize, rim: RimMode) -> TbarRollRow {
        self.tbar_row_watched(n, rim, None)
    }

    /// As [`TbarRollRequest::tbar_row`], the T-bar run handing the wheel's node frames at the
    /// watched times to the watch's observer (the nodes of [`TbarRollRequest::drawing`]).
    pub fn tbar_row_watched(&self, n: usize, rim: RimMode, watch: Option<Watch>) -> TbarRollRow {
        let mut row = TbarRollRow::new(n);
        let p = self.tbar_params(n, rim);
        match self.fidelity {
            FidelityChoice::Rigid => self.rigid_columns(&p, &mut row, watch),
            FidelityChoice::Full | FidelityChoice::Auto => self.full_columns(&p, &mut row, watch),
        }
        row
    }

    /// The rigid model: mass properties of the geometry, its run (its nodes placed by the
    /// rigid pose when watched), tip-over.
    fn rigid_columns(&self, p: &TbarParams, row: &mut TbarRollRow, watch: Option<Watch>) {
        let built = TbarGeometry::new(*p).and_then(|g| {
            let mp = mass_properties_with(&g, self.bar_density, self.rim_density())?;
            Ok((mp, g))
        });
        match built {
            Ok((mp, g)) => {
                row.mass_properties = Some(mp);
                self.tipover(&g, &mp, row);
                match self.posed_run(&g, &mp, watch) {
                    Ok(s) => row.tbar = Some(s),
                    Err(e) => row.errors.push(format!("T-bar rolling: {e}")),
                }
            }
            Err(e) => row.errors.push(format!("T-bar wheel: {e}")),
        }
    }

    /// The full model: the structure that ran (its mass properties, with the isostatic rim
    /// body), its run, the rigid polygon of the same mass and I₁, tip-over.
    fn full_columns(&self, p: &TbarParams, row: &mut TbarRollRow, watch: Option<Watch>) {
        let (run, details, w) = match self.full_run_watched(p, watch) {
            Ok(r) => r,
            Err(e) => return row.errors.push(format!("T-bar full rolling: {e}")),
        };
        row.mass_properties = Some(w.mass);
        self.tipover(&w.geometry, &w.mass, row);
        match self.rigid_run(&w.mass.polygon()) {
            Ok(r) => row.tbar_rigid_reference = Some(r),
            Err(e) => row.errors.push(format!("T-bar rigid reference: {e}")),
        }
        (row.tbar, row.full) = (Some(run), Some(details));
    }

    /// The full tensegrity rolling of the T-bar wheel of `p` (with `auto`: the model the
    /// fidelity policy chose, the full structure built either way): its run, its structure
    /// and prestress, and the wheel.
    pub fn full_run(
        &self,
        p: &TbarParams,
    ) -> Result<(WheelRun, FullDetails, crate::rolling_full::FullWheel)> {
        self.full_run_watched(p, None)
    }

    /// As [`TbarRollRequest::full_run`], watched (see [`TbarRollRequest::tbar_row_watched`]).
    pub fn full_run_watched(
        &self,
        p: &TbarParams,
        watch: Option<Watch>,
    ) -> Result<(WheelRun, FullDetails, crate::rolling_full::FullWheel)> {
        let w = full_wheel(p, &self.full_wheel_request())?;
        let choice = match self.fidelity {
            FidelityChoice::Rigid => FidelityChoice::Full,
            c => c,
        };
        let mut r = self.checked_run(&w, choice, watch)?;
        if r.fidelity == Fidelity::Full {
            let gravity = self.settings.gravity;
            r.result.validity.warnings.extend(w.warnings(gravity));
        }
        let details = FullDetails::of(&w, r.ground_damping.unwrap_or_default());
        let run =
            WheelRun::of(r.fidelity, &w.mass.polygon(), &r.result, self.t_end()).because(r.reason);
        Ok((run, details, w))
    }

    /// The run of `wheel` with `fidelity`, repeated at the refined resolution beside it when
    /// `convergence_check` is set.
    fn checked_run<W>(
        &self,
        wheel: &W,
        fidelity: FidelityChoice,
        watch: Option<Watch>,
    ) -> Result<wheel_rolling::Rolled>
    where
        W: wheel_rolling::Wheel + Sync,
        W::Error: Send + std::fmt::Display,
        crate::TbarError: From<W::Error>,
    {
        let spec = self.spec(fidelity);
        let decision = Decision::of(&spec, &wheel.polygon());
        let check = self.checks.convergence_check;
        let (times, observer) = match watch {
            Some(w) => (w.times, Some(w.observer)),
            None => (&[][..], None),
        };
        Ok(roll_checked(
            wheel, &spec, &decision, times, observer, check,
        )?)
    }

    fn tipover(&self, g: &TbarGeometry, mp: &MassProperties, row: &mut TbarRollRow) {
        match tipover(g, mp.mass, self.settings.gravity) {
            Ok(t) => row.tipover = Some(t),
            Err(e) => row.errors.push(format!("tip-over: {e}")),
        }
    }
}

#[cfg(test)]
mod tests;
