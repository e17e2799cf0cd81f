//! Validity of a finished run: the invariants the equations conserve, checked against
//! documented limits, so a drifted trajectory never comes back without a word.
//!
//! * Bar lengths: rigid bars keep their length exactly; the largest error relative to the
//!   shortest bar must stay below [`DriftLimits::bar_length`] (default 10⁻⁶).
//! * Linear constraints N P = D (class-k joints, supports): the largest ‖N P − D‖ component
//!   relative to the shortest bar must stay below [`DriftLimits::constraint`] (10⁻⁶).
//! * Energy, only when the model is conservative ([`Model::is_conservative`]: no string or
//!   ground damping, no friction, no thesis ground, no actuation): the relative drift
//!   max|E − E₀| / max(|E₀|, max kinetic energy) must stay below [`DriftLimits::energy`]
//!   (10⁻³).
//! * Energy growth, when the model is passive ([`Model::is_passive`]: no actuation and no
//!   thesis ground, so damping and friction can only remove energy): the largest gain
//!   max(E − E₀) / max(|E₀|, max kinetic energy) must stay below
//!   [`DriftLimits::energy_growth`] (5·10⁻²). A damped scene whose energy grows was
//!   integrated unstably (e.g. RATTLE at a step beyond its stiff strings' period).
//!
//! * Implicit stage equations ([`super::ImexArk`]): the fraction whose Newton residual
//!   stayed above its acceptance must stay below [`DriftLimits::implicit_solve`] (10⁻¹).
//!
//! Each breach is a [`DriftWarning`] whose message names the remedy: a smaller step, the
//! adaptive `rk45`, the constraint-preserving `rattle`, or projection.

use super::forces::{Ground, GroundModel};
use super::integrator::IntegratorKind;
use super::model::Model;
use std::fmt;
use tensegrity_core::warning::{DriftInvariant, Warning};

/// Default of [`DriftLimits::implicit_solve`]: a tenth of the stages. Measured under
/// IMEX-ARK on the toroid wheel (penalty ground): 3.0 % at its default 2.5·10⁻⁴ s on the
/// n = 8, 30° pivot (every one within 0.1 s after the impact, where the Stribeck-weakened
/// friction gives the stage equation several roots), 0.8 % on the hopping n = 24 wheel, none
/// at 10⁻⁴ s; 37 % at 10⁻³ s, where the pivot's slip fraction is 0.58 against 0.035.
pub const IMPLICIT_SOLVE_LIMIT: f64 = 0.1;

/// Limits of the invariants' drift (relative; see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriftLimits {
    /// Relative energy drift of a conservative model.
    pub energy: f64,
    /// Relative energy gain of a passive (conservative or dissipative) model.
    pub energy_growth: f64,
    /// Bar-length error relative to the shortest bar.
    pub bar_length: f64,
    /// ‖N P − D‖ relative to the shortest bar.
    pub constraint: f64,
    /// Fraction of an implicit method's stage equations whose Newton residual stayed above
    /// its acceptance ([`Integrator::implicit_solves`](super::Integrator::implicit_solves)).
    pub implicit_solve: f64,
}

impl Default for DriftLimits {
    fn default() -> Self {
        Self {
            energy: 1e-3,
            energy_growth: 5e-2,
            bar_length: 1e-6,
            constraint: 1e-6,
            implicit_solve: IMPLICIT_SOLVE_LIMIT,
        }
    }
}

/// The invariant a warning is about (the core's [`DriftInvariant`]).
pub type DriftQuantity = DriftInvariant;

/// One invariant past its limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DriftWarning {
    /// Which invariant.
    pub quantity: DriftQuantity,
    /// The measured relative drift.
    pub value: f64,
    /// The limit it passed.
    pub limit: f64,
    /// The integrator that ran (the remedy depends on it).
    pub integrator: IntegratorKind,
}

