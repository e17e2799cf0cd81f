//! Reading input text files under a size limit, so that a huge file or an endless stream
//! (`/dev/zero`, a pipe) is refused at once instead of being read into memory.
//!
//! A regular file larger than the limit is refused from its size, before any byte is read;
//! any other file (a device, a FIFO) is read to at most `limit + 1` bytes, and refused when
//! it gave more than `limit`.
//!
//! ```
//! use tensegrity_io::read::read_text;
//! let e = read_text("/dev/zero".as_ref(), 1024, "a scene file").unwrap_err().to_string();
//! assert!(e.contains("/dev/zero") && e.contains("more than 1024 bytes"), "{e}");
//! ```

use crate::error::{IoError, Result};
use std::io::Read;
use std::path::Path;

/// The largest scene file read (64 MiB: a scene of about a million nodes; larger structures
/// are built by the topology commands, not written out as TOML).
pub const MAX_SCENE_BYTES: u64 = 64 << 20;

/// Reads a UTF-8 text file of at most `limit` bytes; `what` names the kind of file in the
/// error (`a scene file`). Errors: [`IoError::TooLarge`] naming the file and its size,
/// [`IoError::Read`] for a file that cannot be opened or is not UTF-8.
pub fn read_text(path: &Path, limit: u64, what: &'static str) -> Result<String> {
    let read_err = |source| IoError::Read {
        path: path.to_path_buf(),
        source,
    };
    let too_large = |size| IoError::TooLarge {
        path: path.to_path_buf(),
        size,
        limit,
        what,
    };
    let file = std::fs::File::open(path).map_err(read_err)?;
    let meta = file.metadata().map_err(read_err)?;
    if meta.is_file() && meta.len() > limit {
        return Err(too_large(Some(meta.len())));
    }
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(read_err)?;
    if bytes.len() as u64 > limit {
        return Err(too_large(None));
    }
    String::from_utf8(bytes).map_err(|e| {
        read_err(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        ))
    })
}
