//! `tensegrity roll` and `fig-rolling` outputs: the CSV contract, the frame drawings, the VTK
//! series, warnings on stderr, and the impulse table.

use crate::common;
use common::{assert_ok, run};

#[test]
fn the_csv_has_the_contract_columns_for_both_fidelities() {
    let dir = common::scratch("roll", "roll-csv");
    for fidelity in ["rigid", "full"] {
        let path = dir.join(format!("{fidelity}.csv"));
        let out = run(&[
            "roll",
            "--fidelity",
            fidelity,
            "--t-end",
            "0.1",
            "--out",
            path.to_str().unwrap(),
        ]);
        assert_ok(&out);
        let text = std::fs::read_to_string(&path).unwrap();
        let mut lines = text.lines();
        assert!(lines.next().unwrap().starts_with("t,axle_s,axle_h,omega,"));
        // the start on a side: the axle at s = −R_o sin(π/8), h = R_o cos(π/8)
        let first: Vec<f64> = lines
            .next()
            .unwrap()
            .split(',')
            .take(3)
            .map(|v| v.parse().unwrap())
            .collect();
        let half = std::f64::consts::PI / 8.0;
        assert_eq!(first[0], 0.0);
        assert!((first[1] + half.sin()).abs() < 1e-12, "{fidelity}");
        assert!((first[2] - half.cos()).abs() < 1e-12, "{fidelity}");
        assert_eq!(
            text.lines().count(),
            102,
            "{fidelity}: 101 samples and a header"
        );
    }
}

#[test]
fn frames_draw_the_members_and_vtk_writes_a_series() {
    let dir = common::scratch("roll", "roll-frames");
    let svg = dir.join("frames.svg");
    let vtk = dir.join("vtk");
    let out = run(&[
        "roll",
        "--fidelity",
        "rigid",
        "--t-end",
        "1",
        "--frames",
        "0,0.5,1",
        "--svg",
        svg.to_str().unwrap(),
        "--vtk",
        vtk.to_str().unwrap(),
    ]);
    assert_ok(&out);
    let text = std::fs::read_to_string(&svg).unwrap();
    for t in ["t = 0.000 s", "t = 0.500 s", "t = 1.000 s"] {
        assert!(text.contains(t), "{t}");
    }
    // n = 8 with spokes + inner rings: 25 bars, 128 strings; one polyline per member and
    // the slope line, in each of the three frames
    let members = 8 * 3 + 1 + 8 * 12 + 8 * 2 + 8 * 2;
    assert_eq!(text.matches("<polyline").count(), 3 * (members + 1));
    let pvd = std::fs::read_to_string(vtk.join("series.pvd")).unwrap();
    // every 10 ms over 1 s; the three --frames lie on that grid: each time once
    assert_eq!(pvd.matches("<DataSet").count(), 101);
    let mut times: Vec<&str> = pvd
        .split("timestep=\"")
        .skip(1)
        .filter_map(|s| s.split('"').next())
        .collect();
    let n = times.len();
    times.dedup();
    assert_eq!((n, times.len()), (101, 101), "{pvd}");
    // the rigid model's frames carry its node velocities (a rigid body has no member force)
    let frame = std::fs::read_to_string(vtk.join("frame_00050.vtu")).unwrap();
    assert!(
        frame.contains(r#"Name="velocity [m/s]""#) && !frame.contains(r#"Name="force [N]""#),
        "{frame}"
    );
    let out = run(&["roll", "--t-end", "1", "--frames", "2", "--svg", "x.svg"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--frames"));
}

#[test]
fn thesis_contact_warnings_reach_stderr_and_the_json() {
    let out = run(&[
        "roll",
        "--fidelity",
        "full",
        "--contact",
        "thesis",
        "--t-end",
        "1.5",
        "--json",
    ]);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["valid"], false);
    assert_eq!(v["contact"], "thesis");
    assert!(v["min_normal_force"].as_f64().unwrap() < 0.0);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("warning: ") && stderr.contains("pulled"),
        "{stderr}"
    );
    let out = run(&["roll", "--restitution", "1.5"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("restitution"));
}

#[test]
fn auto_reports_its_reason_and_the_help_names_the_kinetic_friction() {
    let out = run(&[
        "roll",
        "--string-stiffness",
        "2e6",
        "--incline",
        "30deg",
        "--mu",
        "1.2",
        "--t-end",
        "2",
        "--json",
    ]);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    // stiff strings: the rigid run first; its scene class's row of the measured fidelity
    // table decides (with the default ground of 10⁵ N/m, softer than the table measured,
    // the full model), and the reason says so
    let reason = v["fidelity_reason"].as_str().unwrap();
    assert!(reason.contains("the wheel is stiff"), "{reason}");
    let class = wheel_rolling::fidelity::SceneClass::ALL
        .into_iter()
        .find(|c| reason.contains(&format!("scene class `{}`", c.name())))
        .expect("the reason names the class");
    let row = wheel_rolling::fidelity::ClassAgreement::of(class);
    let rigid = row.agrees() && row.covers(7.1e-5, 1e5);
    assert_eq!(
        v["fidelity"],
        if rigid { "rigid" } else { "full" },
        "{reason}"
    );
    if rigid {
        assert!(reason.ends_with("rigid run is valid: rigid"), "{reason}");
        let first = &v["first_impact"];
        let (after, before) = (&first["omega_after"], &first["omega_before"]);
        assert!(after.as_f64().unwrap() < before.as_f64().unwrap());
    } else {
        assert!(reason.ends_with("full"), "{reason}");
    }
    let help = run(&["roll", "--help"]);
    let text = String::from_utf8_lossy(&help.stdout);
    assert!(text.contains("0.75"), "{text}");
    assert!(text.contains("--restitution") && text.contains("--ground-damping"));
}

#[test]
fn fig_rolling_prints_the_impulse_table() {
    let dir = common::scratch("roll", "fig-rolling-table");
    let svg = dir.join("rolling.svg");
    let out = run(&[
        "fig-rolling",
        "--fidelity",
        "rigid",
        "--t-end",
        "2",
        "--out",
        svg.to_str().unwrap(),
    ]);
    assert_ok(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("impact impulse per new contact"));
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip_while(|l| !l.contains("omega+/omega-"))
        .skip(1)
        .take(4)
        .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(
        rows.iter().map(|r| r[0]).collect::<Vec<_>>(),
        [8.0, 12.0, 16.0, 24.0]
    );
    // §3.3.1: the impulse per new contact, per unit of wheel mass, falls with n
    assert!(rows.windows(2).all(|w| w[1][4] < w[0][4]), "{rows:?}");
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(svg.contains("axle height above the slope [m]"));
}

#[test]
fn a_diverged_roll_writes_what_it_computed_and_exits_with_an_error() {
    let dir = common::scratch("roll", "roll-diverged");
    let path = dir.join("partial.csv");
    let out = run(&[
        "roll",
        "--fidelity",
        "full",
        "--string-stiffness",
        "1e9",
        "--t-end",
        "0.01",
        "--out",
        path.to_str().unwrap(),
        "--json",
    ]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("stopped at t = "), "{stderr}");
    assert!(stderr.contains("use a smaller --dt"), "{stderr}");
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["valid"], false);
    let t = json["stopped_at"].as_f64().unwrap();
    assert!((0.0..0.01).contains(&t), "{t}");
    // the CSV holds the samples up to the stop
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.starts_with("t,axle_s,axle_h,omega,"));
    assert!(text.lines().count() >= 2);
}

