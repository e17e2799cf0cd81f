//! A small WebM (Matroska) muxer for one video track, and a reader of what it writes.
//!
//! [`WebmMuxer`] collects the coded frames of one video track (AV1 here: CodecID `V_AV1`,
//! CodecPrivate the `av1C` record) and writes, at [`WebmMuxer::finish`], a complete WebM file
//! whose every element has a known size:
//!
//! ```text
//! EBML header        DocType "webm", DocTypeVersion 4, DocTypeReadVersion 2
//! Segment
//!   SeekHead         where Info, Tracks and Cues are (8-byte positions)
//!   Info             TimecodeScale 1 000 000 ns (timestamps in ms), Duration, Muxing/WritingApp
//!   Tracks           one TrackEntry: number 1, type video, CodecID, CodecPrivate,
//!                    DefaultDuration (ns), Video { PixelWidth, PixelHeight }
//!   Cluster …        Timestamp (ms) + SimpleBlocks (track 1, 16-bit relative time, key flag);
//!                    a new cluster at every keyframe and before a relative time would pass
//!                    30 s
//!   Cues             one CuePoint per cluster that starts with a keyframe
//! ```
//!
//! Frame k shows at round(1000 k / fps) ms; the Duration is frames × 1000 / fps ms. The coded
//! frames are held in memory until `finish` (compressed: a few kB a frame for a drawing), so
//! the sizes and positions are known when the file is written.
//!
//! [`read`] parses such a file back ([`WebmInfo`]: the DocType, codec, size, duration and every
//! frame's time and key flag), checking that each element's size fits its parent; it reads
//! only the elements this muxer writes (others are skipped) and is meant for checks and tests.

use crate::error::{IoError, Result};
use std::io::Write;

/// EBML element IDs (with their length-marker bits, as written).
pub mod id {
    /// EBML header.
    pub const EBML: u32 = 0x1A45_DFA3;
    /// EBMLVersion.
    pub const EBML_VERSION: u32 = 0x4286;
    /// EBMLReadVersion.
    pub const EBML_READ_VERSION: u32 = 0x42F7;
    /// EBMLMaxIDLength.
    pub const EBML_MAX_ID_LENGTH: u32 = 0x42F2;
    /// EBMLMaxSizeLength.
    pub const EBML_MAX_SIZE_LENGTH: u32 = 0x42F3;
    /// DocType.
    pub const DOC_TYPE: u32 = 0x4282;
    /// DocTypeVersion.
    pub const DOC_TYPE_VERSION: u32 = 0x4287;
    /// DocTypeReadVersion.
    pub const DOC_TYPE_READ_VERSION: u32 = 0x4285;
    /// Segment.
    pub const SEGMENT: u32 = 0x1853_8067;
    /// SeekHead.
    pub const SEEK_HEAD: u32 = 0x114D_9B74;
    /// Seek.
    pub const SEEK: u32 = 0x4DBB;
    /// SeekID.
    pub const SEEK_ID: u32 = 0x53AB;
    /// SeekPosition.
    pub const SEEK_POSITION: u32 = 0x53AC;
    /// Info.
    pub const INFO: u32 = 0x1549_A966;
    /// TimecodeScale (ns per timestamp unit).
    pub const TIMECODE_SCALE: u32 = 0x2A_D7B1;
    /// Duration (float, timestamp units).
    pub const DURATION: u32 = 0x4489;
    /// MuxingApp.
    pub const MUXING_APP: u32 = 0x4D80;
    /// WritingApp.
    pub const WRITING_APP: u32 = 0x5741;
    /// Tracks.
    pub const TRACKS: u32 = 0x1654_AE6B;
    /// TrackEntry.
    pub const TRACK_ENTRY: u32 = 0xAE;
    /// TrackNumber.
    pub const TRACK_NUMBER: u32 = 0xD7;
    /// TrackUID.
    pub const TRACK_UID: u32 = 0x73C5;
    /// TrackType (1: video).
    pub const TRACK_TYPE: u32 = 0x83;
    /// FlagLacing.
    pub const FLAG_LACING: u32 = 0x9C;
    /// CodecID.
    pub const CODEC_ID: u32 = 0x86;
    /// CodecPrivate.
    pub const CODEC_PRIVATE: u32 = 0x63A2;
    /// DefaultDuration (ns per frame).
    pub const DEFAULT_DURATION: u32 = 0x23_E383;
    /// Video.
    pub const VIDEO: u32 = 0xE0;
    /// PixelWidth.
    pub const PIXEL_WIDTH: u32 = 0xB0;
    /// PixelHeight.
    pub const PIXEL_HEIGHT: u32 = 0xBA;
    /// Cluster.
    pub const CLUSTER: u32 = 0x1F43_B675;
    /// Cluster Timestamp.
    pub const TIMESTAMP: u32 = 0xE7;
    /// SimpleBlock.
    pub const SIMPLE_BLOCK: u32 = 0xA3;
    /// Cues.
    pub const CUES: u32 = 0x1C53_BB6B;
    /// CuePoint.
    pub const CUE_POINT: u32 = 0xBB;
    /// CueTime.
    pub const CUE_TIME: u32 = 0xB3;
    /// CueTrackPositions.
    pub const CUE_TRACK_POSITIONS: u32 = 0xB7;
    /// CueTrack.
    pub const CUE_TRACK: u32 = 0xF7;
    /// CueClusterPosition.
    pub const CUE_CLUSTER_POSITION: u32 = 0xF1;
}

