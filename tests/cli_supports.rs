//! Supports along any unit direction and elastic supports, end to end through the scene
//! keys `along` and `stiffness`:
//!
//! - `statics` of examples/inclined_roller.toml: the incline's reaction P / cos 30° along its
//!   normal and the bar's −P tan 30°, the closed forms; the same numbers with the roller on a
//!   spring (the equilibrium analyses count a spring as a support);
//! - `solve` of the same scene: node 1 slides down the incline to the hand calculation's
//!   equilibrium (bisected);
//! - `solve` of a leaning bar held at its top by horizontal springs: the state built by hand
//!   to balance, the spring's force its reaction;
//! - bad directions and stiffnesses refused before any work, naming the support and its line;
//!   `simulate` refuses both keys and a support's `displacement`.

use crate::common;

use common::{assert_ok, run};

fn json(out: &std::process::Output) -> serde_json::Value {
    assert_ok(out);
    serde_json::from_slice(&out.stdout).unwrap()
}

fn stderr(out: &std::process::Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

const ROLLER: &str = "examples/inclined_roller.toml";

#[test]
fn the_inclined_roller_reacts_along_its_normal_with_the_closed_form() {
    let (p, theta) = (1000.0f64, 30f64.to_radians());
    let r = json(&run(&["statics", ROLLER, "--json"]));
    assert_eq!(
        (r["rank"].as_u64(), r["mechanisms"].as_u64()),
        (Some(1), Some(0))
    );
    let force = r["member_force"][0].as_f64().unwrap();
    assert!((force + p * theta.tan()).abs() < 1e-9 * p, "{force}");
    let roller = &r["reactions"][1];
    let normal = roller["along"][0].as_f64().unwrap();
    assert!((normal - p / theta.cos()).abs() < 1e-9 * p, "{roller}");
    assert!(
        roller["along"][1].as_f64().unwrap().abs() < 1e-9 * p,
        "{roller}"
    );
    assert!(
        (roller["force"][2].as_f64().unwrap() - p).abs() < 1e-9 * p,
        "{roller}"
    );
    // the pinned node has no `along`
    assert!(r["reactions"][0].get("along").is_none());
    // on a spring: the same forces and reactions (a spring is a support to equilibrium)
    let text = std::fs::read_to_string(ROLLER).unwrap();
    let sprung = text.replace("along = [[-0.5", "stiffness = 2e4\nalong = [[-0.5");
    let s = json(&run(&["statics", &sprung, "--json"]));
    assert_eq!(s["member_force"], r["member_force"]);
    assert_eq!(s["reactions"], r["reactions"]);
}

#[test]
fn the_inclined_roller_slides_down_to_the_hand_calculation() {
    // node 1 at (2 + s cos θ, 0, s sin θ), L = ‖·‖, T = EA (L − 2)/2; along the incline the
    // bar's −T (2 cos θ + s)/L balances the load's P sin θ = 500 N
    let (c, sn) = (30f64.to_radians().cos(), 0.5);
    let ea = 1e7 * std::f64::consts::PI * 1e-4;
    let f = |s: f64| {
        let l = ((2.0 + s * c).powi(2) + (s * sn).powi(2)).sqrt();
        -ea * (l - 2.0) / 2.0 * (2.0 * c + s) / l - 1000.0 * sn
    };
    let (mut lo, mut hi) = (-1.0, 0.0);
    assert!(f(lo) > 0.0 && f(hi) < 0.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let s = 0.5 * (lo + hi);
    assert!((s + 0.495).abs() < 1e-3, "{s}");
    let r = json(&run(&["solve", ROLLER, "--json"]));
    assert_eq!(r["final_load_factor"], 1.0);
    assert_eq!(r["limit_points"], 0);
    let points = r["path"]["points"].as_array().unwrap();
    let node = &points.last().unwrap()["nodes"][1];
    let at = |i: usize| node[i].as_f64().unwrap();
    assert!((at(0) - (2.0 + s * c)).abs() < 1e-9, "{node}");
    assert!(
        at(1).abs() < 1e-12 && (at(2) - s * sn).abs() < 1e-9,
        "{node}"
    );
}

/// A bar (E = 10 MPa, r = 1 cm) from a pin at the origin to node 1 at (1, 0, 1), node 1 on
/// springs k along x and y (`fixed = [true, true, false]`, `stiffness = k`), P down: k and P
/// chosen by hand so that node 1 balances at (1 + u, 0, 1 + w).
#[test]
fn a_leaning_bar_on_springs_reaches_the_state_built_by_hand() {
    let (u, w) = (0.22f64, -0.3f64);
    let ea = 1e7 * std::f64::consts::PI * 1e-4;
    let l0 = 2f64.sqrt();
    let (x, z) = (1.0 + u, 1.0 + w);
    let l = x.hypot(z);
    // the bar's tension T pushes node 1 along (x, 0, z)/L: −P − T z/L = 0, −k u − T x/L = 0
    let t = ea * (l - l0) / l0;
    let (p, k) = (-t * z / l, -t * x / (l * u));
    let scene = format!(
        r#"nodes = [[0.0, 0.0, 0.0], [1.0, 0.0, 1.0]]
[materials.soft]
density = 1000.0
youngs_modulus = 1e7
yield_strength = 1e6
[[bars]]
nodes = [0, 1]
material = "soft"
radius = 0.01
[[supports]]
node = 0
[[supports]]
node = 1
fixed = [true, true, false]
stiffness = {k:?}
[[loads]]
node = 1
force = [0.0, 0.0, {:?}]
"#,
        -p
    );
    let r = json(&run(&["solve", &scene, "--json"]));
    assert_eq!(r["final_load_factor"], 1.0);
    let last = r["path"]["points"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()
        .clone();
    let at = |i: usize| last["nodes"][1][i].as_f64().unwrap();
    assert!(
        (at(0) - x).abs() < 1e-9 && at(1).abs() < 1e-12,
        "{}",
        last["nodes"]
    );
    assert!((at(2) - z).abs() < 1e-9, "{}", last["nodes"]);
    // the springs' reactions: −k u along x, nothing along y
    let springs: Vec<&serde_json::Value> = last["reactions"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|r| r["node"] == 1)
        .collect();
    assert_eq!(springs.len(), 2);
    let fx = springs[0]["force"].as_f64().unwrap();
    assert!((fx + k * u).abs() < 1e-8 * k * u, "{fx} against {}", -k * u);
    assert!(springs[1]["force"].as_f64().unwrap().abs() < 1e-12);
    // statics reads the same scene (the spring a support there)
    let s = json(&run(&["statics", &scene, "--json"]));
    assert_eq!(s["mechanisms"].as_u64(), Some(0));
}

/// The inclined roller's scene with node 1's support lines replaced by `support`.
fn roller_with(support: &str) -> String {
    std::fs::read_to_string(ROLLER).unwrap().replace(
        "along = [[-0.5, 0.0, 0.8660254037844386], [0.0, 1.0, 0.0]]",
        support,
    )
}

#[test]
fn bad_directions_and_stiffnesses_are_refused_naming_the_support_and_its_line() {
    // node 1's support starts on line 27 of the example
    let line = std::fs::read_to_string(ROLLER)
        .unwrap()
        .lines()
        .position(|l| l.starts_with("node = 1"))
        .unwrap();
    let cases = [
        (
            "along = [[1.0, 1.0, 0.0]]",
            "support 1: along direction 0 [1.0, 1.0, 0.0] has norm 1.414214, not 1: give a unit vector (to 1e-6), e.g. [0.7071067811865475, 0.7071067811865475, 0.0]",
        ),
        (
            "along = [[0.0, 0.0, 0.0]]",
            "support 1: along direction 0 [0.0, 0.0, 0.0] has norm 0.000000, not 1",
        ),
        (
            "along = [[nan, 0.0, 1.0]]",
            "support 1: along direction 0 [NaN, 0.0, 1.0] is not finite",
        ),
        (
            "along = [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]",
            "support 1: along direction 1 [0.0, 0.0, -1.0] is dependent on the held directions before it",
        ),
        (
            "along = [[0.0, 0.0, 1.0]]\nstiffness = -5.0",
            "support 1: stiffness must be positive and finite, got -5",
        ),
        (
            "along = [[0.0, 0.0, 1.0]]\nstiffness = inf",
            "support 1: stiffness must be positive and finite, got inf",
        ),
        (
            "along = [[0.0, 0.0, 1.0]]\ndirections = [\"z\"]",
            "support 1: give either along (any orientation) or directions/fixed (x, y, z), not both",
        ),
    ];
    for (support, message) in cases {
        let scene = roller_with(support);
        for command in ["statics", "solve"] {
            let out = run(&[command, &scene]);
            assert_eq!(out.status.code(), Some(2), "{command} {support}");
            let err = stderr(&out);
            assert!(err.contains(message), "{command} {support}: {err}");
            assert!(err.contains(&format!("(line {})", line)), "{err}");
        }
    }
}

#[test]
fn simulate_refuses_the_support_keys_and_a_displacement() {
    let out = run(&[
        "simulate",
        &roller_with("stiffness = 1e4\nfixed = [false, false, true]"),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(
        err.contains(
            "support 1: stiffness is read by `solve`, `statics` and elastic `simulate` scenes only"
        ),
        "{err}"
    );
    let out = run(&["simulate", ROLLER]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains(
        "support 1: along is read by `solve`, `statics` and elastic `simulate` scenes only"
    ));
    // `statics` reads a support's displacement (its linear response,
    // tests/statics_response.rs); `simulate` refuses it
    let out = run(&[
        "simulate",
        &roller_with("fixed = [false, false, true]\ndisplacement = [0.0, 0.0, 0.1]"),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains(
            "support 1: displacement is read by `solve` (a load path's driver) and `statics` (its linear response) only"
        ),
        "{}",
        stderr(&out)
    );
}
