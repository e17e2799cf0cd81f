//! The rolling study of the toroid: one wheel down an incline ([`roll`]) with the models of
//! wheel-rolling, and the series of wheels of thesis Fig. 3.10 ([`rolling_series`]).
//!
//! The toroid supplies its wheel description ([`ToroidWheel`]: the polygon of its n prisms,
//! its nodes in the starting pose, and for the full model the prestressed [`scene`]);
//! wheel-rolling decides the model and runs it. The decision ([`RollRequest::decision`]) is
//! the one the resource estimate ([`crate::budget::roll`]) budgets: `rigid` runs the reduced
//! polygon model, `full` the prestressed tensegrity dynamics, and `auto` the rigid model only
//! where the two models agree within their uncertainty on the scene's class (a measured
//! table), m g / (k R_o) < 10⁻³ **and** the rigid run is valid, else the full model (see
//! [`wheel_rolling::fidelity`]). The report says which model ran and why
//! (`fidelity_reason`).
//!
//! Both models start from the same state, at rest on a side of the contact polygon about to
//! pivot about its downhill pair, and report the same coordinates (s along the slope from
//! that pair, h above the slope), so their histories compare from t = 0.

mod report;
mod wheel;

use crate::analysis::analyse;
use crate::defaults;
use crate::error::Result;
use crate::report::WheelSpec;
pub use report::RollReport;
use serde::{Deserialize, Serialize};
use tensegrity_core::request::{InvalidParameter, Request};
use tensegrity_derive::Params;
use tensegrity_dynamics::IntegratorKind;
pub use wheel::{rigid_frames, scene, start_pose, ToroidWheel};
use wheel_rolling::{
    ContactKind, Decision, FidelityChoice, Observer, RollSettings, RunChecks, RunSpec,
};

/// What [`roll`] runs: the wheel, the shared rolling settings and the toroid's own choices.
/// Its serde form is flat, every field named as the `roll` flag in snake_case:
/// `{"sides": 12, "incline": "30deg", "fidelity": "rigid", ...}`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Params)]
#[params(
    order = "incline, t_end, dt, fidelity, contact, ground_damping, ground_stiffness, mu, restitution, string_stiffness, min_tension, integrator, gravity"
)]
#[serde(default, deny_unknown_fields)]
pub struct RollRequest {
    /// The wheel.
    #[serde(flatten)]
    pub wheel: WheelSpec,
    /// Slope, step, gravity, restitution, string and ground stiffness, ground damping.
    #[serde(flatten)]
    pub settings: RollSettings,
    /// Simulated time (s).
    #[param(number, unit = "s", help = "Simulated time", positive)]
    pub t_end: f64,
    /// The model: `rigid`, `full` or `auto`.
    #[param(choice = FidelityChoice::NAMES, help = "Model: rigid polygon, full tensegrity, or auto (the cheapest valid one)")]
    pub fidelity: FidelityChoice,
    /// Ground contact of the full model: `penalty` or `thesis`.
    #[param(choice = ContactKind::NAMES, help = "Ground contact of the full model")]
    pub contact: ContactKind,
    /// Static friction coefficient μ_s; μ_k = 0.75 μ_s
    /// ([`defaults::KINETIC_FRICTION_RATIO`]).
    #[param(
        number,
        help = "Static friction coefficient μ_s (μ_k = 0.75 μ_s)",
        non_negative
    )]
    pub mu: f64,
    /// Smallest string tension of the full model's prestress (N).
    #[param(
        number,
        unit = "N",
        help = "Smallest string tension of the full model's prestress",
        positive
    )]
    pub min_tension: f64,
    /// Integrator of the full model (`dt` is its step, or its largest step when adaptive):
    /// IMEX-ARK by default (its implicit contact stages see the explicit forces, so a pivot's
    /// first impact converges with the step: `wheel_rolling::convergence`); the split `imex`
    /// is cheaper (about ½) where only statistics of hops are asked.
    #[param(choice = IntegratorKind::RIGID_NAMES, help = "Integrator of the full model")]
    pub integrator: IntegratorKind,
    /// `strict` (an invalid result is an error) and `convergence_check` (the run repeated at
    /// a refined resolution, [`wheel_rolling::convergence`]).
    #[serde(flatten)]
    pub checks: RunChecks,
    /// Copies from perturbed starting poses run beside the run ([`wheel_rolling::ensemble`]);
    /// 0 or 1: none.
    #[param(
        count,
        help = "Also roll K copies from starting poses turned by ±1e-6 rad, ±2e-6 rad, … (in parallel) and report the mean and 95 % interval of every headline quantity against the other model (0: none)"
    )]
    pub ensemble: usize,
}

