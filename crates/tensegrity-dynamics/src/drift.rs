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
//! * Creep chatter ([`super::Imex`], the split): the fraction of contact node-steps whose
//!   tangential velocity reversed its change from the previous step by a large part of the
//!   node's speed ([`Integrator::contact_chatter`](super::Integrator::contact_chatter)) must
//!   stay below [`DriftLimits::contact_chatter`] ([`CONTACT_CHATTER_LIMIT`]). Smooth motion
//!   reverses its velocity change only at the velocity's extrema, where the change is small;
//!   the split reverses it at nearly every step on a creeping contact whose friction
//!   relaxation time is short against the step (module docs of [`super::imex`]).
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

/// Default of [`DriftLimits::contact_chatter`]: a tenth of the contact node-steps. Measured
/// under the split IMEX on the toroid wheel's penalty ground (docs/notes/ROLLING.md,
/// "Detecting the split's chatter"; slip fraction in brackets, against IMEX-ARK at 10⁻⁴ s):
///
/// * the n = 8, 30°, μ = 1.2 pivot (reference slip 0.035): 58 % at 5·10⁻⁴ s (0.876), 58 % at
///   2.5·10⁻⁴ s (0.759), 53 % at 10⁻⁴ s (0.246), 7.2 % at 5·10⁻⁵ s (0.103), 5.3 % at
///   2.5·10⁻⁵ s (0.042), 3.4 % at 10⁻⁵ s (0.035);
/// * the hopping n = 8, 50° default (reference 0.213): 5.0 % at 5·10⁻⁴ s (0.218), 2.9 % at
///   2.5·10⁻⁵ s (0.225); n = 8, 30° (reference 0.225, IMEX-ARK at its default 0.307): 21.5 % at
///   5·10⁻⁴ s (0.354), 19.4 % at 10⁻⁴ s (0.325), 7.8 % at 2.5·10⁻⁵ s (0.263), 7.1 % at
///   1.25·10⁻⁵ s (0.266);
/// * the hopping n = 24, 50° (reference 0.396): 11.7 % at 5·10⁻⁴ s (0.450), 8.4 % at
///   2.5·10⁻⁴ s (0.453), 8.8 % at 10⁻⁴ s (0.453), 5.7 % at 2.5·10⁻⁵ s (0.409).
///
/// The same count on IMEX-ARK's steps (which do not chatter: its implicit stages see the load)
/// is 0.2–1.5 %. Converged split runs still count 3–8 % (the landings' high normal loads make
/// even a short step long against the friction's relaxation time, for a few milliseconds),
/// so the limit sits above them; split runs at 7–9 % are biased on the pivot (5·10⁻⁵ s) and on
/// n = 24 (2.5·10⁻⁴ and 10⁻⁴ s) and pass it: the count cannot tell them from converged ones.
pub const CONTACT_CHATTER_LIMIT: f64 = 0.1;

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
    /// Fraction of contact node-steps whose tangential velocity chattered
    /// ([`Integrator::contact_chatter`](super::Integrator::contact_chatter)).
    pub contact_chatter: f64,
}

