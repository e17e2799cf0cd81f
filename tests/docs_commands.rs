//! The docs checked: every command line of README.md and docs/*.md that states an outcome is
//! run here and its stated outcome compared.
//!
//! The convention (README.md, "Checked examples"): a fenced `text` block whose lines start with
//! `$ tensegrity …` is an example with an outcome. The lines after a `$` line, up to the next
//! one, are its expected output (stdout and stderr together), each matched in order against
//! a whole output line; `…` in an expected line stands for any text (a pid, a limit that
//! depends on the machine). The line just before the fence says what is checked:
//!
//! - `<!-- checked: exit N -->`: each command is run with the test binary in a scratch
//!   directory (`examples/` linked in) and must exit with N and print the stated lines;
//! - `<!-- not run: REASON -->`: the block is only parsed (a long run, a machine-dependent
//!   outcome), the reason stated.
//!
//! A `$ tensegrity` block with neither marker fails the test, so a new example cannot go
//! unchecked by accident.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The longest a checked example may take: the checked set stays fast.
const LIMIT: Duration = Duration::from_secs(30);

#[derive(Debug, Clone, Copy)]
enum Marker {
    Exit(i32),
    NotRun,
}

#[derive(Debug)]
struct Example {
    file: String,
    line: usize,
    marker: Marker,
    command: String,
    expected: Vec<String>,
}

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// README.md and every docs/*.md.
fn documents() -> Vec<PathBuf> {
    let mut docs = vec![root().join("README.md")];
    let mut more: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    more.sort();
    docs.extend(more);
    docs
}

fn marker(line: &str, file: &str, at: usize) -> Marker {
    let inner = line
        .trim()
        .strip_prefix("<!--")
        .and_then(|l| l.strip_suffix("-->"))
        .map(str::trim);
    match inner {
        Some(m) if m.starts_with("checked: exit ") => Marker::Exit(
            m["checked: exit ".len()..]
                .trim()
                .parse()
                .unwrap_or_else(|_| panic!("{file}:{at}: bad exit code in `{line}`")),
        ),
        Some(m) if m.starts_with("not run:") && m.len() > "not run:".len() + 1 => Marker::NotRun,
        _ => panic!(
            "{file}:{at}: a `$ tensegrity` example needs `<!-- checked: exit N -->` or \
             `<!-- not run: REASON -->` on the line before its fence, found `{line}`"
        ),
    }
}

/// The examples of one document.
fn examples(path: &Path) -> Vec<Example> {
    let file = path.strip_prefix(root()).unwrap().display().to_string();
    let text = std::fs::read_to_string(path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        let fence = lines[i].trim_start();
        let opens_text = fence.starts_with("```text");
        if !(opens_text
            && lines
                .get(i + 1)
                .is_some_and(|l| l.starts_with("$ tensegrity")))
        {
            i += 1;
            continue;
        }
        let m = marker(if i > 0 { lines[i - 1] } else { "" }, &file, i + 1);
        i += 1;
        while i < lines.len() && !lines[i].trim_start().starts_with("```") {
            let command = lines[i].strip_prefix("$ ").unwrap_or_else(|| {
                panic!(
                    "{file}:{}: expected a `$ ` line, found `{}`",
                    i + 1,
                    lines[i]
                )
            });
            let line = i + 1;
            i += 1;
            let mut expected = Vec::new();
            while i < lines.len() && !lines[i].starts_with("$ ") && !lines[i].starts_with("```") {
                expected.push(lines[i].to_string());
                i += 1;
            }
            out.push(Example {
                file: file.clone(),
                line,
                marker: m,
                command: command.to_string(),
                expected,
            });
        }
        i += 1;
    }
    out
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

/// Whether `line` matches `pattern`, where `…` stands for any text.
fn matches(pattern: &str, line: &str) -> bool {
    let parts: Vec<&str> = pattern.split('…').collect();
    if parts.len() == 1 {
        return pattern == line;
    }
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if line.len() < first.len() + last.len() {
        return false;
    }
    if !line.starts_with(first) || !line[first.len()..].ends_with(last) {
        return false;
    }
    let mut rest = &line[first.len()..line.len() - last.len()];
    for part in &parts[1..parts.len() - 1] {
        match rest.find(part) {
            Some(at) => rest = &rest[at + part.len()..],
            None => return false,
        }
    }
    true
}

/// Runs one example in `dir`; returns what is wrong with it, if anything.
fn check(example: &Example, code: i32, dir: &Path) -> Option<String> {
    let args = words(&example.command);
    assert_eq!(args[0], "tensegrity");
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(&args[1..])
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > LIMIT {
            child.kill().unwrap();
            let _ = child.wait();
            return Some(format!("ran longer than {LIMIT:?}: mark it `not run`"));
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    let printed = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    let lines: Vec<&str> = printed.lines().collect();
    let mut at = 0;
    for want in &example.expected {
        match lines[at..].iter().position(|l| matches(want, l)) {
            Some(k) => at += k + 1,
            None => return Some(format!("no line `{want}` in the output:\n{printed}")),
        }
    }
    (out.status.code() != Some(code)).then(|| {
        format!(
            "exit code {:?}, the docs say {code}; output:\n{printed}",
            out.status.code()
        )
    })
}

#[test]
fn every_stated_outcome_in_the_docs_is_what_the_command_does() {
    let all: Vec<Example> = documents().iter().flat_map(|d| examples(d)).collect();
    assert!(
        all.iter().any(|e| e.file == "README.md"),
        "the README's examples were not found"
    );
    let dir = std::env::temp_dir().join(format!("tensegrity-docs-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let link = dir.join("examples");
    if !link.exists() {
        std::os::unix::fs::symlink(root().join("examples"), &link).unwrap();
    }
    let mut failures = Vec::new();
    let mut ran = 0;
    for e in &all {
        if let Marker::Exit(code) = e.marker {
            ran += 1;
            if let Some(why) = check(e, code, &dir) {
                failures.push(format!("{}:{}: `{}`: {why}", e.file, e.line, e.command));
            }
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(ran >= 4, "only {ran} checked examples");
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
}
