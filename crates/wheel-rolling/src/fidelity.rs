//! The fidelity decision: which model a run uses, made in one place for the run and for its
//! resource estimate.
//!
//! A request chooses [`FidelityChoice::Rigid`], [`FidelityChoice::Full`] or
//! [`FidelityChoice::Auto`]. `Auto` runs the cheapest model whose assumptions hold. Its first
//! test is the strain measure ε = m g / (k R_o) — the strain one string of stiffness k would
//! take carrying the whole wheel weight m g over the wheel radius R_o
//! ([`deformation_measure`]): at ε ≥ [`RIGID_THRESHOLD`] the wheel deforms and only the full
//! model applies. Below it the rigid model applies if its run is valid, which is known only
//! after the rigid run. So the decision before any run is a [`Plan`]:
//!
//! | choice | ε | plan |
//! |---|---|---|
//! | rigid | any | [`Plan::Rigid`] |
//! | full | any | [`Plan::Full`] |
//! | auto | ≥ 10⁻³ | [`Plan::Full`] |
//! | auto | < 10⁻³ | [`Plan::RigidThenFullIfInvalid`] |
//!
//! The run follows the plan ([`crate::run::roll_wheel`]) and the estimate budgets exactly
//! what the plan may do ([`crate::estimate::plan`]: the rigid run and then the full one for
//! `RigidThenFullIfInvalid`), so a request the guard admits never runs a model the guard did
//! not count.

use crate::defaults::RIGID_THRESHOLD;
use crate::validity::RollValidity;
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

/// The model a request asks for; serialises as `"rigid"`, `"full"` or `"auto"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FidelityChoice {
    /// The reduced rigid polygon.
    Rigid,
    /// The full tensegrity dynamics.
    Full,
    /// The cheapest valid model: rigid when the strings barely stretch under the wheel's
    /// weight and the rigid run is valid, else full.
    #[default]
    Auto,
}

impl FidelityChoice {
    /// The names as requests write them.
    pub const NAMES: &'static [&'static str] = &["rigid", "full", "auto"];
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
    /// that stretch), or why a rigid run that `rigid` describes was (not) enough.
    pub fn reason(&self, rigid: Option<&RollValidity>) -> String {
        let (strain, k) = (self.strain, self.string_stiffness);
        match (self.choice, rigid) {
            (FidelityChoice::Rigid | FidelityChoice::Full, _) => "requested".to_string(),
            (FidelityChoice::Auto, None) => format!(
                "the strings stretch: m g / (k R_o) = {strain:.2e} ≥ {RIGID_THRESHOLD:.0e} with k = {k} N/m"
            ),
            (FidelityChoice::Auto, Some(v)) if v.valid() => format!(
                "the wheel is stiff (m g / (k R_o) = {strain:.2e} < {RIGID_THRESHOLD:.0e}) and the rigid run is valid"
            ),
            (FidelityChoice::Auto, Some(v)) => format!(
                "the wheel is stiff (m g / (k R_o) = {strain:.2e}) but the rigid run is not valid: {}",
                v.warnings.join("; ")
            ),
        }
    }
}

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
