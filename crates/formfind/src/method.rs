//! The form-finding methods and their settings.

use serde::{Deserialize, Serialize};
use std::fmt;
use std::str::FromStr;

/// A form-finding method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Force density method with the given force densities.
    Fdm,
    /// Adaptive force density: force densities found from the connectivity.
    Adaptive,
    /// Dynamic relaxation with kinetic damping from rest lengths and stiffnesses.
    Dr,
    /// As [`Method::Given`], except that force densities which admit no free-standing form,
    /// and force densities given on only some members, fall back to the adaptive method
    /// (started from them, so it replaces them); the result says what was chosen and why
    /// ([`crate::FormFound::choice`]). Asked for by name only (`auto`).
    Auto,
    /// The method the topology's data call for (the default): the force density method
    /// when every member has a force density, dynamic relaxation when every member has a
    /// length instead, the adaptive method when it gives neither; data some members give
    /// and others do not is refused, and so is the failure of the force density method
    /// (no fallback: its error names the adaptive method). See [`crate::form_find`].
    #[default]
    Given,
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Method::Fdm => "fdm",
            Method::Adaptive => "adaptive",
            Method::Dr => "dr",
            Method::Auto => "auto",
            Method::Given => "given",
        })
    }
}

impl FromStr for Method {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s.to_ascii_lowercase().as_str() {
            "fdm" => Ok(Method::Fdm),
            "adaptive" => Ok(Method::Adaptive),
            "dr" => Ok(Method::Dr),
            "auto" => Ok(Method::Auto),
            _ => Err(format!(
                "unknown method \"{s}\" (fdm, adaptive, dr or auto)"
            )),
        }
    }
}

/// Settings of a form-finding run.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// The method.
    pub method: Method,
    /// Convergence tolerance of the iterative methods (relative residual).
    pub tolerance: f64,
    /// Iteration cap of the iterative methods.
    pub max_iterations: usize,
    /// Default axial stiffness EA (N) of members that give none (dynamic relaxation).
    pub stiffness: f64,
    /// Whether to analyse the found form: its self-stress dimension, prestressability and
    /// prestress stability (the `analysis` module; default [`ANALYSE`]). Without, those
    /// fields of the result are `None` and the form costs the method alone.
    pub analyse: bool,
}

/// Whether form-finding analyses the found form unless told otherwise: no — the form is
/// returned at the cost of the method, and the statics (rank, the prestress-margin LP,
/// stability: most of the time on a large form) only where asked for.
pub const ANALYSE: bool = false;

impl Default for Settings {
    fn default() -> Self {
        Settings {
            method: Method::default(),
            tolerance: 1e-12,
            max_iterations: 10_000,
            stiffness: 1e5,
            analyse: ANALYSE,
        }
    }
}

impl Settings {
    /// Checks the tolerances and the stiffness; the error names the field.
    pub fn validate(&self) -> crate::Result<()> {
        use tensegrity_core::request::InvalidParameter;
        if !(self.tolerance.is_finite() && self.tolerance > 0.0 && self.tolerance < 1.0) {
            return Err(InvalidParameter::new(
                "tolerance",
                self.tolerance,
                "must lie strictly between 0 and 1",
            )
            .into());
        }
        if self.max_iterations == 0 {
            return Err(InvalidParameter::raw("max_iterations", 0, "must be at least 1").into());
        }
        if !(self.stiffness.is_finite() && self.stiffness > 0.0) {
            return Err(InvalidParameter::new(
                "stiffness",
                self.stiffness,
                "must be finite and positive",
            )
            .into());
        }
        Ok(())
    }
}

/// What [`crate::synthesize`] makes of a found form.
#[derive(Debug, Clone, PartialEq)]
pub struct Synthesis {
    /// Prestress level: the largest string tension (N) of the scaled self-stress.
    pub prestress: f64,
    /// Axial stiffness EA (N) of the strings (and bars, where they are elastic).
    pub stiffness: f64,
    /// Mass of each bar (kg), for the dynamics.
    pub bar_mass: f64,
}

impl Default for Synthesis {
    fn default() -> Self {
        Synthesis {
            prestress: 100.0,
            stiffness: 1e5,
            bar_mass: 1.0,
        }
    }
}
