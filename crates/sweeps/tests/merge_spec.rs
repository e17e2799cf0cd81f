//! Shards carry the hash of their spec (issue 26): `merge` refuses shards of two specs that
//! share a header, `resume` refuses a shard of another spec, and files without the line (a
//! single run's, or an older version's shards) merge and resume as before.

use std::path::{Path, PathBuf};
use sweeps::table::{spec_hash, spec_line, SPEC_LINE};
use sweeps::{merge, run, RunOptions, Shard, Silent, Spec};

/// Cheap cases (a closed form); the variant B differs only in a fixed value, so both write
/// the same header.
const A: &str = r#"
study = "tipover"
[fixed]
outer_radius = 1.0
[axes]
sides = [6, 8]
sigma = [0.2, 0.4]
"#;

fn b() -> Spec {
    Spec::parse(&A.replace("outer_radius = 1.0", "outer_radius = 2.0")).unwrap()
}

fn shard(spec: &Spec, out: &Path, k: usize, n: usize) -> PathBuf {
    let opts = RunOptions {
        shard: Shard { index: k, count: n },
        threads: Some(1),
        ..Default::default()
    };
    run(spec, out, &opts, &mut Silent).unwrap();
    out.to_path_buf()
}

/// The file without its first line.
fn strip_first_line(path: &Path) {
    let text = std::fs::read_to_string(path).unwrap();
    let (_, rest) = text.split_once('\n').unwrap();
    std::fs::write(path, rest).unwrap();
}

#[test]
fn the_hash_is_of_the_content_not_the_text() {
    let a = Spec::parse(A).unwrap();
    let reformatted = Spec::parse(&format!("# a comment\n{}", A.replace(" = ", "="))).unwrap();
    assert_eq!(spec_hash(&a), spec_hash(&reformatted));
    assert_ne!(spec_hash(&a), spec_hash(&b()));
    let line = String::from_utf8(spec_line(&a)).unwrap();
    assert_eq!(line, format!("{SPEC_LINE}{:016x}\n", spec_hash(&a)));
}

#[test]
fn merge_refuses_shards_of_two_specs_sharing_a_header() {
    let dir = tempfile::tempdir().unwrap();
    let a = Spec::parse(A).unwrap();
    let single = dir.path().join("single.csv");
    run(&a, &single, &RunOptions::default(), &mut Silent).unwrap();
    let single_text = std::fs::read_to_string(&single).unwrap();
    assert!(
        single_text.starts_with("case,"),
        "a single run has no spec line"
    );
    let a1 = shard(&a, &dir.path().join("a1.csv"), 0, 2);
    let a2 = shard(&a, &dir.path().join("a2.csv"), 1, 2);
    let b2 = shard(&b(), &dir.path().join("b2.csv"), 1, 2);
    let first = std::fs::read_to_string(&a1).unwrap();
    assert!(first.starts_with(&format!("{SPEC_LINE}{:016x}\ncase,", spec_hash(&a))));
    // same header, other spec: refused, naming both files and both hashes
    let out = dir.path().join("m.csv");
    let e = merge(&[a1.clone(), b2.clone()], &out)
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        format!(
            "cannot merge {}: it comes from another spec than {} (spec {:016x} there, {:016x} here)",
            b2.display(),
            a1.display(),
            spec_hash(&a),
            spec_hash(&b())
        )
    );
    assert!(!out.exists());
    // the shards of one spec merge into the single run's bytes (no spec line)
    merge(&[a2.clone(), a1.clone()], &out).unwrap();
    assert_eq!(std::fs::read_to_string(&out).unwrap(), single_text);
    // files without the line (older shards) merge as before
    strip_first_line(&a1);
    strip_first_line(&a2);
    let out2 = dir.path().join("m2.csv");
    merge(&[a1, a2], &out2).unwrap();
    assert_eq!(std::fs::read_to_string(&out2).unwrap(), single_text);
}

#[test]
fn resume_refuses_a_shard_of_another_spec_and_continues_an_old_shard() {
    let dir = tempfile::tempdir().unwrap();
    let a = Spec::parse(A).unwrap();
    let want = std::fs::read_to_string(shard(&a, &dir.path().join("want.csv"), 0, 2)).unwrap();
    let path = shard(&b(), &dir.path().join("s.csv"), 0, 2);
    let opts = RunOptions {
        shard: Shard { index: 0, count: 2 },
        resume: true,
        threads: Some(1),
        ..Default::default()
    };
    let e = run(&a, &path, &opts, &mut Silent).unwrap_err().to_string();
    assert!(e.contains("a shard of another spec"), "{e}");
    // an old shard (no spec line), cut after its first row, is continued as it is
    let old: String = want.split_inclusive('\n').skip(1).take(2).collect();
    std::fs::write(&path, &old).unwrap();
    let s = run(&a, &path, &opts, &mut Silent).unwrap();
    assert_eq!((s.resumed, s.written), (1, 1));
    let (_, rest) = want.split_once('\n').unwrap();
    assert_eq!(std::fs::read_to_string(&path).unwrap(), rest);
}
