//! Output directories (a VTK series, a benchmark's or the figures' folder): checked, and
//! created when missing, before any work; removed again when the run created it and left
//! nothing in it.

use crate::error::{IoError, Result};
use crate::interrupt::{self, Interruptible};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

#[derive(Debug)]
struct DirState {
    path: PathBuf,
    /// Whether this run created the directory.
    created: bool,
    /// Whether the outputs inside were finished (the directory stays).
    kept: bool,
}

impl DirState {
    fn tidy(&mut self) {
        if self.created && !self.kept {
            // only an empty directory goes: anything written in it stays
            let _ = std::fs::remove_dir(&self.path);
        }
        self.kept = true;
    }
}

impl Interruptible for Mutex<DirState> {
    fn interrupt(&self, _reason: &str) -> Option<PathBuf> {
        self.lock().unwrap_or_else(|e| e.into_inner()).tidy();
        None
    }
}

/// A directory that outputs are written into.
///
/// ```
/// use tensegrity_io::sink::OutputDir;
/// let base = std::env::temp_dir().join(format!("output-dir-doc-{}", std::process::id()));
/// # let _ = std::fs::remove_dir_all(&base);
/// assert!(OutputDir::create(&base.join("a").join("b")).is_err()); // its parent must exist
/// let dir = OutputDir::create(&base)?;
/// assert!(base.is_dir());
/// drop(dir); // nothing written in it: the directory this run created goes again
/// assert!(!base.exists());
/// let dir = OutputDir::create(&base)?;
/// std::fs::write(dir.path().join("x.csv"), "a\n1\n").unwrap();
/// dir.keep();
/// assert!(base.join("x.csv").exists());
/// # std::fs::remove_dir_all(&base).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
#[derive(Debug)]
pub struct OutputDir {
    state: Arc<Mutex<DirState>>,
    path: PathBuf,
}

impl OutputDir {
    /// Creates `path` if missing (its parent must exist: a mistyped parent is an error, not
    /// a new tree), or checks that the existing directory is writable (a probe file is
    /// created and removed).
    pub fn create(path: &Path) -> Result<Self> {
        let write_err = |source| IoError::Write {
            path: path.to_path_buf(),
            source,
        };
        let created = if path.is_dir() {
            let probe = path.join(format!(".tensegrity-probe-{}", std::process::id()));
            std::fs::File::create(&probe).map_err(write_err)?;
            let _ = std::fs::remove_file(&probe);
            false
        } else {
            std::fs::create_dir(path).map_err(write_err)?;
            true
        };
        let state = Arc::new(Mutex::new(DirState {
            path: path.to_path_buf(),
            created,
            kept: false,
        }));
        interrupt::register(&state);
        Ok(Self {
            state,
            path: path.to_path_buf(),
        })
    }

    /// The directory.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// `path` joined to the directory.
    pub fn join(&self, name: impl AsRef<Path>) -> PathBuf {
        self.path.join(name)
    }

    /// Keeps the directory whatever it holds (its outputs were finished).
    pub fn keep(self) {
        self.mark_kept();
    }

    pub(crate) fn mark_kept(&self) {
        self.state.lock().unwrap_or_else(|e| e.into_inner()).kept = true;
    }
}

impl Drop for OutputDir {
    /// Removes the directory if this run created it and it is still empty.
    fn drop(&mut self) {
        self.state.lock().unwrap_or_else(|e| e.into_inner()).tidy();
    }
}