impl Default for DriftLimits {
    fn default() -> Self {
        Self {
            energy: 1e-3,
            energy_growth: 5e-2,
            bar_length: 1e-6,
            constraint: 1e-6,
            implicit_solve: IMPLICIT_SOLVE_LIMIT,
            contact_chatter: CONTACT_CHATTER_LIMIT,
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
    /// Whether the model was elastic (node masses, no rigid-bar integrator to point to).
    pub elastic: bool,
}

impl DriftWarning {
    /// What to change: depends on the invariant and the integrator that ran.
    pub fn remedy(&self) -> &'static str {
        match (self.quantity, self.integrator) {
            (DriftQuantity::ImplicitSolve, _) => "use a smaller `dt`",
            // the rigid-bar methods are refused on an elastic model
            (_, IntegratorKind::Newmark) => {
                "use a smaller `dt` (the trapezoidal rule keeps the energy of a linear model; it drifts where strings slacken or members turn far within a step)"
            }
            _ if self.elastic => "use a smaller `dt`, or `integrator = newmark` (implicit, energy-conserving on a linear model)",
            // IMEX-ARK's implicit stages see the explicit forces, so a creeping node's velocity
            // balances its load within every stage at any step: the cure, not just a palliative
            (DriftQuantity::CreepChatter, _) => {
                "use `integrator = imex-ark` (its implicit stages see the load, so a creeping contact does not chatter), or a much smaller `dt`"
            }
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

/// What an integrator counted along a run that [`check`] judges.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct IntegratorCounts {
    /// Implicit stage equations solved and those left unconverged
    /// ([`Integrator::implicit_solves`](super::Integrator::implicit_solves)).
    pub implicit_solves: (u64, u64),
    /// Contact node-steps and those that chattered
    /// ([`Integrator::contact_chatter`](super::Integrator::contact_chatter)).
    pub contact_chatter: (u64, u64),
}

/// The warnings of a run with the given drifts (`energy`: relative drift, `energy_gain`:
/// relative gain, `bar_length` and `constraint` in metres) and the integrator's `counts`.
pub fn check(
    model: &Model,
    integrator: IntegratorKind,
    limits: &DriftLimits,
    [energy, energy_gain]: [f64; 2],
    bar_length: f64,
    constraint: f64,
    counts: IntegratorCounts,
) -> Vec<DriftWarning> {
    let (solves, unconverged) = counts.implicit_solves;
    let (node_steps, chattering) = counts.contact_chatter;
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
                elastic: false,
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
    if node_steps > 0 {
        push(
            DriftQuantity::CreepChatter,
            chattering as f64 / node_steps as f64,
            limits.contact_chatter,
        );
    }
    out
}

impl Model {
    /// Whether total energy is conserved by the equations: no string or cluster damping, no
    /// damping or friction at a penalty ground, no thesis ground, no rest-length or load
    /// schedules.
    pub fn is_conservative(&self) -> bool {
        self.strings.iter().all(|s| s.law.damping == 0.0)
            && self.clusters.iter().all(|c| c.damping == 0.0)
            && self.rest_fn.is_none()
            && self.load_fn.is_none()
            && self.drives.is_empty()
            && self.ground.as_ref().is_none_or(ground_is_conservative)
    }

    /// Whether the equations can only lose energy: no rest-length or load schedules
    /// (actuation) and no thesis ground (which pulls); string and ground damping and friction
    /// only dissipate.
    pub fn is_passive(&self) -> bool {
        self.rest_fn.is_none()
            && self.load_fn.is_none()
            && self.drives.is_empty()
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_models::{dropped_prism, dropped_prism_ground};

    /// The dropped prism on its (damped, frictional: passive) penalty ground.
    fn model() -> Model {
        let s = dropped_prism(0.1, 0.0).unwrap();
        let mut model = Model::new(&s, None).unwrap();
        model.set_ground(dropped_prism_ground(1e4, 50.0)).unwrap();
        model
    }

    fn chatter(model: &Model, integrator: IntegratorKind, counts: (u64, u64)) -> Vec<DriftWarning> {
        let counts = IntegratorCounts {
            contact_chatter: counts,
            ..Default::default()
        };
        check(
            model,
            integrator,
            &DriftLimits::default(),
            [0.0; 2],
            0.0,
            0.0,
            counts,
        )
    }

    #[test]
    fn a_chattering_fraction_above_the_limit_is_a_warning_that_names_imex_ark() {
        let model = model();
        // 580 of 1000 node-steps: the split at its default step on the creeping pivot
        let w = chatter(&model, IntegratorKind::Imex, (1000, 580));
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0].quantity, DriftQuantity::CreepChatter);
        assert_eq!(w[0].value, 0.58);
        assert_eq!(w[0].limit, CONTACT_CHATTER_LIMIT);
        let text = w[0].to_string();
        assert!(
            text.contains("58.0 % of their steps, above the limit 10 %")
                && text.contains("`integrator = imex-ark`")
                && text.contains("`dt`"),
            "{text}"
        );
        let json = serde_json::to_value(Warning::from(w[0])).unwrap();
        assert_eq!(json["invariant"], "creep_chatter");
        assert_eq!(json["value"], 0.58);
    }

    #[test]
    fn a_chattering_fraction_at_or_below_the_limit_or_no_count_is_no_warning() {
        let model = model();
        // 5 %: the hopping default; exactly the limit passes; no node-steps: nothing to judge
        for counts in [(1000, 50), (1000, 100), (0, 0)] {
            let w = chatter(&model, IntegratorKind::Imex, counts);
            assert!(w.is_empty(), "{counts:?}: {w:?}");
        }
        let tight = DriftLimits {
            contact_chatter: 0.01,
            ..Default::default()
        };
        let counts = IntegratorCounts {
            contact_chatter: (1000, 50),
            ..Default::default()
        };
        let w = check(
            &model,
            IntegratorKind::Imex,
            &tight,
            [0.0; 2],
            0.0,
            0.0,
            counts,
        );
        assert_eq!(w.len(), 1, "the limit is the settings': {w:?}");
        assert_eq!(w[0].limit, 0.01);
    }
}
