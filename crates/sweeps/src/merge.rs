//! `tensegrity sweep merge`: shard files (or any files of the same sweep) combined into the
//! file a single run writes.
//!
//! Every input must have the same preamble (units line and header) and end with a complete
//! row; inputs with a `# spec: …` line (the files of shards, [`crate::table::spec_hash`])
//! must have the same one, so shards of two specs that share a header are refused (a file
//! without the line — a single run's, or a shard written by an older version — is checked by
//! its header only, as before). The merged file leaves the spec line out; rows are keyed by
//! their `case` id and written in id order, each exactly as it is in its input, so merging the
//! shards `1/N … N/N` of a sweep gives byte for byte the file of one run. A case found twice
//! must have identical rows; a gap in the ids (a shard missing, or one that stopped early) is
//! an error naming the first missing case. (Cases missing after the largest id present cannot
//! be seen: check the row count against the sweep.)
//!
//! The merge streams: every input is read a row at a time, in case order (a sweep writes its
//! rows in that order), and the inputs are merged like sorted lists — the smallest pending id
//! next — so its memory is one row per input, whatever the size of the files. A row longer
//! than [`MAX_ROW_BYTES`] is refused, and so is a file whose rows are out of case order.

use crate::error::{Result, SweepError};
use std::cmp::Reverse;
use std::collections::BinaryHeap;
use std::fs::File;
use std::io::{BufRead, BufReader, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};

/// The longest row (or preamble line) a merge reads: 16 MiB.
pub const MAX_ROW_BYTES: u64 = 16 << 20;
/// The bytes at the end of an input read to check its last line (the interrupted trailer).
const TAIL_BYTES: u64 = 4096;

/// What a merge wrote.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MergeSummary {
    /// Input files.
    pub files: usize,
    /// Rows written.
    pub rows: usize,
}

/// One input being read: its spec line (if any), its preamble without it, and its next row.
struct Input<'a> {
    path: &'a PathBuf,
    reader: BufReader<File>,
    spec: Option<Vec<u8>>,
    preamble: Vec<u8>,
    /// The id of the row read last (rows come in case order).
    last: Option<usize>,
}

fn bad(path: &Path, reason: impl Into<String>) -> SweepError {
    SweepError::Merge {
        path: path.to_path_buf(),
        reason: reason.into(),
    }
}

/// Refuses an input that is empty, ends inside a row, or ends with the trailer of an
/// interrupted sweep, from its last bytes alone (before anything is merged).
fn check_tail(file: &mut File, path: &Path) -> Result<()> {
    let io = |source| SweepError::Io {
        what: "reading",
        path: path.to_path_buf(),
        source,
    };
    let len = file.seek(SeekFrom::End(0)).map_err(&io)?;
    let start = len.saturating_sub(TAIL_BYTES);
    file.seek(SeekFrom::Start(start)).map_err(&io)?;
    let mut tail = Vec::new();
    file.read_to_end(&mut tail).map_err(&io)?;
    file.seek(SeekFrom::Start(0)).map_err(&io)?;
    if tail.last() != Some(&b'\n') {
        return Err(bad(
            path,
            "it is empty or its last row is incomplete (finish it by resuming its sweep)",
        ));
    }
    let body = &tail[..tail.len() - 1];
    let last_line = &body[body.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1)..];
    if last_line.starts_with(crate::table::INCOMPLETE.as_bytes()) {
        return Err(interrupted(path));
    }
    Ok(())
}

fn interrupted(path: &Path) -> SweepError {
    bad(
        path,
        "it is the file of an interrupted sweep (finish it with resume)",
    )
}

impl<'a> Input<'a> {
    /// Opens `path` and reads its preamble (up to and including the header row).
    fn open(path: &'a PathBuf) -> Result<Self> {
        let mut file = File::open(path).map_err(SweepError::io("reading", path))?;
        check_tail(&mut file, path)?;
        let mut input = Input {
            path,
            reader: BufReader::new(file),
            spec: None,
            preamble: Vec::new(),
            last: None,
        };
        let header = loop {
            let line = input.line()?.ok_or_else(|| bad(path, "no header row"))?;
            if line.starts_with(crate::table::SPEC_LINE.as_bytes()) && input.spec.is_none() {
                input.spec = Some(line);
                continue;
            }
            input.preamble.extend_from_slice(&line);
            if !line.starts_with(b"#") {
                break line;
            }
        };
        if !(header.starts_with(b"case,") && header.ends_with(b",status,message\n")) {
            return Err(bad(
                path,
                "it is not a sweep file (no `case,…,status,message` header)",
            ));
        }
        Ok(input)
    }

    /// The next line with its line break (`None` at the end), at most [`MAX_ROW_BYTES`].
    fn line(&mut self) -> Result<Option<Vec<u8>>> {
        let mut line = Vec::new();
        (&mut self.reader)
            .take(MAX_ROW_BYTES + 1)
            .read_until(b'\n', &mut line)
            .map_err(SweepError::io("reading", self.path))?;
        if line.len() as u64 > MAX_ROW_BYTES {
            return Err(bad(
                self.path,
                format!("a row is longer than {} MiB", MAX_ROW_BYTES >> 20),
            ));
        }
        if line.is_empty() {
            return Ok(None);
        }
        if line.last() != Some(&b'\n') {
            // the file grew or was cut while it was read
            return Err(bad(
                self.path,
                "it is empty or its last row is incomplete (finish it by resuming its sweep)",
            ));
        }
        Ok(Some(line))
    }