/// Nanoseconds per timestamp unit: timestamps are in milliseconds.
pub const TIMECODE_SCALE_NS: u64 = 1_000_000;

/// The longest time (ms) from a cluster's start to a block in it (a block's relative time is
/// a signed 16-bit number).
const MAX_CLUSTER_SPAN_MS: u64 = 30_000;

/// The bytes of an element ID (its marker bits included), most significant first.
fn id_bytes(id: u32) -> Vec<u8> {
    let b = id.to_be_bytes();
    let skip = b.iter().take_while(|&&x| x == 0).count().min(3);
    b[skip..].to_vec()
}

/// An element size as an EBML variable-length integer of the fewest bytes (the all-ones
/// value of each length is reserved for "unknown", so it is never used).
fn size_vint(size: u64) -> Vec<u8> {
    let mut n = 1;
    while n < 8 && size >= (1u64 << (7 * n)) - 1 {
        n += 1;
    }
    let v = size | (1u64 << (7 * n));
    v.to_be_bytes()[8 - n..].to_vec()
}

/// An element: ID, size, payload.
fn element(id: u32, payload: &[u8]) -> Vec<u8> {
    let mut out = id_bytes(id);
    out.extend(size_vint(payload.len() as u64));
    out.extend_from_slice(payload);
    out
}

/// An unsigned-integer element in the fewest bytes (at least one).
fn uint(id: u32, v: u64) -> Vec<u8> {
    let b = v.to_be_bytes();
    let skip = b.iter().take_while(|&&x| x == 0).count().min(7);
    element(id, &b[skip..])
}

/// An unsigned-integer element in exactly 8 bytes (a position whose size must not depend on
/// its value).
fn uint8(id: u32, v: u64) -> Vec<u8> {
    element(id, &v.to_be_bytes())
}

fn float(id: u32, v: f64) -> Vec<u8> {
    element(id, &v.to_be_bytes())
}

/// A cluster being filled.
#[derive(Debug)]
struct OpenCluster {
    start_ms: u64,
    blocks: Vec<u8>,
    keyed: bool,
}

