//! Resuming a sweep's file (`resume` of [`crate::run::RunOptions`]): the file checked against
//! the spec (its preamble, every complete row's id, axis values and width), cut after its
//! last complete row and opened for appending.

use crate::error::{Result, SweepError};
use crate::shard::Shard;
use crate::spec::Spec;
use crate::table::{self, INCOMPLETE};
use std::fs::File;
use std::io::{BufRead, BufReader, Read, Seek, Write};
use std::path::Path;

/// Checks an existing file against the spec and returns it, cut after its last complete
/// row and opened for appending, with the number of complete rows. `preambles`: the one
/// this run writes, and the one an older version wrote (a shard's file without its spec
/// line, which is continued as it is).
pub(crate) fn resume(
    spec: &Spec,
    out: &Path,
    preambles: [&[u8]; 2],
    shard: Shard,
) -> Result<(File, usize)> {
    let [preamble, legacy] = preambles;
    let bad = |reason: String| SweepError::Resume {
        path: out.to_path_buf(),
        reason,
    };
    let mut file = File::options()
        .read(true)
        .write(true)
        .open(out)
        .map_err(SweepError::io("opening", out))?;
    let mut head = Vec::new();
    (&mut file)
        .take(preamble.len() as u64)
        .read_to_end(&mut head)
        .map_err(SweepError::io("reading", out))?;
    if head.len() < preamble.len() && preamble.starts_with(&head) {
        // killed while the header was written: start anew
        file.set_len(0).map_err(SweepError::io("truncating", out))?;
        file.rewind().map_err(SweepError::io("writing", out))?;
        file.write_all(preamble)
            .map_err(SweepError::io("writing", out))?;
        return Ok((file, 0));
    }
    let start = if head == preamble {
        preamble.len()
    } else if legacy != preamble && head.starts_with(legacy) {
        file.seek(std::io::SeekFrom::Start(legacy.len() as u64))
            .map_err(SweepError::io("reading", out))?;
        legacy.len()
    } else if head.starts_with(table::SPEC_LINE.as_bytes())
        && preamble.starts_with(table::SPEC_LINE.as_bytes())
        && first_line(&head) != first_line(preamble)
    {
        return Err(bad(
            "it is a shard of another spec (its `# spec:` line differs from this spec's)".into(),
        ));
    } else {
        return Err(bad(
            "its header is not the one this spec writes (another spec, or `units` differs)".into(),
        ));
    };
    let mut reader = BufReader::new(&file);
    let (mut end, mut rows, mut line) = (start as u64, 0usize, Vec::new());
    let total = spec.case_count()?;
    let width = table::header(spec).len();
    loop {
        line.clear();
        let n = reader
            .read_until(b'\n', &mut line)
            .map_err(SweepError::io("reading", out))?;
        if n == 0 || line.last() != Some(&b'\n') || line.starts_with(INCOMPLETE.as_bytes()) {
            break; // end of file, a partial last line, or an interrupted run's trailer: redone
        }
        if rows >= shard.len(total) {
            return Err(bad(format!(
                "it has more rows than the {} cases of this shard",
                shard.len(total)
            )));
        }
        let id = shard.id(rows);
        check_row(spec, &line, id, width)
            .map_err(|reason| bad(format!("row of case {id}: {reason}")))?;
        end += n as u64;
        rows += 1;
    }
    drop(reader);
    file.set_len(end)
        .map_err(SweepError::io("truncating", out))?;
    file.seek(std::io::SeekFrom::End(0))
        .map_err(SweepError::io("writing", out))?;
    Ok((file, rows))
}

/// The bytes up to and with the first `\n`.
fn first_line(bytes: &[u8]) -> &[u8] {
    bytes
        .split_inclusive(|&b| b == b'\n')
        .next()
        .unwrap_or(bytes)
}

/// Checks that a complete line is the row of case `id`: its id, axis values and width.
fn check_row(spec: &Spec, line: &[u8], id: usize, width: usize) -> std::result::Result<(), String> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(line);
    let mut rec = csv::StringRecord::new();
    match reader.read_record(&mut rec) {
        Ok(true) => {}
        _ => return Err("not a CSV record".into()),
    }
    if rec.len() != width {
        return Err(format!("{} fields, the header has {width}", rec.len()));
    }
    if rec.get(0) != Some(id.to_string().as_str()) {
        return Err(format!("found case `{}`", rec.get(0).unwrap_or("")));
    }
    let texts = spec.axis_texts(id);
    if rec
        .iter()
        .skip(1)
        .take(texts.len())
        .ne(texts.iter().map(String::as_str))
    {
        return Err("its axis values are not this spec's".into());
    }
    Ok(())
}
