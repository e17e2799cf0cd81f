//! The docs checked: every command line of README.md and docs/*.md that states an outcome is
//! run here and its stated outcome compared.
//!
//! # What counts as a command line
//!
//! A line of a fenced block, or an inline code span, that runs `tensegrity` (also as
//! `target/release/tensegrity`) or `cargo run`. `cargo run --release -- ARGS` is run as
//! `tensegrity ARGS`.
//!
//! # Fenced blocks: a marker on the line before the fence
//!
//! Every fenced block holding a command line needs one of these on the line just before its
//! fence (a block without one fails the test, so a new example cannot go unchecked by
//! accident):
//!
//! - `<!-- checked: exit N -->`: each command is run by the default test and must exit with N;
//! - `<!-- checked slow: exit N -->`: the same, run only by the ignored test
//!   `slow_examples_in_the_docs` (`cargo test --release --test integration docs_commands:: -- --ignored`,
//!   minutes): commands that take longer than a few seconds in the test build;
//! - `<!-- not run: REASON -->`: the block is only parsed; REASON says why (a synopsis with
//!   placeholders, a measured timing that depends on the machine, an hour of cluster work).
//!
//! In a ```` ```text ```` block, lines starting with `$ ` are commands and the lines after one
//! (up to the next `$ ` line) its expected output. In a ```` ```sh ```` block every line is a
//! command (`\` at the end continues it, `# …` is a comment); it has no expected output: its
//! exit code and the files it writes are checked. `cargo` lines other than `cargo run` (the
//! test and bench commands CI runs itself) are never run, nor are CI's scripts (`bash .ci/…`,
//! the README's test command).
//!
//! # Hidden checks: a statement in prose
//!
//! A number, a count or a table in prose is checked by an HTML comment right after it that
//! spans lines, with the marker's words on its first line and `$ ` lines with expected lines
//! like a `text` block:
//!
//! ```text
//! <!-- checked: exit 0
//! $ tensegrity statics examples/dbar_loaded.toml --json
//! json: mass_kg = 8.858023 ± 5e-7
//! -->
//! ```
//!
//! `<!-- not run: REASON` with `$ ` lines lists commands named in prose that are not run.
//!
//! # Inline code spans
//!
//! An inline span holding a concrete command (arguments, no placeholder: no all-capitals word
//! such as `SCENE` or `N`, no `[`, `|`, `…`, `<`) must be the start of a `$ ` command (or of an
//! `sh` line) of a marked block of the same document — it is then run, or listed as not run
//! with a reason. A bare command name, with mode flags but no values (`tensegrity roll`,
//! `tensegrity tbar roll`, `tensegrity tipover --rolling`), is a name, not a command line.
//!
//! # Expected lines
//!
//! Matched against the output (stdout, then stderr):
//!
//! - plain text: a whole output line, matched in order (each after the previous one); `…`
//!   stands for any text (a pid, a limit that depends on the machine), `{X±T}` for a number
//!   within T of X (`mean speed {11.48±0.005} m/s`);
//! - `json: PATH = VALUE`: stdout parsed as JSON, PATH dotted with array indices
//!   (`rows.0.mean_speed`); VALUE `X ± T` compares a number to a tolerance, anything else is
//!   JSON compared exactly (`json: prestressable = true`, `json: statics_method = "cyclic"`);
//! - `file: PATH`: the command wrote PATH (relative to the scratch directory).
//!
//! Besides, after a successful checked command every file named by an output flag
//! (`--out`, `--svg`, `--vtk`, `--sign-map`, `--gamma-sweep`, `--export-scene`, `--grid`,
//! `--animate`)
//! must exist.
//!
//! # How commands run
//!
//! Through `sh -c` in a scratch directory holding a link to `examples/`, empty `docs/data`
//! and `docs/figures`, and `repo`, a link to the repository (a hidden check
//! `$ cmp docs/data/roll.csv repo/docs/data/roll.csv` shows that the committed data are what
//! the documented command makes), with the binary under test first on the PATH as
//! `tensegrity` (so pipes, `sed` and globs work). The commands of one document run in order
//! in one scratch directory, so a block may read what an earlier one wrote. A checked command taking longer than [`LIMIT`] fails:
//! mark it `checked slow` or give a smaller variant.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The longest a checked example may take in the default run: the checked set stays fast.
const LIMIT: Duration = Duration::from_secs(30);
/// The longest a slow example may take (the ignored test).
const SLOW_LIMIT: Duration = Duration::from_secs(600);

