//! The ground contact a rolling request chooses for the full model ([`ContactKind`]). A leaf
//! of the crate: it names nothing else of it, so the defaults and the settings can read it.

use serde::{Deserialize, Serialize};

/// The ground contact a request asks of the full model; serialises as `"penalty"`,
/// `"thesis"` or `"stick"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ContactKind {
    /// Penalty spring–damper (never pulling) with regularised Coulomb friction.
    #[default]
    Penalty,
    /// Thesis §3.2.2: weight-based normal reaction plus velocity damping (it can pull and
    /// sink; its runs are flagged when they do).
    Thesis,
    /// The penalty spring–damper with friction that sticks: an elastic–plastic tangential
    /// spring per contact node (`tensegrity_dynamics::stick`).
    Stick,
}

impl ContactKind {
    /// The names as requests write them.
    pub const NAMES: &'static [&'static str] = &["penalty", "thesis", "stick"];

    /// Whether the contact is a penalty spring (its stiffness is refined by the convergence
    /// check).
    pub fn is_penalty(self) -> bool {
        matches!(self, Self::Penalty | Self::Stick)
    }
}
