//! `tensegrity solve`: the load path of a scene end to end — the two-bar truss through both
//! limit points at the closed form's load factor, the CSV of its points, and bad input refused
//! before any work, naming the flag or the item.

use std::process::Command;

fn run(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_tensegrity"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("binary runs")
}

/// λ* of the two-bar truss of examples/von_mises.toml: L*³ = a² L₀, w* = √(L*² − a²),
/// λ* = 2 EA w* (1/L* − 1/L₀) / 100 N.
fn closed_form_fold() -> f64 {
    let (a, h, ea) = (1.0f64, 0.5f64, 1e7 * std::f64::consts::PI * 1e-4);
    let l0 = a.hypot(h);
    let l = (a * a * l0).cbrt();
    let w = (l * l - a * a).sqrt();
    2.0 * ea * w * (1.0 / l - 1.0 / l0) / 100.0
}

#[test]
fn the_two_bar_truss_snaps_through_at_the_closed_form_load() {
    let dir = std::env::temp_dir().join(format!("tensegrity-solve-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("path.csv");
    let out = run(&[
        "solve",
        "examples/von_mises.toml",
        "--target",
        "2",
        "--json",
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let fold = closed_form_fold();
    assert_eq!(json["limit_points"], 2);
    let first = json["first_limit_load_factor"].as_f64().unwrap();
    assert!((first - fold).abs() < 1e-8 * fold, "{first} against {fold}");
    assert_eq!(json["final_load_factor"], 2.0);
    assert_eq!(json["stop"], "reached_target");
    // one CSV row per point, λ as in the JSON
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<&str> = text.lines().skip(1).collect();
    let points = json["path"]["points"].as_array().unwrap();
    assert_eq!(rows.len(), points.len());
    let lambda: f64 = rows[rows.len() - 1]
        .split(',')
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(lambda, 2.0);
    // the figure and the VTK series: one frame per point, the member forces as cell data
    let (svg, vtk) = (dir.join("path.svg"), dir.join("vtk"));
    let out = run(&[
        "solve",
        "examples/von_mises.toml",
        "--target",
        "2",
        "--svg",
        svg.to_str().unwrap(),
        "--vtk",
        vtk.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let picture = std::fs::read_to_string(&svg).unwrap();
    assert!(
        picture.contains("limit point") && picture.contains("unstable"),
        "legend"
    );
    let frames = std::fs::read_dir(&vtk)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .path()
                .extension()
                .is_some_and(|x| x == "vtu")
        })
        .count();
    assert_eq!(frames, points.len());
    let last =
        std::fs::read_to_string(vtk.join(format!("frame_{:05}.vtu", points.len() - 1))).unwrap();
    assert!(last.contains(r#"Name="force [N]""#));
    // the text names both folds
    let text = run(&["solve", "examples/von_mises.toml", "--target", "2"]);
    let stdout = String::from_utf8_lossy(&text.stdout);
    assert_eq!(stdout.matches("limit point at λ = ").count(), 2, "{stdout}");
}

#[test]
fn bad_input_is_refused_naming_the_flag_or_the_item() {
    for (args, needle) in [
        (
            vec!["solve", "examples/von_mises.toml", "--target", "0"],
            "--target",
        ),
        (
            vec!["solve", "examples/von_mises.toml", "--load-steps", "0"],
            "--load-steps",
        ),
        (
            vec![
                "solve",
                "examples/von_mises.toml",
                "--path",
                "--load-steps",
                "3",
            ],
            "--load-steps",
        ),
        // bars without a radius: not elastic
        (
            vec!["solve", "examples/dbar_loaded.toml"],
            "bar 0: an elastic bar needs a radius",
        ),
        // nothing loaded
        (
            vec!["solve", "examples/prism.toml"],
            "the reference load is zero",
        ),
    ] {
        let out = run(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

/// examples/column.toml: the braced column bifurcates near λ_c = 2 k L/P = 2 (the bar's
/// shortening and the strings' share of the load move it by 10⁻⁵), and `--switch-branch`
/// follows the leaning branch, on which the string it leans to slackens.
#[test]
fn the_braced_column_bifurcates_and_the_switch_follows_the_leaning_branch() {
    let out = run(&[
        "solve",
        "examples/column.toml",
        "--switch-branch",
        "--max-steps",
        "60",
        "--target",
        "3",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let events = json["path"]["events"].as_array().unwrap();
    let first = &events[0];
    assert_eq!(first["kind"], "bifurcation");
    assert_eq!(first["switched"], true);
    assert!(
        (first["lambda"].as_f64().unwrap() - 2.0).abs() < 1e-4,
        "{first}"
    );
    assert!(events
        .iter()
        .any(|e| e["kind"] == "slackened" && e["members"] == serde_json::json!([2])));
    assert_eq!(json["stability"], "unstable");
    // without the switch the column stays straight
    let straight = run(&["solve", "examples/column.toml", "--target", "3", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&straight.stdout).unwrap();
    let last = json["path"]["points"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()
        .clone();
    assert!(last["nodes"][1][0].as_f64().unwrap().abs() < 1e-9);
}

/// The drivers from a scene (examples/solve_drivers.toml): a bar's `rest_length_change` and a
/// support's `displacement` move node 1 as the closed form of two bars in series; `statics`
/// and `simulate` refuse the scene rather than ignore the keys.
#[test]
fn scene_drivers_move_the_node_as_the_closed_form_and_other_commands_refuse_them() {
    let out = run(&["solve", "examples/solve_drivers.toml", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let last = json["path"]["points"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()
        .clone();
    let (ea, eb, dl, d) = (1000.0, 3000.0, 0.2, 0.1);
    let u = (ea * dl + eb * d * (1.0 + dl)) / (ea + eb * (1.0 + dl));
    let z = last["nodes"][1][2].as_f64().unwrap();
    assert!((z - 1.0 - u).abs() < 1e-12, "{z} against {}", 1.0 + u);
    assert!((last["nodes"][2][2].as_f64().unwrap() - 2.1).abs() < 1e-15);
    for command in ["statics", "simulate"] {
        let out = run(&[command, "examples/solve_drivers.toml"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{command}: {err}");
        assert!(
            err.contains("bar 0: rest_length_change is read by `solve` only"),
            "{command}: {err}"
        );
    }
}

/// A support `along` a direction of any orientation: the two-bar truss turned by 40° about x
/// (its apex held along the turned normal of its plane, the load turned with it) snaps
/// through at the same load factor as the upright one; `statics` reads the key too: both
/// bars carry the upright truss's −100 N · √1.25 (each bar's share of the load along it).
#[test]
fn a_support_along_any_direction_gives_the_turned_truss_the_same_fold() {
    let (s, c) = 40f64.to_radians().sin_cos();
    let scene = format!(
        r#"nodes = [[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, {:?}, {:?}]]
[materials.soft]
density = 1000.0
youngs_modulus = 1e7
yield_strength = 1e6
[[bars]]
nodes = [0, 2]
material = "soft"
radius = 0.01
[[bars]]
nodes = [1, 2]
material = "soft"
radius = 0.01
[[supports]]
node = 0
[[supports]]
node = 1
[[supports]]
node = 2
along = [[0.0, {:?}, {:?}]]
[[loads]]
node = 2
force = [0.0, {:?}, {:?}]
"#,
        0.5 * c,
        0.5 * s,
        -s,
        c,
        -100.0 * c,
        -100.0 * s
    );
    let out = run(&["solve", &scene, "--target", "2", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["limit_points"], 2);
    let fold = json["first_limit_load_factor"].as_f64().unwrap();
    assert!((fold - closed_form_fold()).abs() < 1e-8 * fold, "{fold}");
    let out = run(&["statics", &scene, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        (json["rank"].as_u64(), json["mechanisms"].as_u64()),
        (Some(2), Some(0))
    );
    for f in json["member_force"].as_array().unwrap() {
        let f = f.as_f64().unwrap();
        assert!((f + 100.0 * 1.25f64.sqrt()).abs() < 1e-10, "{f}");
    }
}

/// A scene not in equilibrium unloaded (a string to an anchor below, stretched to twice its
/// rest length, pulls the soft bar's top down at λ = 0) is solved from its equilibrium, with a
/// warning that the displacements count that move; a support giving `along` and `directions`
/// is refused.
#[test]
fn an_unbalanced_start_is_warned_and_an_ambiguous_support_refused() {
    let scene = |support: &str| {
        format!(
            r#"nodes = [[0.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]
[materials.soft]
density = 1000.0
youngs_modulus = 1e7
yield_strength = 1e6
[[bars]]
nodes = [0, 1]
material = "soft"
radius = 0.01
[[strings]]
nodes = [1, 2]
stiffness = 1000.0
rest_length = 1.0
[[supports]]
node = 0
[[supports]]
node = 2
[[supports]]
node = 1
{support}
[[loads]]
node = 1
force = [0.0, 0.0, -1.0]
"#
        )
    };
    let out = run(&["solve", &scene("directions = [\"x\", \"y\"]"), "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("the unloaded scene is not in equilibrium"),
        "{err}"
    );
    // the moved start is the closed form: the string's k z balances the bar's EA (1 − z),
    // EA = 1e7 π 10⁻⁴
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let z = json["path"]["points"][0]["nodes"][1][2].as_f64().unwrap();
    let ea = 1e7 * std::f64::consts::PI * 1e-4;
    let l = ea / (ea + 1000.0);
    assert!((z - l).abs() < 1e-12, "{z} against {l}");
    let out = run(&[
        "solve",
        &scene("directions = [\"x\", \"y\"]\nalong = [[1.0, 0.0, 0.0]]"),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("support 2: give either along"),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// λ at which the verticals of examples/prism_axial.toml slacken, by the hand calculation of
/// crates/tensegrity-path/tests/prism_slack.rs: at the twist 60° (each bar through the axis)
/// the vertical is at its rest length, r² + h² = L₀,v², the bar √(3r² + L₀,v²) long, and the
/// radial balance q_b = −(3/2) q_s gives one equation in r (bisected); F = (√3/2) t_s h/r.
fn prism_axial_slack() -> f64 {
    let s3 = 3f64.sqrt();
    // the scene's strings: EA = k L₀ = 10⁴ N, L₀ = L/(1 + q L/EA) (q = 100, 100√3 N/m)
    let (ea_s, twist, h0) = (1e4, std::f64::consts::FRAC_PI_6, 2.0);
    let lv = (2.0 * (1.0 - twist.cos()) + h0 * h0).sqrt();
    let (l0s, l0v) = (
        s3 / (1.0 + 100.0 * s3 / ea_s),
        lv / (1.0 + 100.0 * s3 * lv / ea_s),
    );
    // the bars: EA = 10¹¹ Pa π (0.01 m)², at rest at their length in the scene
    let ea_b = 1e11 * std::f64::consts::PI * 1e-4;
    let l0b = (2.0 * (1.0 - (twist + 2.0 * std::f64::consts::FRAC_PI_3).cos()) + h0 * h0).sqrt();
    let ts = |r: f64| ea_s * (s3 * r - l0s) / l0s;
    let f = |r: f64| {
        let lb = (3.0 * r * r + l0v * l0v).sqrt();
        ea_b * (lb - l0b) / l0b / lb + 0.5 * s3 * ts(r) / r
    };
    let (mut lo, mut hi) = (l0s / s3, l0v);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let h = (l0v * l0v - lo * lo).sqrt();
    0.5 * s3 * ts(lo) * h / lo / 1000.0
}

/// examples/prism_axial.toml: the prestressed prism's three verticals slacken together at the
/// hand calculation's load factor, where the prism loses its stability. To 10⁻⁶: `solve` takes
/// the default arc-length steps (up to 0.25), with which the crate's bisection of the crossing
/// step lands on a non-symmetric equilibrium (one vertical slack) 2.8·10⁻⁷ early; the library
/// test with steps of 0.05 agrees to 10⁻¹⁴ (crates/tensegrity-path/tests/prism_slack.rs).
#[test]
fn the_prism_under_an_axial_load_slackens_its_verticals_at_the_hand_calculation() {
    let out = run(&[
        "solve",
        "examples/prism_axial.toml",
        "--target",
        "1.77",
        "--json",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let expected = prism_axial_slack();
    assert!((expected - 1.7617829).abs() < 1e-7, "{expected}");
    let first = json["first_slack_load_factor"].as_f64().unwrap();
    assert!(
        (first - expected).abs() < 1e-6 * expected,
        "{first} against {expected}"
    );
    let slackened: Vec<&serde_json::Value> = json["path"]["events"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|e| e["kind"] == "slackened")
        .collect();
    assert_eq!(slackened[0]["members"], serde_json::json!([9, 10, 11]));
    assert_eq!(json["limit_points"], 0);
    assert_eq!(json["stability"], "unstable");
}

/// examples/prism_axial.toml past its collapse: to λ = 1.8 `solve` found "no equilibrium at
/// load factor 1.8" (its last point was Newton at the target from a point between two points,
/// on the unstable symmetric path after the slack) while 1.77, 1.85 and 2 worked. It now lands
/// on the target on the path, with the three verticals slack and the bars at one force (the
/// symmetric branch), and with the default steps the slack is at the hand calculation's load
/// factor to 10⁻⁸. To 2.5 — the collapsed prism's load factor never exceeds 2.29 — `solve`
/// met a NaN residual and lost every point; it now keeps them and says why it stopped.
#[test]
fn the_prism_lands_on_a_target_past_its_collapse_and_keeps_its_points_beyond() {
    let expected = prism_axial_slack();
    let solve = |target: &str| {
        let out = run(&[
            "solve",
            "examples/prism_axial.toml",
            "--target",
            target,
            "--json",
        ]);
        assert!(
            out.status.success(),
            "{target}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice::<serde_json::Value>(&out.stdout).unwrap()
    };
    let json = solve("1.8");
    assert_eq!(json["stop"], "reached_target");
    let first = json["first_slack_load_factor"].as_f64().unwrap();
    assert!(
        (first - expected).abs() < 1e-8 * expected,
        "{first} against {expected}"
    );
    let last = json["path"]["points"].as_array().unwrap().last().unwrap();
    assert_eq!(last["lambda"], 1.8);
    assert_eq!(last["slack"], serde_json::json!([9, 10, 11]));
    let bars: Vec<f64> = (0..3)
        .map(|k| last["tensions"][k].as_f64().unwrap())
        .collect();
    assert!(
        bars.iter()
            .all(|t| (t - bars[0]).abs() < 1e-9 * bars[0].abs()),
        "{bars:?}"
    );

    let json = solve("2.5");
    let stop = json["stop"].as_str().unwrap();
    assert!(stop == "max_steps" || stop == "step_too_small", "{stop}");
    let points = json["path"]["points"].as_array().unwrap();
    assert!(points.len() > 20, "{}", points.len());
    assert!(points
        .iter()
        .all(|p| p["lambda"].as_f64().is_some_and(f64::is_finite)));
    assert!(json["first_limit_load_factor"].as_f64().unwrap() < 2.5);
}

/// A path whose points outrun `--max-work` (the two-bar truss toward λ = 10⁶, millions of
/// points away) stops at the limit with its points, says so beside them and how to go on;
/// the estimate counts at most 100 points, so a `--max-steps` of 4·10⁹ is not refused.
#[test]
fn a_path_that_outruns_its_work_limit_keeps_its_points_and_says_so() {
    let out = run(&[
        "solve",
        "examples/von_mises.toml",
        "--target",
        "1e6",
        "--max-steps",
        "4000000000",
        "--max-work",
        "0.05",
        "--json",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains(
            "before its target 1000000 (its work limit of 0.05 s spent: raise it with --max-work)"
        ),
        "{err}"
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["stop"], "max_work");
    let points = v["points"].as_u64().unwrap();
    assert!(points > 10 && v["path"]["points"].as_array().unwrap().len() as u64 == points);
    // past both folds, on the inverted truss
    assert_eq!(v["limit_points"], 2);
    assert!(v["final_load_factor"].as_f64().unwrap() > 1.3);
}