#[derive(Debug, Clone, PartialEq)]
enum Marker {
    Exit(i32),
    Slow(i32),
    NotRun(String),
}

/// Where a command came from: a fenced block or a hidden check, or an inline span.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    Text,
    Sh,
    Hidden,
}

#[derive(Debug)]
struct Example {
    file: String,
    line: usize,
    marker: Marker,
    kind: Kind,
    command: String,
    expected: Vec<String>,
}

/// An inline code span holding a command.
#[derive(Debug)]
struct Inline {
    file: String,
    line: usize,
    command: String,
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md, then every `.md` under docs/ and its subfolders (docs/guide/, docs/notes/),
/// sorted by path.
fn documents() -> Vec<PathBuf> {
    fn markdown_under(dir: &Path, out: &mut Vec<PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                markdown_under(&path, out);
            } else if path.extension().is_some_and(|e| e == "md") {
                out.push(path);
            }
        }
    }
    let mut docs = vec![root().join("README.md")];
    let mut more = Vec::new();
    markdown_under(&root().join("docs"), &mut more);
    more.sort();
    docs.extend(more);
    docs
}

/// The marker of `text` (the inside of a comment, or its first line), if it is one.
fn parse_marker(text: &str) -> Option<Result<Marker, String>> {
    let m = text.trim();
    for (word, slow) in [("checked: exit ", false), ("checked slow: exit ", true)] {
        if let Some(code) = m.strip_prefix(word) {
            return Some(match code.trim().parse() {
                Ok(c) if slow => Ok(Marker::Slow(c)),
                Ok(c) => Ok(Marker::Exit(c)),
                Err(_) => Err(format!("bad exit code in `{m}`")),
            });
        }
    }
    if let Some(reason) = m.strip_prefix("not run:") {
        return Some(if reason.trim().is_empty() {
            Err("`not run:` needs a reason".into())
        } else {
            Ok(Marker::NotRun(reason.trim().to_string()))
        });
    }
    None
}

/// The marker on a line `<!-- … -->`.
fn line_marker(line: &str) -> Option<Result<Marker, String>> {
    let inner = line
        .trim()
        .strip_prefix("<!--")
        .and_then(|l| l.strip_suffix("-->"))?;
    parse_marker(inner)
}

/// `cargo run --release -- ARGS` and `target/release/tensegrity ARGS` as `tensegrity ARGS`;
/// a leading `time ` dropped.
fn normalise(command: &str) -> String {
    let mut c = command.trim();
    for p in ["time ", "/usr/bin/time "] {
        c = c.strip_prefix(p).unwrap_or(c).trim_start();
    }
    for p in [
        "cargo run --release -- ",
        "./target/release/tensegrity ",
        "target/release/tensegrity ",
    ] {
        if let Some(rest) = c.strip_prefix(p) {
            return format!("tensegrity {rest}");
        }
    }
    c.to_string()
}

/// Whether a line runs the binary or cargo.
fn is_command(line: &str) -> bool {
    let words = words(line);
    line.trim_start().starts_with("cargo run")
        || words
            .iter()
            .any(|w| w == "tensegrity" || w.ends_with("/tensegrity"))
}

/// Whether a word is a placeholder of a synopsis.
fn placeholder(word: &str) -> bool {
    if word.contains(['[', ']', '|', '…', '<', '>']) {
        return true;
    }
    word.split(|c: char| !c.is_ascii_alphanumeric() && c != '_')
        .any(|t| {
            t.chars().any(|c| c.is_ascii_uppercase())
                && t.chars().all(|c| c.is_ascii_uppercase() || c == '_')
        })
}

/// The lines of an `sh` block as commands: continuations joined, comments dropped.
fn sh_commands(lines: &[(usize, &str)]) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut current: Option<(usize, String)> = None;
    for &(at, raw) in lines {
        let line = strip_comment(raw);
        let (text, cont) = match line.trim_end().strip_suffix('\\') {
            Some(t) => (t.to_string(), true),
            None => (line.trim_end().to_string(), false),
        };
        let entry = current.get_or_insert((at, String::new()));
        if !entry.1.is_empty() {
            entry.1.push(' ');
        }
        entry.1.push_str(text.trim());
        if !cont {
            let (at, c) = current.take().unwrap();
            if !c.trim().is_empty() {
                out.push((at, c));
            }
        }
    }
    out.extend(current.filter(|(_, c)| !c.trim().is_empty()));
    out
}

