//! Rank decisions on rounded real data (issue 42, docs/ROBUSTNESS.md "Statics on rounded
//! data"): a form-found structure written with 9 (or 6) significant digits has the
//! self-stresses of the exact one in `statics` on its defaults, as `formfind` reports them for
//! the same form; data taken as exact (`--input-precision 0`) lose it, and data rounded
//! coarser than the judged precision say so in a warning naming `--input-precision`.

use crate::common;
use common::{assert_ok, run, scratch};
use std::path::{Path, PathBuf};

fn json(args: &[&str]) -> serde_json::Value {
    let out = run(args);
    assert_ok(&out);
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The scene `formfind` writes for `topology`, and its report.
fn found(topology: &str, dir: &Path) -> (PathBuf, serde_json::Value) {
    let name = Path::new(topology).file_stem().unwrap().to_str().unwrap();
    let scene = dir.join(format!("{name}.toml"));
    let report = json(&[
        "formfind",
        topology,
        "--out",
        scene.to_str().unwrap(),
        "--analyse",
        "--json",
    ]);
    (scene, report)
}

/// `scene` with every node coordinate rounded to `digits` significant digits.
fn rounded(scene: &Path, digits: usize, dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(scene).unwrap();
    let start = text.find("nodes = [").unwrap();
    let end = start + text[start..].find("\n]").unwrap() + 2;
    let nodes: String = text[start..end]
        .split_inclusive([',', '[', ']'])
        .map(|piece| {
            let (number, rest) = piece.split_at(piece.len() - 1);
            match number.trim().parse::<f64>() {
                Ok(x) => {
                    let r: f64 = format!("{x:.*e}", digits - 1).parse().unwrap();
                    format!(" {r:?}{rest}")
                }
                Err(_) => piece.to_string(),
            }
        })
        .collect();
    let out = dir.join(format!(
        "{}_{digits}.toml",
        scene.file_stem().unwrap().to_str().unwrap()
    ));
    std::fs::write(&out, format!("{}{nodes}{}", &text[..start], &text[end..])).unwrap();
    out
}

fn statics(scene: &Path, extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["statics", scene.to_str().unwrap(), "--json"];
    args.extend_from_slice(extra);
    json(&args)
}

#[test]
fn a_form_written_to_nine_digits_keeps_its_self_stress() {
    let dir = scratch("rank", "nine");
    for topology in [
        "examples/formfind/cable_net.toml",
        "examples/formfind/icosidodecahedron30.toml",
        "examples/formfind/prism5.toml",
        "examples/formfind/tower3.toml",
    ] {
        let (scene, ff) = found(topology, &dir);
        let exact = statics(&scene, &[]);
        assert_eq!(
            exact["self_stress_dim"], ff["self_stress_dim"],
            "{topology}"
        );
        assert_eq!(exact["input_rounding"], 0.0, "{topology}");
        for digits in [9, 6] {
            let r = rounded(&scene, digits, &dir);
            let s = statics(&r, &[]);
            assert_eq!(
                (&s["self_stress_dim"], &s["prestressable"]),
                (&exact["self_stress_dim"], &serde_json::Value::Bool(true)),
                "{topology} at {digits} digits: {s}"
            );
            // the rounding judged from the digits: half a unit of the last one kept
            let e = s["input_rounding"].as_f64().unwrap();
            assert!(e > 0.0 && e <= 0.5 * 10f64.powi(2 - digits as i32), "{e}");
            // the decision is certified: the physical singular value lies below the cut
            assert!(s.get("statics_warning").is_none(), "{s}");
            let gap = &s["spectral_gap"];
            assert!(gap["sigma_below"].as_f64().unwrap() < gap["tolerance"].as_f64().unwrap());
        }
    }
    // the net at nine digits taken as exact: the rounding's singular value (8e-10, far above
    // the arithmetic's search window) counts, and the self-stress is lost, as before the
    // data-aware decision
    let net = rounded(&dir.join("cable_net.toml"), 9, &dir);
    let exact_data = statics(&net, &["--input-precision", "0"]);
    assert_eq!(exact_data["self_stress_dim"], 0);
    assert_eq!(exact_data["input_rounding"], 0.0);
}

#[test]
fn data_rounded_coarser_than_judged_are_flagged_and_counted_with_the_precision_given() {
    let dir = scratch("rank", "coarse");
    let (scene, ff) = found("examples/formfind/cable_net.toml", &dir);
    // four digits are read as typed by hand (exact): the isolated singular value is flagged
    let r = rounded(&scene, 4, &dir);
    let out = run(&["statics", r.to_str().unwrap()]);
    assert_ok(&out);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("one more self-stress") && stderr.contains("--input-precision"),
        "{stderr}"
    );
    let s = statics(&r, &["--input-precision", "1e-4"]);
    assert_eq!(s["self_stress_dim"], ff["self_stress_dim"]);
    assert_eq!(s["prestressable"], true);
    // the precision must be a fraction below 0.1
    for bad in ["-1e-9", "0.5", "nan"] {
        let out = run(&["statics", r.to_str().unwrap(), "--input-precision", bad]);
        assert_eq!(out.status.code(), Some(2), "{bad}");
        assert!(String::from_utf8_lossy(&out.stderr).contains("input-precision"));
    }
}

#[test]
fn hand_typed_and_exact_examples_keep_their_decisions() {
    // the bundled scenes: coordinates typed by hand or computed; nothing moves
    for (scene, dim) in [
        ("examples/prism.toml", 1),
        ("examples/dbar.toml", 1),
        ("examples/tower.toml", 2),
        ("examples/tower200.toml", 200),
    ] {
        let s = json(&["statics", scene, "--json"]);
        assert_eq!(s["self_stress_dim"], dim, "{scene}");
        assert_eq!(s["input_rounding"], 0.0, "{scene}");
    }
}
