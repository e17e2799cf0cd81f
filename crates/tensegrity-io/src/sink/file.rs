//! Whole-file sinks: any bytes ([`FileSink`]: scenes, `.vtu` files, tables written at once),
//! figures ([`FigureSink`]) and JSON documents ([`JsonSink`]). On an interrupt they are removed,
//! not kept: half a picture or half a document is of no use.

use super::staged::Staged;
use crate::error::{IoError, Result};
use crate::figure::{Figure, RenderOptions};
use crate::interrupt::{self, Interruptible};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// The state shared with the interrupt handler: the file, and its paths outside the mutex.
#[derive(Debug)]
struct Shared {
    staged: Mutex<Staged<BufWriter<File>>>,
    tmp: PathBuf,
    lock: PathBuf,
}

impl Shared {
    fn lock(&self) -> std::sync::MutexGuard<'_, Staged<BufWriter<File>>> {
        self.staged.lock().unwrap_or_else(|e| e.into_inner())
    }
}

impl Interruptible for Shared {
    fn interrupt(&self, _reason: &str) -> Option<PathBuf> {
        match self.staged.try_lock() {
            Ok(mut staged) => staged.discard(),
            Err(std::sync::TryLockError::Poisoned(e)) => e.into_inner().discard(),
            // the command is filling the file (a long table written at once): remove it
            // under its feet, the process is about to exit
            Err(std::sync::TryLockError::WouldBlock) => {
                let _ = std::fs::remove_file(&self.tmp);
                let _ = std::fs::remove_file(&self.lock);
            }
        }
        None
    }
}

/// An output file written whole (see the [module](super) protocol).
///
/// ```
/// use std::io::Write;
/// use tensegrity_io::sink::FileSink;
/// let path = std::env::temp_dir().join(format!("file-sink-doc-{}.toml", std::process::id()));
/// let mut sink = FileSink::open(&path)?; // a bad path fails here, before any work
/// writeln!(sink, "nodes = []").unwrap();
/// assert!(!path.exists()); // not there until finished
/// sink.finish()?;
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "nodes = []\n");
/// FileSink::open(&path)?.finish_with("nodes = [[0.0, 0.0, 0.0]]\n")?;
/// assert!(std::fs::read_to_string(&path).unwrap().contains("0.0"));
/// # std::fs::remove_file(&path).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
#[derive(Debug)]
pub struct FileSink {
    state: Arc<Shared>,
    path: PathBuf,
}

impl FileSink {
    /// Locks `path` and creates its temporary file.
    pub fn open(path: &Path) -> Result<Self> {
        let state = Arc::new(Shared {
            staged: Mutex::new(Staged::open(path, BufWriter::new)?),
            tmp: super::staged::temporary_path(path),
            lock: super::lock::lock_path(path),
        });
        interrupt::register(&state);
        Ok(Self {
            state,
            path: path.to_path_buf(),
        })
    }

    /// The target path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Writes through `fill` (e.g. one of the [`crate::csv`] writers); its stream errors come
    /// back as [`IoError::Write`] naming the target.
    pub fn write_with<T>(&mut self, fill: impl FnOnce(&mut dyn Write) -> Result<T>) -> Result<T> {
        let mut staged = self.state.lock();
        let out = staged.out()?;
        fill(out).map_err(|e| e.at(&self.path))
    }

    /// Writes `bytes`, then finishes (a file whose whole text is known at the end).
    pub fn finish_with(mut self, bytes: impl AsRef<[u8]>) -> Result<()> {
        self.write_with(|w| {
            w.write_all(bytes.as_ref())
                .map_err(IoError::stream("output file"))
        })?;
        self.finish()
    }

    /// Flushes the file and renames it onto the target.
    pub fn finish(self) -> Result<()> {
        let mut staged = self.state.lock();
        staged.commit(|w| w.into_inner().map_err(|e| e.into_error()), None)
    }
}

impl Write for FileSink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let mut staged = self.state.lock();
        staged.out().map_err(std::io::Error::other)?.write(buf)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        let mut staged = self.state.lock();
        staged.out().map_err(std::io::Error::other)?.flush()
    }
}

/// The picture formats of [`FigureSink`], chosen by the file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// `.svg`: text stays text.
    Svg,
    /// `.png`: rendered with the embedded font at the chosen dpi.
    Png,
    /// `.pdf`: one page of the figure's size, text with the embedded font.
    Pdf,
}

