//! `tensegrity sweep merge`: shard files (or any files of the same sweep) combined into the
//! file a single run writes.
//!
//! Every input must have the same preamble (units line and header) and end with a complete
//! row; inputs with a `# spec: …` line (the files of shards, [`crate::table::spec_hash`])
//! must have the same one, so shards of two specs that share a header are refused (a file
//! without the line — a single run's, or a shard written by an older version — is checked by
//! its header only, as before). The merged file leaves the spec line out; rows are keyed by their `case` id and written in id order, each exactly as it is in
//! its input, so merging the shards `1/N … N/N` of a sweep gives byte for byte the file of
//! one run. A case found twice must have identical rows; a gap in the ids (a shard missing,
//! or one that stopped early) is an error naming the first missing case. (Cases missing
//! after the largest id present cannot be seen: check the row count against the sweep.)

use crate::error::{Result, SweepError};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What a merge wrote.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MergeSummary {
    /// Input files.
    pub files: usize,
    /// Rows written.
    pub rows: usize,
}

/// One input: its spec line (if any), its preamble without it, and its rows.
struct Input {
    spec: Option<Vec<u8>>,
    preamble: Vec<u8>,
    rows: Vec<(usize, Vec<u8>)>,
}

fn read_input(path: &Path) -> Result<Input> {
    let bad = |reason: String| SweepError::Merge {
        path: path.to_path_buf(),
        reason,
    };
    let bytes = std::fs::read(path).map_err(SweepError::io("reading", path))?;
    if bytes.last() != Some(&b'\n') {
        return Err(bad(
            "it is empty or its last row is incomplete (finish it by resuming its sweep)".into(),
        ));
    }
    let mut lines = bytes.split_inclusive(|&b| b == b'\n');
    let (mut preamble, mut spec) = (Vec::new(), None);
    let header = loop {
        let line = lines.next().ok_or_else(|| bad("no header row".into()))?;
        if line.starts_with(crate::table::SPEC_LINE.as_bytes()) && spec.is_none() {
            spec = Some(line.to_vec());
            continue;
        }
        preamble.extend_from_slice(line);
        if !line.starts_with(b"#") {
            break line;
        }
    };
    if !(header.starts_with(b"case,") && header.ends_with(b",status,message\n")) {
        return Err(bad(
            "it is not a sweep file (no `case,…,status,message` header)".into(),
        ));
    }
    let rows = lines
        .map(|line| {
            if line.starts_with(crate::run::INCOMPLETE.as_bytes()) {
                return Err(bad(
                    "it is the file of an interrupted sweep (finish it with resume)".into(),
                ));
            }
            let id = line
                .split(|&b| b == b',')
                .next()
                .and_then(|f| std::str::from_utf8(f).ok())
                .and_then(|f| f.parse::<usize>().ok())
                .ok_or_else(|| {
                    bad(format!(
                        "a row without a case id: {}",
                        String::from_utf8_lossy(line).trim_end()
                    ))
                })?;
            Ok((id, line.to_vec()))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Input {
        spec,
        preamble,
        rows,
    })
}

/// The hash of a `# spec: …` line.
fn hash_text(line: &[u8]) -> String {
    String::from_utf8_lossy(&line[crate::table::SPEC_LINE.len()..])
        .trim_end()
        .to_string()
}

/// Merges `inputs` into `out` (a [`tensegrity_io::sink::FileSink`]: locked and opened before
/// the inputs are read, renamed into place at the end).
pub fn merge(inputs: &[PathBuf], out: &Path) -> Result<MergeSummary> {
    // opened first: an unwritable or busy output fails before the inputs are read
    let mut sink = tensegrity_io::sink::FileSink::open(out)?;
    let first = inputs.first().ok_or_else(|| SweepError::Merge {
        path: out.to_path_buf(),
        reason: "no input files".into(),
    })?;
    let mut preamble: Option<Vec<u8>> = None;
    let mut spec: Option<(Vec<u8>, &PathBuf)> = None;
    let mut rows: BTreeMap<usize, Vec<u8>> = BTreeMap::new();
    for path in inputs {
        let input = read_input(path)?;
        let bad = |reason: String| SweepError::Merge {
            path: path.clone(),
            reason,
        };
        match &preamble {
            None => preamble = Some(input.preamble),
            Some(p) if *p != input.preamble => {
                return Err(bad(format!(
                    "its header differs from that of {}",
                    first.display()
                )))
            }
            Some(_) => {}
        }
        match (&spec, input.spec) {
            (Some((s, from)), Some(this)) if *s != this => {
                return Err(bad(format!(
                    "it comes from another spec than {} (spec {} there, {} here)",
                    from.display(),
                    hash_text(s),
                    hash_text(&this)
                )))
            }
            (None, Some(this)) => spec = Some((this, path)),
            _ => {}
        }
        for (id, row) in input.rows {
            match rows.get(&id) {
                Some(other) if *other != row => {
                    return Err(bad(format!(
                        "case {id} is also in another file, with another row"
                    )))
                }
                Some(_) => {}
                None => {
                    rows.insert(id, row);
                }
            }
        }
    }
    if let Some(missing) = rows
        .keys()
        .enumerate()
        .find(|&(i, &id)| i != id)
        .map(|(i, _)| i)
    {
        return Err(SweepError::Merge {
            path: out.to_path_buf(),
            reason: format!(
                "case {missing} is in none of the files (a shard is missing or unfinished)"
            ),
        });
    }
    let mut bytes = preamble.unwrap_or_default();
    for row in rows.values() {
        bytes.extend_from_slice(row);
    }
    sink.write_with(|w| {
        w.write_all(&bytes)
            .map_err(tensegrity_io::IoError::stream("merged CSV"))
    })?;
    sink.finish()?;
    Ok(MergeSummary {
        files: inputs.len(),
        rows: rows.len(),
    })
}