/// A line without its `# comment` (a `#` at the start or after a space, outside quotes).
fn strip_comment(line: &str) -> &str {
    let mut quote = None;
    let mut prev = ' ';
    for (i, c) in line.char_indices() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (None, '\'' | '"') => quote = Some(c),
            (None, '#') if prev.is_whitespace() => return &line[..i],
            _ => {}
        }
        prev = c;
    }
    line
}

/// `$ ` commands and their expected lines.
fn dollar_commands(lines: &[(usize, &str)]) -> Result<Vec<(usize, String, Vec<String>)>, String> {
    let mut out: Vec<(usize, String, Vec<String>)> = Vec::new();
    for &(at, line) in lines {
        if let Some(c) = line.strip_prefix("$ ") {
            out.push((at, c.to_string(), Vec::new()));
        } else if let Some(last) = out.last_mut() {
            last.2.push(line.to_string());
        } else if !line.trim().is_empty() {
            return Err(format!("line {at}: expected a `$ ` line, found `{line}`"));
        }
    }
    Ok(out)
}

/// The examples and inline commands of one document, and the blocks of commands without a
/// marker.
fn parse(path: &Path) -> (Vec<Example>, Vec<Inline>, Vec<String>) {
    let file = path.strip_prefix(root()).unwrap().display().to_string();
    let text = std::fs::read_to_string(path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let fail = |at: usize, why: String| -> ! { panic!("{file}:{at}: {why}") };
    let mut examples = Vec::new();
    let mut inline = Vec::new();
    let mut unmarked = Vec::new();
    let mut prose = String::new();
    let mut prose_lines: Vec<(usize, usize)> = Vec::new(); // (offset, line)
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        let trimmed = line.trim_start();
        if trimmed.starts_with("```") {
            let lang = trimmed.trim_start_matches('`').trim().to_string();
            let start = i + 1;
            let mut end = start;
            while end < lines.len() && !lines[end].trim_start().starts_with("```") {
                end += 1;
            }
            let body: Vec<(usize, &str)> = (start..end).map(|k| (k + 1, lines[k])).collect();
            i = end + 1;
            let commands: Vec<(usize, String, Vec<String>)> = if lang == "text" {
                if !body.iter().any(|(_, l)| l.starts_with("$ ")) {
                    continue;
                }
                dollar_commands(&body).unwrap_or_else(|e| fail(start, e))
            } else if lang == "sh" || lang == "bash" || lang.is_empty() {
                sh_commands(&body)
                    .into_iter()
                    .filter(|(_, c)| {
                        let n = normalise(c);
                        // CI's own commands (the test command, `bash .ci/…`) are never run here
                        (!n.starts_with("cargo ") || n.starts_with("cargo run"))
                            && !n.starts_with("bash .ci/")
                    })
                    .map(|(at, c)| (at, c, Vec::new()))
                    .collect()
            } else {
                continue;
            };
            if !commands.iter().any(|(_, c, _)| is_command(c)) {
                continue;
            }
            let before = if start >= 2 { lines[start - 2] } else { "" };
            let marker = match line_marker(before) {
                Some(Ok(m)) => m,
                Some(Err(e)) => fail(start - 1, e),
                None => {
                    unmarked.push(format!(
                        "{file}:{start}: a block of commands needs `<!-- checked: exit N -->`, \
                         `<!-- checked slow: exit N -->` or `<!-- not run: REASON -->` on \
                         the line before its fence, found `{before}`"
                    ));
                    continue;
                }
            };
            let kind = if lang == "text" { Kind::Text } else { Kind::Sh };
            for (at, command, expected) in commands {
                examples.push(Example {
                    file: file.clone(),
                    line: at,
                    marker: marker.clone(),
                    kind,
                    command: normalise(&command),
                    expected,
                });
            }
            continue;
        }
        if let Some(first) = trimmed.strip_prefix("<!--") {
            if !first.contains("-->") {
                // a comment spanning lines: a hidden check when its first line is a marker
                let start = i + 1;
                let mut end = i + 1;
                while end < lines.len() && !lines[end].contains("-->") {
                    end += 1;
                }
                i = end + 1;
                let Some(marker) = parse_marker(first) else {
                    continue;
                };
                let marker = marker.unwrap_or_else(|e| fail(start, e));
                let body: Vec<(usize, &str)> = (start..end).map(|k| (k + 1, lines[k])).collect();
                let commands = dollar_commands(&body).unwrap_or_else(|e| fail(start, e));
                if commands.is_empty() {
                    fail(start, "a hidden check without a `$ ` command".into());
                }
                for (at, command, expected) in commands {
                    examples.push(Example {
                        file: file.clone(),
                        line: at,
                        marker: marker.clone(),
                        kind: Kind::Hidden,
                        command: normalise(&command),
                        expected,
                    });
                }
                continue;
            }
        }
        prose_lines.push((prose.len(), i + 1));
        prose.push_str(line);
        prose.push(' ');
        i += 1;
    }
    // inline spans over the prose (a span may cross a line break)
    let mut parts = prose.split('`');
    let mut offset = parts.next().map_or(0, |p| p.len() + 1);
    let mut inside = true;
    for part in parts {
        if inside && is_command(part) && !part.contains('\n') {
            let line = prose_lines
                .iter()
                .rev()
                .find(|(o, _)| *o <= offset)
                .map_or(0, |(_, l)| *l);
            inline.push(Inline {
                file: file.clone(),
                line,
                command: normalise(part),
            });
        }
        offset += part.len() + 1;
        inside = !inside;
    }
    (examples, inline, unmarked)
}

