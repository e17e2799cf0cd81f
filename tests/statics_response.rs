//! The linear response of `statics` (prescribed support displacements, `--response`) end to
//! end:
//!
//! - against `solve` (two independent codes): a prestressed 4 × 4 string net on a saddle
//!   (the net of `tests/solve_linear.rs`, its nodes at the path's prestressed equilibrium),
//!   one border node moved by a prescribed displacement: the statics' linear response equals
//!   the path's displacement over the load factor at λ = 10⁻⁵, to 10⁻⁶ relative;
//! - `statics --json` of `examples/prescribed_displacement.toml`: the closed form of two bars
//!   in series, and `solve` of the same scene (collinear bars: linear at any size) on it;
//! - `--response` under loads: the determinate inclined roller's member force change and
//!   reactions are the load solve's;
//! - bad input: a member without an axial stiffness (exit 2, named), a mechanism (exit 1,
//!   named, no NaN), and `simulate` still refusing a `displacement`.

use crate::common;

use common::{assert_ok, run};
use nalgebra::Vector3;
use tensegrity_core::request::Request;
use tensegrity_core::{StringMember, Structure, Support};
use tensegrity_engine::scene::SceneSource;
use tensegrity_engine::solve::{solve, SolveCommand};
use tensegrity_engine::statics::{statics, StaticsCommand};
use tensegrity_path::{load_steps, ElasticModel};

/// The 4 × 4 grid without its corners (12 nodes: 8 on the border, pinned on the saddle
/// z = (x² − y²)/8, 4 inner ones at z = 0), strings along the grid lines between an inner
/// node and any other (k = 100 N/m, rest length 0.9 of the grid length): positions, strings
/// (nodes, rest length) and whether a node is on the border.
fn grid() -> Net {
    let border = |i: usize, j: usize| i == 0 || i == 3 || j == 0 || j == 3;
    let corner = |i: usize, j: usize| (i == 0 || i == 3) && (j == 0 || j == 3);
    let mut index = [[usize::MAX; 4]; 4];
    let (mut nodes, mut on_border) = (Vec::new(), Vec::new());
    for i in 0..4 {
        for j in 0..4 {
            if corner(i, j) {
                continue;
            }
            let (a, b) = (i as f64 - 1.5, j as f64 - 1.5);
            let z = if border(i, j) {
                (a * a - b * b) / 8.0
            } else {
                0.0
            };
            index[i][j] = nodes.len();
            nodes.push([a, b, z]);
            on_border.push(border(i, j));
        }
    }
    let mut strings = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            for (ni, nj) in [(i + 1, j), (i, j + 1)] {
                if ni < 4 && nj < 4 && !(border(i, j) && border(ni, nj)) {
                    let (p, q) = (index[i][j], index[ni][nj]);
                    let l = (Vector3::from(nodes[q]) - Vector3::from(nodes[p])).norm();
                    strings.push(([p, q], 0.9 * l));
                }
            }
        }
    }
    Net {
        nodes,
        strings,
        on_border,
    }
}

/// The net's grid: node positions, strings (nodes, rest length), border nodes.
struct Net {
    nodes: Vec<[f64; 3]>,
    strings: Vec<([usize; 2], f64)>,
    on_border: Vec<bool>,
}

/// The net's prestressed equilibrium: the path's point at λ = 0 (the inner nodes move from
/// the grid to where the strings balance).
fn equilibrium() -> Vec<[f64; 3]> {
    let Net {
        nodes,
        strings,
        on_border,
    } = grid();
    let mut b = Structure::builder().nodes(nodes.clone());
    for ([p, q], l0) in &strings {
        b = b.string(StringMember::new(*p, *q).stiffness(100.0).rest_length(*l0));
    }
    for (i, &held) in on_border.iter().enumerate() {
        if held {
            b = b.support(Support::pinned(i));
        } else {
            // a token load: the path needs one; its point at λ = 0 is unloaded
            b = b.load(i, [0.0, 0.0, -1.0]);
        }
    }
    let model = ElasticModel::from_structure(&b.build().unwrap()).unwrap();
    let path = load_steps(&model, 1, 1e-9).unwrap();
    path.points[0].nodes.clone()
}

