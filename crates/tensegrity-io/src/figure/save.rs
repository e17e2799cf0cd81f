//! Writing a figure to a file ([`Figure::save`]): through a [`FigureSink`], which picks SVG,
//! PNG or PDF by the extension and renames the finished file into place.

use super::{Figure, RenderOptions};
use crate::error::Result;
use crate::sink::FigureSink;
use std::path::Path;

impl Figure {
    /// Writes the figure to `path` at its own size: SVG for `.svg`, PNG for `.png`, PDF for
    /// `.pdf` (case-insensitive), through a [`crate::sink::FigureSink`] (a command opens the
    /// sink before its work instead).
    ///
    /// ```
    /// use tensegrity_io::figure::{Figure, Panel, Series};
    /// let fig = Figure::new(vec![Panel::new("error", "time [s]", "error [m]")
    ///     .log_log()
    ///     .series(Series::new("rk4", vec![(1e-3, 1e-4), (1e-2, 1e-8)]).with_markers())]);
    /// let dir = std::env::temp_dir();
    /// let path = dir.join(format!("tensegrity-io-fig-{}.png", std::process::id()));
    /// fig.save(&path)?;
    /// assert!(std::fs::read(&path).unwrap().starts_with(b"\x89PNG"));
    /// # std::fs::remove_file(&path).unwrap();
    /// assert!(fig.save(&dir.join("figure.bmp")).is_err());
    /// # Ok::<(), tensegrity_io::IoError>(())
    /// ```
    pub fn save(&self, path: &Path) -> Result<()> {
        FigureSink::open(path)?.finish(self)
    }

    /// [`Figure::save`] under `options` (size, dpi).
    pub fn save_with(&self, path: &Path, options: &RenderOptions) -> Result<()> {
        FigureSink::open_with(path, *options)?.finish(self)
    }
}