/// Whether an inline command is a bare name (`tensegrity tbar roll`, `tensegrity tipover
/// --rolling`: words and flags without values), not a command line.
fn bare_name(command: &str) -> bool {
    let w = words(command);
    w[0] == "tensegrity"
        && w[1..]
            .iter()
            .all(|x| x.chars().all(|c| c.is_ascii_lowercase() || c == '-'))
}

/// Shell-like words: whitespace separates, single or double quotes group.
fn words(command: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut word: Option<String> = None;
    let mut quote: Option<char> = None;
    for c in command.chars() {
        match (quote, c) {
            (Some(q), c) if c == q => quote = None,
            (Some(_), c) => word.get_or_insert_with(String::new).push(c),
            (None, '\'' | '"') => {
                quote = Some(c);
                word.get_or_insert_with(String::new);
            }
            (None, c) if c.is_whitespace() => out.extend(word.take()),
            (None, c) => word.get_or_insert_with(String::new).push(c),
        }
    }
    out.extend(word);
    out
}

/// A piece of an expected line.
#[derive(Debug, Clone, PartialEq)]
enum Piece {
    Text(String),
    Any,
    Number(f64, f64),
}

/// An expected line as pieces: `…` any text, `{X±T}` a number.
fn pieces(pattern: &str) -> Vec<Piece> {
    let mut out = Vec::new();
    let mut text = String::new();
    let mut rest = pattern;
    while let Some(c) = rest.chars().next() {
        if c == '…' {
            out.push(Piece::Text(std::mem::take(&mut text)));
            out.push(Piece::Any);
            rest = &rest[c.len_utf8()..];
            continue;
        }
        if c == '{' {
            if let Some(close) = rest.find('}') {
                let inner = &rest[1..close];
                if let Some((x, t)) = inner.split_once('±') {
                    if let (Ok(x), Ok(t)) = (x.trim().parse(), t.trim().parse()) {
                        out.push(Piece::Text(std::mem::take(&mut text)));
                        out.push(Piece::Number(x, t));
                        rest = &rest[close + 1..];
                        continue;
                    }
                }
            }
        }
        text.push(c);
        rest = &rest[c.len_utf8()..];
    }
    out.push(Piece::Text(text));
    out.retain(|p| *p != Piece::Text(String::new()));
    out
}

/// The longest number at the start of `s` and its length.
fn leading_number(s: &str) -> Option<(f64, usize)> {
    let end = s
        .char_indices()
        .take_while(|&(i, c)| {
            c.is_ascii_digit()
                || c == '.'
                || ((c == '-' || c == '+') && (i == 0 || s[..i].ends_with(['e', 'E'])))
                || ((c == 'e' || c == 'E') && i > 0)
        })
        .map(|(i, c)| i + c.len_utf8())
        .last()?;
    (1..=end)
        .rev()
        .find_map(|k| s[..k].parse::<f64>().ok().map(|v| (v, k)))
}

