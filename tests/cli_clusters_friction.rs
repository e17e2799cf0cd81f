//! Pulley friction on clustered strings (issue 44; the capstan law t_out ≤ t_in e^{μθ},
//! `tensegrity_core::capstan`) against closed forms, through the CLI:
//!
//! - `solve` of examples/capstan.toml: while the pulley sticks, the anchored side keeps its
//!   tension; from the step where the loaded side reaches e^{μθ} times it, the pulley slips
//!   and the ratio of the two segments' tensions is e^{μθ} at every point (θ the wrap angle
//!   from the point's nodes) to 10⁻⁹;
//! - `simulate` of examples/atwood_friction.toml: the masses accelerate at
//!   a = g (m₁ − m₂ e^{μπ})/(m₁ + m₂ e^{μπ}) (second differences of the trajectory, which
//!   cancel the initial transient's velocity offset), the energy balance with the friction's
//!   work holds; above μ = ln(m₁/m₂)/π the pulley holds the weights (the string's first
//!   oscillations slip at their peaks, then it sticks): they move by the string's stretch.

use crate::common;

use common::{json, points, scratch};

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn norm(a: [f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}

/// The wrap angle at `p` of a string from `a` over `p` to `b`.
fn wrap(a: [f64; 3], p: [f64; 3], b: [f64; 3]) -> f64 {
    let (u, v) = (sub(p, a), sub(b, p));
    let c = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    norm(c).atan2(u[0] * v[0] + u[1] * v[1] + u[2] * v[2])
}

#[test]
fn the_capstan_law_holds_at_the_slip_limit_on_a_load_path() {
    let mu = 0.3;
    let r = json(&["solve", "examples/capstan.toml", "--json"]);
    assert_eq!(r["method"], "load_steps", "{r}");
    assert_eq!(r["stop"], "reached_target");
    let path = r["path"]["points"].as_array().unwrap();
    let t0 = path[0]["segment_tensions"][0][0].as_f64().unwrap();
    let (mut stuck, mut slipping) = (0, 0);
    for p in path {
        let x = points(&p["nodes"]);
        let t: Vec<f64> = p["segment_tensions"][0]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        let rho = (mu * wrap(x[1], x[0], x[2])).exp();
        match p["pulleys"][0][0].as_str().unwrap() {
            "stick" => {
                stuck += 1;
                // the anchored side does not feel the load; inside the cone
                assert!((t[0] - t0).abs() < 1e-9 * t0, "{p}");
                assert!(t[1] < rho * t[0] && t[0] < rho * t[1], "{p}");
            }
            "slip_forward" => {
                slipping += 1;
                assert!((t[1] / t[0] / rho - 1.0).abs() < 1e-9, "{t:?} vs {rho}");
                // the cluster's entry in `tensions` is its largest segment's
                assert_eq!(p["tensions"][0].as_f64().unwrap(), t[1]);
            }
            other => panic!("{other}: {p}"),
        }
        // node 2 on its vertical guide: the loaded segment's vertical pull carries the
        // weight (98.1 N) and λ P
        let lambda = p["lambda"].as_f64().unwrap();
        let e = sub(x[0], x[2]);
        let vertical = t[1] * e[2] / norm(e);
        assert!(
            (vertical - (98.1 + 200.0 * lambda)).abs() < 1e-8 * vertical,
            "{p}"
        );
    }
    // the load passes the slip limit on the way: first stuck, then slipping
    assert!(stuck >= 5 && slipping >= 5, "{stuck} {slipping}");
}

fn fall(r: &serde_json::Value) -> f64 {
    -1.0 - points(&r["final_nodes"])[1][2]
}

#[test]
fn the_atwood_machine_over_a_rough_pulley_slips_at_the_capstan_acceleration() {
    let (m1, m2, g, mu) = (3.0, 1.0, 9.81, 0.1_f64);
    let rho = (mu * std::f64::consts::PI).exp();
    let a = g * (m1 - m2 * rho) / (m1 + m2 * rho);
    let dir = scratch("clusters", "atwood_friction");
    let text = std::fs::read_to_string("examples/atwood_friction.toml").unwrap();
    // the fall at t, 2t/3 … from the same run's end time changed
    let at = |t_end: f64| {
        let scene = dir.join(format!("atwood_{t_end}.toml"));
        std::fs::write(
            &scene,
            text.replace("t_end = 0.5", &format!("t_end = {t_end}")),
        )
        .unwrap();
        json(&["simulate", scene.to_str().unwrap(), "--json"])
    };
    let (r1, r2, r3) = (at(0.3), at(0.4), at(0.5));
    for r in [&r1, &r2, &r3] {
        assert_eq!(r["valid"], true, "{r}");
        assert!(r["energy_drift"].as_f64().unwrap() < 1e-4, "{r}");
    }
    let accel = (fall(&r3) - 2.0 * fall(&r2) + fall(&r1)) / (0.1 * 0.1);
    assert!((accel / a - 1.0).abs() < 1e-4, "{accel} vs {a}");
    // far from the frictionless machine's (m1 − m2) g/(m1 + m2) = 4.905 m/s²
    assert!(accel < 0.8 * (m1 - m2) * g / (m1 + m2));
}

#[test]
fn a_rough_enough_pulley_holds_the_atwood_machine() {
    // μ = 0.5: e^{μπ} = 4.81 > m1/m2 = 3, the pulley holds: only the string's stretch
    let dir = scratch("clusters", "atwood_stick");
    let text = std::fs::read_to_string("examples/atwood_friction.toml").unwrap();
    let scene = dir.join("stick.toml");
    std::fs::write(&scene, text.replace("friction = [0.1]", "friction = [0.5]")).unwrap();
    let r = json(&["simulate", scene.to_str().unwrap(), "--json"]);
    assert_eq!(r["valid"], true, "{r}");
    // the static stretch of the heavy side: (m1 g − T0) s0/EA ≈ 14.7 N × 1 m/2.5e6 N
    assert!(fall(&r).abs() < 2e-5, "{}", fall(&r));
}
