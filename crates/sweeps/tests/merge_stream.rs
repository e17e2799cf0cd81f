//! `sweep merge` streams (issue 26): shards are read a row at a time and merged by case id,
//! so merging files far larger than memory holds only a row per input. Tested: the merged
//! bytes of strided shards (as `--shard K/N` writes them), the refusals that streaming adds
//! (rows out of case order, a row over the length limit) and keeps (a case twice with other
//! rows, a gap, an interrupted file, a file cut inside a row, two specs), each naming the
//! file. (The memory a merge holds: `merge_memory.rs`.)

use crate::shards;

use shards::{row, shard, HEADER};
use std::path::{Path, PathBuf};
use sweeps::merge;
use sweeps::merge::MAX_ROW_BYTES;

fn single(total: usize) -> String {
    let mut text = HEADER.to_string();
    for id in 0..total {
        text += &row(id);
    }
    text
}

fn merge_err(inputs: &[PathBuf], out: &Path) -> String {
    let e = merge(inputs, out).unwrap_err().to_string();
    assert!(!out.exists(), "no output after an error: {e}");
    e
}

#[test]
fn strided_shards_merge_into_the_single_run_in_any_order() {
    let dir = tempfile::tempdir().unwrap();
    let total = 1000;
    let mut parts: Vec<PathBuf> = (0..7).map(|k| shard(dir.path(), k, 7, total)).collect();
    parts.swap(0, 5);
    let out = dir.path().join("merged.csv");
    let s = merge(&parts, &out).unwrap();
    assert_eq!((s.files, s.rows), (7, total));
    assert_eq!(std::fs::read_to_string(&out).unwrap(), single(total));
    // the same file given twice: every case twice with the same row, merged once
    let twice = dir.path().join("twice.csv");
    parts.push(parts[0].clone());
    assert_eq!(merge(&parts, &twice).unwrap().rows, total);
    assert_eq!(std::fs::read_to_string(&twice).unwrap(), single(total));
}

#[test]
fn streaming_refusals_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("m.csv");
    let a = shard(dir.path(), 0, 2, 20);
    let b = shard(dir.path(), 1, 2, 20);
    // rows out of case order
    let text = std::fs::read_to_string(&b).unwrap();
    let swapped = text
        .replace(&row(3), "X")
        .replace(&row(5), &row(3))
        .replace('X', &row(5));
    let unordered = dir.path().join("unordered.csv");
    std::fs::write(&unordered, swapped).unwrap();
    let e = merge_err(&[a.clone(), unordered.clone()], &out);
    assert_eq!(
        e,
        format!(
            "cannot merge {}: its rows are not in case order (case 3 after case 5)",
            unordered.display()
        )
    );
    // a case in two files with other rows
    let other = dir.path().join("other.csv");
    std::fs::write(&other, text.replace(&row(7), "7,1.0,ok,\n")).unwrap();
    let e = merge_err(&[a.clone(), b.clone(), other.clone()], &out);
    assert_eq!(
        e,
        format!(
            "cannot merge {}: case 7 is also in another file, with another row",
            other.display()
        )
    );
    // a gap (the second shard missing)
    let e = merge_err(std::slice::from_ref(&a), &out);
    assert!(e.contains("case 1 is in none of the files"), "{e}");
    // a file cut inside a row, and an interrupted one
    let cut = dir.path().join("cut.csv");
    std::fs::write(&cut, &text[..text.len() - 3]).unwrap();
    let e = merge_err(&[a.clone(), cut.clone()], &out);
    assert!(
        e.contains(&cut.display().to_string()) && e.contains("last row is incomplete"),
        "{e}"
    );
    let stopped = dir.path().join("stopped.csv");
    std::fs::write(
        &stopped,
        format!("{text}# incomplete: interrupted after 10 of 20 cases\n"),
    )
    .unwrap();
    let e = merge_err(&[a.clone(), stopped.clone()], &out);
    assert!(
        e.contains(&stopped.display().to_string()) && e.contains("interrupted sweep"),
        "{e}"
    );
    // a row over the length limit
    let long = dir.path().join("long.csv");
    let huge = "y".repeat(MAX_ROW_BYTES as usize + 10);
    std::fs::write(&long, format!("{HEADER}0,{huge},ok,\n")).unwrap();
    let e = merge_err(std::slice::from_ref(&long), &out);
    assert_eq!(
        e,
        format!(
            "cannot merge {}: a row is longer than 16 MiB",
            long.display()
        )
    );
    // another spec's shard (same header)
    let spec_b = dir.path().join("spec_b.csv");
    std::fs::write(
        &spec_b,
        text.replace("00000000000000aa", "00000000000000bb"),
    )
    .unwrap();
    let e = merge_err(&[a.clone(), spec_b.clone()], &out);
    assert!(
        e.contains("another spec") && e.contains("00000000000000aa there, 00000000000000bb here"),
        "{e}"
    );
    // and the good pair still merges
    merge(&[b, a], &out).unwrap();
    assert_eq!(std::fs::read_to_string(&out).unwrap(), single(20));
}
