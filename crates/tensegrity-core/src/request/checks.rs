//! [`RunChecks`]: what every dynamic request (`roll`, `tbar_roll`, `tipover_dynamic`,
//! `tipover_rolling`, `simulate`) shares about judging its own result — whether an invalid or
//! unconverged result is an error (`strict`), and whether the result is re-estimated at a
//! refined resolution (`convergence_check`, see [`crate::dynamics::convergence`]).
//!
//! Flattened into each request, so that the command line takes `--strict` and
//! `--no-convergence-check` (a flag whose default is true is written negated) and Python the
//! keywords `strict=`, `convergence_check=`.

use serde::{Deserialize, Serialize};
use tensegrity_derive::Params;

/// The result checks of a dynamic request (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Params)]
#[serde(default)]
pub struct RunChecks {
    /// An invalid (or unconverged) result is an error, after the outputs are written.
    #[param(
        flag,
        help = "Fail (exit 1, after writing the outputs) when the result is not valid: outside its model's assumptions or not converged"
    )]
    pub strict: bool,
    /// Re-run at a refined resolution and report each headline quantity's change.
    #[param(
        flag,
        help = Self::CONVERGENCE_CHECK_HELP
    )]
    pub convergence_check: bool,
}

impl Default for RunChecks {
    /// Not strict; convergence checked.
    fn default() -> Self {
        Self {
            strict: false,
            convergence_check: true,
        }
    }
}

impl RunChecks {
    /// No convergence run, not strict (a run inside another study, e.g. a refined run itself).
    pub const NONE: Self = Self {
        strict: false,
        convergence_check: false,
    };

    /// The help text of `convergence_check` (also of the requests that spell the field
    /// themselves, `simulate`).
    pub const CONVERGENCE_CHECK_HELP: &'static str = "Re-run at a companion resolution beside the run (twice a fixed step where that stays stable and accurate, half a run's work; else half the step) and report each headline quantity's change, extrapolated error and status, and the check's cost, in `convergence`; rolling: the companion starts turned by 1e-6 rad, and where a quantity moved a second run tells chaotic quantities; an unconverged result is not valid";
}
