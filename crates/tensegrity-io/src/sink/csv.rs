//! The CSV table sink: a header whose column names carry the units, then rows streamed to the
//! temporary file as they are produced (bounded memory); an interrupted or failed run keeps the
//! rows so far as a complete table with a `# incomplete: <reason>` trailer.

use super::staged::Staged;
use crate::error::{IoError, Result};
use crate::interrupt::{self, Interruptible};
use serde::Serialize;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// The state shared with the interrupt handler.
#[derive(Debug)]
struct Table {
    staged: Staged<::csv::Writer<File>>,
    /// Rows written (the header not counted).
    rows: usize,
    /// Whether anything (a header or a row) was written.
    started: bool,
}

impl Table {
    /// Ends the table: renamed onto the target, with a trailer when `incomplete`. A table
    /// with nothing in it is only kept when it is complete.
    fn close(&mut self, incomplete: Option<&str>) -> Result<Option<PathBuf>> {
        if incomplete.is_some() && !self.started {
            self.staged.discard();
            return Ok(None);
        }
        self.staged
            .commit(|w| w.into_inner().map_err(|e| e.into_error()), incomplete)?;
        Ok(Some(self.staged.target().to_path_buf()))
    }
}

impl Interruptible for Mutex<Table> {
    fn interrupt(&self, reason: &str) -> Option<PathBuf> {
        let mut table = self.lock().unwrap_or_else(|e| e.into_inner());
        if !table.staged.is_open() {
            return None;
        }
        table.close(Some(reason)).ok().flatten()
    }
}

/// A CSV table being written (see the [module](super) protocol).
///
/// ```
/// use tensegrity_io::sink::CsvSink;
/// #[derive(serde::Serialize)]
/// struct Row {
///     #[serde(rename = "t [s]")]
///     t: f64,
///     #[serde(rename = "z [m]")]
///     z: f64,
/// }
/// let dir = std::env::temp_dir();
/// let path = dir.join(format!("csv-sink-doc-{}.csv", std::process::id()));
/// let mut sink = CsvSink::open(&path, "drop CSV")?; // before the run: a bad path fails here
/// sink.serialize(&Row { t: 0.0, z: 1.0 })?;
/// sink.serialize(&Row { t: 0.5, z: 0.75 })?;
/// assert_eq!(sink.finish_incomplete("interrupted at t = 0.5 s")?, 2);
/// let text = std::fs::read_to_string(&path).unwrap();
/// assert_eq!(text, "t [s],z [m]\n0.0,1.0\n0.5,0.75\n# incomplete: interrupted at t = 0.5 s\n");
/// # std::fs::remove_file(&path).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
#[derive(Debug)]
pub struct CsvSink {
    state: Arc<Mutex<Table>>,
    path: PathBuf,
    what: &'static str,
}

impl CsvSink {
    /// Opens a table whose header is the field names (or serde renames) of the rows given to
    /// [`CsvSink::serialize`], written with the first row. `what` names the table in errors.
    pub fn open(path: &Path, what: &'static str) -> Result<Self> {
        Self::with_builder(path, what, true)
    }

    /// Opens a table and writes `header` now (rows through [`CsvSink::record`] or
    /// [`CsvSink::serialize`] of tuples or structs, whose names are then not written).
    pub fn with_header<H: AsRef<[u8]>>(
        path: &Path,
        what: &'static str,
        header: &[H],
    ) -> Result<Self> {
        let mut sink = Self::with_builder(path, what, false)?;
        sink.record(header)?;
        sink.lock().rows = 0;
        Ok(sink)
    }

    /// Opens a table without a header: every line, the header included, is given to
    /// [`CsvSink::record`] (a header known only once the first row is, e.g. a trajectory's).
    pub fn open_records(path: &Path, what: &'static str) -> Result<Self> {
        Self::with_builder(path, what, false)
    }

    fn with_builder(path: &Path, what: &'static str, headers: bool) -> Result<Self> {
        let wrap = |file| {
            ::csv::WriterBuilder::new()
                .has_headers(headers)
                .from_writer(file)
        };
        let table = Table {
            staged: Staged::open(path, wrap)?,
            rows: 0,
            started: false,
        };
        let state = Arc::new(Mutex::new(table));
        interrupt::register(&state);
        Ok(Self {
            state,
            path: path.to_path_buf(),
            what,
        })
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Table> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The target path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// What the table holds, as given at open.
    pub fn what(&self) -> &'static str {
        self.what
    }

    /// Rows written so far (the header not counted).
    pub fn rows(&self) -> usize {
        self.lock().rows
    }

    /// Appends one row of text fields.
    pub fn record<I, T>(&mut self, fields: I) -> Result<()>
    where
        I: IntoIterator<Item = T>,
        T: AsRef<[u8]>,
    {
        let path = self.path.clone();
        let mut table = self.lock();
        table
            .staged
            .out()?
            .write_record(fields)
            .map_err(|e| csv_error(&path, e))?;
        table.rows += 1;
        table.started = true;
        Ok(())
    }

    /// Appends one `Serialize` row (a struct: its field names make the header of
    /// [`CsvSink::open`]).
    pub fn serialize<R: Serialize>(&mut self, row: &R) -> Result<()> {
        let path = self.path.clone();
        let mut table = self.lock();
        table
            .staged
            .out()?
            .serialize(row)
            .map_err(|e| csv_error(&path, e))?;
        table.rows += 1;
        table.started = true;
        Ok(())
    }

    /// Appends every row of `rows`; returns how many.
    pub fn extend<R: Serialize>(&mut self, rows: impl IntoIterator<Item = R>) -> Result<usize> {
        let mut n = 0;
        for row in rows {
            self.serialize(&row)?;
            n += 1;
        }
        Ok(n)
    }

    /// Flushes the table and renames it onto the target; returns the number of rows.
    pub fn finish(self) -> Result<usize> {
        let mut table = self.lock();
        table.close(None)?;
        Ok(table.rows)
    }

    /// Ends a run that stopped early (interrupted, or failed part-way): the rows so far, then
    /// `# incomplete: {reason}`, renamed onto the target as a complete table. A table with
    /// nothing written leaves no file. Returns the number of rows kept.
    pub fn finish_incomplete(self, reason: &str) -> Result<usize> {
        let mut table = self.lock();
        table.close(Some(reason))?;
        Ok(table.rows)
    }
}

fn csv_error(path: &Path, e: ::csv::Error) -> IoError {
    IoError::Write {
        path: path.to_path_buf(),
        source: e.into(),
    }
}