impl DriftWarning {
    /// What to change: depends on the invariant and the integrator that ran.
    pub fn remedy(&self) -> &'static str {
        match (self.quantity, self.integrator) {
            (DriftQuantity::ImplicitSolve, _) => "use a smaller `dt`",
            (_, IntegratorKind::Rattle) => "use a smaller `dt`",
            (DriftQuantity::EnergyGrowth, _) => {
                "use a smaller `dt`, or the L-stable `integrator = sdirk` for stiff strings and contact"
            }
            (DriftQuantity::Energy, IntegratorKind::Rk45 | IntegratorKind::Sdirk) => {
                "tighten `rtol` and `atol`, or use `integrator = rattle` (symplectic)"
            }
            (DriftQuantity::Energy, _) => {
                "use a smaller `dt`, `integrator = rk45`, or `integrator = rattle` (symplectic, no secular drift)"
            }
            _ => "use a smaller `dt`, `integrator = rattle` (keeps lengths and joints exactly), or projection ([simulation] project = true)",
        }
    }
}

impl From<DriftWarning> for Warning {
    fn from(w: DriftWarning) -> Warning {
        Warning::Drift {
            invariant: w.quantity,
            value: w.value,
            limit: w.limit,
            remedy: w.remedy().to_string(),
        }
    }
}

impl fmt::Display for DriftWarning {
    /// The text of the core's [`Warning::Drift`] (warnings are rendered in one place).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        Warning::from(*self).fmt(f)
    }
}

/// The warnings of a run with the given drifts (`energy`: relative drift, `energy_gain`:
/// relative gain, `bar_length` and `constraint` in metres) and implicit stage solves
/// (solved, unconverged).
pub fn check(
    model: &Model,
    integrator: IntegratorKind,
    limits: &DriftLimits,
    [energy, energy_gain]: [f64; 2],
    bar_length: f64,
    constraint: f64,
    (solves, unconverged): (u64, u64),
) -> Vec<DriftWarning> {
    let l_min = model.shortest_bar();
    let mut out = Vec::new();
    let mut push = |quantity, value: f64, limit: f64| {
        // NaN drifts count as breaches
        if value.is_nan() || value > limit {
            out.push(DriftWarning {
                quantity,
                value,
                limit,
                integrator,
            });
        }
    };
    if model.is_conservative() {
        push(DriftQuantity::Energy, energy, limits.energy);
    }
    if model.is_passive() {
        push(
            DriftQuantity::EnergyGrowth,
            energy_gain,
            limits.energy_growth,
        );
    }
    push(
        DriftQuantity::BarLength,
        bar_length / l_min,
        limits.bar_length,
    );
    push(
        DriftQuantity::Constraint,
        constraint / l_min,
        limits.constraint,
    );
    if solves > 0 {
        push(
            DriftQuantity::ImplicitSolve,
            unconverged as f64 / solves as f64,
            limits.implicit_solve,
        );
    }
    out
}

impl Model {
    /// Whether total energy is conserved by the equations: no string damping, no damping or
    /// friction at a penalty ground, no thesis ground, no rest-length or load schedules.
    pub fn is_conservative(&self) -> bool {
        self.strings.iter().all(|s| s.law.damping == 0.0)
            && self.rest_fn.is_none()
            && self.load_fn.is_none()
            && self.ground.as_ref().is_none_or(ground_is_conservative)
    }

    /// Whether the equations can only lose energy: no rest-length or load schedules
    /// (actuation) and no thesis ground (which pulls); string and ground damping and friction
    /// only dissipate.
    pub fn is_passive(&self) -> bool {
        self.rest_fn.is_none()
            && self.load_fn.is_none()
            && self.ground.as_ref().is_none_or(|g| {
                matches!(
                    g.model,
                    GroundModel::Penalty { .. } | GroundModel::Stick { .. }
                )
            })
    }

    /// The shortest bar's length (m) of the initial state (1/ε when there is no bar).
    pub fn shortest_bar(&self) -> f64 {
        self.bars
            .iter()
            .map(|b| b.length0)
            .fold(f64::INFINITY, f64::min)
            .clamp(f64::MIN_POSITIVE, 1.0 / f64::EPSILON)
    }
}

/// A ground stores energy without losing it only as an undamped, frictionless penalty spring.
fn ground_is_conservative(g: &Ground) -> bool {
    match g.model {
        GroundModel::Penalty {
            damping,
            mu_static,
            mu_kinetic,
            ..
        } => damping == 0.0 && mu_static == 0.0 && mu_kinetic == 0.0,
        _ => false,
    }
}
