//! The fidelity decision: which model a run uses, made in one place for the run and for its
//! resource estimate.
//!
//! A request chooses [`FidelityChoice::Rigid`], [`FidelityChoice::Full`] or
//! [`FidelityChoice::Auto`]. `Auto` runs the rigid model only where the rigid and the full
//! model agree within their uncertainty on the scene's class, and the full model otherwise.
//! Its first test is the strain measure ε = m g / (k R_o) — the strain one string of
//! stiffness k would take carrying the whole wheel weight m g over the wheel radius R_o
//! ([`deformation_measure`]): at ε ≥ [`RIGID_THRESHOLD`] the wheel deforms and only the full
//! model applies. Below it the scene's class ([`SceneClass`]) is read from a rigid run (it
//! costs milliseconds) and looked up in the measured table [`MEASURED`]; the rigid run is
//! the answer when its class agrees there ([`ClassAgreement::agrees`]: the largest measured
//! difference between the models is within their combined uncertainty), the scene lies
//! inside the measured range (ε and ground stiffness, [`ClassAgreement::covers`]) and the
//! rigid run is valid. So the decision before any run is a [`Plan`]:
//!
//! | choice | ε | plan |
//! |---|---|---|
//! | rigid | any | [`Plan::Rigid`] |
//! | full | any | [`Plan::Full`] |
//! | auto | ≥ 10⁻³ | [`Plan::Full`] |
//! | auto | < 10⁻³ | [`Plan::RigidThenFullIfInvalid`]: the rigid run; the full one when the rigid run is not valid or its class is not one where the models agree |
//!
//! The run follows the plan ([`crate::run::roll_wheel`]) and the estimate budgets exactly
//! what the plan may do ([`crate::estimate::plan`]: the rigid run and then the full one for
//! `RigidThenFullIfInvalid`), so a request the guard admits never runs a model the guard did
//! not count. [`Decision::reason`] says in words which test decided (the reports'
//! `fidelity_reason`).
//!
//! **The table is data.** Each row of [`MEASURED`] is a measurement of rigid against full
//! (`cargo test --release -p toroid --test integration fidelity_classes:: -- --ignored --nocapture`
//! prints the rows to paste here): per scene of the class, for each headline quantity q the
//! difference d_q = |x_rigid − x_full| / max(|x_rigid|, |x_full|, floor_q) and the combined
//! uncertainty U_q = u_rigid + u_full, each model's u being its stated convergence
//! tolerance τ_q when its convergence check reports q converged (the check's rule bounds
//! its distance to any finer run by τ_q), else its measured change at the refinement (at
//! least τ_q). The row keeps the quantity with the largest d_q / U_q over the class's
//! scenes; the class agrees when that ratio is at most 1. When a model changes (its
//! friction, its integrator), re-measure and replace the rows: the policy follows.
use crate::defaults::RIGID_THRESHOLD;
pub use crate::fidelity_choice::FidelityChoice;
use crate::sample::RollingResult;
use serde::{Deserialize, Serialize};

/// Which model a rolling run used; serialises as `"rigid"` or `"full"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Fidelity {
    /// The reduced rigid polygon ([`crate::RigidRolling`]).
    Rigid,
    /// The full tensegrity dynamics ([`crate::FullRolling`]).
    Full,
}

impl Fidelity {
    /// `"rigid"` or `"full"`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Rigid => "rigid",
            Self::Full => "full",
        }
    }
}

/// What a run will do, decided before it starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plan {
    /// The rigid model only.
    Rigid,
    /// The full model only.
    Full,
    /// The rigid model; the full model too when the rigid run is not valid.
    RigidThenFullIfInvalid,
}

impl Plan {
    /// Whether the plan may run the full model.
    pub fn may_run_full(self) -> bool {
        self != Plan::Rigid
    }

    /// Whether the plan runs the rigid model.
    pub fn runs_rigid(self) -> bool {
        self != Plan::Full
    }
}

/// The fidelity decision of one request for one wheel: the plan and what it was made from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Decision {
    /// The choice of the request.
    pub choice: FidelityChoice,
    /// The plan.
    pub plan: Plan,
    /// The strain measure ε = m g / (k R_o) it was made with.
    pub strain: f64,
    /// The string stiffness k (N/m).
    pub string_stiffness: f64,
}

