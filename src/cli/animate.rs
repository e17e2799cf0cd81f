//! `--animate FILE.gif|FILE.webm [--fps F] [--duration S]` of `simulate`, `roll` and `tbar
//! roll`, at the command's `--size`/`--dpi` ([`super::figure_args::FigureArgs`]): the sink
//! ([`AnimationSink`]: an animated GIF, or AV1 video in WebM, by the extension; `.mp4` is
//! refused with the reason, exit 2) is opened before the work, the run hands its nodes to a
//! [`tensegrity_figures::animation::Animation`], which draws round(F·S) frames spread over
//! the run when it ends.

use anyhow::{Context, Result};
use std::path::PathBuf;
use tensegrity_figures::animation::{Animation, AnimationSpec, Scenery};
use tensegrity_io::figure::{Figure, Panel, RenderOptions};
use tensegrity_io::sink::AnimationSink;

/// The animation flags.
#[derive(clap::Args, Debug, Clone)]
pub struct AnimateArgs {
    /// Write an animation of the structure over time (to scale, with the ground and the
    /// time): round(fps × duration) frames spread evenly over the run; FILE.gif an animated
    /// GIF, FILE.webm an AV1 video in WebM (an odd pixel width or height padded to even with
    /// white). MP4 is not written.
    #[arg(long, value_name = "FILE.gif|FILE.webm")]
    pub animate: Option<PathBuf>,
    /// Frames per second of --animate (default 10).
    #[arg(long, value_name = "F", requires = "animate")]
    pub fps: Option<f64>,
    /// Playing time of --animate in seconds (default 5).
    #[arg(long, value_name = "S", requires = "animate")]
    pub duration: Option<f64>,
}

/// An opened animation not yet given its scenery.
pub struct Opened(AnimationSink, AnimationSpec);

impl AnimateArgs {
    /// The spec checked and the file opened (before the work), if asked for; the frames at
    /// their own size and 96 dpi.
    pub fn open(&self) -> Result<Option<Opened>> {
        self.open_with(RenderOptions::default())
    }

    /// [`AnimateArgs::open`] with the frames drawn under `options` (`--size`, `--dpi`).
    pub fn open_with(&self, options: RenderOptions) -> Result<Option<Opened>> {
        let Some(path) = &self.animate else {
            return Ok(None);
        };
        let spec =
            AnimationSpec::new(self.fps, self.duration).map_err(super::request_args::usage)?;
        // a size no frame can have is refused before the run (exit 2)
        let blank = Figure::new(vec![Panel::new("", "", "")]);
        blank.page_px(&options).context("--size")?;
        let sink = super::output::open_required("--animate", path, |p| {
            AnimationSink::open(p, spec.fps, options)
        })?;
        Ok(Some(Opened(sink, spec)))
    }
}

impl Opened {
    /// The animation of `scenery` over [0, `t_end`].
    pub fn start(self, scenery: Scenery, t_end: f64) -> Animation {
        Animation::new(self.0, scenery, &self.1, t_end)
    }
}

/// Draws and writes the animation, saying so on stderr.
pub fn finish(animation: Option<Animation>, path: Option<&std::path::Path>) -> Result<()> {
    if let (Some(a), Some(p)) = (animation, path) {
        let n = a.finish()?;
        eprintln!("wrote {n} frames to {}", p.display());
    }
    Ok(())
}
