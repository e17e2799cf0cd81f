//! The example specs of examples/sweeps parse, and the Fig. 4.18 sweep agrees with the
//! mass–complexity table of michell3d (an independent code path: propagation and sizing
//! called directly, not through the report).

use sweeps::{run, RunOptions, Silent, Spec};

#[test]
fn every_example_spec_parses() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/sweeps");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let spec = Spec::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert!(spec.case_count().unwrap() > 1, "{}", path.display());
            n += 1;
        }
    }
    assert!(n >= 5);
}

#[test]
fn the_fig_4_18_sweep_is_the_mass_table() {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../examples/sweeps/michell_fig_4_18.toml"),
    )
    .unwrap()
    .replace("to = 35", "to = 7");
    let spec = Spec::parse(&text).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fig.csv");
    run(&spec, &out, &RunOptions::default(), &mut Silent).unwrap();
    let steel = *tensegrity_core::MaterialTable::builtin()
        .lookup("steel", "material")
        .unwrap();
    let qs: Vec<usize> = (2..=7).collect();
    let table = michell3d::mass_vs_complexity(&qs, &[0.1, 0.25, 0.5], 1000.0, &steel).unwrap();
    let mut r = csv::Reader::from_path(&out).unwrap();
    let mut rows = 0;
    for rec in r.records() {
        let rec = rec.unwrap();
        let (delta, q): (f64, usize) = (rec[1].parse().unwrap(), rec[2].parse().unwrap());
        let want = table
            .iter()
            .find(|m| m.delta == delta && m.complexity == q)
            .unwrap();
        let got = |k: usize| rec[k].parse::<f64>().unwrap();
        assert!(
            (got(3) - want.yield_mass_kg).abs() <= 1e-9 * want.yield_mass_kg,
            "{q} {delta}"
        );
        assert!((got(4) - want.yield_buckling_mass_kg).abs() <= 1e-9 * want.yield_buckling_mass_kg);
        assert!((got(5) - want.normalized_yield_mass).abs() <= 1e-9 * want.normalized_yield_mass);
        rows += 1;
    }
    assert_eq!(rows, 18);
}
