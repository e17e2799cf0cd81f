//! Output flags: each opens its io sink ([`tensegrity_io::sink`]) before the command's work,
//! so a bad path fails at once, naming the flag and the path (exit code 2).

use anyhow::{Context, Result};
use std::path::Path;

/// Opens the sink of the output flag `flag` (e.g. `--out`) when a path was given.
pub fn open<T>(
    flag: &str,
    path: Option<&Path>,
    open: impl FnOnce(&Path) -> tensegrity_io::Result<T>,
) -> Result<Option<T>> {
    path.map(|p| open(p).with_context(|| flag.to_string()))
        .transpose()
}

/// Opens the sink of an output flag that always has a path (a default value).
pub fn open_required<T>(
    flag: &str,
    path: &Path,
    open: impl FnOnce(&Path) -> tensegrity_io::Result<T>,
) -> Result<T> {
    open(path).with_context(|| flag.to_string())
}
