//! Animated GIF files ([`GifSink`]): frames are [`Figure`]s drawn to RGB
//! ([`Figure::to_rgb`]), each quantised to its own 256-colour palette (NeuQuant, the `gif`
//! crate's `Frame::from_rgb_speed`) and LZW-encoded as it comes, so only one frame's pixels
//! are held at a time. The file loops forever; every frame shows for the same delay
//! (hundredths of a second: 100/fps rounded, at least 2, as browsers clamp shorter ones).
//! On an interrupt the file is removed, like any picture ([`FileSink`]).

use super::file::FileSink;
use crate::error::{IoError, Result};
use crate::figure::Figure;
use std::path::Path;

/// NeuQuant sampling factor: 1 best, 30 fastest (figures have few colours).
const QUANTISE_SPEED: i32 = 20;

/// An animated GIF, opened before the work that draws its frames.
///
/// ```
/// use tensegrity_io::figure::{Figure, Panel, Series};
/// use tensegrity_io::sink::GifSink;
/// let dir = std::env::temp_dir();
/// assert!(GifSink::open(&dir.join("movie.mp4"), 10.0).is_err()); // extension checked at once
/// let path = dir.join(format!("gif-sink-doc-{}.gif", std::process::id()));
/// let mut sink = GifSink::open(&path, 10.0)?;
/// for k in 0..3 {
///     let p = Panel::new(format!("t = {k} s"), "y [m]", "z [m]")
///         .series(Series::new("bar", vec![(0.0, 0.0), (1.0, k as f64)]));
///     sink.frame(&Figure::new(vec![p]).with_panel_size(200, 150))?;
/// }
/// assert_eq!(sink.finish()?, 3);
/// assert!(std::fs::read(&path).unwrap().starts_with(b"GIF89a"));
/// # std::fs::remove_file(&path).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
pub struct GifSink {
    state: State,
    delay_cs: u16,
    frames: usize,
}

enum State {
    /// Opened; the size comes with the first frame.
    Open(FileSink),
    /// Encoding frames of this size.
    Encoding(gif::Encoder<FileSink>, (u32, u32)),
    /// Failed or taken.
    Gone,
}

impl std::fmt::Debug for GifSink {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GifSink")
            .field("delay_cs", &self.delay_cs)
            .field("frames", &self.frames)
            .finish_non_exhaustive()
    }
}

fn encoding(e: gif::EncodingError) -> IoError {
    IoError::Drawing {
        message: format!("GIF encoding: {e}"),
    }
}

impl GifSink {
    /// Checks the extension (`.gif`), locks `path` and creates its temporary file; frames
    /// will show at `fps` frames per second.
    pub fn open(path: &Path, fps: f64) -> Result<Self> {
        let ext = path.extension().and_then(|e| e.to_str());
        if !ext.is_some_and(|e| e.eq_ignore_ascii_case("gif")) {
            return Err(IoError::UnsupportedFormat {
                path: path.to_path_buf(),
                expected: "gif",
            });
        }
        let delay = if fps.is_finite() && fps > 0.0 {
            (100.0 / fps).round().clamp(2.0, 65535.0)
        } else {
            10.0
        };
        Ok(Self {
            state: State::Open(FileSink::open(path)?),
            delay_cs: delay as u16,
            frames: 0,
        })
    }

    /// The delay of every frame (hundredths of a second).
    pub fn delay_cs(&self) -> u16 {
        self.delay_cs
    }

    /// Frames written so far.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// Draws `figure` and appends it as the next frame; every frame must have the first's
    /// size.
    pub fn frame(&mut self, figure: &Figure) -> Result<()> {
        let (rgb, (w, h)) = figure.to_rgb()?;
        if w > u32::from(u16::MAX) || h > u32::from(u16::MAX) {
            return Err(IoError::InvalidFigure {
                reason: "a GIF frame is at most 65535 pixels a side",
            });
        }
        let state = std::mem::replace(&mut self.state, State::Gone);
        let mut encoder = match state {
            State::Open(file) => {
                let mut e = gif::Encoder::new(file, w as u16, h as u16, &[]).map_err(encoding)?;
                e.set_repeat(gif::Repeat::Infinite).map_err(encoding)?;
                e
            }
            State::Encoding(e, size) if size == (w, h) => e,
            State::Encoding(..) => {
                return Err(IoError::InvalidFigure {
                    reason: "every frame of an animation must have the size of the first",
                })
            }
            State::Gone => {
                return Err(IoError::InvalidFigure {
                    reason: "the animation failed before this frame",
                })
            }
        };
        let mut frame = gif::Frame::from_rgb_speed(w as u16, h as u16, &rgb, QUANTISE_SPEED);
        frame.delay = self.delay_cs;
        encoder.write_frame(&frame).map_err(encoding)?;
        self.state = State::Encoding(encoder, (w, h));
        self.frames += 1;
        Ok(())
    }

    /// Ends the file (its trailer) and renames it onto the target; the number of frames. An
    /// animation without a frame is refused (the temporary file is removed).
    pub fn finish(self) -> Result<usize> {
        match self.state {
            State::Encoding(e, _) => {
                e.into_inner().map_err(encoding)?.finish()?;
                Ok(self.frames)
            }
            _ => Err(IoError::InvalidFigure {
                reason: "an animation needs at least one frame",
            }),
        }
    }
}
