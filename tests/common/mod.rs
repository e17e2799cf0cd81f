//! Helpers shared by the CLI integration tests: run the binary, check its exit, a scratch
//! directory per test binary.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Runs `tensegrity ARGS` from the repository root.
pub fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("binary runs")
}

/// Asserts a zero exit, showing stderr otherwise.
pub fn assert_ok(out: &Output) {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Asserts the exit 2 of bad input and that stderr says `says` (`case` labels the failure);
/// returns stderr.
pub fn assert_refused(out: &Output, case: &str, says: &str) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{case}: {err}");
    assert!(err.contains(says), "{case}: expected `{says}` in: {err}");
    err
}

/// A fresh directory `tensegrity-PREFIX-NAME-PID` under the system's temporary directory.
pub fn scratch(prefix: &str, name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("tensegrity-{prefix}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `tensegrity` as a command run from the repository root (arguments, pipes and signals left
/// to the caller).
pub fn bin() -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_tensegrity"));
    c.current_dir(env!("CARGO_MANIFEST_DIR"));
    c
}

/// Resource limits far above any request: the point of the bad-path tests is that the path is
/// checked before the (deliberately huge) work, not that the guard refuses the work.
pub const NO_LIMITS: [&str; 6] = [
    "--max-work",
    "1e12",
    "--max-memory",
    "1000Ti",
    "--max-output",
    "1000Ti",
];

/// The names in `dir`, sorted.
pub fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// A planar zig-zag chain of `n` nodes along x, written as a scene in `dir`: bars between
/// neighbours, strings between every other node (a triangulated strip: rank 2n − 3, no
/// self-stress, n + 3 mechanisms out of its plane). Its path.
pub fn chain(dir: &Path, n: usize) -> String {
    let mut s = String::from("nodes = [\n");
    for i in 0..n {
        s += &format!("  [{i}.0, {}, 0.0],\n", 0.5 * (i % 2) as f64);
    }
    s += "]\n";
    for i in 0..n - 1 {
        s += &format!("[[bars]]\nnodes = [{i}, {}]\n", i + 1);
    }
    for i in 0..n - 2 {
        s += &format!("[[strings]]\nnodes = [{i}, {}]\n", i + 2);
    }
    let path = dir.join(format!("chain{n}.toml"));
    std::fs::write(&path, s).unwrap();
    path.display().to_string()
}

/// The JSON that `tensegrity ARGS` prints (the run must succeed; its stderr shown if not).
pub fn json(args: &[&str]) -> serde_json::Value {
    let out = run(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// A JSON list of [x, y, z] points (nodes, velocities) as arrays.
pub fn points(v: &serde_json::Value) -> Vec<[f64; 3]> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let p: Vec<f64> = p
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            [p[0], p[1], p[2]]
        })
        .collect()
}

/// A JSON list of numbers as a vector.
pub fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// One frame of an animated GIF: width, height, delay (1/100 s).
pub type GifFrame = (u16, u16, u16);

/// The frames of an animated GIF: its logical screen (width, height) and each frame.
pub fn gif_frames(path: &Path) -> ((u16, u16), Vec<GifFrame>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::fs::File::open(path).unwrap())
        .unwrap();
    let screen = (decoder.width(), decoder.height());
    let mut frames = Vec::new();
    while let Some(f) = decoder.read_next_frame().unwrap() {
        frames.push((f.width, f.height, f.delay));
    }
    (screen, frames)
}
