//! WebM video files ([`WebmSink`]): frames are [`Figure`]s drawn to RGB at the sink's
//! [`RenderOptions`] (in parallel, a batch at a time, like [`super::GifSink`]), converted to
//! BT.709 limited-range Y′CbCr 4:2:0 ([`super::yuv`]), encoded as AV1 by rav1e (pure Rust, no
//! assembly and no system library: speed preset [`SPEED`], constant quantizer [`QUANTIZER`],
//! low-latency mode so frames leave the encoder in order, one keyframe at the start and then
//! at most every [`KEY_INTERVAL`] frames, [`TILES`] tiles encoded in parallel) and muxed into
//! WebM ([`super::webm::WebmMuxer`]).
//!
//! AV1 4:2:0 needs an even width and height: a frame with an odd one is padded with a white
//! column or row ([`super::yuv::even`]), so a 541 × 401 picture makes a 542 × 402 video. The
//! coded frames are held (compressed) until [`WebmSink::finish`] writes the file; on an
//! interrupt or an error the temporary file is removed, like any picture ([`FileSink`]).

use super::file::FileSink;
use super::webm::WebmMuxer;
use super::yuv::{rgb_to_yuv420, Yuv420};
use crate::error::{IoError, Result};
use crate::figure::{Figure, RenderOptions};
use rav1e::prelude::*;
use rayon::prelude::*;
use std::path::Path;

/// rav1e's speed preset (0 slowest … 10 fastest).
pub const SPEED: u8 = 10;
/// rav1e's constant quantizer (0 lossless … 255): rav1e's own default, 100 (at 80 the
/// 50-frame 420 × 420 rolling-wheel video of `roll --animate` was 747 kB, more than its
/// 626 kB GIF).
pub const QUANTIZER: usize = 100;
/// The most frames between keyframes.
pub const KEY_INTERVAL: u64 = 120;
/// Tiles a frame is cut into, encoded in parallel (rayon): a fixed number, so the file does
/// not depend on the machine. Four tiles encode a 420 × 420 frame 1.7 times as fast on two
/// cores as one tile, for a file 1.4 % larger.
pub const TILES: usize = 4;

/// Frames rasterised together (their pixels held at once).
const BATCH: usize = 32;

/// A WebM (AV1) video, opened before the work that draws its frames.
///
/// ```
/// use tensegrity_io::figure::{Figure, Panel, Series};
/// use tensegrity_io::sink::{webm, WebmSink};
/// let dir = std::env::temp_dir();
/// let path = dir.join(format!("webm-sink-doc-{}.webm", std::process::id()));
/// let mut sink = WebmSink::open(&path, 10.0)?;
/// let frames: Vec<Figure> = (0..3)
///     .map(|k| {
///         let p = Panel::new(format!("t = {k} s"), "y [m]", "z [m]")
///             .series(Series::new("bar", vec![(0.0, 0.0), (1.0, k as f64)]));
///         Figure::new(vec![p]).with_panel_size(201, 150) // odd: padded to 202
///     })
///     .collect();
/// sink.frames_of(&frames)?;
/// assert_eq!(sink.finish()?, 3);
/// let info = webm::read(&std::fs::read(&path).unwrap())?;
/// assert_eq!((info.codec_id.as_str(), info.width, info.height), ("V_AV1", 202, 150));
/// assert_eq!(info.frames.len(), 3);
/// # std::fs::remove_file(&path).unwrap();
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
pub struct WebmSink {
    file: Option<FileSink>,
    fps: f64,
    options: RenderOptions,
    encoder: Option<Box<Encoder>>,
    frames: usize,
}

/// The encoder and the muxer, made with the first frame (its size).
struct Encoder {
    context: Context<u8>,
    muxer: WebmMuxer,
    /// The picture size (before padding to even).
    size: (u32, u32),
}

impl std::fmt::Debug for WebmSink {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("WebmSink")
            .field("fps", &self.fps)
            .field("frames", &self.frames)
            .field("options", &self.options)
            .finish_non_exhaustive()
    }
}

fn encoding(what: impl std::fmt::Display) -> IoError {
    IoError::Drawing {
        message: format!("AV1 encoding: {what}"),
    }
}

