//! One writer per output path: an exclusive advisory lock on `.NAME.lock` beside the target.
//!
//! The lock is taken with [`std::fs::File::try_lock`] (`flock` on Unix, `LockFileEx` on
//! Windows), so the operating system releases it when the process ends in any way, `kill -9`
//! included. A second writer — another process, or another sink of the same process — is
//! refused at once with [`IoError::Busy`], which names the target and the holder (`pid N`,
//! written into the lock file).
//!
//! The lock file is removed on release, while still locked. A writer that locked a file which
//! was removed (or replaced) in the meantime sees that the path no longer leads to the file it
//! holds and starts over, so two writers can never both hold "the" lock of one path.

use crate::error::{IoError, Result};
use std::fs::{File, TryLockError};
use std::io::Write;
use std::path::{Path, PathBuf};

/// An exclusive lock on an output path, held until dropped.
///
/// ```
/// use tensegrity_io::sink::PathLock;
/// let target = std::env::temp_dir().join(format!("lock-doc-{}.csv", std::process::id()));
/// let lock = PathLock::acquire(&target)?;
/// let err = PathLock::acquire(&target).unwrap_err(); // a second writer is refused
/// assert!(err.to_string().contains(&format!("pid {}", std::process::id())), "{err}");
/// drop(lock);
/// let again = PathLock::acquire(&target)?; // free again
/// # drop(again);
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
#[derive(Debug)]
pub struct PathLock {
    file: Option<File>,
    path: PathBuf,
}

impl PathLock {
    /// Locks `target` (the output file or, for a series, its index file) for this process.
    /// Fails with [`IoError::Write`] naming `target` when the lock file cannot be created
    /// there (a missing or read-only directory), and with [`IoError::Busy`] when another
    /// writer holds it.
    pub fn acquire(target: &Path) -> Result<Self> {
        let path = lock_path(target);
        let write_err = |source| IoError::Write {
            path: target.to_path_buf(),
            source,
        };
        loop {
            let mut file = File::options()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .map_err(write_err)?;
            match file.try_lock() {
                Ok(()) => {}
                Err(TryLockError::WouldBlock) => {
                    return Err(IoError::Busy {
                        path: target.to_path_buf(),
                        holder: holder(&path),
                    })
                }
                Err(TryLockError::Error(source)) => return Err(write_err(source)),
            }
            if !still_at(&file, &path) {
                continue; // released and removed meanwhile: lock the current file
            }
            // who holds it, for the message of a refused writer (best effort)
            let _ = file.set_len(0);
            let _ = writeln!(file, "pid {}", std::process::id());
            crate::interrupt::hold_lock(&path);
            return Ok(Self {
                file: Some(file),
                path,
            });
        }
    }

    /// The lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for PathLock {
    fn drop(&mut self) {
        // removed while still held, then unlocked by closing
        let _ = std::fs::remove_file(&self.path);
        crate::interrupt::release_lock(&self.path);
        drop(self.file.take());
    }
}

/// `dir/.NAME.lock` beside `target`.
pub(crate) fn lock_path(target: &Path) -> PathBuf {
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    target.with_file_name(format!(".{name}.lock"))
}

/// What the holder wrote into the lock file.
fn holder(path: &Path) -> String {
    std::fs::read_to_string(path)
        .ok()
        .map(|t| t.trim().to_string())
        .filter(|t| !t.is_empty())
        .unwrap_or_else(|| "pid unknown".into())
}

/// Whether `path` still names the file `file` holds.
#[cfg(unix)]
fn still_at(file: &File, path: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    match (file.metadata(), std::fs::metadata(path)) {
        (Ok(a), Ok(b)) => a.dev() == b.dev() && a.ino() == b.ino(),
        _ => false,
    }
}

/// Whether `path` still names the file `file` holds (without file identities: exists).
#[cfg(not(unix))]
fn still_at(_file: &File, path: &Path) -> bool {
    path.exists()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn target(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("io-lock-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir.join("out.csv")
    }

    #[test]
    fn a_second_writer_is_refused_until_the_first_releases() {
        let t = target("second");
        let first = PathLock::acquire(&t).unwrap();
        assert!(first.path().ends_with(".out.csv.lock"));
        match PathLock::acquire(&t) {
            Err(IoError::Busy { path, holder }) => {
                assert_eq!(path, t);
                assert_eq!(holder, format!("pid {}", std::process::id()));
            }
            other => panic!("{other:?}"),
        }
        drop(first);
        assert!(!lock_path(&t).exists(), "the lock file is removed");
        let _second = PathLock::acquire(&t).unwrap();
    }

    #[test]
    fn a_stale_lock_file_of_a_killed_writer_is_taken_over() {
        let t = target("stale");
        std::fs::write(lock_path(&t), "pid 999999999\n").unwrap();
        let lock = PathLock::acquire(&t).unwrap();
        let text = std::fs::read_to_string(lock.path()).unwrap();
        assert_eq!(text, format!("pid {}\n", std::process::id()));
    }

    #[test]
    fn a_missing_directory_fails_naming_the_target() {
        let t = target("missing").join("no").join("x.csv");
        match PathLock::acquire(&t) {
            Err(e @ IoError::Write { .. }) => assert!(e.to_string().contains("x.csv"), "{e}"),
            other => panic!("{other:?}"),
        }
    }
}
