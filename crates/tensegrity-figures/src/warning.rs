//! Warnings of the figure table: a figure drawn from a model used outside its assumptions,
//! recorded in the [`crate::Context`] and returned beside the outcomes of
//! [`crate::build_figures`].

/// A figure drawn from a model used outside its assumptions: what the front end shows beside
/// the list of files.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    /// The figure's number.
    pub figure: &'static str,
    /// What is outside the model's assumptions.
    pub warning: tensegrity_core::Warning,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Fig. {}: {}", self.figure, self.warning)
    }
}
