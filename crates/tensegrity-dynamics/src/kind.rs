//! [`IntegratorKind`]: the names of the time integrators, how a scene file and a front end
//! spell them, and [`IntegratorFacts`], the one table of what each method is (order, which
//! parts are implicit, step control, events, what it is for). The constructors are in
//! `factory.rs` ([`IntegratorKind::build`]), the methods one per file.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// Which part of the right-hand side a method treats implicitly.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Implicit {
    /// Fully explicit.
    None,
    /// The joint constraints only (a projection after each explicit stage).
    Constraints,
    /// The ground contact's stiff part; the smooth forces explicit.
    Contact,
    /// The whole right-hand side (Newton on every stage).
    Full,
}

/// The facts of one method ([`IntegratorKind::facts`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct IntegratorFacts {
    /// Classical order of accuracy on smooth problems.
    pub order: u32,
    /// What is treated implicitly.
    pub implicit: Implicit,
    /// Whether the method chooses its own steps (`dt` is then the largest one).
    pub adaptive: bool,
    /// Whether the method locates events (sign changes) inside a step.
    pub events: bool,
    /// What the method is for, in a few words.
    pub purpose: &'static str,
}

/// The time integrators known to [`Simulation`](crate::Simulation) and the scene files.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum IntegratorKind {
    /// Classic fixed-step RK4 (MOTES parity).
    #[default]
    Rk4,
    /// Adaptive Dormand–Prince 5(4) with dense output and event location.
    Rk45,
    /// Fixed-step constraint-preserving RATTLE (2nd order, symplectic).
    Rattle,
    /// Adaptive L-stable SDIRK 3(2) with Newton iterations (stiff strings and contact).
    Sdirk,
    /// Fixed-step IMEX splitting: RK4 for the smooth forces, a linearly implicit ROS2 step
    /// for the penalty ground contact ([`Imex`](crate::Imex)): stiff contact at the step of the motion.
    Imex,
    /// Fixed-step additive Runge–Kutta ARK3(2)4L\[2\]SA: the smooth forces explicit, the
    /// ground's damping and friction implicit at every stage ([`ImexArk`](crate::ImexArk)): it follows a
    /// contact that creeps under the regularised friction at steps of the motion, at the cost
    /// of a Newton solve on the contact velocities per stage.
    #[serde(rename = "imex-ark")]
    ImexArk,
    /// RK4 at `dt` while a ground contact node touches or approaches the ground, and at
    /// [`FLIGHT_RATIO`](crate::flight::FLIGHT_RATIO)·dt in flight ([`Flight`](crate::Flight)).
    #[serde(rename = "rk4-flight")]
    Rk4Flight,
    /// Fixed-step Newmark average acceleration (the implicit trapezoidal rule: 2nd order,
    /// unconditionally stable, no numerical damping) with Newton on the tangent stiffness:
    /// elastic models only (`tensegrity_path::transient`), whose stiff axial modes it steps
    /// over at the step of the motion.
    Newmark,
}

impl IntegratorKind {
    /// The name of every kind, as [`fmt::Display`] writes it and [`FromStr`] reads it (the
    /// choices of a front end's `integrator` parameter).
    pub const NAMES: &'static [&'static str] = &[
        "rk4",
        "rk45",
        "rattle",
        "sdirk",
        "imex",
        "imex-ark",
        "rk4-flight",
        "newmark",
    ];

    /// The names of the integrators of rigid-bar models ([`NAMES`](Self::NAMES) but
    /// `newmark`): the choices of a front end that runs rigid bars only.
    pub const RIGID_NAMES: &'static [&'static str] = Self::NAMES.split_at(7).0;

    /// Every integrator of rigid-bar models, in the order of [`NAMES`](Self::NAMES) (for
    /// studies and tests; [`IntegratorKind::Newmark`], the last name, steps elastic models
    /// only).
    pub const ALL: [IntegratorKind; 7] = [
        Self::Rk4,
        Self::Rk45,
        Self::Rattle,
        Self::Sdirk,
        Self::Imex,
        Self::ImexArk,
        Self::Rk4Flight,
    ];

    /// What this method is: its order, which parts are implicit, whether it adapts its step
    /// and locates events, and what it is for (the one table of per-method facts).
    ///
    /// ```
    /// use tensegrity_dynamics::IntegratorKind;
    /// assert_eq!(IntegratorKind::Rk4.facts().order, 4);
    /// assert!(IntegratorKind::ALL.iter().filter(|k| k.facts().adaptive).count() == 2);
    /// ```
    pub fn facts(self) -> IntegratorFacts {
        let (order, implicit, adaptive, events, purpose) = match self {
            Self::Rk4 => (
                4,
                Implicit::None,
                false,
                false,
                "non-stiff scenes; MOTES parity",
            ),
            Self::Rk45 => (
                5,
                Implicit::None,
                true,
                true,
                "non-stiff scenes to a tolerance, with event location",
            ),
            Self::Rattle => (
                2,
                Implicit::Constraints,
                false,
                false,
                "long runs that must keep the joint constraints and the energy",
            ),
            Self::Sdirk => (
                3,
                Implicit::Full,
                true,
                false,
                "stiff strings and stiff or damped contact",
            ),
            Self::Imex => (
                2,
                Implicit::Contact,
                false,
                false,
                "stiff penalty contact at the step of the motion",
            ),
            Self::ImexArk => (
                3,
                Implicit::Contact,
                false,
                false,
                "contact that creeps under regularised friction",
            ),
            Self::Rk4Flight => (
                4,
                Implicit::None,
                false,
                false,
                "contact scenes that spend long phases in flight",
            ),
            Self::Newmark => (
                2,
                Implicit::Full,
                false,
                false,
                "elastic members with stiff axial modes (elastic models only)",
            ),
        };
        IntegratorFacts {
            order,
            implicit,
            adaptive,
            events,
            purpose,
        }
    }

    /// Whether the integrator chooses its own steps (`dt` is then the largest step, and
    /// `rtol`/`atol` apply).
    pub fn is_adaptive(self) -> bool {
        matches!(self, Self::Rk45 | Self::Sdirk)
    }
}

impl fmt::Display for IntegratorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            IntegratorKind::Rk4 => "rk4",
            IntegratorKind::Rk45 => "rk45",
            IntegratorKind::Rattle => "rattle",
            IntegratorKind::Sdirk => "sdirk",
            IntegratorKind::Imex => "imex",
            IntegratorKind::ImexArk => "imex-ark",
            IntegratorKind::Rk4Flight => "rk4-flight",
            IntegratorKind::Newmark => "newmark",
        })
    }
}

impl FromStr for IntegratorKind {
    type Err = String;
    /// Parses `rk4`, `rk45` (or `dopri5`), `rattle`, `sdirk`, `imex`, `imex-ark` (or `ark`),
    /// `rk4-flight` or `newmark` (case-insensitive).
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "rk4" => Ok(Self::Rk4),
            "rk45" | "dopri5" => Ok(Self::Rk45),
            "rattle" => Ok(Self::Rattle),
            "sdirk" => Ok(Self::Sdirk),
            "imex" => Ok(Self::Imex),
            "imex-ark" | "ark" => Ok(Self::ImexArk),
            "rk4-flight" | "rk4flight" => Ok(Self::Rk4Flight),
            "newmark" => Ok(Self::Newmark),
            other => Err(format!(
                "unknown integrator \"{other}\" (expected rk4, rk45, rattle, sdirk, imex, imex-ark, rk4-flight or newmark)"
            )),
        }
    }
}
