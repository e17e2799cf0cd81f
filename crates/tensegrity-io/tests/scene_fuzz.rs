//! Property tests of the scene reader: whatever the text — a valid scene with one token
//! replaced, cut short, or garbage — reading it never panics, and a rejected scene gets an
//! error that names the file. Bounded: a few hundred cases, well under a second.

use proptest::prelude::*;
use tensegrity_io::scene::Scene;

const BASE: &str = r#"nodes = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.0, 0.0]]
[materials.alu]
density = 2700.0
youngs_modulus = 60e9
yield_strength = 110e6
[[bars]]
nodes = [0, 1]
mass = 1.0
material = "alu"
[[strings]]
nodes = [0, 2]
stiffness = 100.0
rest_length = 0.9
[[supports]]
node = 0
[[loads]]
node = 1
force = [-1.0e4, 0.0, 0.0]
[gravity]
acceleration = [0.0, 0.0, -9.81]
[simulation]
t_end = 1.0
integrator = "rk45"
[ground]
stiffness = 1e5
"#;

/// Tokens a user might mistype a value into.
const TOKENS: &[&str] = &[
    "-1.0",
    "0",
    "nan",
    "inf",
    "-inf",
    "1e400",
    "\"x\"",
    "[]",
    "[0, 99]",
    "[0, 0]",
    "true",
    "-5",
    "18446744073709551616",
    "{}",
    "[[]]",
    "\"rk9\"",
    "",
];

fn check(text: &str) {
    match Scene::from_str_named(text, "fuzz.toml") {
        Ok(scene) => {
            // an accepted scene has a finite geometry
            assert!(scene
                .structure
                .nodes()
                .iter()
                .all(|n| n.iter().all(|v| v.is_finite())));
            // the dynamics tables are checked when the simulation is built: an error, never a
            // panic
            if let Ok(sim) = scene.simulation() {
                assert!(sim.settings.t_end.is_finite() && sim.settings.t_end > 0.0);
            }
        }
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.contains("fuzz.toml"), "the error names the file: {msg}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn a_value_replaced_by_a_bad_token_never_panics(
        line in 0usize..26, token in 0usize..TOKENS.len()
    ) {
        let text: Vec<String> = BASE
            .lines()
            .enumerate()
            .map(|(i, l)| match (i == line, l.split_once(" = ")) {
                (true, Some((k, _))) => format!("{k} = {}", TOKENS[token]),
                _ => l.to_string(),
            })
            .collect();
        check(&text.join("\n"));
    }

    #[test]
    fn a_truncated_scene_never_panics(cut in 0usize..BASE.len()) {
        if BASE.is_char_boundary(cut) {
            check(&BASE[..cut]);
        }
    }

    #[test]
    fn garbage_never_panics(text in "[ -~\n]{0,200}") {
        check(&text);
    }
}
