//! Built-in topologies by name: `prism:N`, `octahedron`, `tower:N:M`, `grid:K`.

use crate::error::{FormFindError, Result};
use crate::topology::Topology;

/// The names (and forms) [`builtin`] knows.
pub const BUILTINS: &[&str] = &["prism:N", "octahedron", "tower:N:M", "grid:K"];

/// A built-in topology by name.
pub fn builtin(name: &str) -> Result<Topology> {
    Err(FormFindError::UnknownBuiltin {
        name: name.to_string(),
        known: BUILTINS.join(", "),
    })
}
