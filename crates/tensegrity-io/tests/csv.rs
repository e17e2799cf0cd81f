//! CSV tables: headers with units, exact round trip of the numbers, the Michell tables.

use michell3d::complexity::{mass_vs_complexity, FIG_4_18_DELTAS};
use michell3d::extra_strings::{gamma_sweep, ExtraStrings};
use michell3d::signmap::{sign_map_rows, sign_maps, AngleGrid};
use michell3d::{Method, MichellParams, MichellTruss};
use std::f64::consts::{FRAC_PI_6, PI};
use tensegrity_core::test_models::double_pendulum;
use tensegrity_core::MaterialTable;
use tensegrity_dynamics::{Simulation, SimulationSettings};
use tensegrity_io::csv;

fn written(f: impl FnOnce(&mut Vec<u8>) -> tensegrity_io::Result<usize>) -> (usize, String) {
    let mut out = Vec::new();
    let n = f(&mut out).unwrap();
    (n, String::from_utf8(out).unwrap())
}

fn parse(line: &str) -> Vec<f64> {
    line.split(',').map(|v| v.parse().unwrap()).collect()
}

#[test]
fn the_trajectory_round_trips_exactly() {
    let s = double_pendulum(0.5).unwrap();
    let mut settings = SimulationSettings {
        t_end: 0.2,
        output_interval: Some(0.05),
        ..Default::default()
    };
    settings.quantities.nodes = true;
    let r = Simulation::new(&s, settings).unwrap().run().unwrap();
    let (n, text) = written(|w| csv::write_trajectory(w, &r));
    assert_eq!(n, r.samples.len());
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header.len(), 1 + 3 * r.final_nodes.len());
    assert_eq!(&header[..3], ["t [s]", "n0_x [m]", "n0_y [m]"]);
    assert_eq!(header.last().copied(), Some("n2_z [m]"));
    for (line, sample) in lines.zip(&r.samples) {
        let v = parse(line);
        assert_eq!(v[0], sample.t);
        let nodes = sample.nodes.as_ref().unwrap();
        for (i, p) in nodes.iter().enumerate() {
            assert_eq!([v[1 + 3 * i], v[2 + 3 * i], v[3 + 3 * i]], [p.x, p.y, p.z]);
        }
        // the fixed scientific layout of the CLI
        assert!(line.starts_with(&format!("{:.17e},", sample.t)), "{line}");
    }
}

#[test]
fn rows_with_units_in_their_names_round_trip() {
    let rows = vec![
        csv::WorkPrecisionRow {
            scene: "prism".into(),
            integrator: "rk4".into(),
            parameter: 1e-3,
            steps: 1000,
            rhs_evals: 4000,
            error_m: 1.0 / 3.0 * 1e-9,
            wall_time_s: 0.1 + 0.2,
        };
        2
    ];
    let (n, text) = written(|w| csv::write_work_precision(w, &rows));
    assert_eq!(n, 2);
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("scene,integrator,parameter (dt [s] or rtol),steps,rhs_evals,error [m],wall_time [s]")
    );
    let first: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(first[..5], ["prism", "rk4", "1e-3", "1000", "4000"]); // `{:e}` as before
    assert_eq!(first[5].parse::<f64>().unwrap(), 1.0 / 3.0 * 1e-9);
    assert_eq!(first[6].parse::<f64>().unwrap(), 0.1 + 0.2);

    let grid = [(0.5, 0.25, 1.0 / 7.0), (1e-7, 2.0, -0.0)];
    let (_, text) = written(|w| csv::write_friction_grid(w, &grid));
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("sigma,epsilon,normalized_friction"));
    assert_eq!(text.lines().nth(2), Some("0.0000001,2,-0")); // `{}` as before
    for (line, &(s, e, v)) in lines.zip(&grid) {
        assert_eq!(parse(line), vec![s, e, v]);
    }
}

