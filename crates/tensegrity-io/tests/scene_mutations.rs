//! Fuzzing the scene reader from the bundled scenes (issue 26): every `examples/*.toml` with a
//! few random bytes overwritten, inserted or deleted — any byte, so also text that is not
//! UTF-8 — is read through the file path the commands use: the scene is accepted (and then
//! building its simulation gives a simulation or an error), or refused with an error naming
//! the file; never a panic. 512 cases, well under a second.

use proptest::prelude::*;
use std::path::PathBuf;
use tensegrity_io::scene::Scene;

fn examples() -> Vec<(String, Vec<u8>)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 7, "{files:?}");
    files
        .into_iter()
        .map(|p| (p.display().to_string(), std::fs::read(&p).unwrap()))
        .collect()
}

/// One edit at a fraction of the text's length: overwrite, insert or delete a byte.
#[derive(Debug, Clone)]
enum Edit {
    Set(f64, u8),
    Insert(f64, u8),
    Delete(f64),
}

fn edit() -> impl Strategy<Value = Edit> {
    // bytes that matter to TOML more often than uniform bytes would
    let byte = prop_oneof![
        any::<u8>(),
        prop::sample::select(b"[]{}=,.\"'#\n-+0123456789eE_ \t".to_vec()),
    ];
    prop_oneof![
        (0.0..1.0f64, byte.clone()).prop_map(|(at, b)| Edit::Set(at, b)),
        (0.0..1.0f64, byte).prop_map(|(at, b)| Edit::Insert(at, b)),
        (0.0..1.0f64).prop_map(Edit::Delete),
    ]
}

fn apply(bytes: &mut Vec<u8>, e: &Edit) {
    let at = |f: f64, len: usize| ((f * len as f64) as usize).min(len.saturating_sub(1));
    match *e {
        Edit::Set(f, b) if !bytes.is_empty() => {
            let i = at(f, bytes.len());
            bytes[i] = b;
        }
        Edit::Insert(f, b) => {
            let i = at(f, bytes.len() + 1);
            bytes.insert(i, b);
        }
        Edit::Delete(f) if !bytes.is_empty() => {
            let i = at(f, bytes.len());
            bytes.remove(i);
        }
        _ => {}
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn a_mutated_example_scene_is_read_or_refused_naming_the_file(
        which in 0usize..64, edits in prop::collection::vec(edit(), 1..6)
    ) {
        let all = examples();
        let (name, original) = &all[which % all.len()];
        let mut bytes = original.clone();
        for e in &edits {
            apply(&mut bytes, e);
        }
        let dir = tempfile_dir();
        let path = dir.join(std::path::Path::new(name).file_name().unwrap());
        std::fs::write(&path, &bytes).unwrap();
        match Scene::from_path(&path) {
            Ok(scene) => {
                let _ = scene.simulation();
            }
            Err(e) => {
                let msg = e.to_string();
                prop_assert!(msg.contains(&path.display().to_string()), "{msg}");
            }
        }
        std::fs::remove_file(&path).unwrap();
    }
}

/// A directory for this test binary's files.
fn tempfile_dir() -> PathBuf {
    let dir = std::env::temp_dir().join(format!("scene-mutations-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
