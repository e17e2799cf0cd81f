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

/// What a figure of a run that is not valid says on it ([`tensegrity_io::figure::Figure::mark_invalid`]):
/// the first warning's kind (a warning of one wheel's run: its kind and the wheel, `n = 8`),
/// and how many more there are; `see the report` without warnings.
///
/// ```
/// use tensegrity_core::Warning;
/// use tensegrity_figures::warning::invalid_reason;
/// let w = Warning::NotPrestressable;
/// assert_eq!(invalid_reason(&[w.clone()]), "not_prestressable");
/// assert_eq!(invalid_reason(&[w.clone(), w.clone().in_run(8, "rigid")]), "not_prestressable (+1 more)");
/// assert_eq!(invalid_reason(&[w.in_run(8, "rigid")]), "n = 8: not_prestressable");
/// ```
pub fn invalid_reason(warnings: &[tensegrity_core::Warning]) -> String {
    let Some(first) = warnings.first() else {
        return "see the report".into();
    };
    let kind = match first {
        tensegrity_core::Warning::InRun { sides, warning, .. } => {
            format!("n = {sides}: {}", warning.kind())
        }
        w => w.kind().to_string(),
    };
    match warnings.len() {
        1 => kind,
        n => format!("{kind} (+{} more)", n - 1),
    }
}

/// `figure` marked as showing a run that is not valid when `valid` is false (the reason from
/// `warnings`, [`invalid_reason`]); as it is otherwise.
pub fn marked(
    figure: tensegrity_io::figure::Figure,
    valid: bool,
    warnings: &[tensegrity_core::Warning],
) -> tensegrity_io::figure::Figure {
    if valid {
        figure
    } else {
        figure.mark_invalid(invalid_reason(warnings))
    }
}