/// The frames of one video track, written as a WebM file at [`WebmMuxer::finish`].
///
/// ```
/// use tensegrity_io::sink::webm::{read, WebmMuxer};
/// let mut mux = WebmMuxer::new("V_AV1", vec![0x81, 0, 0, 0], (64, 48), 10.0);
/// for k in 0..3 {
///     mux.push(&[k as u8; 5], k == 0);
/// }
/// let mut bytes = Vec::new();
/// mux.finish(&mut bytes).unwrap();
/// let info = read(&bytes)?;
/// assert_eq!((info.width, info.height, info.frames.len()), (64, 48, 3));
/// assert_eq!(info.frames[2].time_ms, 200);
/// assert!((info.duration_s - 0.3).abs() < 1e-12);
/// # Ok::<(), tensegrity_io::IoError>(())
/// ```
#[derive(Debug)]
pub struct WebmMuxer {
    codec_id: String,
    codec_private: Vec<u8>,
    size: (u32, u32),
    fps: f64,
    frames: usize,
    /// Finished clusters, each with its start time and whether it starts with a keyframe.
    clusters: Vec<(u64, bool, Vec<u8>)>,
    open: Option<OpenCluster>,
}

impl WebmMuxer {
    /// A muxer of frames `size` pixels (width, height) shown at `fps` frames per second, coded
    /// by `codec_id` (e.g. `V_AV1`) with its `codec_private` record.
    pub fn new(codec_id: &str, codec_private: Vec<u8>, size: (u32, u32), fps: f64) -> Self {
        Self {
            codec_id: codec_id.to_string(),
            codec_private,
            size,
            fps: if fps.is_finite() && fps > 0.0 {
                fps
            } else {
                10.0
            },
            frames: 0,
            clusters: Vec::new(),
            open: None,
        }
    }

    /// The codec's record (CodecPrivate), e.g. once the first frame has shown what it holds.
    pub fn codec_private(&self) -> &[u8] {
        &self.codec_private
    }

    /// Replaces the codec's record (CodecPrivate); it is written at [`WebmMuxer::finish`].
    pub fn set_codec_private(&mut self, codec_private: Vec<u8>) {
        self.codec_private = codec_private;
    }

    /// Frames pushed so far.
    pub fn frames(&self) -> usize {
        self.frames
    }

    /// The time (ms) of frame `k`: round(1000 k / fps).
    pub fn time_ms(&self, k: usize) -> u64 {
        (k as f64 * 1000.0 / self.fps).round() as u64
    }

    /// Appends the next frame's coded bytes (`keyframe`: decodable on its own).
    pub fn push(&mut self, data: &[u8], keyframe: bool) {
        let t = self.time_ms(self.frames);
        let fits = |c: &OpenCluster| !keyframe && t - c.start_ms <= MAX_CLUSTER_SPAN_MS;
        if !self.open.as_ref().is_some_and(fits) {
            self.close_cluster();
            self.open = Some(OpenCluster {
                start_ms: t,
                blocks: uint(id::TIMESTAMP, t),
                keyed: keyframe,
            });
        }
        if let Some(c) = self.open.as_mut() {
            let rel = (t - c.start_ms) as i16;
            // track number 1 as a 1-byte vint, the relative time, the flags (0x80: key)
            let mut block = vec![0x81];
            block.extend(rel.to_be_bytes());
            block.push(if keyframe { 0x80 } else { 0x00 });
            block.extend_from_slice(data);
            c.blocks.extend(element(id::SIMPLE_BLOCK, &block));
        }
        self.frames += 1;
    }

    fn close_cluster(&mut self) {
        if let Some(c) = self.open.take() {
            self.clusters
                .push((c.start_ms, c.keyed, element(id::CLUSTER, &c.blocks)));
        }
    }

