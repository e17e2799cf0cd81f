//! The file under every sink: a temporary file `.NAME.tmp` beside the target, renamed onto it
//! when the sink is finished, removed when it is abandoned.

use super::lock::PathLock;
use crate::error::{IoError, Result};
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

/// A temporary file being written for `target` (see the module documentation).
#[derive(Debug)]
pub(crate) struct Staged<W> {
    target: PathBuf,
    tmp: PathBuf,
    out: Option<W>,
    lock: Option<PathLock>,
}

impl<W> Staged<W> {
    /// Locks `target`, then creates the temporary file beside it: a missing or read-only
    /// directory, a target that is a directory, or another writer fail here, before any work.
    pub(crate) fn open(target: &Path, wrap: impl FnOnce(File) -> W) -> Result<Self> {
        refuse_directory(target)?;
        let lock = PathLock::acquire(target)?;
        let mut staged = Self::open_unlocked(target, wrap)?;
        staged.lock = Some(lock);
        Ok(staged)
    }

    /// [`Staged::open`] without a lock of its own (a frame of a locked series).
    pub(crate) fn open_unlocked(target: &Path, wrap: impl FnOnce(File) -> W) -> Result<Self> {
        let tmp = temporary_path(target);
        let file = File::create(&tmp).map_err(|source| IoError::Write {
            path: target.to_path_buf(),
            source,
        })?;
        Ok(Self {
            target: target.to_path_buf(),
            tmp,
            out: Some(wrap(file)),
            lock: None,
        })
    }

    /// The target path.
    pub(crate) fn target(&self) -> &Path {
        &self.target
    }

    /// Whether the file is still being written (neither finished nor abandoned).
    pub(crate) fn is_open(&self) -> bool {
        self.out.is_some()
    }

    /// The writer, or [`IoError::Closed`] once the sink was finished (by an interrupt).
    pub(crate) fn out(&mut self) -> Result<&mut W> {
        let target = &self.target;
        self.out.as_mut().ok_or_else(|| IoError::Closed {
            path: target.clone(),
        })
    }

    /// A write error naming the target.
    pub(crate) fn write_error(&self) -> impl Fn(std::io::Error) -> IoError + use<W> {
        let path = self.target.clone();
        move |source| IoError::Write {
            path: path.clone(),
            source,
        }
    }

    /// Closes the writer (`close` flushes it and gives the file back), appends
    /// `# incomplete: {reason}` when a reason is given, and renames the file onto the target;
    /// on any failure the temporary file is removed.
    pub(crate) fn commit(
        &mut self,
        close: impl FnOnce(W) -> std::io::Result<File>,
        incomplete: Option<&str>,
    ) -> Result<()> {
        let Some(out) = self.out.take() else {
            return Err(IoError::Closed {
                path: self.target.clone(),
            });
        };
        let result = close(out).and_then(|mut file| {
            if let Some(reason) = incomplete {
                writeln!(file, "# incomplete: {}", reason.replace(['\n', '\r'], " "))?;
            }
            drop(file);
            std::fs::rename(&self.tmp, &self.target)
        });
        if result.is_err() {
            let _ = std::fs::remove_file(&self.tmp);
        }
        self.lock = None;
        result.map_err(self.write_error())
    }

    /// Abandons the file: the temporary file is removed and the lock released.
    pub(crate) fn discard(&mut self) {
        if let Some(out) = self.out.take() {
            drop(out);
            let _ = std::fs::remove_file(&self.tmp);
        }
        self.lock = None;
    }
}

impl<W> Drop for Staged<W> {
    /// A file neither finished nor abandoned is abandoned: nothing at the target.
    fn drop(&mut self) {
        self.discard();
    }
}

/// `dir/.NAME.tmp` beside `path`.
pub(crate) fn temporary_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "output".into());
    path.with_file_name(format!(".{name}.tmp"))
}

/// A target that is an existing directory could never be renamed onto: refused at open.
fn refuse_directory(target: &Path) -> Result<()> {
    if target.is_dir() {
        return Err(IoError::Write {
            path: target.to_path_buf(),
            source: std::io::Error::new(
                std::io::ErrorKind::IsADirectory,
                "is a directory, not a file",
            ),
        });
    }
    Ok(())
}
