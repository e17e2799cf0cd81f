//! `--size` and `--dpi` reach `--animate` (issue 46, item 4): the GIF's logical screen and
//! every frame are size × dpi pixels for `simulate`, `roll` and `tbar roll`; the frames share
//! one global palette (no local ones) that holds the figure's colours exactly, and the
//! members are drawn in them; a size no frame can have is refused before the run.

use crate::common;
use common::{assert_ok, run, scratch};

use std::fs::File;
use std::path::Path;
use tensegrity_figures::draw::{BAR_COLOR, RED};

/// What a GIF holds: the logical screen (from the header bytes), the global palette, and each
/// frame's (width, height, whether it has a local palette, its indices).
struct Gif {
    screen: (u16, u16),
    palette: Vec<(u8, u8, u8)>,
    frames: Vec<(u16, u16, bool, Vec<u8>)>,
}

fn read(path: &Path) -> Gif {
    let bytes = std::fs::read(path).unwrap();
    assert!(bytes.starts_with(b"GIF89a"));
    let screen = (
        u16::from_le_bytes([bytes[6], bytes[7]]),
        u16::from_le_bytes([bytes[8], bytes[9]]),
    );
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::Indexed);
    let mut decoder = options.read_info(File::open(path).unwrap()).unwrap();
    let palette = decoder
        .global_palette()
        .expect("a global palette")
        .chunks_exact(3)
        .map(|c| (c[0], c[1], c[2]))
        .collect();
    let mut frames = Vec::new();
    while let Some(f) = decoder.read_next_frame().unwrap() {
        frames.push((f.width, f.height, f.palette.is_some(), f.buffer.to_vec()));
    }
    Gif {
        screen,
        palette,
        frames,
    }
}

const WHITE: (u8, u8, u8) = (255, 255, 255);

/// Pixels of `cm` centimetres at `dpi`.
fn px(cm: f64, dpi: f64) -> f64 {
    cm / 2.54 * dpi
}

/// Checks the screen and every frame are `want` pixels (±1), `n` frames, one palette holding
/// the bar and string colours exactly, and the colours `drawn` in the first frame (a string
/// thinner than a pixel, at a low dpi, never covers one whole).
fn check(gif: &Gif, want: (f64, f64), n: usize, drawn: &[(u8, u8, u8)]) {
    let (w, h) = gif.screen;
    assert!(
        (f64::from(w) - want.0).abs() <= 1.0 && (f64::from(h) - want.1).abs() <= 1.0,
        "screen {w} × {h}, want {want:?}"
    );
    assert_eq!(gif.frames.len(), n);
    assert!(gif.palette.len() <= 256);
    for (fw, fh, local, pixels) in &gif.frames {
        assert_eq!((*fw, *fh, *local), (w, h, false));
        assert_eq!(pixels.len(), usize::from(w) * usize::from(h));
    }
    let index = |colour: (u8, u8, u8)| {
        let k = gif.palette.iter().position(|&c| c == colour);
        k.unwrap_or_else(|| panic!("{colour:?} not in the palette")) as u8
    };
    assert_ne!(index(BAR_COLOR), index(RED));
    for &colour in drawn {
        assert!(
            gif.frames[0].3.contains(&index(colour)),
            "{colour:?} not drawn in the first frame"
        );
    }
}

#[test]
fn simulate_animates_at_the_given_size_and_dpi() {
    let dir = scratch("anim-size", "simulate");
    let gif = dir.join("a.gif");
    let out = run(&[
        "simulate",
        "examples/prism_drop.toml",
        "--t-end",
        "0.2",
        "--animate",
        gif.to_str().unwrap(),
        "--size",
        "8x6cm",
        "--dpi",
        "100",
    ]);
    assert_ok(&out);
    // 8 cm × 6 cm at 100 dpi: 315 × 236 pixels; 10 fps × 5 s = 50 frames
    check(
        &read(&gif),
        (px(8.0, 100.0), px(6.0, 100.0)),
        50,
        &[BAR_COLOR, RED, WHITE],
    );
    // a size no frame can have is refused before the run: exit 2, no file
    let small = dir.join("small.gif");
    let out = run(&[
        "simulate",
        "examples/prism_drop.toml",
        "--animate",
        small.to_str().unwrap(),
        "--size",
        "1x1cm",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!small.exists());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("--size") && !stderr.contains("simulated"),
        "{stderr}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn roll_and_tbar_roll_animate_at_the_given_size_and_dpi() {
    let dir = scratch("anim-size", "roll");
    let gif = dir.join("r.gif");
    let out = run(&[
        "roll",
        "--fidelity",
        "rigid",
        "--t-end",
        "0.5",
        "--animate",
        gif.to_str().unwrap(),
        "--fps",
        "4",
        "--duration",
        "2",
        "--size",
        "4x3in",
        "--dpi",
        "50",
    ]);
    assert_ok(&out);
    check(&read(&gif), (200.0, 150.0), 8, &[BAR_COLOR, WHITE]);
    let out = run(&[
        "tbar",
        "roll",
        "--treads",
        "8",
        "--t-end",
        "0.5",
        "--animate",
        gif.to_str().unwrap(),
        "--fps",
        "3",
        "--duration",
        "1",
        "--size",
        "60x45mm",
        "--dpi",
        "200",
    ]);
    assert_ok(&out);
    check(
        &read(&gif),
        (px(6.0, 200.0), px(4.5, 200.0)),
        3,
        &[BAR_COLOR, RED, WHITE],
    );
    let _ = std::fs::remove_dir_all(&dir);
}
