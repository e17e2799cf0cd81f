//! The committed figures are current: `scripts/regen-figures --out-dir TMP` (the one command
//! that regenerates every `docs/figures/*.svg` from `docs/data/*.csv`, with the documented
//! `tensegrity sweep plot … --out docs/figures/…` lines) is run with the binary under test, and
//! every figure it makes must equal the committed file byte for byte.
//!
//! No normalisation: the SVG of `sweep plot` holds nothing that depends on the run (no
//! timestamp, no absolute path: the title is the CSV's file name, the output path is not
//! written into the file), so two runs, into any directory, write the same bytes.
//!
//! A stale figure fails the test with its file, the command that makes it and the command
//! that refreshes them all. The script itself fails (and so does this test) when a committed
//! figure has no documented plot line or two lines write one file; a documented figure that
//! is not committed fails here.

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A directory removed when dropped.
struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// The first line where `a` and `b` differ: (1-based number, line of a, line of b).
fn first_difference(a: &str, b: &str) -> (usize, String, String) {
    let cut = |s: &str| s.chars().take(160).collect::<String>();
    let (mut la, mut lb) = (a.lines(), b.lines());
    let mut n = 0;
    loop {
        n += 1;
        match (la.next(), lb.next()) {
            (Some(x), Some(y)) if x == y => continue,
            (x, y) => {
                return (
                    n,
                    cut(x.unwrap_or("(end of file)")),
                    cut(y.unwrap_or("(end of file)")),
                )
            }
        }
    }
}

/// The committed `docs/figures/*.svg`, as `docs/figures/NAME.svg`.
fn committed_figures() -> Vec<String> {
    let mut out: Vec<String> = std::fs::read_dir(root().join("docs/figures"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "svg"))
        .map(|p| format!("docs/figures/{}", p.file_name().unwrap().to_string_lossy()))
        .collect();
    out.sort();
    out
}

#[test]
fn committed_figures_are_what_the_documented_commands_make_from_the_committed_data() {
    let scratch = Scratch(
        std::env::temp_dir().join(format!("tensegrity-docs-figures-{}", std::process::id())),
    );
    let _ = std::fs::remove_dir_all(&scratch.0);
    let out = Command::new("bash")
        .arg(root().join("scripts/regen-figures"))
        .arg("--out-dir")
        .arg(&scratch.0)
        .arg(env!("CARGO_BIN_EXE_tensegrity"))
        .current_dir(root())
        .output()
        .expect("bash runs scripts/regen-figures");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    // the script's own failures (a figure without a documented line, a command that fails)
    // are reported with the comparison of what it did make
    let mut problems = Vec::new();
    if !out.status.success() {
        problems.push(format!(
            "scripts/regen-figures failed ({}):\n{}",
            out.status,
            stderr.trim_end()
        ));
    }

    // `docs/figures/NAME.svg: COMMAND`, one line per figure made
    let made: Vec<(&str, &str)> = stdout
        .lines()
        .map(|l| {
            l.split_once(": ")
                .unwrap_or_else(|| panic!("unexpected line from scripts/regen-figures: {l}"))
        })
        .collect();
    let committed = committed_figures();
    assert!(!committed.is_empty(), "no docs/figures/*.svg");
    let refresh = "cargo build --release && scripts/regen-figures \
                   (or scripts/regen-figures target/debug/tensegrity), then commit docs/figures/";

    for (file, command) in &made {
        let name = Path::new(file).file_name().unwrap();
        let fresh = std::fs::read_to_string(scratch.0.join(name))
            .unwrap_or_else(|e| panic!("{file}: `{command}` wrote no file ({e})"));
        let Ok(old) = std::fs::read_to_string(root().join(file)) else {
            problems.push(format!(
                "{file} is documented (`{command}`) but not committed: {refresh}"
            ));
            continue;
        };
        if old != fresh {
            let (n, was, now) = first_difference(&old, &fresh);
            problems.push(format!(
                "{file} is stale: it differs from what `{command}` makes now \
                 (first at line {n}:\n    committed: {was}\n    made now:  {now})"
            ));
        }
    }
    // the script checks this too (above); kept so that the test does not depend on it alone
    for file in &committed {
        if !made.iter().any(|(f, _)| f == file) {
            problems.push(format!(
                "{file} is committed but no documented `tensegrity sweep plot … --out {file}` \
                 line makes it"
            ));
        }
    }
    assert!(
        problems.is_empty(),
        "the committed figures (docs/figures/*.svg, {} files) are not what their commands \
         make from docs/data/:\n\n{}\n\nRefresh them all: {refresh}",
        committed.len(),
        problems.join("\n\n")
    );
}