impl Default for RollRequest {
    /// The reference wheel down 50° for 10 s, the rigid model at a 0.1 ms step and the full
    /// one by IMEX-ARK at 0.25 ms ([`wheel_rolling::defaults::full_dt`]),
    /// `auto` fidelity, penalty contact with e = 0, and the contact and string defaults of
    /// [`crate::defaults`].
    fn default() -> Self {
        Self {
            wheel: WheelSpec::default(),
            settings: RollSettings::default(),
            t_end: defaults::ROLL_T_END,
            fidelity: FidelityChoice::Auto,
            contact: ContactKind::Penalty,
            mu: defaults::STATIC_FRICTION,
            min_tension: defaults::ROLL_MIN_TENSION,
            integrator: IntegratorKind::ImexArk,
            checks: RunChecks::default(),
            ensemble: 0,
        }
    }
}

impl Request for RollRequest {
    const NAME: &'static str = "roll";

    /// Finite numbers (which the per-field rules cannot see otherwise), `dt` within the output
    /// interval ([`RollSettings::check`]), and the wheel's geometry rules across its
    /// parameters (R_i < R_o). (A front end also applies
    /// [`RollRequest::check_rigid_reads`] to what its user gave; a library caller may compare
    /// the two models on one set of settings.)
    fn check(&self) -> std::result::Result<(), InvalidParameter> {
        self.settings.check()?;
        wheel_rolling::settings::finite(&[
            ("t_end", self.t_end),
            ("mu", self.mu),
            ("min_tension", self.min_tension),
            ("bar_density", self.wheel.bar_density),
        ])?;
        self.wheel.check()
    }
}

/// Why a setting of the full model is refused under `fidelity = rigid`.
const READ_BY_FULL_ONLY: &str = "only the full model reads it, and `fidelity = rigid` runs the rigid polygon model, which ignores it: choose `fidelity = full` (or `fidelity = auto`, which may run the full model), or leave it out";

impl RollRequest {
    /// Under `fidelity = rigid` (and no `ensemble`, whose other run is the full model's) the
    /// settings only the full model reads must keep their defaults: `integrator`, `contact`,
    /// `string_stiffness`, `ground_stiffness`, `ground_damping`, `min_tension`. A value
    /// given is refused naming it, rather than dropped without a word (the command line's
    /// `roll` applies it to its flags).
    ///
    /// ```
    /// use toroid::RollRequest;
    /// use wheel_rolling::{ContactKind, FidelityChoice};
    /// let rigid = RollRequest { fidelity: FidelityChoice::Rigid, ..Default::default() };
    /// assert!(rigid.check_rigid_reads().is_ok());
    /// let stick = RollRequest { contact: ContactKind::Stick, ..rigid };
    /// let e = stick.check_rigid_reads().unwrap_err();
    /// assert_eq!(e.name, "contact");
    /// assert!(e.reason.contains("`fidelity = rigid`"), "{e}");
    /// // the full model reads it, and so does the other run of an ensemble
    /// assert!(RollRequest { fidelity: FidelityChoice::Full, ..stick }.check_rigid_reads().is_ok());
    /// assert!(RollRequest { ensemble: 3, ..stick }.check_rigid_reads().is_ok());
    /// ```
    pub fn check_rigid_reads(&self) -> std::result::Result<(), InvalidParameter> {
        self.check_rigid_given(|_| false)
    }