fn match_pieces(p: &[Piece], line: &str) -> bool {
    match p.first() {
        None => line.is_empty(),
        Some(Piece::Text(t)) => line
            .strip_prefix(t.as_str())
            .is_some_and(|rest| match_pieces(&p[1..], rest)),
        Some(Piece::Any) => line
            .char_indices()
            .map(|(i, _)| i)
            .chain([line.len()])
            .any(|i| match_pieces(&p[1..], &line[i..])),
        Some(Piece::Number(x, t)) => leading_number(line)
            .is_some_and(|(v, k)| (v - x).abs() <= *t && match_pieces(&p[1..], &line[k..])),
    }
}

/// Whether `line` matches `pattern`, where `…` stands for any text and `{X±T}` for a number.
fn matches(pattern: &str, line: &str) -> bool {
    match_pieces(&pieces(pattern), line)
}

/// The value at a dotted path (`rows.0.mean_speed`).
fn at_path<'a>(v: &'a serde_json::Value, path: &str) -> Option<&'a serde_json::Value> {
    path.split('.')
        .try_fold(v, |v, key| match key.parse::<usize>() {
            Ok(i) if v.is_array() => v.get(i),
            _ => v.get(key),
        })
}

/// Checks a `json: PATH = VALUE` line against stdout.
fn check_json(line: &str, stdout: &str) -> Result<(), String> {
    let (path, want) = line
        .split_once('=')
        .ok_or_else(|| format!("`json: {line}` has no `=`"))?;
    let (path, want) = (path.trim(), want.trim());
    let doc: serde_json::Value =
        serde_json::from_str(stdout).map_err(|e| format!("stdout is not JSON ({e})"))?;
    let got = at_path(&doc, path).ok_or_else(|| format!("no `{path}` in the JSON"))?;
    if let Some((x, t)) = want.split_once('±') {
        let (x, t): (f64, f64) = (
            x.trim()
                .parse()
                .map_err(|_| format!("bad number in `{want}`"))?,
            t.trim()
                .parse()
                .map_err(|_| format!("bad tolerance in `{want}`"))?,
        );
        let v = got
            .as_f64()
            .ok_or_else(|| format!("`{path}` is {got}, not a number"))?;
        if (v - x).abs() > t {
            return Err(format!("`{path}` is {v}, the docs say {x} ± {t}"));
        }
        return Ok(());
    }
    let want_v: serde_json::Value =
        serde_json::from_str(want).map_err(|_| format!("`{want}` is not JSON"))?;
    let same = match (got.as_f64(), want_v.as_f64()) {
        (Some(a), Some(b)) => a == b,
        _ => *got == want_v,
    };
    if !same {
        return Err(format!("`{path}` is {got}, the docs say {want}"));
    }
    Ok(())
}

/// The files named by output flags in a command.
fn outputs(command: &str) -> Vec<String> {
    let w = words(command);
    w.windows(2)
        .filter(|p| {
            [
                "--out",
                "--svg",
                "--vtk",
                "--sign-map",
                "--gamma-sweep",
                "--export-scene",
                "--grid",
                "--animate",
            ]
            .contains(&p[0].as_str())
        })
        .map(|p| p[1].clone())
        .collect()
}

/// The scratch directory of one run: `examples/` linked, `docs/data` and `docs/figures`
/// empty, `repo` the repository (to compare committed data with what a command makes), and
/// `bin/tensegrity` the binary under test.
struct Scratch {
    dir: PathBuf,
    path_var: String,
}

