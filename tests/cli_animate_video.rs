//! `--animate FILE.webm` (issue 46, video output): an AV1 video in WebM, parsed back with the
//! io crate's reader (`tensegrity_io::sink::webm::read`): round(fps × duration) frames at
//! k·1000/fps ms, the first a keyframe, the frame size the picture's rounded up to even, the
//! duration frames/fps, CodecID `V_AV1` with an `av1C` record; `.mp4` is refused (exit 2, the
//! reason, no file) and an unknown extension lists `gif, webm`; the same run's GIF has as many
//! frames as its video.

use crate::common;
use common::{assert_ok, assert_refused, run, scratch};
use tensegrity_io::sink::webm;

/// Checks a WebM file: `frames` frames at `fps`, `size` pixels, lasting frames/fps seconds.
fn check(path: &std::path::Path, frames: usize, fps: f64, size: (u32, u32)) {
    let info = webm::read(&std::fs::read(path).unwrap()).unwrap();
    assert_eq!(info.doc_type, "webm");
    assert_eq!(info.codec_id, "V_AV1");
    // av1C: marker 1, version 1; then profile 0 (main: 8-bit 4:2:0)
    assert_eq!(info.codec_private[0], 0x81, "{:x?}", info.codec_private);
    assert_eq!(info.codec_private[1] >> 5, 0);
    assert_eq!((info.width, info.height), size);
    assert_eq!(info.frames.len(), frames);
    assert!(info.frames[0].keyframe);
    // the av1C carries the sequence header OBU (type 1) of the first keyframe, which starts
    // with it; no block holds a temporal delimiter (type 2)
    assert_eq!(
        info.codec_private[4] >> 3 & 0x0F,
        1,
        "{:x?}",
        info.codec_private
    );
    assert!(info.frames[0].data.starts_with(&info.codec_private[4..]));
    for f in &info.frames {
        assert_ne!(f.data[0] >> 3 & 0x0F, 2);
    }
    for (k, f) in info.frames.iter().enumerate() {
        assert_eq!(
            f.time_ms,
            (k as f64 * 1000.0 / fps).round() as u64,
            "frame {k}"
        );
        assert!(!f.data.is_empty(), "frame {k} has no data");
    }
    assert_eq!(info.timecode_scale_ns, 1_000_000);
    assert!(
        (info.duration_s - frames as f64 / fps).abs() < 1e-9,
        "{} s",
        info.duration_s
    );
    assert_eq!(info.cue_times_ms.first(), Some(&0));
}

#[test]
fn simulate_writes_a_webm_of_fps_times_duration_frames_at_an_even_size() {
    let dir = scratch("anim-video", "simulate");
    let video = dir.join("drop.webm");
    // 315 × 237 px: the odd height is padded with a white row to 238
    let out = run(&[
        "simulate",
        "examples/prism_drop.toml",
        "--t-end",
        "0.2",
        "--animate",
        video.to_str().unwrap(),
        "--fps",
        "8",
        "--duration",
        "1.5",
        "--size",
        "315x237",
    ]);
    assert_ok(&out);
    assert!(String::from_utf8_lossy(&out.stderr).contains("wrote 12 frames"));
    check(&video, 12, 8.0, (316, 238));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn roll_writes_the_same_frames_as_video_and_as_gif() {
    let dir = scratch("anim-video", "roll");
    let (video, gif) = (dir.join("roll.webm"), dir.join("roll.gif"));
    for path in [&video, &gif] {
        let out = run(&[
            "roll",
            "--fidelity",
            "rigid",
            "--t-end",
            "1",
            "--no-convergence-check",
            "--animate",
            path.to_str().unwrap(),
            "--fps",
            "5",
            "--duration",
            "2",
        ]);
        assert_ok(&out);
    }
    let ((w, h), frames) = common::gif_frames(&gif);
    let (w, h) = (w as u32, h as u32);
    assert_eq!(frames.len(), 10);
    check(&video, 10, 5.0, (w + (w & 1), h + (h & 1)));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn mp4_is_refused_with_the_reason_and_other_types_list_gif_and_webm() {
    let dir = scratch("anim-video", "refused");
    let mp4 = dir.join("drop.mp4");
    let out = run(&[
        "simulate",
        "examples/prism_drop.toml",
        "--animate",
        mp4.to_str().unwrap(),
    ]);
    let err = assert_refused(&out, ".mp4", "MP4 is not written");
    assert!(
        err.contains("--animate") && err.contains(".webm") && err.contains(".gif"),
        "{err}"
    );
    // refused before the run: nothing written, nothing simulated
    assert!(!mp4.exists());
    assert!(!err.contains("simulated"), "{err}");
    let avi = dir.join("drop.avi");
    let out = run(&[
        "roll",
        "--fidelity",
        "rigid",
        "--animate",
        avi.to_str().unwrap(),
    ]);
    assert_refused(&out, ".avi", "expected one of: gif, webm");
    assert!(!avi.exists());
    let _ = std::fs::remove_dir_all(&dir);
}
