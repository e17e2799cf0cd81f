//! The model a rolling request asks for ([`FidelityChoice`]: rigid, full or the `auto`
//! policy of [`crate::fidelity`]). A leaf of the crate: it names nothing else of it, so the
//! settings can hold it while the fidelity decision reads the settings.

use serde::{Deserialize, Serialize};

/// The model a request asks for; serialises as `"rigid"`, `"full"` or `"auto"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FidelityChoice {
    /// The reduced rigid polygon.
    Rigid,
    /// The full tensegrity dynamics.
    Full,
    /// The fidelity policy (the module docs of [`crate::fidelity`]): rigid where the strings barely stretch under the
    /// wheel's weight, the models agree on the scene's class and the rigid run is valid, else
    /// full.
    #[default]
    Auto,
}

impl FidelityChoice {
    /// The names as requests write them.
    pub const NAMES: &'static [&'static str] = &["rigid", "full", "auto"];
}
