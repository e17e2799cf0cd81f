//! The arrays of the VTK output, with their units in their names, against the other outputs
//! of the same run: `simulate --vtk` of the dropped prism (contact recorded) carries the
//! ground's force on every node as `contact_force [N]`, equal at every frame to the CSV's
//! `c{node}_x|y|z [N]` columns (zero at the nodes off the ground); `tbar --vtk` carries the
//! minimum-prestress member forces of its `--json` report as `force [N]`.

use crate::common;

/// The numbers of the `DataArray` named `name` in a `.vtu` (empty when absent).
fn array(vtu: &str, name: &str) -> Vec<f64> {
    let doc = roxmltree::Document::parse(vtu).unwrap();
    doc.descendants()
        .find(|n| n.has_tag_name("DataArray") && n.attribute("Name") == Some(name))
        .map(|n| {
            n.text()
                .unwrap_or("")
                .split_whitespace()
                .map(|t| t.parse().unwrap())
                .collect()
        })
        .unwrap_or_default()
}

#[test]
fn contact_forces_in_the_vtk_equal_the_csv() {
    let dir = common::scratch("vtk-arrays", "drop");
    let csv = dir.join("drop.csv");
    let vtk = dir.join("vtk");
    let out = common::run(&[
        "simulate",
        "examples/prism_drop.toml",
        "--t-end",
        "1.0",
        "--output-interval",
        "0.1",
        "--out",
        csv.to_str().unwrap(),
        "--vtk",
        vtk.to_str().unwrap(),
    ]);
    common::assert_ok(&out);
    let mut rows = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(&csv)
        .unwrap();
    let header: Vec<String> = rows.headers().unwrap().iter().map(String::from).collect();
    let rows: Vec<Vec<f64>> = rows
        .records()
        .map(|r| r.unwrap().iter().map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 11);
    let mut touched = 0;
    for (k, row) in rows.iter().enumerate() {
        let vtu = std::fs::read_to_string(vtk.join(format!("frame_{k:05}.vtu"))).unwrap();
        let f = array(&vtu, "contact_force [N]");
        let nodes = f.len() / 3;
        assert_eq!(nodes, 6, "frame {k}: one force per node");
        for node in 0..nodes {
            for (axis, c) in ["x", "y", "z"].iter().enumerate() {
                let column = format!("c{node}_{c} [N]");
                // a node the ground cannot touch has no column: its force is zero
                let want = header
                    .iter()
                    .position(|h| *h == column)
                    .map_or(0.0, |i| row[i]);
                assert_eq!(f[3 * node + axis], want, "frame {k}, {column}");
            }
            touched += usize::from(f[3 * node + 2] > 0.0);
        }
    }
    // the prism lands at ~0.65 s: the later frames have the ground pushing up
    assert!(touched > 0);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn tbar_vtk_carries_the_prestress_forces_of_its_report() {
    let dir = common::scratch("vtk-arrays", "tbar");
    let vtu = dir.join("tbar.vtu");
    let out = common::run(&[
        "tbar",
        "--beta",
        "pi/6",
        "--phi",
        "pi/8",
        "--cylindrical",
        "0.25",
        "--json",
        "--vtk",
        vtu.to_str().unwrap(),
    ]);
    common::assert_ok(&out);
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let want: Vec<f64> = report["prestress_force"]
        .as_array()
        .expect("a prestressable tread has a prestress")
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let text = std::fs::read_to_string(&vtu).unwrap();
    let got = array(&text, "force [N]");
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(&want) {
        assert!((g - w).abs() <= 1e-12 * w.abs().max(1.0), "{g} vs {w}");
    }
    // bars in compression, strings in tension
    let bars = report["bars"].as_u64().unwrap() as usize;
    assert!(got[..bars].iter().all(|&f| f <= 0.0) && got[bars..].iter().all(|&f| f >= 0.0));
    let _ = std::fs::remove_dir_all(&dir);
}