impl WebmSink {
    /// Checks the extension (`.webm`), locks `path` and creates its temporary file; frames
    /// will show at `fps` frames per second, drawn at each figure's own size and 96 dpi.
    pub fn open(path: &Path, fps: f64) -> Result<Self> {
        Self::open_with(path, fps, RenderOptions::default())
    }

    /// [`WebmSink::open`] with frames drawn under `options` (a size, a dpi).
    pub fn open_with(path: &Path, fps: f64, options: RenderOptions) -> Result<Self> {
        let ext = path.extension().and_then(|e| e.to_str());
        if !ext.is_some_and(|e| e.eq_ignore_ascii_case("webm")) {
            return Err(IoError::UnsupportedFormat {
                path: path.to_path_buf(),
                expected: "webm",
            });
        }
        Ok(Self {
            file: Some(FileSink::open(path)?),
            fps: if fps.is_finite() && fps > 0.0 {
                fps
            } else {
                10.0
            },
            options,
            encoder: None,
            frames: 0,
        })
    }

    /// Frames written so far.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// Draws `figures` (in parallel) and encodes them in order; every frame must have the
    /// first's size.
    pub fn frames_of(&mut self, figures: &[Figure]) -> Result<()> {
        for batch in figures.chunks(BATCH) {
            let pictures: Vec<(Yuv420, (u32, u32))> = batch
                .par_iter()
                .map(|f| {
                    let (rgb, size) = f.to_rgb_with(&self.options)?;
                    Ok((rgb_to_yuv420(&rgb, size), size))
                })
                .collect::<Result<_>>()?;
            self.pictures(pictures)?;
        }
        Ok(())
    }

    fn pictures(&mut self, pictures: Vec<(Yuv420, (u32, u32))>) -> Result<()> {
        for (yuv, size) in pictures {
            if self.encoder.is_none() {
                self.encoder = Some(Box::new(Encoder::new(&yuv, size, self.fps)?));
            }
            let Some(encoder) = self.encoder.as_mut() else {
                continue;
            };
            if encoder.size != size {
                return Err(IoError::InvalidFigure {
                    reason: "every frame of an animation must have the size of the first",
                });
            }
            encoder.send(&yuv)?;
            self.frames += 1;
        }
        Ok(())
    }

    /// Flushes the encoder, writes the WebM file and renames it onto the target; the number
    /// of frames. An animation without a frame is refused (the temporary file is removed).
    pub fn finish(mut self) -> Result<usize> {
        let (Some(mut encoder), Some(mut file)) = (self.encoder.take(), self.file.take()) else {
            return Err(IoError::InvalidFigure {
                reason: "an animation needs at least one frame",
            });
        };
        encoder.context.flush();
        encoder.drain()?;
        if encoder.muxer.frames() != self.frames {
            return Err(encoding(format!(
                "{} frames in, {} out",
                self.frames,
                encoder.muxer.frames()
            )));
        }
        encoder
            .muxer
            .finish(&mut file)
            .map_err(|source| IoError::Stream {
                what: "WebM video",
                source,
            })?;
        file.finish()?;
        Ok(self.frames)
    }
}

impl Encoder {
    fn new(first: &Yuv420, size: (u32, u32), fps: f64) -> Result<Self> {
        let mut enc = EncoderConfig::with_speed_preset(SPEED);
        (enc.width, enc.height) = (first.width, first.height);
        enc.bit_depth = 8;
        enc.chroma_sampling = ChromaSampling::Cs420;
        enc.pixel_range = PixelRange::Limited;
        enc.color_description = Some(ColorDescription {
            color_primaries: ColorPrimaries::BT709,
            transfer_characteristics: TransferCharacteristics::SRGB,
            matrix_coefficients: MatrixCoefficients::BT709,
        });
        // the frame rate as a fraction of whole numbers (to 1/1000 frame per second)
        let milli = (fps * 1000.0).round().max(1.0) as u64;
        enc.time_base = Rational::new(1000, milli);
        enc.quantizer = QUANTIZER;
        enc.low_latency = true;
        enc.tiles = TILES;
        enc.max_key_frame_interval = KEY_INTERVAL;
        enc.min_key_frame_interval = KEY_INTERVAL.min(12);
        let context: Context<u8> = Config::new()
            .with_encoder_config(enc)
            .new_context()
            .map_err(encoding)?;
        let muxer = WebmMuxer::new(
            "V_AV1",
            context.container_sequence_header(),
            (first.width as u32, first.height as u32),
            fps,
        );
        Ok(Self {
            context,
            muxer,
            size,
        })
    }

