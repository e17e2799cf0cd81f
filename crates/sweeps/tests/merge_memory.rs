//! `sweep merge` holds a row per input, not its files (issue 26): the peak resident memory of
//! a 40 MB merge of four strided shards (Linux: the kernel's high-water mark of this test
//! process, /proc/self/status, reset through clear_refs) stays far below the size of its
//! inputs. Alone in its test binary, so no other test's allocations count.

use crate::shards;

use shards::{row, shard, HEADER};
use std::path::PathBuf;
use sweeps::merge;

/// A field of /proc/self/status in bytes (`VmRSS`, `VmHWM`).
fn status(key: &str) -> f64 {
    let text = std::fs::read_to_string("/proc/self/status").unwrap();
    let line = text.lines().find(|l| l.starts_with(key)).unwrap();
    let kb: f64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    1024.0 * kb
}

#[test]
fn a_merge_holds_a_row_per_input_not_the_files() {
    if std::fs::write("/proc/self/clear_refs", "5").is_err() {
        eprintln!("note: /proc/self/clear_refs is not writable here; the measurement is skipped");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    // 4 shards of 2 million cases: ~40 MB of rows
    let total = 2_000_000;
    let parts: Vec<PathBuf> = (0..4).map(|k| shard(dir.path(), k, 4, total)).collect();
    let bytes: u64 = parts
        .iter()
        .map(|p| std::fs::metadata(p).unwrap().len())
        .sum();
    let out = dir.path().join("merged.csv");
    std::fs::write("/proc/self/clear_refs", "5").unwrap();
    let before = status("VmRSS");
    let s = merge(&parts, &out).unwrap();
    let peak = status("VmHWM") - before;
    eprintln!("merged {bytes} B with a peak of {peak:.3e} B above the resident set");
    assert_eq!(s.rows, total);
    let want: usize = HEADER.len() + (0..total).map(|id| row(id).len()).sum::<usize>();
    assert_eq!(std::fs::metadata(&out).unwrap().len() as usize, want);
    assert!(bytes > 30_000_000, "{bytes}");
    // reading the inputs whole would hold ~40 MB (and the rows again in a map)
    assert!(peak < 4e6, "a peak of {peak} B for {bytes} B of input");
}