/// `roll --vtk` of the full model: node velocities as point data and member forces as cell
/// data, each time once; `--strict` on the thesis contact (which sinks and pulls) exits 1.
#[test]
fn the_full_series_carries_forces_and_strict_fails_an_invalid_run() {
    let dir = common::scratch("roll", "roll-full-vtk");
    let vtk = dir.join("vtk");
    let out = run(&[
        "roll",
        "--fidelity",
        "full",
        "--t-end",
        "0.05",
        "--no-convergence-check",
        "--vtk",
        vtk.to_str().unwrap(),
    ]);
    assert_ok(&out);
    let frame = std::fs::read_to_string(vtk.join("frame_00003.vtu")).unwrap();
    assert!(frame.contains(r#"Name="velocity [m/s]""#) && frame.contains(r#"Name="force [N]""#));
    let strict = run(&[
        "roll",
        "--contact",
        "thesis",
        "--t-end",
        "1.5",
        "--no-convergence-check",
        "--strict",
    ]);
    assert_eq!(strict.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&strict.stdout);
    assert!(
        stdout.lines().next().unwrap().contains("INVALID"),
        "{stdout}"
    );
    assert!(String::from_utf8_lossy(&strict.stderr).contains("strict: "));
}

/// A step longer than the 1 ms output interval would be cut to it (the JSON's `dt` would not
/// be the step that ran, and the convergence check's half step would refine nothing): `roll`
/// and `tbar roll` refuse it by name; the interval itself runs.
#[test]
fn a_step_longer_than_the_output_interval_is_refused() {
    for args in [
        &["roll", "--dt", "2e-3"][..],
        &["roll", "--fidelity", "full", "--dt", "1e300"][..],
        &["tbar", "roll", "--dt", "5e-3"][..],
    ] {
        let out = run(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains("dt") && err.contains("output interval"),
            "{args:?}: {err}"
        );
    }
    let out = run(&[
        "roll",
        "--fidelity",
        "rigid",
        "--t-end",
        "0.05",
        "--dt",
        "1e-3",
        "--no-convergence-check",
        "--json",
    ]);
    assert_ok(&out);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["dt"], 1e-3);
}
