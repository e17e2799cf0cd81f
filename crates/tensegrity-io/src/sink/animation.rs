//! The file of an animation, chosen by its extension ([`AnimationSink`]): `.gif` an animated
//! GIF ([`GifSink`]), `.webm` an AV1 video in WebM ([`WebmSink`]). `.mp4` is refused with the
//! reason ([`MP4_REFUSED`]); any other extension is an unknown file type.

use super::gif::GifSink;
use super::video::WebmSink;
use crate::error::{IoError, Result};
use crate::figure::{Figure, RenderOptions};
use std::path::Path;

/// Why an `.mp4` animation is not written.
pub const MP4_REFUSED: &str = "MP4 is not written: its usual codec, H.264, has no encoder that \
builds here without a C/C++ toolchain or a system library (and AV1 in MP4 plays in fewer \
places than AV1 in WebM); write the animation as .webm (AV1 video) or .gif instead";

/// The extensions an animation may have.
const EXTENSIONS: &str = "gif, webm";

/// An animation file, opened before the work that draws its frames.
#[derive(Debug)]
pub enum AnimationSink {
    /// An animated GIF.
    Gif(GifSink),
    /// An AV1 video in WebM.
    Webm(WebmSink),
}

impl AnimationSink {
    /// Opens `path` by its extension (`.gif` or `.webm`, any case) with frames shown at `fps`
    /// frames per second and drawn under `options`; `.mp4` is refused
    /// ([`IoError::UnwrittenFormat`], [`MP4_REFUSED`]), another extension is
    /// [`IoError::UnsupportedFormat`].
    ///
    /// ```
    /// use tensegrity_io::sink::AnimationSink;
    /// use tensegrity_io::figure::RenderOptions;
    /// let dir = std::env::temp_dir();
    /// let e = AnimationSink::open(&dir.join("run.mp4"), 10.0, RenderOptions::default()).unwrap_err();
    /// assert!(e.to_string().contains("MP4 is not written"));
    /// let e = AnimationSink::open(&dir.join("run.avi"), 10.0, RenderOptions::default()).unwrap_err();
    /// assert!(e.to_string().contains("gif, webm"));
    /// ```
    pub fn open(path: &Path, fps: f64, options: RenderOptions) -> Result<Self> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("gif") => Ok(Self::Gif(GifSink::open_with(path, fps, options)?)),
            Some("webm") => Ok(Self::Webm(WebmSink::open_with(path, fps, options)?)),
            Some("mp4") => Err(IoError::UnwrittenFormat {
                path: path.to_path_buf(),
                reason: MP4_REFUSED,
            }),
            _ => Err(IoError::UnsupportedFormat {
                path: path.to_path_buf(),
                expected: EXTENSIONS,
            }),
        }
    }

    /// Draws `figures` (in parallel) and appends them in order.
    pub fn frames_of(&mut self, figures: &[Figure]) -> Result<()> {
        match self {
            Self::Gif(s) => s.frames_of(figures),
            Self::Webm(s) => s.frames_of(figures),
        }
    }

    /// Ends the file and renames it onto the target; the number of frames.
    pub fn finish(self) -> Result<usize> {
        match self {
            Self::Gif(s) => s.finish(),
            Self::Webm(s) => s.finish(),
        }
    }
}
