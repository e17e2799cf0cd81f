//! Sweeps of form-finding parameters through `tensegrity sweep` (issue 23): the example
//! specs `examples/sweeps/formfind_prism_n.toml` (the prism's N) and
//! `examples/sweeps/formfind_net_ratio.toml` (a force-density ratio of Schek's cable net),
//! each run to a CSV whose rows are checked against what the forms must give.

use crate::common;

/// Runs a spec to a CSV; its header and rows.
fn sweep(spec: &str, name: &str) -> (csv::StringRecord, Vec<csv::StringRecord>) {
    let out = common::scratch("formfind-sweeps", name).join("out.csv");
    let args = ["sweep", spec, "--out", out.to_str().unwrap(), "--quiet"];
    common::assert_ok(&common::run(&args));
    let mut reader = csv::Reader::from_path(&out).unwrap();
    let header = reader.headers().unwrap().clone();
    let rows = reader.records().map(Result::unwrap).collect();
    (header, rows)
}

fn column(header: &csv::StringRecord, name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name || h.starts_with(&format!("{name} [")))
        .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
}

#[test]
fn the_prism_sweep_finds_every_n_from_3_to_12() {
    let (h, rows) = sweep("examples/sweeps/formfind_prism_n.toml", "prism");
    assert_eq!(rows.len(), 10);
    let (n, nodes, status) = (column(&h, "n"), column(&h, "n_nodes"), column(&h, "status"));
    let (s, p, stable) = (
        column(&h, "self_stress_dim"),
        column(&h, "prestressable"),
        column(&h, "prestress_stable"),
    );
    let (residual, height, bar) = (
        column(&h, "residual"),
        column(&h, "height"),
        column(&h, "max_bar_length"),
    );
    for (row, want) in rows.iter().zip(3..) {
        assert_eq!(&row[status], "ok", "{row:?}");
        assert_eq!(row[n].parse::<usize>().unwrap(), want);
        assert_eq!(row[nodes].parse::<usize>().unwrap(), 2 * want);
        assert_eq!(
            (&row[s], &row[p], &row[stable]),
            ("1", "true", "true"),
            "{row:?}"
        );
        assert!(row[residual].parse::<f64>().unwrap() < 1e-12, "{row:?}");
        // the built-in's positions fix the affine freedom: unit rings at z = 0 and 1, the top
        // turned by π/2 + π/N, so a bar spans √(1 + 2 − 2 cos(π/2 + π/N)) = √(3 + 2 sin(π/N))
        let (h, l) = (
            row[height].parse::<f64>().unwrap(),
            row[bar].parse::<f64>().unwrap(),
        );
        let want = (3.0 + 2.0 * (std::f64::consts::PI / want as f64).sin()).sqrt();
        assert!(
            (h - 1.0).abs() < 1e-12 && (l - want).abs() < 1e-12,
            "{row:?}: {l} vs {want}"
        );
    }
}

#[test]
fn the_net_sweep_varies_a_force_density_ratio() {
    let (h, rows) = sweep("examples/sweeps/formfind_net_ratio.toml", "net");
    assert_eq!(rows.len(), 9);
    let (ratio, height, status) = (
        column(&h, "ratio"),
        column(&h, "height"),
        column(&h, "status"),
    );
    let mut heights = Vec::new();
    for row in &rows {
        assert_eq!(&row[status], "ok", "{row:?}");
        heights.push((
            row[ratio].parse::<f64>().unwrap(),
            row[height].parse::<f64>().unwrap(),
        ));
    }
    // q_y = 2 ratio, q_x = 1: at ratio ½ both are 1 and the net is the discrete hyperbolic
    // paraboloid z = ((u − 2)² − (v − 2)²)/4 of its boundary (harmonic: each inner node at
    // the mean of its four neighbours), whose inner nodes span z = −¼…¼
    let half = heights.iter().find(|(r, _)| *r == 0.5).unwrap().1;
    assert!((half - 0.5).abs() < 1e-12, "{half}");
    // swapping x and y with z → −z maps the boundary onto itself: the net at q_y/q_x = t is
    // the mirror of the net at 1/t (ratio r ↔ 1/(4r)), of the same extent, and the extent is
    // largest for the harmonic net at t = 1
    let at = |r: f64| {
        heights
            .iter()
            .find(|(x, _)| (x - r).abs() < 1e-12)
            .unwrap()
            .1
    };
    for (r, z) in &heights {
        assert!((z - at(1.0 / (4.0 * r))).abs() < 1e-12, "{heights:?}");
        assert!(*r == 0.5 || *z < half - 1e-3, "{heights:?}");
    }
}