impl Decision {
    /// The decision for a wheel of `mass` (kg) and outer radius R_o (m) under `gravity` with
    /// strings of `string_stiffness` (N/m) (table of the module docs).
    ///
    /// ```
    /// use wheel_rolling::fidelity::{Decision, Plan};
    /// use wheel_rolling::FidelityChoice;
    /// // 14.4 kg on 2·10⁴ N/m strings: m g / (k R_o) ≈ 7·10⁻³ > 10⁻³, the wheel deforms
    /// let soft = Decision::new(FidelityChoice::Auto, 14.4, 9.81, 2e4, 1.0);
    /// assert_eq!(soft.plan, Plan::Full);
    /// let stiff = Decision::new(FidelityChoice::Auto, 14.4, 9.81, 2e6, 1.0);
    /// assert_eq!(stiff.plan, Plan::RigidThenFullIfInvalid);
    /// let rigid = Decision::new(FidelityChoice::Rigid, 14.4, 9.81, 2e4, 1.0);
    /// assert_eq!(rigid.plan, Plan::Rigid);
    /// ```
    pub fn new(
        choice: FidelityChoice,
        mass: f64,
        gravity: f64,
        string_stiffness: f64,
        outer_radius: f64,
    ) -> Self {
        let strain = deformation_measure(mass, gravity, string_stiffness, outer_radius);
        let plan = match choice {
            FidelityChoice::Rigid => Plan::Rigid,
            FidelityChoice::Full => Plan::Full,
            FidelityChoice::Auto if strain >= RIGID_THRESHOLD => Plan::Full,
            FidelityChoice::Auto => Plan::RigidThenFullIfInvalid,
        };
        Self {
            choice,
            plan,
            strain,
            string_stiffness,
        }
    }

    /// The decision of `spec` for the wheel `polygon` (its mass and R_o; the settings' g
    /// and string stiffness).
    pub fn of(spec: &crate::RunSpec, polygon: &crate::Polygon) -> Self {
        let s = &spec.settings;
        Self::new(
            spec.fidelity,
            polygon.mass,
            s.gravity,
            s.string_stiffness,
            polygon.outer_radius,
        )
    }

    /// Why the plan runs the full model without a rigid run (a requested model, or strings
    /// that stretch), or, from the rigid run `probe` of a scene with `ground_stiffness`
    /// (N/m), whether it was the answer ([`Decision::rigid_answers`]) and why.
    pub fn reason(&self, probe: Option<(&RollingResult, f64)>) -> String {
        let (strain, k) = (self.strain, self.string_stiffness);
        match (self.choice, probe) {
            (FidelityChoice::Rigid | FidelityChoice::Full, _) => "requested".to_string(),
            (FidelityChoice::Auto, None) => format!(
                "the strings stretch: m g / (k R_o) = {strain:.2e} ≥ {RIGID_THRESHOLD:.0e} with k = {k} N/m"
            ),
            (FidelityChoice::Auto, Some((r, ground))) => self.probe_reason(r, ground),
        }
    }

    /// Whether the rigid run `probe` (of a scene with `ground_stiffness`, N/m) is the answer
    /// of `auto`: it is valid, and its class agrees in [`MEASURED`] and covers this scene.
    pub fn rigid_answers(&self, probe: &RollingResult, ground_stiffness: f64) -> bool {
        let row = ClassAgreement::of(SceneClass::of(probe));
        probe.validity.valid() && row.agrees() && row.covers(self.strain, ground_stiffness)
    }