    /// The next row and its case id (`None` at the end of the file).
    fn row(&mut self) -> Result<Option<(usize, Vec<u8>)>> {
        let Some(line) = self.line()? else {
            return Ok(None);
        };
        if line.starts_with(crate::table::INCOMPLETE.as_bytes()) {
            return Err(interrupted(self.path));
        }
        let id = line
            .split(|&b| b == b',')
            .next()
            .and_then(|f| std::str::from_utf8(f).ok())
            .and_then(|f| f.parse::<usize>().ok())
            .ok_or_else(|| {
                bad(
                    self.path,
                    format!(
                        "a row without a case id: {}",
                        String::from_utf8_lossy(&line).trim_end()
                    ),
                )
            })?;
        if let Some(last) = self.last.filter(|&last| id < last) {
            return Err(bad(
                self.path,
                format!("its rows are not in case order (case {id} after case {last})"),
            ));
        }
        self.last = Some(id);
        Ok(Some((id, line)))
    }
}

/// The hash of a `# spec: …` line.
fn hash_text(line: &[u8]) -> String {
    String::from_utf8_lossy(&line[crate::table::SPEC_LINE.len()..])
        .trim_end()
        .to_string()
}

/// Opens every input and checks that their preambles and spec lines agree.
fn open_all(inputs: &[PathBuf]) -> Result<Vec<Input<'_>>> {
    let mut opened: Vec<Input<'_>> = Vec::with_capacity(inputs.len());
    let mut spec: Option<usize> = None;
    for path in inputs {
        let input = Input::open(path)?;
        if let Some(first) = opened.first() {
            if first.preamble != input.preamble {
                return Err(bad(
                    path,
                    format!("its header differs from that of {}", first.path.display()),
                ));
            }
        }
        match (spec.map(|k| &opened[k]), &input.spec) {
            (Some(from), Some(this)) if from.spec.as_ref() != Some(this) => {
                let there = from.spec.as_deref().unwrap_or_default();
                return Err(bad(
                    path,
                    format!(
                        "it comes from another spec than {} (spec {} there, {} here)",
                        from.path.display(),
                        hash_text(there),
                        hash_text(this)
                    ),
                ));
            }
            (None, Some(_)) => spec = Some(opened.len()),
            _ => {}
        }
        opened.push(input);
    }
    Ok(opened)
}

/// Merges `inputs` into `out` (a [`tensegrity_io::sink::FileSink`]: locked and opened before
/// the inputs are read, renamed into place at the end; on an error it is not written).
pub fn merge(inputs: &[PathBuf], out: &Path) -> Result<MergeSummary> {
    // opened first: an unwritable or busy output fails before the inputs are read
    let mut sink = tensegrity_io::sink::FileSink::open(out)?;
    if inputs.is_empty() {
        return Err(bad(out, "no input files"));
    }
    let mut opened = open_all(inputs)?;
    let write = |sink: &mut tensegrity_io::sink::FileSink, bytes: &[u8]| -> Result<()> {
        sink.write_with(|w| {
            w.write_all(bytes)
                .map_err(tensegrity_io::IoError::stream("merged CSV"))
        })?;
        Ok(())
    };
    write(&mut sink, &opened[0].preamble)?;
    // the next row of every input, smallest id first (ties: the earlier input first)
    let mut pending: Vec<Option<Vec<u8>>> = vec![None; opened.len()];
    let mut heap = BinaryHeap::new();
    for (k, input) in opened.iter_mut().enumerate() {
        if let Some((id, row)) = input.row()? {
            pending[k] = Some(row);
            heap.push(Reverse((id, k)));
        }
    }
    let (mut next, mut last_row) = (0usize, Vec::new());
    while let Some(Reverse((id, k))) = heap.pop() {
        let row = pending[k].take().unwrap_or_default();
        if id + 1 == next {
            // a case already written: the same row, or an error
            if row != last_row {
                return Err(bad(
                    inputs[k].as_path(),
                    format!("case {id} is also in another file, with another row"),
                ));
            }
        } else if id != next {
            // a gap, unless a file further on is out of order or unfinished: read them all
            for input in &mut opened {
                while input.row()?.is_some() {}
            }
            return Err(bad(
                out,
                format!("case {next} is in none of the files (a shard is missing or unfinished)"),
            ));
        } else {
            write(&mut sink, &row)?;
            next = id + 1;
            last_row = row;
        }
        if let Some((id, row)) = opened[k].row()? {
            pending[k] = Some(row);
            heap.push(Reverse((id, k)));
        }
    }
    sink.finish()?;
    Ok(MergeSummary {
        files: inputs.len(),
        rows: next,
    })
}
