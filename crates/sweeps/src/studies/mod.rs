//! The studies a sweep can run: each builds, from one case's [`Params`], the same library
//! request as its single-point command and returns that command's report as JSON.
//!
//! | study | single-point command | library call |
//! |---|---|---|
//! | `toroid` | `tensegrity toroid --json` | [`toroid::toroid_report`] |
//! | `roll` | `tensegrity roll --json` | [`toroid::roll`] |
//! | `tipover` | `tensegrity tipover --json` | [`toroid::tipover_report`] |
//! | `michell` | `tensegrity michell --json` | [`michell3d::analyse`] |
//! | `integrators` | `tensegrity bench work-precision` (one point) | [`tensegrity_core::dynamics::work_precision::run_one`] |
//! | `tbar` | `tensegrity tbar --json` | [`tbar_wheel::tbar_report`] |
//! | `lean` | `tensegrity tipover --rolling --json` | [`toroid::rolling_lean::LeanRolling::run`] |
//!
//! A parameter left out of a spec takes the library's default (the CLI's default too):
//! [`toroid::WheelSpec::default`], [`toroid::ToroidRequest::default`],
//! [`toroid::RollRequest::default`], [`toroid::TipoverRequest::default`],
//! [`michell3d::AnalysisRequest::new`], [`tbar_wheel::TbarRequest::new`].

mod integrators;
mod michell;
mod tbar;
#[macro_use]
mod wheel;
mod roll;

use crate::error::{Result, SweepError};
use crate::params::{ParamDef, Params};
use serde::Serialize;

pub use integrators::Context;

/// A result column: a scalar of the single-point report, named by its JSON key (a nested
/// key as `outer.inner`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Column {
    /// The JSON key path.
    pub name: &'static str,
    /// SI unit (`""` when dimensionless or not a number).
    pub unit: &'static str,
}

pub(crate) const fn col(name: &'static str, unit: &'static str) -> Column {
    Column { name, unit }
}

/// A study.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Study {
    /// Statics, mass and inertia of the toroid wheel.
    Toroid,
    /// The toroid wheel rolling down an incline.
    Roll,
    /// Tip-over of the toroid wheel under a lateral force.
    Tipover,
    /// The discrete Michell truss.
    Michell,
    /// One point of the integrators' work–precision study.
    Integrators,
    /// The T-bar tread or wheel: statics, load envelope, mass.
    Tbar,
    /// Lean of the toroid rolling down a cross-sloped plane (`tipover --rolling`).
    Lean,
}

impl Study {
    /// Every study.
    pub const ALL: [Study; 7] = [
        Study::Toroid,
        Study::Roll,
        Study::Tipover,
        Study::Michell,
        Study::Integrators,
        Study::Tbar,
        Study::Lean,
    ];

    /// The name a spec's `study` gives.
    pub fn name(self) -> &'static str {
        match self {
            Study::Toroid => "toroid",
            Study::Roll => "roll",
            Study::Tipover => "tipover",
            Study::Michell => "michell",
            Study::Integrators => "integrators",
            Study::Tbar => "tbar",
            Study::Lean => "lean",
        }
    }

    /// The study of that name.
    pub fn from_name(name: &str) -> Result<Study> {
        Study::ALL
            .into_iter()
            .find(|s| s.name() == name)
            .ok_or_else(|| SweepError::UnknownStudy {
                study: name.to_string(),
                known: Study::ALL.map(Study::name).join(", "),
            })
    }

    /// The study's parameters.
    pub fn params(self) -> &'static [ParamDef] {
        match self {
            Study::Toroid => &wheel::TOROID_PARAMS,
            Study::Roll => &roll::ROLL_PARAMS,
            Study::Tipover => &wheel::TIPOVER_PARAMS,
            Study::Michell => &michell::PARAMS,
            Study::Integrators => &integrators::PARAMS,
            Study::Tbar => &tbar::PARAMS,
            Study::Lean => &wheel::LEAN_PARAMS,
        }
    }

    /// The parameter of that name.
    pub fn param(self, name: &str) -> Option<&'static ParamDef> {
        self.params().iter().find(|p| p.name == name)
    }

    /// The result columns, in the report's key order.
    pub fn columns(self) -> &'static [Column] {
        match self {
            Study::Toroid => &wheel::TOROID_COLUMNS,
            Study::Roll => &roll::ROLL_COLUMNS,
            Study::Tipover => &wheel::TIPOVER_COLUMNS,
            Study::Michell => &michell::COLUMNS,
            Study::Integrators => &integrators::COLUMNS,
            Study::Tbar => &tbar::COLUMNS,
            Study::Lean => &wheel::LEAN_COLUMNS,
        }
    }

    /// Runs one case: the single-point report as JSON (`serde_json::to_value` of the library
    /// report), or the error's message.
    pub fn report(self, p: &Params, ctx: &Context) -> Result<serde_json::Value, String> {
        match self {
            Study::Toroid => json(toroid::toroid_report(&wheel::toroid_request(p)?)),
            Study::Roll => json(toroid::roll(&roll::roll_request(p)?)),
            Study::Tipover => json(toroid::tipover_report(&wheel::tipover_request(p)?)),
            Study::Michell => json(michell3d::analyse(&michell::request(p)?)),
            Study::Integrators => json(integrators::point(p, ctx)),
            Study::Tbar => json(tbar_wheel::tbar_report(&tbar::request(p)?)),
            Study::Lean => json(wheel::lean_report(p)),
        }
    }
}

impl From<SweepError> for String {
    fn from(e: SweepError) -> String {
        e.to_string()
    }
}

fn json<T: Serialize, E: std::fmt::Display>(
    r: std::result::Result<T, E>,
) -> Result<serde_json::Value, String> {
    let report = r.map_err(|e| e.to_string())?;
    serde_json::to_value(&report).map_err(|e| format!("the report does not serialise: {e}"))
}

#[cfg(test)]
mod tests;
