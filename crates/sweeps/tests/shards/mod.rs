//! Shard files of a made-up sweep, shared by the merge tests (`merge_stream.rs`,
//! `merge_memory.rs`): one column `x` = √case, a spec line, the header with units.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

/// The units comment and header of every shard.
pub const HEADER: &str = "# units: case, x [m], status, message\ncase,x,status,message\n";

/// The row of case `id`.
pub fn row(id: usize) -> String {
    format!("{id},{:.6},ok,\n", (id as f64).sqrt())
}

/// Shard `k` of `n` of a sweep of `total` cases (`--shard k+1/n`: ids k, k + n, …), with a
/// spec line, written to `dir`.
pub fn shard(dir: &Path, k: usize, n: usize, total: usize) -> PathBuf {
    let path = dir.join(format!("s{k}of{n}.csv"));
    let mut text = format!("# spec: 00000000000000aa\n{HEADER}");
    for id in (k..total).step_by(n) {
        text += &row(id);
    }
    std::fs::write(&path, text).unwrap();
    path
}