    /// The reasoning of `auto` after its rigid run (module docs).
    fn probe_reason(&self, r: &RollingResult, ground: f64) -> String {
        let class = SceneClass::of(r);
        let row = ClassAgreement::of(class);
        let stiff = format!(
            "the wheel is stiff (m g / (k R_o) = {:.2e} < {RIGID_THRESHOLD:.0e})",
            self.strain
        );
        let measured = row.measured();
        if !row.agrees() {
            return format!(
                "{stiff}, but on the scene class `{}` rigid and full differ beyond their uncertainty ({measured}): full",
                class.name()
            );
        }
        if !row.covers(self.strain, ground) {
            return format!(
                "{stiff} and rigid and full agree on the scene class `{}` ({measured}), but only measured for m g / (k R_o) ≤ {:.1e} and ground stiffness ≥ {:.1e} N/m (here {:.2e}, {ground:.1e} N/m): full",
                class.name(),
                row.max_strain,
                row.min_ground_stiffness,
                self.strain
            );
        }
        if !r.validity.valid() {
            return format!(
                "{stiff} and rigid and full agree on the scene class `{}`, but the rigid run is not valid: {}",
                class.name(),
                tensegrity_core::warning::joined(&r.validity.warnings)
            );
        }
        format!(
            "{stiff}, rigid and full agree within their uncertainty on the scene class `{}` ({measured}) and the rigid run is valid: rigid",
            class.name()
        )
    }
}

/// The class of a rolling scene, read from its rigid run (cheap and deterministic): what the
/// rigid wheel does in the time asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SceneClass {
    /// The rigid wheel does not move (φ < π/n and the friction holds it): no impact, no
    /// speed.
    AtRest,
    /// It pivots about its downhill side but reaches no next side before the end: no impact.
    FirstPivot,
    /// Impacts, and always in contact (never airborne).
    Rolling,
    /// Impacts and flights (hops).
    Hopping,
}

impl SceneClass {
    /// Every class, in the order of [`MEASURED`].
    pub const ALL: [SceneClass; 4] = [
        SceneClass::AtRest,
        SceneClass::FirstPivot,
        SceneClass::Rolling,
        SceneClass::Hopping,
    ];

    /// The class of a rigid run `r`: no impact and (to 10⁻⁹ m/s) no speed at the end and on
    /// average: at rest; no impact: first pivot; never airborne: rolling; else hopping.
    pub fn of(r: &RollingResult) -> Self {
        let s0 = r.samples.first().map_or(0.0, |s| s.s);
        let still = r.final_speed.abs() <= 1e-9
            && r.samples
                .iter()
                .all(|s| (s.s - s0).abs() <= 1e-9 && s.omega.abs() <= 1e-9);
        match (r.impacts, still, r.validity.airborne_fraction > 0.0) {
            (0, true, _) => Self::AtRest,
            (0, false, _) => Self::FirstPivot,
            (_, _, false) => Self::Rolling,
            (_, _, true) => Self::Hopping,
        }
    }

    /// `at rest`, `first pivot`, `rolling`, `hopping`.
    pub fn name(self) -> &'static str {
        match self {
            Self::AtRest => "at rest",
            Self::FirstPivot => "first pivot",
            Self::Rolling => "rolling",
            Self::Hopping => "hopping",
        }
    }
}

/// One measured row of the fidelity table: rigid against full on the scenes of one class
/// (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClassAgreement {
    /// The class.
    pub class: SceneClass,
    /// The scenes measured (slopes, sides, times, stiffnesses, friction).
    pub scenes: &'static str,
    /// The headline quantity with the largest difference-to-uncertainty ratio.
    pub quantity: &'static str,
    /// Its difference d_q between the models (relative, module docs).
    pub difference: f64,
    /// Its combined uncertainty U_q (relative).
    pub uncertainty: f64,
    /// The largest strain measure m g / (k R_o) of the scenes measured.
    pub max_strain: f64,
    /// The softest ground of the scenes measured (N/m per node).
    pub min_ground_stiffness: f64,
}

impl ClassAgreement {
    /// The row of `class` in [`MEASURED`].
    pub fn of(class: SceneClass) -> &'static ClassAgreement {
        MEASURED
            .iter()
            .find(|r| r.class == class)
            .unwrap_or(&MEASURED[MEASURED.len() - 1])
    }

    /// The models agree on this class: the largest difference is within the combined
    /// uncertainty.
    pub fn agrees(&self) -> bool {
        self.difference <= self.uncertainty
    }

    /// A scene of strain measure `strain` on a ground of `ground_stiffness` (N/m) lies in
    /// the measured range (no stiffer-than-measured claim is extrapolated).
    pub fn covers(&self, strain: f64, ground_stiffness: f64) -> bool {
        strain <= self.max_strain && ground_stiffness >= self.min_ground_stiffness
    }

    /// `measured: <quantity> differs by d against an uncertainty U on <scenes>`.
    pub fn measured(&self) -> String {
        format!(
            "measured: `{}` differs by {:.3} against an uncertainty of {:.3} on {}; {MEASURED_SETTINGS}",
            self.quantity, self.difference, self.uncertainty, self.scenes
        )
    }
}

