//! Why a case of a sweep gave no result ([`CaseError`]): its row is an `error` row whose
//! `error` column is this error's text.

use crate::expr::ExprError;
use crate::limits::Refused;

/// Why one case gave no result.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum CaseError {
    /// A derived rule could not be evaluated for this case (e.g. a division by zero).
    #[error("derived `{name}`: {source}")]
    Derived {
        /// The derived parameter.
        name: String,
        /// Why its rule failed.
        source: ExprError,
    },
    /// The case's estimate is above a limit: refused before it ran.
    #[error(transparent)]
    Refused(#[from] Refused),
    /// The analysis refused the case's values or failed.
    #[error("{message}")]
    Analysis {
        /// The analysis's error, as the command line words it.
        message: String,
    },
    /// The analysis panicked (a defect: the sweep goes on and records it).
    #[error("the analysis panicked: {message}")]
    Panicked {
        /// The panic's message.
        message: String,
    },
}