/// The scene of the net at `nodes`, border node `moved` displaced by `d`.
fn net_scene(nodes: &[[f64; 3]], moved: usize, d: [f64; 3]) -> String {
    let Net {
        strings, on_border, ..
    } = grid();
    let list: Vec<String> = nodes
        .iter()
        .map(|n| format!("[{:?}, {:?}, {:?}]", n[0], n[1], n[2]))
        .collect();
    let mut text = format!("nodes = [{}]\n", list.join(", "));
    for ([p, q], l0) in &strings {
        text +=
            &format!("[[strings]]\nnodes = [{p}, {q}]\nstiffness = 100.0\nrest_length = {l0:?}\n");
    }
    for (i, &held) in on_border.iter().enumerate() {
        if held {
            text += &format!("[[supports]]\nnode = {i}\n");
            if i == moved {
                text += &format!("displacement = [{:?}, {:?}, {:?}]\n", d[0], d[1], d[2]);
            }
        }
    }
    text
}

#[test]
fn a_prescribed_displacement_moves_the_prestressed_net_as_solve_at_small_load_factor() {
    let nodes = equilibrium();
    let on_border = grid().on_border;
    let moved = 1; // the border node (0, 1), between two corners
    assert!(on_border[moved]);
    let scene = SceneSource::parse(&net_scene(&nodes, moved, [0.02, -0.01, 0.03]));
    let command = StaticsCommand {
        scene: Some(scene.clone()),
        ..StaticsCommand::default()
    };
    let linear = statics(&command).unwrap().linear_response.unwrap();
    assert!(linear.warnings.is_empty(), "{:?}", linear.warnings);
    assert!(linear.initial_force.iter().all(|&t| t > 1.0), "prestressed");
    let lambda = 1e-5;
    let solve_command = SolveCommand {
        scene: Some(scene),
        load_steps: Some(1),
        target: lambda,
        ..SolveCommand::default()
    };
    solve_command.validate().unwrap();
    let path = solve(&solve_command).unwrap().path;
    let (rest, moved_point) = (&path.points[0], &path.points[1]);
    let scale = linear.max_displacement;
    let mut worst = 0.0f64;
    for i in 0..nodes.len() {
        for a in 0..3 {
            let u_path = (moved_point.displacements[i][a] - rest.displacements[i][a]) / lambda;
            worst = worst.max((u_path - linear.displacements[i][a]).abs() / scale);
        }
    }
    assert!(worst < 1e-6, "relative difference {worst:.3e}");
    // the inner nodes did move (the test can fail), and the moved node as prescribed
    let inner = (0..nodes.len()).filter(|&i| !on_border[i]);
    assert!(inner
        .map(|i| Vector3::from(linear.displacements[i]).norm())
        .all(|u| u > 1e-4));
    assert_eq!(linear.displacements[moved], [0.02, -0.01, 0.03]);
    // the member force changes against the path's tensions
    for (k, dt) in linear.member_force_change.iter().enumerate() {
        let path_dt = (moved_point.tensions[k] - rest.tensions[k]) / lambda;
        assert!(
            (path_dt - dt).abs() < 1e-6 * 100.0 * scale,
            "{k}: {path_dt} {dt}"
        );
    }
}

fn json(out: &std::process::Output) -> serde_json::Value {
    assert_ok(out);
    serde_json::from_slice(&out.stdout).unwrap()
}