impl Scratch {
    fn new(name: &str) -> Self {
        let dir =
            std::env::temp_dir().join(format!("tensegrity-docs-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        for d in ["bin", "docs/data", "docs/figures"] {
            std::fs::create_dir_all(dir.join(d)).unwrap();
        }
        std::os::unix::fs::symlink(root().join("examples"), dir.join("examples")).unwrap();
        std::os::unix::fs::symlink(root(), dir.join("repo")).unwrap();
        std::os::unix::fs::symlink(env!("CARGO_BIN_EXE_tensegrity"), dir.join("bin/tensegrity"))
            .unwrap();
        let path_var = format!(
            "{}:{}",
            dir.join("bin").display(),
            std::env::var("PATH").unwrap_or_default()
        );
        Self { dir, path_var }
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// Runs one example; what is wrong with it, if anything.
fn check(example: &Example, code: i32, scratch: &Scratch, limit: Duration) -> Option<String> {
    // `|`, `<` and `>` are the shell's here, not a synopsis's
    let synopsis = |w: &String| {
        w.contains(['[', ']', '…']) || (placeholder(w) && !w.contains(['|', '<', '>']))
    };
    if let Some(w) = words(&example.command).iter().find(|w| synopsis(w)) {
        return Some(format!("placeholder `{w}` in a checked command"));
    }
    let start = Instant::now();
    let mut child = {
        use std::os::unix::process::CommandExt;
        Command::new("sh")
            .arg("-c")
            .arg(&example.command)
            .current_dir(&scratch.dir)
            .env("PATH", &scratch.path_var)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .process_group(0)
            .spawn()
            .unwrap()
    };
    // drain the pipes while waiting, so a long output cannot block the child
    let mut so = child.stdout.take().unwrap();
    let mut se = child.stderr.take().unwrap();
    let t_out = std::thread::spawn(move || {
        let mut b = Vec::new();
        std::io::Read::read_to_end(&mut so, &mut b).ok();
        b
    });
    let t_err = std::thread::spawn(move || {
        let mut b = Vec::new();
        std::io::Read::read_to_end(&mut se, &mut b).ok();
        b
    });
    let status = loop {
        if let Some(s) = child.try_wait().unwrap() {
            break s;
        }
        if start.elapsed() > limit {
            let _ = Command::new("kill")
                .args(["-KILL", &format!("-{}", child.id())])
                .status();
            let _ = child.wait();
            return Some(format!(
                "ran longer than {limit:?}: mark it `checked slow` or give a smaller variant"
            ));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    let stdout = String::from_utf8_lossy(&t_out.join().unwrap()).to_string();
    let stderr = String::from_utf8_lossy(&t_err.join().unwrap()).to_string();
    let printed = format!("{stdout}{stderr}");
    let shown = || {
        let mut s: String = printed.chars().take(4000).collect();
        if s.len() < printed.len() {
            s.push_str("\n[…]");
        }
        s
    };
    if status.code() != Some(code) {
        return Some(format!(
            "exit code {:?}, the docs say {code}; output:\n{}",
            status.code(),
            shown()
        ));
    }
    let lines: Vec<&str> = printed.lines().collect();
    let mut at = 0;
    for want in &example.expected {
        if want.trim().is_empty() {
            continue;
        }
        if let Some(j) = want.strip_prefix("json: ") {
            if let Err(why) = check_json(j, &stdout) {
                return Some(why);
            }
        } else if let Some(f) = want.strip_prefix("file: ") {
            if !scratch.dir.join(f.trim()).exists() {
                return Some(format!("no file `{}` written", f.trim()));
            }
        } else {
            match lines[at..].iter().position(|l| matches(want, l)) {
                Some(k) => at += k + 1,
                None => return Some(format!("no line `{want}` in the output:\n{}", shown())),
            }
        }
    }
    if code == 0 {
        for f in outputs(&example.command) {
            if !scratch.dir.join(&f).exists() {
                return Some(format!("the output `{f}` was not written"));
            }
        }
    }
    None
}

/// Every example and inline command of README.md and docs/*.md.
fn inventory() -> (Vec<Example>, Vec<Inline>, Vec<String>) {
    let (mut ex, mut inl, mut un) = (Vec::new(), Vec::new(), Vec::new());
    for d in documents() {
        let (e, i, u) = parse(&d);
        ex.extend(e);
        inl.extend(i);
        un.extend(u);
    }
    (ex, inl, un)
}

/// Runs the examples `pick` selects; the failures.
fn run_examples(
    name: &str,
    pick: impl Fn(&Marker) -> Option<(i32, Duration)>,
) -> (usize, Vec<String>) {
    let (all, _, _) = inventory();
    let scratch = Scratch::new(name);
    let mut failures = Vec::new();
    let mut ran = 0;
    for e in &all {
        if let Some((code, limit)) = pick(&e.marker) {
            ran += 1;
            if let Some(why) = check(e, code, &scratch, limit) {
                failures.push(format!("{}:{}: `{}`: {why}", e.file, e.line, e.command));
            }
        }
    }
    (ran, failures)
}

#[test]
fn every_stated_outcome_in_the_docs_is_what_the_command_does() {
    let (ran, failures) = run_examples("fast", |m| match m {
        Marker::Exit(c) => Some((*c, LIMIT)),
        _ => None,
    });
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(ran >= 40, "only {ran} checked examples");
}

#[test]
#[ignore = "minutes: cargo test --release --test integration docs_commands:: -- --ignored"]
fn slow_examples_in_the_docs() {
    let (ran, failures) = run_examples("slow", |m| match m {
        Marker::Slow(c) => Some((*c, SLOW_LIMIT)),
        _ => None,
    });
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(ran >= 1, "no slow examples");
}

#[test]
fn every_command_line_in_the_docs_is_checked_or_says_why_not() {
    let (examples, inline, mut unmatched) = inventory();
    assert!(
        examples.iter().any(|e| e.file == "README.md"),
        "the README's examples were not found"
    );
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    for s in &inline {
        let w = words(&s.command);
        let class = if w.iter().any(|x| placeholder(x)) {
            "inline synopsis"
        } else if bare_name(&s.command) {
            "inline name"
        } else if examples
            .iter()
            .any(|e| e.file == s.file && words(&e.command).starts_with(&w))
        {
            "inline, run by a block"
        } else {
            unmatched.push(format!(
                "{}:{}: `{}`: an inline command line that no marked block of {} runs or \
                 lists as not run",
                s.file, s.line, s.command, s.file
            ));
            "unmatched"
        };
        *counts.entry(class).or_default() += 1;
    }
    for e in &examples {
        let class = match (&e.marker, e.kind) {
            (Marker::Exit(_), Kind::Hidden) => "checked (hidden, prose)",
            (Marker::Exit(_), _) => "checked (block)",
            (Marker::Slow(_), _) => "checked slow (ignored test)",
            (Marker::NotRun(_), _) => "not run (reason given)",
        };
        *counts.entry(class).or_default() += 1;
    }
    println!("command lines in README.md and docs/*.md: {counts:#?}");
    for e in examples
        .iter()
        .filter(|e| matches!(e.marker, Marker::NotRun(_)))
    {
        if let Marker::NotRun(why) = &e.marker {
            println!("not run: {}:{}: `{}`: {why}", e.file, e.line, e.command);
        }
    }
    assert!(unmatched.is_empty(), "{}", unmatched.join("\n"));
}

#[test]
fn the_convention_parses_and_matches_as_documented() {
    assert_eq!(
        words(r#"tensegrity a "b c" 'd' e"#),
        ["tensegrity", "a", "b c", "d", "e"]
    );
    assert!(matches(
        "error: above the limit of …; raise",
        "error: above the limit of 8 GiB; raise"
    ));
    assert!(matches("a … b … c", "a 1 b 2 c"));
    assert!(!matches("a … b … c", "a 1 c 2 b"));
    assert!(!matches("exact", "exact but longer"));
    assert!(matches("speed {11.48±0.005} m/s", "speed 11.4812 m/s"));
    assert!(!matches("speed {11.48±0.005} m/s", "speed 11.49 m/s"));
    assert!(matches("{-2.5e-3±1e-4}, …", "-0.0025, x"));
    assert!(matches(
        "\"mass_kg\": {8.858023±1e-6},",
        "\"mass_kg\": 8.8580231,"
    ));
    assert_eq!(
        normalise("cargo run --release -- statics x.toml"),
        "tensegrity statics x.toml"
    );
    assert_eq!(
        normalise("time target/release/tensegrity toroid"),
        "tensegrity toroid"
    );
    assert!(placeholder("SCENE.toml") && placeholder("pi/N") && placeholder("[--json]"));
    assert!(!placeholder("57Gi") && !placeholder("3pi/4") && !placeholder("1e-9"));
    assert!(bare_name("tensegrity tbar roll") && bare_name("tensegrity tipover --rolling"));
    assert!(!bare_name("tensegrity toroid --sides 8"));
    assert_eq!(
        sh_commands(&[
            (1, "tensegrity a \\"),
            (2, "    --b 1   # note"),
            (3, "# only")
        ]),
        [(1, "tensegrity a --b 1".to_string())]
    );
    let json = r#"{"rows": [{"v": 1.5}], "ok": true, "m": "cyclic"}"#;
    assert!(check_json("rows.0.v = 1.5 ± 0.01", json).is_ok());
    assert!(check_json("rows.0.v = 1.6 ± 0.01", json).is_err());
    assert!(check_json("ok = true", json).is_ok());
    assert!(check_json("rows.0.v = 1.5", json).is_ok());
    assert!(check_json(r#"m = "cyclic""#, json).is_ok());
    assert_eq!(
        outputs("tensegrity michell-table --out a.csv --svg b.svg"),
        ["a.csv", "b.svg"]
    );
}