    /// Sends one picture and muxes whatever packets come out.
    fn send(&mut self, yuv: &Yuv420) -> Result<()> {
        let mut frame = self.context.new_frame();
        let widths = [yuv.width, yuv.width / 2, yuv.width / 2];
        for ((plane, data), w) in frame
            .planes
            .iter_mut()
            .zip([&yuv.y, &yuv.u, &yuv.v])
            .zip(widths)
        {
            plane.copy_from_raw_u8(data, w, 1);
        }
        self.context.send_frame(frame).map_err(encoding)?;
        self.drain()
    }

    /// Muxes the packets ready: temporal delimiters dropped (Matroska's AV1 mapping).
    fn drain(&mut self) -> Result<()> {
        loop {
            match self.context.receive_packet() {
                Ok(packet) => {
                    let key = packet.frame_type == FrameType::KEY;
                    let data = without_temporal_delimiters(&packet.data);
                    // av1C's configOBUs: the sequence header of the first keyframe
                    if self.muxer.codec_private().len() == 4 {
                        if let Some(header) = obus(&data).into_iter().find(|o| o.0 == 1) {
                            let mut record = self.muxer.codec_private().to_vec();
                            record.extend_from_slice(header.1);
                            self.muxer.set_codec_private(record);
                        }
                    }
                    self.muxer.push(&data, key);
                }
                Err(EncoderStatus::Encoded) => {}
                Err(EncoderStatus::NeedMoreData | EncoderStatus::LimitReached) => return Ok(()),
                Err(e) => return Err(encoding(e)),
            }
        }
    }
}

/// The OBUs of a temporal unit: (OBU type, its bytes with header and size). An OBU without
/// a size field runs to the end of the unit.
fn obus(data: &[u8]) -> Vec<(u8, &[u8])> {
    let mut out = Vec::new();
    let mut at = 0;
    while at < data.len() {
        let header = data[at];
        let kind = (header >> 3) & 0x0F;
        let ext = usize::from(header >> 2 & 1);
        let has_size = header >> 1 & 1 == 1;
        if !has_size {
            out.push((kind, &data[at..]));
            break;
        }
        // LEB128 size after the header (and its extension byte)
        let (mut size, mut len) = (0usize, 0usize);
        while let Some(&b) = data.get(at + 1 + ext + len) {
            size |= usize::from(b & 0x7F) << (7 * len);
            len += 1;
            if b & 0x80 == 0 || len == 8 {
                break;
            }
        }
        let end = (at + 1 + ext + len).saturating_add(size).min(data.len());
        out.push((kind, &data[at..end]));
        at = end;
    }
    out
}

/// The OBUs of a temporal unit without its temporal delimiters (OBU type 2), which the
/// Matroska AV1 mapping leaves out of blocks.
fn without_temporal_delimiters(data: &[u8]) -> Vec<u8> {
    obus(data)
        .into_iter()
        .filter(|o| o.0 != 2)
        .flat_map(|o| o.1.iter().copied())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporal_delimiters_are_dropped_and_other_obus_kept() {
        // TD (type 2, size 0), a sequence header (type 1) of 2 bytes, a frame (type 6) of 3
        let td = [0x12, 0x00];
        let seq = [0x0A, 0x02, 0xAA, 0xBB];
        let frame = [0x32, 0x03, 1, 2, 3];
        let unit = [&td[..], &seq, &frame].concat();
        assert_eq!(
            without_temporal_delimiters(&unit),
            [&seq[..], &frame].concat()
        );
        let kinds: Vec<u8> = obus(&unit).iter().map(|o| o.0).collect();
        assert_eq!(kinds, [2, 1, 6]);
        assert_eq!(obus(&unit)[2].1, frame);
    }
}
