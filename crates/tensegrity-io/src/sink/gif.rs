//! Animated GIF files ([`GifSink`]): frames are [`Figure`]s drawn to pixels
//! ([`Figure::to_svg_with`] rasterised by [`crate::figure::render::rgba`], at the sink's
//! [`RenderOptions`]: `--size`/`--dpi`), rasterised and LZW-coded in parallel (rayon, a batch of frames at a time, so only a batch's pixels
//! are held; the LZW is [`super::lzw`], which codes a figure's runs of white 3–4 times as
//! fast as the `gif` crate's own), every frame indexed into one global palette built once
//! ([`palette`]): the
//! figures' own colours (the series style table, the text and axis greys, the NOT VALID red,
//! the colours the figures name) exactly, each with three tints towards white (the
//! anti-aliased edges), and a ramp of greys; a pixel takes the nearest palette colour. The
//! file loops forever; every frame shows for the same delay (hundredths of a second: 100/fps
//! rounded, at least 2, as browsers clamp shorter ones). On an interrupt the file is
//! removed, like any picture ([`FileSink`]).

use super::file::FileSink;
use crate::error::{IoError, Result};
use crate::figure::{style, Figure, RenderOptions};
use rayon::prelude::*;
use std::path::Path;

/// Frames rasterised together (their RGB held at once).
const BATCH: usize = 32;