    /// Writes the whole file to `out`; its length in bytes.
    pub fn finish(mut self, out: &mut impl Write) -> std::io::Result<u64> {
        self.close_cluster();
        let header = element(
            id::EBML,
            &[
                uint(id::EBML_VERSION, 1),
                uint(id::EBML_READ_VERSION, 1),
                uint(id::EBML_MAX_ID_LENGTH, 4),
                uint(id::EBML_MAX_SIZE_LENGTH, 8),
                element(id::DOC_TYPE, b"webm"),
                uint(id::DOC_TYPE_VERSION, 4),
                uint(id::DOC_TYPE_READ_VERSION, 2),
            ]
            .concat(),
        );
        let app = concat!("tensegrity ", env!("CARGO_PKG_VERSION"));
        let info = element(
            id::INFO,
            &[
                uint(id::TIMECODE_SCALE, TIMECODE_SCALE_NS),
                float(id::DURATION, self.frames as f64 * 1000.0 / self.fps),
                element(id::MUXING_APP, app.as_bytes()),
                element(id::WRITING_APP, app.as_bytes()),
            ]
            .concat(),
        );
        let video = element(
            id::VIDEO,
            &[
                uint(id::PIXEL_WIDTH, u64::from(self.size.0)),
                uint(id::PIXEL_HEIGHT, u64::from(self.size.1)),
            ]
            .concat(),
        );
        let entry = element(
            id::TRACK_ENTRY,
            &[
                uint(id::TRACK_NUMBER, 1),
                uint(id::TRACK_UID, 1),
                uint(id::TRACK_TYPE, 1),
                uint(id::FLAG_LACING, 0),
                element(id::CODEC_ID, self.codec_id.as_bytes()),
                element(id::CODEC_PRIVATE, &self.codec_private),
                uint(id::DEFAULT_DURATION, (1e9 / self.fps).round() as u64),
                video,
            ]
            .concat(),
        );
        let tracks = element(id::TRACKS, &entry);
        // positions are relative to the start of the Segment's payload; the SeekHead's size
        // does not depend on them (8-byte positions)
        let seek = |target: u32, at: u64| {
            element(
                id::SEEK,
                &[
                    element(id::SEEK_ID, &id_bytes(target)),
                    uint8(id::SEEK_POSITION, at),
                ]
                .concat(),
            )
        };
        let seek_len = element(
            id::SEEK_HEAD,
            &[seek(id::INFO, 0), seek(id::TRACKS, 0), seek(id::CUES, 0)].concat(),
        )
        .len() as u64;
        let info_at = seek_len;
        let tracks_at = info_at + info.len() as u64;
        let mut at = tracks_at + tracks.len() as u64;
        let mut points = Vec::new();
        for (start, keyed, bytes) in &self.clusters {
            if *keyed {
                let positions = [uint(id::CUE_TRACK, 1), uint(id::CUE_CLUSTER_POSITION, at)];
                points.extend(element(
                    id::CUE_POINT,
                    &[
                        uint(id::CUE_TIME, *start),
                        element(id::CUE_TRACK_POSITIONS, &positions.concat()),
                    ]
                    .concat(),
                ));
            }
            at += bytes.len() as u64;
        }
        let cues = element(id::CUES, &points);
        let seek_head = element(
            id::SEEK_HEAD,
            &[
                seek(id::INFO, info_at),
                seek(id::TRACKS, tracks_at),
                seek(id::CUES, at),
            ]
            .concat(),
        );
        let body_len = at + cues.len() as u64;
        let mut segment_head = id_bytes(id::SEGMENT);
        segment_head.extend(size_vint(body_len));
        out.write_all(&header)?;
        out.write_all(&segment_head)?;
        out.write_all(&seek_head)?;
        out.write_all(&info)?;
        out.write_all(&tracks)?;
        for (_, _, bytes) in &self.clusters {
            out.write_all(bytes)?;
        }
        out.write_all(&cues)?;
        Ok((header.len() + segment_head.len()) as u64 + body_len)
    }
}

/// One frame read back.
#[derive(Debug, Clone, PartialEq)]
pub struct WebmFrame {
    /// Its time (ms): the cluster's timestamp plus the block's relative time.
    pub time_ms: u64,
    /// The SimpleBlock's key flag.
    pub keyframe: bool,
    /// The coded bytes.
    pub data: Vec<u8>,
}