fn number(v: &serde_json::Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

#[test]
fn the_settled_support_of_two_bars_in_series_gives_the_closed_form() {
    let r = json(&run(&[
        "statics",
        "examples/prescribed_displacement.toml",
        "--json",
    ]));
    let lr = &r["linear_response"];
    // k_a = 1000, k_b = 3000 N/m, the top support raised by d = 0.1 m
    let (ka, kb, d) = (1000.0, 3000.0, 0.1);
    let u = kb * d / (ka + kb);
    let t = ka * kb / (ka + kb) * d;
    assert!(
        (number(&lr["displacements"][1][2]) - u).abs() < 1e-12,
        "{lr}"
    );
    assert!((number(&lr["max_displacement"]) - d).abs() < 1e-15);
    for k in 0..2 {
        assert!(
            (number(&lr["member_force_change"][k]) - t).abs() < 1e-9,
            "{lr}"
        );
    }
    assert!((number(&lr["reactions"][0]["force"][2]) + t).abs() < 1e-9);
    assert!((number(&lr["reactions"][2]["force"][2]) - t).abs() < 1e-9);
    assert_eq!(lr["slack"], serde_json::json!([]));
    // `solve` of the same scene: collinear bars respond linearly at any size
    let s = json(&run(&[
        "solve",
        "examples/prescribed_displacement.toml",
        "--json",
    ]));
    let last = s["path"]["points"].as_array().unwrap().last().unwrap();
    assert!(
        (number(&last["nodes"][1][2]) - 1.0 - u).abs() < 1e-12,
        "{last}"
    );
    // the text report has the block
    let out = run(&["statics", "examples/prescribed_displacement.toml"]);
    assert_ok(&out);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("linear response at this geometry"), "{text}");
}

#[test]
fn response_under_loads_gives_the_load_solve_of_a_determinate_structure() {
    let r = json(&run(&[
        "statics",
        "examples/inclined_roller.toml",
        "--response",
        "--json",
    ]));
    let lr = &r["linear_response"];
    let (f, df) = (
        number(&r["member_force"][0]),
        number(&lr["member_force_change"][0]),
    );
    assert!((f - df).abs() < 1e-9 * f.abs(), "{f} {df}");
    for s in 0..2 {
        for a in 0..3 {
            let (x, y) = (
                number(&r["reactions"][s]["force"][a]),
                number(&lr["reactions"][s]["force"][a]),
            );
            assert!((x - y).abs() < 1e-9 * 1000.0, "{s} {a}: {x} {y}");
        }
    }
    // along the incline's normal, as the load solve reports it
    let normal = number(&lr["reactions"][1]["along"][0]);
    assert!((normal - 1000.0 / 30f64.to_radians().cos()).abs() < 1e-9 * 1000.0);
    // without the flag and without a displacement: no response
    let plain = json(&run(&[
        "statics",
        "examples/inclined_roller.toml",
        "--json",
    ]));
    assert!(plain.get("linear_response").is_none());
}

/// A bar along x from a pin to a node held along `held` with a prescribed displacement,
/// `bar` its extra keys.
fn bar_scene(bar: &str, held: &str) -> String {
    format!(
        "nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0]]\n[materials.m]\ndensity = 1000.0\nyoungs_modulus = 1e9\nyield_strength = 1e6\n[[bars]]\nnodes = [0, 1]\n{bar}\n[[supports]]\nnode = 0\n[[supports]]\nnode = 1\n{held}\ndisplacement = [0.01, 0.0, 0.0]\n"
    )
}

#[test]
fn bad_input_is_refused_naming_the_member_or_the_mechanism() {
    // a bar without a radius: no axial stiffness
    let out = run(&["statics", &bar_scene("material = \"m\"", "")]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("bar 0") && err.contains("radius"), "{err}");
    // held along x only: the bar's end swings freely across (no prestress)
    let mechanism = bar_scene("material = \"m\"\nradius = 0.01", "directions = [\"x\"]");
    let out = run(&["statics", &mechanism, "--json"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("2 mechanism(s)") && err.contains("node 1"),
        "{err}"
    );
    assert!(out.stdout.is_empty() && !err.contains("NaN"), "{err}");
    // a displacement off the held directions
    let off = bar_scene(
        "material = \"m\"\nradius = 0.01",
        "directions = [\"y\", \"z\"]",
    );
    let out = run(&["statics", &off]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("support 1 (node 1)"), "{err}");
    // `simulate` still refuses the key
    let out = run(&["simulate", "examples/prescribed_displacement.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("support 2: displacement is read by `solve`"),
        "{err}"
    );
}