    /// The settings only the full model reads ([`RollRequest::check_rigid_reads`]).
    pub const FULL_MODEL_ONLY: [&'static str; 6] = [
        "integrator",
        "contact",
        "string_stiffness",
        "ground_stiffness",
        "ground_damping",
        "min_tension",
    ];

    /// [`RollRequest::check_rigid_reads`], and also refusing a setting only the full model
    /// reads that the caller `given` (e.g. a flag on the command line), even at its default
    /// value: `--fidelity rigid --integrator imex-ark` is refused like any other value.
    ///
    /// ```
    /// use toroid::RollRequest;
    /// use wheel_rolling::FidelityChoice;
    /// let rigid = RollRequest { fidelity: FidelityChoice::Rigid, ..Default::default() };
    /// let e = rigid.check_rigid_given(|name| name == "integrator").unwrap_err();
    /// assert_eq!(e.name, "integrator");
    /// assert!(e.value.contains("imex-ark"), "{}", e.value);
    /// assert!(rigid.check_rigid_given(|name| name == "incline").is_ok());
    /// ```
    pub fn check_rigid_given(
        &self,
        given: impl Fn(&str) -> bool,
    ) -> std::result::Result<(), InvalidParameter> {
        if self.fidelity != FidelityChoice::Rigid || self.ensemble >= 2 {
            return Ok(());
        }
        let (d, s) = (Self::default(), &self.settings);
        let number = |name, value: f64, default: f64| {
            (value != default).then(|| InvalidParameter::new(name, value, READ_BY_FULL_ONLY))
        };
        let text = |name, value: String, differs: bool| {
            differs.then(|| InvalidParameter::text(name, value, READ_BY_FULL_ONLY))
        };
        let number = |name, value: f64, default: f64| {
            number(name, value, if given(name) { f64::NAN } else { default })
        };
        let contact = format!("{:?}", self.contact).to_lowercase();
        let unread = [
            text(
                "integrator",
                self.integrator.to_string(),
                self.integrator != d.integrator || given("integrator"),
            ),
            text(
                "contact",
                contact,
                self.contact != d.contact || given("contact"),
            ),
            number(
                "string_stiffness",
                s.string_stiffness,
                d.settings.string_stiffness,
            ),
            number(
                "ground_stiffness",
                s.ground_stiffness,
                d.settings.ground_stiffness,
            ),
            s.ground_damping
                .and_then(|c| number("ground_damping", c, f64::NAN)),
            number("min_tension", self.min_tension, d.min_tension),
        ];
        match unread.into_iter().flatten().next() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}

impl RollRequest {
    /// The reference wheel with `n` sides and the default settings.
    pub fn with_sides(n: usize) -> Self {
        Self {
            wheel: WheelSpec::with_sides(n),
            ..Self::default()
        }
    }

    /// The run both models read: μ_k = 0.75 μ = [`defaults::KINETIC_FRICTION_RATIO`] μ, 1 ms
    /// samples.
    pub fn spec(&self) -> RunSpec {
        RunSpec {
            settings: self.settings,
            t_end: self.t_end,
            fidelity: self.fidelity,
            contact: self.contact,
            mu_static: self.mu,
            mu_kinetic: defaults::KINETIC_FRICTION_RATIO * self.mu,
            integrator: self.integrator,
            output_dt: defaults::ROLL_OUTPUT_DT,
            step_scale: 1.0,
        }
    }

    /// The coarser of the two models' steps (s): how far from its time a frame of either
    /// model may lie.
    ///
    /// ```
    /// let r = toroid::RollRequest::default();
    /// assert_eq!(r.coarser_step(), 2.5e-4); // IMEX-ARK on the penalty ground
    /// ```
    pub fn coarser_step(&self) -> f64 {
        let spec = self.spec();
        spec.rigid_dt().max(spec.full_dt())
    }