/// The colours every figure may draw besides its own: white, black, the axis and text
/// greys, the NOT VALID red.
const FIXED: [(u8, u8, u8); 6] = [
    (0xff, 0xff, 0xff),
    (0x00, 0x00, 0x00),
    (0x44, 0x44, 0x44),
    (0x66, 0x66, 0x66),
    (0xe3, 0xe3, 0xe3),
    (0xd0, 0x00, 0x00),
];

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
    options: RenderOptions,
    palette: Option<Vec<(u8, u8, u8)>>,
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
            .field("options", &self.options)
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
    /// will show at `fps` frames per second, drawn at each figure's own size and 96 dpi.
    pub fn open(path: &Path, fps: f64) -> Result<Self> {
        Self::open_with(path, fps, RenderOptions::default())
    }

    /// [`GifSink::open`] with frames drawn under `options` (a size, a dpi: the GIF is
    /// size × dpi pixels).
    pub fn open_with(path: &Path, fps: f64, options: RenderOptions) -> Result<Self> {
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
            options,
            palette: None,
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

    /// The global palette (at most 256 colours), once the first frame has fixed it.
    pub fn palette(&self) -> Option<&[(u8, u8, u8)]> {
        self.palette.as_deref()
    }

    /// Draws `figure` and appends it as the next frame; every frame must have the first's
    /// size.
    pub fn frame(&mut self, figure: &Figure) -> Result<()> {
        self.frames_of(std::slice::from_ref(figure))
    }

    /// Draws `figures` (in parallel) and appends them in order; the palette is fixed by the
    /// first call's figures ([`palette`]), and every frame must have the first's size.
    pub fn frames_of(&mut self, figures: &[Figure]) -> Result<()> {
        let palette = self.palette.get_or_insert_with(|| palette(figures)).clone();
        for batch in figures.chunks(BATCH) {
            let encoded: Vec<(gif::Frame<'static>, (u32, u32))> = batch
                .par_iter()
                .map(|f| encoded_frame(f, &self.options, &palette, self.delay_cs))
                .collect::<Result<_>>()?;
            for (frame, size) in encoded {
                self.write(&frame, size, &palette)?;
            }
        }
        Ok(())
    }

    fn write(
        &mut self,
        frame: &gif::Frame<'_>,
        (w, h): (u32, u32),
        pal: &[(u8, u8, u8)],
    ) -> Result<()> {
        let state = std::mem::replace(&mut self.state, State::Gone);
        let mut encoder = match state {
            State::Open(file) => {
                let flat: Vec<u8> = pal.iter().flat_map(|&(r, g, b)| [r, g, b]).collect();
                let mut e = gif::Encoder::new(file, w as u16, h as u16, &flat).map_err(encoding)?;
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
        encoder
            .write_lzw_pre_encoded_frame(frame)
            .map_err(encoding)?;
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

/// One frame drawn, indexed into `palette` and LZW-encoded, with its size.
fn encoded_frame(
    figure: &Figure,
    options: &RenderOptions,
    palette: &[(u8, u8, u8)],
    delay_cs: u16,
) -> Result<(gif::Frame<'static>, (u32, u32))> {
    let svg = figure.to_svg_with(options)?;
    let (rgba, (w, h)) = crate::figure::render::rgba(&svg, options.dpi)?;
    if w > u32::from(u16::MAX) || h > u32::from(u16::MAX) {
        return Err(IoError::InvalidFigure {
            reason: "a GIF frame is at most 65535 pixels a side",
        });
    }
    let pixels = indexed_pixels(&rgba, 4, palette);
    // the narrowest codes for the indices used (GIF: at least 2 bits)
    let used = u32::from(pixels.iter().copied().max().unwrap_or(0)) + 1;
    let min_code_size = used.max(4).next_power_of_two().trailing_zeros() as u8;
    let frame = gif::Frame {
        width: w as u16,
        height: h as u16,
        delay: delay_cs,
        buffer: std::borrow::Cow::Owned(super::lzw::encode(&pixels, min_code_size)),
        ..gif::Frame::default()
    };
    Ok((frame, (w, h)))
}

/// Each pixel's nearest palette index (squared RGB distance), the pixels `stride` bytes
/// apart, red, green and blue first (3: RGB, 4: RGBA), through a direct-mapped cache of
/// 4096 colours (a figure has few) and the previous pixel's (a figure's rows are runs of
/// one colour).
fn indexed_pixels(data: &[u8], stride: usize, palette: &[(u8, u8, u8)]) -> Vec<u8> {
    const EMPTY: u32 = u32::MAX;
    let mut cache = vec![(EMPTY, 0u8); 4096];
    let mut last = (EMPTY, 0u8);
    let mut out = Vec::with_capacity(data.len() / stride);
    for p in data.chunks_exact(stride) {
        let key = u32::from(p[0]) << 16 | u32::from(p[1]) << 8 | u32::from(p[2]);
        if key != last.0 {
            let slot = &mut cache[(key.wrapping_mul(0x9E37_79B1) >> 20) as usize];
            if slot.0 != key {
                *slot = (key, nearest([p[0], p[1], p[2]], palette));
            }
            last = *slot;
        }
        out.push(last.1);
    }
    out
}

fn nearest([r, g, b]: [u8; 3], palette: &[(u8, u8, u8)]) -> u8 {
    let d = |&(pr, pg, pb): &(u8, u8, u8)| {
        let (dr, dg, db) = (
            i32::from(pr) - i32::from(r),
            i32::from(pg) - i32::from(g),
            i32::from(pb) - i32::from(b),
        );
        dr * dr + dg * dg + db * db
    };
    (0..palette.len())
        .min_by_key(|&k| d(&palette[k]))
        .unwrap_or(0) as u8
}

/// The global palette of `figures`, at most 256 colours: the [`FIXED`] ones, the series
/// style table ([`style::PALETTE`]) and every colour the figures name (series, arrows,
/// marks), each exactly, then each of them (greys aside) at 1/4, 1/2 and 3/4 of the way to
/// white, then greys every 8 levels; a colour already there is not repeated.
pub fn palette(figures: &[Figure]) -> Vec<(u8, u8, u8)> {
    let mut named: Vec<(u8, u8, u8)> = FIXED.to_vec();
    named.extend(style::PALETTE);
    for panel in figures.iter().flat_map(|f| &f.panels) {
        named.extend(panel.series.iter().filter_map(|s| s.color));
        named.extend(panel.arrows.iter().map(|a| a.color));
        named.extend(panel.marks.iter().map(|m| m.color));
    }
    let mut out: Vec<(u8, u8, u8)> = Vec::with_capacity(256);
    let push = |c: (u8, u8, u8), out: &mut Vec<(u8, u8, u8)>| {
        if out.len() < 256 && !out.contains(&c) {
            out.push(c);
        }
    };
    for &c in &named {
        push(c, &mut out);
    }
    let tint = |v: u8, f: u32| (u32::from(v) + (255 - u32::from(v)) * f / 4) as u8;
    for f in 1..4 {
        for &(r, g, b) in &named {
            if !(r == g && g == b) {
                push((tint(r, f), tint(g, f), tint(b, f)), &mut out);
            }
        }
    }
    for v in (0..=255u32).step_by(8) {
        push((v as u8, v as u8, v as u8), &mut out);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::{Panel, Series};

    #[test]
    fn the_palette_holds_the_figures_colours_exactly_and_indexes_them_to_themselves() {
        let own = (0x1b, 0x2a, 0x49);
        let p = Panel::new("t", "x", "y")
            .series(Series::new("bar", vec![(0.0, 0.0), (1.0, 1.0)]).with_color(own));
        let pal = palette(&[Figure::new(vec![p])]);
        assert!(pal.len() <= 256);
        for c in FIXED.iter().chain(&style::PALETTE).chain([&own]) {
            let k = pal
                .iter()
                .position(|p| p == c)
                .expect("colour in the palette");
            assert_eq!(indexed_pixels(&[c.0, c.1, c.2], 3, &pal), vec![k as u8]);
        }
    }
}