/// What [`read`] finds in a WebM file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct WebmInfo {
    /// The EBML DocType (`webm`).
    pub doc_type: String,
    /// Nanoseconds per timestamp unit.
    pub timecode_scale_ns: u64,
    /// The Segment's Duration (s): its value in timestamp units times the TimecodeScale.
    pub duration_s: f64,
    /// The video track's CodecID.
    pub codec_id: String,
    /// Its CodecPrivate.
    pub codec_private: Vec<u8>,
    /// Its DefaultDuration (ns per frame).
    pub default_duration_ns: u64,
    /// PixelWidth.
    pub width: u32,
    /// PixelHeight.
    pub height: u32,
    /// The frames, in file order.
    pub frames: Vec<WebmFrame>,
    /// The times (ms) of the CuePoints.
    pub cue_times_ms: Vec<u64>,
}

fn bad(at: usize, reason: impl Into<String>) -> IoError {
    IoError::InvalidModel {
        file: "WebM".into(),
        item: format!("byte {at}"),
        reason: reason.into(),
    }
}

/// A variable-length integer at `at`: its value (marker removed) and length; `None` when the
/// bytes end or the first is 0.
fn vint(bytes: &[u8], at: usize) -> Option<(u64, usize)> {
    let first = *bytes.get(at)?;
    let n = first.leading_zeros() as usize + 1;
    if n > 8 || at + n > bytes.len() {
        return None;
    }
    let mut v = u64::from(first) & (0xFF >> n);
    for &b in &bytes[at + 1..at + n] {
        v = v << 8 | u64::from(b);
    }
    Some((v, n))
}

/// The elements directly inside `bytes[range]`: (ID, payload range).
fn children(bytes: &[u8], from: usize, to: usize) -> Result<Vec<(u32, usize, usize)>> {
    let mut out = Vec::new();
    let mut at = from;
    while at < to {
        let (_, id_len) = vint(bytes, at).ok_or_else(|| bad(at, "bad element ID"))?;
        if id_len > 4 {
            return Err(bad(at, "element ID longer than 4 bytes"));
        }
        let id = bytes[at..at + id_len]
            .iter()
            .fold(0u32, |a, &b| a << 8 | u32::from(b));
        let (size, size_len) =
            vint(bytes, at + id_len).ok_or_else(|| bad(at + id_len, "bad element size"))?;
        let start = at + id_len + size_len;
        let end = usize::try_from(size)
            .ok()
            .and_then(|s| start.checked_add(s))
            .filter(|&e| e <= to)
            .ok_or_else(|| bad(at, format!("element {id:#x} runs past its parent")))?;
        out.push((id, start, end));
        at = end;
    }
    Ok(out)
}

fn read_uint(b: &[u8]) -> u64 {
    b.iter().take(8).fold(0u64, |a, &x| a << 8 | u64::from(x))
}

fn read_float(b: &[u8], at: usize) -> Result<f64> {
    match b.len() {
        4 => Ok(f64::from(f32::from_be_bytes([b[0], b[1], b[2], b[3]]))),
        8 => Ok(f64::from_be_bytes(b.try_into().unwrap_or([0; 8]))),
        _ => Err(bad(at, "a float must be 4 or 8 bytes")),
    }
}