    /// The `strict` rule: under `strict`, a report that is not valid is an error
    /// ([`wheel_rolling::RollingError::Strict`], exit code 1 on the command line).
    pub fn strict_check(&self, report: &RollReport) -> Result<()> {
        Ok(wheel_rolling::strict_check(
            self.checks.strict,
            &report.summary.warnings,
        )?)
    }

    /// The fidelity decision of this request: from the wheel's mass computed from its
    /// parameters ([`crate::budget::wheel_mass`], nothing built), so the resource estimate
    /// ([`crate::budget::roll`]) and the run ([`roll`]) follow the same plan.
    ///
    /// ```
    /// use toroid::RollRequest;
    /// use wheel_rolling::{FidelityChoice, Plan, RollSettings};
    /// let auto = RollRequest::default();
    /// // 14.4 kg on 2·10⁴ N/m strings: m g / (k R_o) ≈ 7·10⁻³ > 10⁻³, the wheel deforms
    /// assert_eq!(auto.decision().plan, Plan::Full);
    /// let settings = RollSettings { string_stiffness: 2e6, ..auto.settings };
    /// let stiff = RollRequest { settings, ..auto };
    /// assert_eq!(stiff.decision().plan, Plan::RigidThenFullIfInvalid);
    /// let rigid = RollRequest { fidelity: FidelityChoice::Rigid, ..stiff };
    /// assert_eq!(rigid.decision().plan, Plan::Rigid);
    /// ```
    pub fn decision(&self) -> Decision {
        let s = &self.settings;
        Decision::new(
            self.fidelity,
            crate::spec_mass::wheel_mass(&self.wheel),
            s.gravity,
            s.string_stiffness,
            self.wheel.params.outer_radius,
        )
    }
}

/// Builds the wheel, decides the model (module docs) and rolls it (and, with
/// `convergence_check`, rolls it again at the refined resolution beside it); under `strict`
/// a result that is not valid is an error ([`RollRequest::strict_check`]).
///
/// ```
/// use toroid::{roll, RollRequest};
/// use wheel_rolling::{Fidelity, FidelityChoice};
/// let request = RollRequest { fidelity: FidelityChoice::Rigid, t_end: 2.0, ..Default::default() };
/// let r = roll(&request).unwrap();
/// assert_eq!(r.fidelity, Fidelity::Rigid);
/// assert!(r.summary.mean_speed > 0.0 && r.summary.impacts > 0);
/// ```
pub fn roll(request: &RollRequest) -> Result<RollReport> {
    let report = roll_observed(request, &[], None)?;
    request.strict_check(&report)?;
    Ok(report)
}

/// As [`roll`], keeping the wheel's nodes at `frame_times` (s) in [`RollReport::frames`]
/// (the rigid model places the rigid wheel by its pose, see [`rigid_frames`]).
pub fn roll_with_frames(request: &RollRequest, frame_times: &[f64]) -> Result<RollReport> {
    roll_observed(request, frame_times, None)
}

/// As [`roll_with_frames`], handing every sample and frame to `observer` as the run makes it;
/// an observer that stops the run gets the report of what was computed, with `stopped_at`
/// and a warning (see [`wheel_rolling::observer`]). The report is returned whatever its
/// validity: a front end writes it, then applies [`RollRequest::strict_check`]. Once the
/// observer's [`Observer::stop_flag`] is set the check's companion runs and the ensemble's
/// copies stop too; an ensemble stopped so is left out (`ensemble` is `None`).
pub fn roll_observed(
    request: &RollRequest,
    frame_times: &[f64],
    observer: Option<&mut dyn Observer>,
) -> Result<RollReport> {
    request.validate()?;
    let t = request.wheel.build()?;
    let a = analyse(&t)?;
    let wheel = ToroidWheel {
        toroid: &t,
        analysis: &a,
        string_stiffness: request.settings.string_stiffness,
        min_tension: request.min_tension,
    };
    let spec = request.spec();
    let stop = observer.as_ref().and_then(|o| o.stop_flag());
    let rolled = wheel_rolling::roll_checked(
        &wheel,
        &spec,
        &request.decision(),
        frame_times,
        observer,
        request.checks.convergence_check,
    )?;
    let interrupted = rolled.result.validity.stopped_at.is_some();
    let ensemble = match (request.ensemble, interrupted) {
        (k, false) if k >= 2 => ensemble(request, &wheel, &spec, rolled.fidelity, stop)?,
        _ => None,
    };
    let mut report = RollReport::of(request, rolled);
    if let Some((e, samples)) = ensemble {
        report.ensemble = Some(e);
        report.ensemble_samples = samples;
    }
    Ok(report)
}

/// The ensemble of `request` (its model: the one that ran, `fidelity`) against one
/// unperturbed run of the other model, and each copy's sampled history; `None` where `stop`
/// was set before its runs ended.
fn ensemble(
    request: &RollRequest,
    wheel: &ToroidWheel,
    spec: &RunSpec,
    fidelity: wheel_rolling::Fidelity,
    stop: Option<&'static std::sync::atomic::AtomicBool>,
) -> Result<Option<wheel_rolling::ensemble::WithHistories>> {
    static NEVER: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
    let stop = stop.unwrap_or(&NEVER);
    let choice = |f: wheel_rolling::Fidelity| match f {
        wheel_rolling::Fidelity::Rigid => FidelityChoice::Rigid,
        wheel_rolling::Fidelity::Full => FidelityChoice::Full,
    };
    let decide = |c: FidelityChoice| {
        RollRequest {
            fidelity: c,
            ..*request
        }
        .decision()
    };
    let other_fidelity = match fidelity {
        wheel_rolling::Fidelity::Rigid => wheel_rolling::Fidelity::Full,
        wheel_rolling::Fidelity::Full => wheel_rolling::Fidelity::Rigid,
    };
    let other_spec = RunSpec {
        fidelity: choice(other_fidelity),
        ..*spec
    };
    let other = wheel_rolling::roll_decided(
        wheel,
        &other_spec,
        &decide(choice(other_fidelity)),
        &[],
        Some(&mut wheel_rolling::observer::StopOn(stop)),
    )?;
    if stop.load(std::sync::atomic::Ordering::Relaxed) {
        return Ok(None);
    }
    let other = wheel_rolling::RunSummary::of(&other.result, spec.t_end);
    let same = RunSpec {
        fidelity: choice(fidelity),
        ..*spec
    };
    let threads = std::thread::available_parallelism().map_or(1, usize::from);
    wheel_rolling::ensemble::ensemble_until(
        wheel,
        &same,
        &decide(choice(fidelity)),
        request.ensemble,
        threads,
        Some(&other),
        stop,
    )
}

/// Rolls `request` once per wheel size in `sides` (the rest of the request unchanged), e.g.
/// the four wheels of thesis Fig. 3.10 with [`defaults::FIG_3_10_SIDES`].
pub fn rolling_series(request: &RollRequest, sides: &[usize]) -> Result<Vec<RollReport>> {
    sides
        .iter()
        .map(|&n| {
            let mut r = *request;
            r.wheel.params.sides = n;
            roll(&r)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use tensegrity_core::request::Params;
    use wheel_rolling::{ContactModel, Fidelity, Plan};

    #[test]
    fn the_request_describes_every_field() {
        tensegrity_core::request::check_description::<RollRequest>().unwrap();
        let names: Vec<&str> = RollRequest::params().iter().map(|p| p.name).collect();
        assert_eq!(names.len(), 26);
        for flag in [
            "sides",
            "stabilize",
            "incline",
            "mu",
            "integrator",
            "gravity",
        ] {
            assert!(names.contains(&flag), "{flag}");
        }
    }

    #[test]
    fn the_request_reads_and_writes_its_flat_serde_form() {
        let r = RollRequest::from_values([
            ("sides", serde_json::json!(12)),
            ("stabilize", serde_json::json!("spokes,outer")),
            ("incline", serde_json::json!("30deg")),
            ("fidelity", serde_json::json!("rigid")),
            ("contact", serde_json::json!("thesis")),
            ("integrator", serde_json::json!("sdirk")),
            ("ground_damping", serde_json::json!(300)),
        ])
        .unwrap();
        assert_eq!(r.wheel.params.sides, 12);
        assert!(r.wheel.stabilize.outer && !r.wheel.stabilize.inner);
        assert!((r.settings.incline - 30f64.to_radians()).abs() < 1e-15);
        assert_eq!(
            (r.fidelity, r.contact, r.integrator),
            (
                FidelityChoice::Rigid,
                ContactKind::Thesis,
                IntegratorKind::Sdirk
            )
        );
        assert_eq!(r.settings.ground_damping, Some(300.0));
        let json = serde_json::to_value(r).unwrap();
        assert_eq!(json["stabilize"], "spokes,outer");
        assert_eq!(json["fidelity"], "rigid");
        let back: RollRequest = serde_json::from_value(json).unwrap();
        assert_eq!(back, r);
        // unknown names and bad values are refused, naming the field
        assert!(serde_json::from_str::<RollRequest>(r#"{"sidez": 8}"#).is_err());
        let e = RollRequest::from_values([("mu", serde_json::json!(-1))]).unwrap_err();
        assert_eq!(e.name, "mu");
        let e = RollRequest::from_values([("inner_radius", serde_json::json!(1.5))]).unwrap_err();
        assert_eq!(e.name, "inner_radius");
        // a NaN set in code (it serialises as null) is refused by name too
        let nan = RollRequest {
            mu: f64::NAN,
            ..RollRequest::default()
        };
        assert_eq!(nan.validate().unwrap_err().name, "mu");
    }

    #[test]
    fn auto_fidelity_follows_the_documented_threshold() {
        // m g / (k R_o) of the reference wheel (≈ 14 kg) at 2·10⁴ N/m is ≈ 7·10⁻³: full;
        // 100 times stiffer strings bring it below 10⁻³: the rigid run first, the answer where
        // the fidelity table says the models agree on its class
        let req = RollRequest::default();
        let d = req.decision();
        assert!(d.strain > defaults::RIGID_THRESHOLD, "{}", d.strain);
        assert_eq!(d.plan, Plan::Full);
        let mut stiff = req;
        stiff.settings.string_stiffness *= 100.0;
        assert_eq!(stiff.decision().plan, Plan::RigidThenFullIfInvalid);
    }

    #[test]
    fn the_penalty_contact_uses_three_quarters_of_mu_as_kinetic_friction() {
        let mut req = RollRequest {
            mu: 0.5,
            contact: ContactKind::Penalty,
            ..Default::default()
        };
        req.settings.ground_damping = Some(300.0);
        let polygon = wheel_rolling::Polygon {
            sides: 8,
            outer_radius: 1.0,
            mass: 10.0,
            i1: 5.0,
        };
        let ContactModel::Penalty {
            mu_static,
            mu_kinetic,
            stiffness,
            damping,
        } = ContactModel::of(&req.spec(), &polygon)
        else {
            panic!("penalty expected");
        };
        assert_eq!(
            (mu_static, mu_kinetic, stiffness, damping),
            (0.5, 0.375, 1e5, 300.0)
        );
    }

    #[test]
    fn a_rolling_series_keeps_the_request_and_changes_the_sides() {
        let req = RollRequest {
            fidelity: FidelityChoice::Rigid,
            t_end: 1.0,
            ..Default::default()
        };
        let runs = rolling_series(&req, &[8, 12]).unwrap();
        assert_eq!(runs.iter().map(|r| r.sides).collect::<Vec<_>>(), [8, 12]);
        assert!(runs.iter().all(|r| r.fidelity == Fidelity::Rigid));
        // the single run of n = 12 is the same as its place in the series
        let twelve = roll(&RollRequest {
            wheel: WheelSpec::with_sides(12),
            ..req
        })
        .unwrap();
        let same = |r: &RollReport| (r.samples.clone(), r.summary.impacts, r.summary.mean_speed);
        assert_eq!(same(&runs[1]), same(&twelve));
    }
}