impl ImageFormat {
    /// The format of `path` by its extension (case-insensitive), or
    /// [`IoError::UnsupportedFormat`].
    pub fn of(path: &Path) -> Result<Self> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("svg") => Ok(Self::Svg),
            Some("png") => Ok(Self::Png),
            Some("pdf") => Ok(Self::Pdf),
            _ => Err(IoError::UnsupportedFormat {
                path: path.to_path_buf(),
                expected: "svg, png, pdf",
            }),
        }
    }
}

/// A figure file, opened before the figure is computed.
///
/// ```
/// use tensegrity_io::figure::{Figure, Panel, Series};
/// use tensegrity_io::sink::FigureSink;
/// let dir = std::env::temp_dir();
/// assert!(FigureSink::open(&dir.join("figure.bmp")).is_err()); // the extension is checked at once
/// let path = dir.join(format!("figure-sink-doc-{}.svg", std::process::id()));
/// let sink = FigureSink::open(&path)?;
/// let figure = Figure::new(vec![Panel::new("drop", "t [s]", "z [m]")
///     .series(Series::new("z", vec![(0.0, 1.0), (1.0, 0.0)]))]);
/// sink.finish(&figure)?;
/// assert!(std::fs::read_to_string(&path).unwrap().contains("<svg"));
/// # std::fs::remove_file(&path).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
#[derive(Debug)]
pub struct FigureSink {
    file: FileSink,
    format: ImageFormat,
    options: RenderOptions,
}

impl FigureSink {
    /// Checks the extension, locks `path` and creates its temporary file; the figure is
    /// rendered at its own size (96 dpi for PNG).
    pub fn open(path: &Path) -> Result<Self> {
        Self::open_with(path, RenderOptions::default())
    }

    /// [`FigureSink::open`] with a size and a dpi for the figure.
    pub fn open_with(path: &Path, options: RenderOptions) -> Result<Self> {
        let format = ImageFormat::of(path)?;
        Ok(Self {
            file: FileSink::open(path)?,
            format,
            options,
        })
    }

    /// The format, by the file's extension.
    pub fn format(&self) -> ImageFormat {
        self.format
    }

    /// The size and dpi the figure is rendered at.
    pub fn options(&self) -> RenderOptions {
        self.options
    }

    /// The target path.
    pub fn path(&self) -> &Path {
        self.file.path()
    }

    /// Draws `figure` into the file and renames it onto the target.
    pub fn finish(mut self, figure: &Figure) -> Result<()> {
        let o = &self.options;
        let (bytes, what) = match self.format {
            ImageFormat::Svg => (figure.to_svg_with(o)?.into_bytes(), "SVG figure"),
            ImageFormat::Png => (figure.to_png_with(o)?, "PNG figure"),
            ImageFormat::Pdf => (figure.to_pdf_with(o)?, "PDF figure"),
        };
        self.file
            .write_with(|w| w.write_all(&bytes).map_err(IoError::stream(what)))?;
        self.file.finish()
    }
}

/// A JSON document, written whole (pretty, one trailing newline) when finished.
///
/// ```
/// use tensegrity_io::sink::JsonSink;
/// let path = std::env::temp_dir().join(format!("json-sink-doc-{}.json", std::process::id()));
/// let sink = JsonSink::open(&path)?;
/// sink.finish(&serde_json::json!({"steps": 3}))?;
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "{\n  \"steps\": 3\n}\n");
/// # std::fs::remove_file(&path).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
#[derive(Debug)]
pub struct JsonSink {
    file: FileSink,
}

impl JsonSink {
    /// Locks `path` and creates its temporary file.
    pub fn open(path: &Path) -> Result<Self> {
        Ok(Self {
            file: FileSink::open(path)?,
        })
    }

    /// The target path.
    pub fn path(&self) -> &Path {
        self.file.path()
    }

    /// Writes `value` and renames the file onto the target.
    pub fn finish<T: serde::Serialize + ?Sized>(mut self, value: &T) -> Result<()> {
        self.file.write_with(|w| {
            serde_json::to_writer_pretty(&mut *w, value)
                .map_err(std::io::Error::from)
                .and_then(|()| w.write_all(b"\n"))
                .map_err(IoError::stream("JSON document"))
        })?;
        self.file.finish()
    }
}