/// The measured scenes' common settings: the toroid wheel with spokes and inner rings,
/// strings 2·10⁶ N/m (m g/(k R_o) = 7.0·10⁻⁵ for n = 8, 1.1·10⁻⁴ for n = 16), penalty ground 10⁶ N/m per node, μ_s = 1.2,
/// e = 0, RK4 at 50 µs, each model with its convergence check.
pub const MEASURED_SETTINGS: &str =
    "the toroid, strings 2e6 N/m, ground 1e6 N/m, mu_s 1.2, e 0, dt 5e-5 s";

/// The measured table of rigid against full per scene class (module docs; docs/notes/ROLLING.md
/// "The fidelity policy"). Measured on the models of this version; re-measure after a
/// model changes.
pub const MEASURED: [ClassAgreement; 4] = [
    ClassAgreement {
        class: SceneClass::AtRest,
        scenes: "10 deg, n = 8, 1 s (the full wheel creeps: final speed 0.75 mm/s)",
        quantity: "final_speed",
        difference: 0.748,
        uncertainty: 0.135,
        max_strain: 7.1e-5,
        min_ground_stiffness: 1e6,
    },
    ClassAgreement {
        class: SceneClass::FirstPivot,
        scenes: "30 deg, n = 8, 1 s (the full wheel started at rest; slip fraction 0 against \
                 0.21, 0 at the refinement: the regularised friction's slip is not converged)",
        quantity: "slip_fraction",
        difference: 0.212,
        uncertainty: 0.232,
        max_strain: 7.1e-5,
        min_ground_stiffness: 1e6,
    },
    ClassAgreement {
        class: SceneClass::Rolling,
        scenes: "20 deg, n = 16, 2 s (the full wheel hops 37 % of the time)",
        quantity: "airborne_fraction",
        difference: 0.365,
        uncertainty: 0.04,
        max_strain: 1.2e-4,
        min_ground_stiffness: 1e6,
    },
    ClassAgreement {
        class: SceneClass::Hopping,
        scenes: "50 deg, n = 8, 2 s (final speeds 27 % apart)",
        quantity: "final_speed",
        difference: 0.269,
        uncertainty: 0.073,
        max_strain: 7.1e-5,
        min_ground_stiffness: 1e6,
    },
];

/// The strain ε = m g / (k R_o) that one string of stiffness k would take carrying the whole
/// wheel weight over the wheel radius: a cheap measure of how much the wheel deforms.
pub fn deformation_measure(
    mass: f64,
    gravity: f64,
    string_stiffness: f64,
    outer_radius: f64,
) -> f64 {
    mass * gravity / (string_stiffness * outer_radius)
}

/// The fidelity the stiffness alone allows: rigid when [`deformation_measure`] <
/// [`RIGID_THRESHOLD`] (`auto` also needs the rigid run to be valid, see [`Plan`]).
///
/// ```
/// use wheel_rolling::fidelity::auto_fidelity;
/// use wheel_rolling::Fidelity;
/// assert_eq!(auto_fidelity(14.4, 9.81, 2e4, 1.0), Fidelity::Full);
/// assert_eq!(auto_fidelity(14.4, 9.81, 2e6, 1.0), Fidelity::Rigid);
/// ```
pub fn auto_fidelity(
    mass: f64,
    gravity: f64,
    string_stiffness: f64,
    outer_radius: f64,
) -> Fidelity {
    if deformation_measure(mass, gravity, string_stiffness, outer_radius) < RIGID_THRESHOLD {
        Fidelity::Rigid
    } else {
        Fidelity::Full
    }
}