/// Parses a WebM file of one video track (as [`WebmMuxer`] writes it) back.
pub fn read(bytes: &[u8]) -> Result<WebmInfo> {
    let top = children(bytes, 0, bytes.len())?;
    let mut info = WebmInfo::default();
    let (Some(&(_, h0, h1)), Some(&(_, s0, s1))) = (
        top.iter().find(|e| e.0 == id::EBML),
        top.iter().find(|e| e.0 == id::SEGMENT),
    ) else {
        return Err(bad(0, "no EBML header or no Segment"));
    };
    for (id, a, b) in children(bytes, h0, h1)? {
        if id == id::DOC_TYPE {
            info.doc_type = String::from_utf8_lossy(&bytes[a..b]).into_owned();
        }
    }
    // in timestamp units until the scale is known
    let mut duration = 0.0;
    for (id, a, b) in children(bytes, s0, s1)? {
        match id {
            id::INFO => {
                for (id, a, b) in children(bytes, a, b)? {
                    match id {
                        id::TIMECODE_SCALE => info.timecode_scale_ns = read_uint(&bytes[a..b]),
                        id::DURATION => duration = read_float(&bytes[a..b], a)?,
                        _ => {}
                    }
                }
            }
            id::TRACKS => {
                for (_, a, b) in children(bytes, a, b)?
                    .into_iter()
                    .filter(|e| e.0 == id::TRACK_ENTRY)
                {
                    for (id, a, b) in children(bytes, a, b)? {
                        match id {
                            id::CODEC_ID => {
                                info.codec_id = String::from_utf8_lossy(&bytes[a..b]).into_owned();
                            }
                            id::CODEC_PRIVATE => info.codec_private = bytes[a..b].to_vec(),
                            id::DEFAULT_DURATION => {
                                info.default_duration_ns = read_uint(&bytes[a..b]);
                            }
                            id::VIDEO => {
                                for (id, a, b) in children(bytes, a, b)? {
                                    let v = u32::try_from(read_uint(&bytes[a..b])).unwrap_or(0);
                                    match id {
                                        id::PIXEL_WIDTH => info.width = v,
                                        id::PIXEL_HEIGHT => info.height = v,
                                        _ => {}
                                    }
                                }
                            }
                            _ => {}
                        }
                    }
                }
            }
            id::CLUSTER => {
                let mut start = 0;
                for (id, a, b) in children(bytes, a, b)? {
                    match id {
                        id::TIMESTAMP => start = read_uint(&bytes[a..b]),
                        id::SIMPLE_BLOCK => {
                            if b - a < 4 || bytes[a] != 0x81 {
                                return Err(bad(
                                    a,
                                    "a SimpleBlock of track 1 needs 4 header bytes",
                                ));
                            }
                            let rel = i16::from_be_bytes([bytes[a + 1], bytes[a + 2]]);
                            info.frames.push(WebmFrame {
                                time_ms: start.saturating_add_signed(i64::from(rel)),
                                keyframe: bytes[a + 3] & 0x80 != 0,
                                data: bytes[a + 4..b].to_vec(),
                            });
                        }
                        _ => {}
                    }
                }
            }
            id::CUES => {
                for (_, a, b) in children(bytes, a, b)? {
                    for (id, a, b) in children(bytes, a, b)? {
                        if id == id::CUE_TIME {
                            info.cue_times_ms.push(read_uint(&bytes[a..b]));
                        }
                    }
                }
            }
            _ => {}
        }
    }
    if info.timecode_scale_ns == 0 {
        // Matroska's default
        info.timecode_scale_ns = TIMECODE_SCALE_NS;
    }
    info.duration_s = duration * info.timecode_scale_ns as f64 * 1e-9;
    Ok(info)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_the_shortest_variable_length_integers() {
        assert_eq!(size_vint(0), vec![0x80]);
        assert_eq!(size_vint(126), vec![0xFE]);
        // 127 is the reserved all-ones of one byte
        assert_eq!(size_vint(127), vec![0x40, 0x7F]);
        assert_eq!(size_vint(16_382), vec![0x7F, 0xFE]);
        assert_eq!(size_vint(16_383), vec![0x20, 0x3F, 0xFF]);
        for v in [0, 1, 126, 127, 5000, 1 << 20, 1 << 40] {
            let b = size_vint(v);
            assert_eq!(vint(&b, 0), Some((v, b.len())));
        }
        assert_eq!(id_bytes(id::EBML), vec![0x1A, 0x45, 0xDF, 0xA3]);
        assert_eq!(id_bytes(id::SIMPLE_BLOCK), vec![0xA3]);
    }

    fn written(frames: usize, fps: f64, keys: &[usize]) -> (Vec<u8>, u64) {
        let mut mux = WebmMuxer::new("V_AV1", vec![0x81, 0x08, 0x0c, 0x00, 0x0a], (320, 240), fps);
        for k in 0..frames {
            mux.push(&vec![k as u8; 3 + k % 5], keys.contains(&k));
        }
        let mut bytes = Vec::new();
        let n = mux.finish(&mut bytes).unwrap();
        (bytes, n)
    }

    #[test]
    fn the_file_parses_back_with_every_frame_its_time_and_its_key_flag() {
        let (bytes, n) = written(7, 4.0, &[0, 4]);
        assert_eq!(n as usize, bytes.len());
        // the EBML header, then one Segment spanning the rest of the file
        let top = children(&bytes, 0, bytes.len()).unwrap();
        assert_eq!(
            top.iter().map(|e| e.0).collect::<Vec<_>>(),
            [id::EBML, id::SEGMENT]
        );
        assert_eq!(top[1].2, bytes.len());
        let segment: Vec<u32> = children(&bytes, top[1].1, top[1].2)
            .unwrap()
            .iter()
            .map(|e| e.0)
            .collect();
        assert_eq!(
            segment,
            [
                id::SEEK_HEAD,
                id::INFO,
                id::TRACKS,
                id::CLUSTER,
                id::CLUSTER,
                id::CUES
            ]
        );
        let info = read(&bytes).unwrap();
        assert_eq!(info.doc_type, "webm");
        assert_eq!(info.timecode_scale_ns, 1_000_000);
        assert_eq!(
            (info.codec_id.as_str(), info.width, info.height),
            ("V_AV1", 320, 240)
        );
        assert_eq!(info.codec_private, [0x81, 0x08, 0x0c, 0x00, 0x0a]);
        assert_eq!(info.default_duration_ns, 250_000_000);
        assert!(
            (info.duration_s - 1.75).abs() < 1e-12,
            "{} s",
            info.duration_s
        );
        let times: Vec<u64> = info.frames.iter().map(|f| f.time_ms).collect();
        assert_eq!(times, [0, 250, 500, 750, 1000, 1250, 1500]);
        let keys: Vec<bool> = info.frames.iter().map(|f| f.keyframe).collect();
        assert_eq!(keys, [true, false, false, false, true, false, false]);
        assert_eq!(info.frames[3].data, vec![3u8; 6]);
        assert_eq!(info.cue_times_ms, [0, 1000]);
    }

    #[test]
    fn the_seek_head_points_at_info_tracks_and_cues() {
        let (bytes, _) = written(3, 10.0, &[0]);
        let top = children(&bytes, 0, bytes.len()).unwrap();
        let body = top[1].1;
        let segment = children(&bytes, body, top[1].2).unwrap();
        let seeks = children(&bytes, segment[0].1, segment[0].2).unwrap();
        assert_eq!(seeks.len(), 3);
        for (_, a, b) in seeks {
            let fields = children(&bytes, a, b).unwrap();
            let target = read_uint(&bytes[fields[0].1..fields[0].2]) as u32;
            let at = body + read_uint(&bytes[fields[1].1..fields[1].2]) as usize;
            let n = id_bytes(target).len();
            let found = bytes[at..at + n]
                .iter()
                .fold(0u32, |x, &y| x << 8 | u32::from(y));
            assert_eq!(found, target);
        }
    }

    #[test]
    fn a_long_run_starts_a_new_cluster_before_the_relative_time_overflows() {
        // 1 fps, one keyframe: 70 frames span 69 s, so three clusters
        let (bytes, _) = written(70, 1.0, &[0]);
        let info = read(&bytes).unwrap();
        assert_eq!(info.frames.len(), 70);
        assert_eq!(info.frames[69].time_ms, 69_000);
        let top = children(&bytes, 0, bytes.len()).unwrap();
        let clusters = children(&bytes, top[1].1, top[1].2)
            .unwrap()
            .iter()
            .filter(|e| e.0 == id::CLUSTER)
            .count();
        assert_eq!(clusters, 3);
        // cues only where a cluster starts with a keyframe
        assert_eq!(info.cue_times_ms, [0]);
    }

    #[test]
    fn truncated_or_overlong_elements_are_refused() {
        let (bytes, _) = written(3, 10.0, &[0]);
        assert!(read(&bytes[..bytes.len() - 1]).is_err());
        assert!(read(&[0x1A, 0x45, 0xDF, 0xA3, 0x88, 0x42]).is_err());
        assert!(read(&[]).is_err());
    }
}