#[test]
fn the_rolling_history_has_the_cli_columns() {
    let sample = wheel_rolling::RollingSample {
        t: 0.001,
        s: 1.0 / 3.0,
        h: 0.5,
        pivot: 0.0,
        omega: -2.5,
        normal: 9.81,
        tangential: 1e-300,
        energy: -0.125,
        slip: 0.0,
    };
    let (n, text) = written(|w| csv::write_rolling_history(w, &[sample, sample]));
    assert_eq!(n, 2);
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("t,axle_s,axle_h,omega,pivot_m,normal_N,tangential_N,energy_J,slip_m_s")
    );
    let v = parse(lines.next().unwrap());
    assert_eq!(
        v,
        vec![0.001, 1.0 / 3.0, 0.5, -2.5, 0.0, 9.81, 1e-300, -0.125, 0.0]
    );
}

#[test]
fn michell_sign_maps_and_gamma_sweeps_keep_their_columns() {
    let t = MichellTruss::new(MichellParams::cylindrical(
        2,
        1.0,
        FRAC_PI_6,
        PI / 8.0,
        0.25,
    ))
    .unwrap();
    let (az, po) = (
        AngleGrid::new(0.0, 2.0 * PI, 37),
        AngleGrid::new(0.0, PI, 19),
    );
    let maps = sign_maps(&t, &[0, 2], 1000.0, az, po, Method::Recursive).unwrap();
    let (n, text) = written(|w| csv::write_sign_maps(w, sign_map_rows(&t, &maps)));
    assert_eq!(n, 2 * 37 * 19);
    assert_eq!(text.lines().count(), 1 + n);
    assert!(text.starts_with(
        "member,parent,child,azimuth_rad,polar_rad,force_density_N_per_m,sign\n0,0-0-0-0,1-0-1-0,"
    ));
    // the load along −ι̂₃ (γ = π) compresses the tip member m₀₁₀₀ (member 2), eq. 4.20
    let row = text
        .lines()
        .find(|l| {
            l.starts_with("2,") && l.contains(",0.00000000000000000e0,3.14159265358979312e0,")
        })
        .expect("member 2 at azimuth 0, polar π");
    assert!(row.ends_with(",-1"), "{row}");
    let q: f64 = row.split(',').nth(5).unwrap().parse().unwrap();
    assert_eq!(q, maps[1].value(18, 0));

    let strings = ExtraStrings::new(&t).unwrap();
    let sweep = gamma_sweep(
        &t,
        &strings,
        1000.0,
        0.0,
        AngleGrid::new(0.0, 2.0 * PI, 9),
        5000.0,
        Method::Recursive,
    )
    .unwrap();
    let (n, text) = written(|w| csv::write_gamma_sweep(w, sweep.rows()));
    assert_eq!(n, 9 * (t.members().len() + strings.len()));
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("polar_rad,member,kind,force_N"));
    let first: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(first[1..3], ["0", "base"]);
    assert_eq!(first[3].parse::<f64>().unwrap(), sweep.base_force[0][0]);
    assert!(text.contains(",0,extra,"));
}

#[test]
fn the_mass_table_round_trips() {
    let rows = mass_vs_complexity(
        &[2, 3],
        &FIG_4_18_DELTAS,
        1000.0,
        MaterialTable::builtin().get("steel").unwrap(),
    )
    .unwrap();
    let (n, text) = written(|w| csv::write_mass_table(w, &rows));
    assert_eq!(text.lines().count(), n + 1);
    assert!(text.starts_with("complexity,delta,normalized_yield_mass,yield_mass_kg,yield_buckling_mass_kg,sign_changes_vs_planar\n"));
    assert!(text.lines().nth(1).unwrap().starts_with("2,0,")); // the planar δ as `{}`
    for (line, r) in text.lines().skip(1).zip(&rows) {
        let v = parse(line);
        assert_eq!(v[0] as usize, r.complexity);
        assert_eq!(v[1], r.delta);
        assert_eq!(v[2], r.normalized_yield_mass);
        assert_eq!(v[4], r.yield_buckling_mass_kg);
    }
}
