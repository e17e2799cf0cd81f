//! Property tests of the sweep-spec reader: a valid spec with one value replaced by a bad
//! token, cut short, or random text is parsed or rejected with an error — never a panic —
//! and an accepted spec has a case count within the limit. Bounded: a few hundred cases.

use proptest::prelude::*;
use sweeps::spec::Spec;

const BASE: &str = r#"study = "michell"
[fixed]
beta = "pi/6"
load = 1000.0
[axes]
cylindrical = [0.1, 0.25, 0.5]
complexity = { from = 2, to = 6, step = 1 }
azimuth = { from = 0.0, to = 1.0, steps = 3 }
[derived]
phi = "pi / complexity"
[output]
columns = ["mass_kg.yield", "normalized_yield_mass"]
"#;

const TOKENS: &[&str] = &[
    "-1",
    "0",
    "nan",
    "inf",
    "1e400",
    "\"x\"",
    "[]",
    "{}",
    "{ from = 1, to = 0, steps = 3 }",
    "{ from = 0, to = 1, step = 0 }",
    "{ from = 0, to = 1e12, step = 1e-12 }",
    "{ from = 0, to = 1, steps = 3, log = true }",
    "\"pi / (complexity - complexity)\"",
    "\"phi\"",
    "\"1 +\"",
    "true",
    "\"rigid\"",
    "18446744073709551616",
    "",
];

fn check(text: &str) {
    if let Ok(spec) = Spec::parse(text) {
        if let Ok(n) = spec.case_count() {
            for id in [0, n.saturating_sub(1)] {
                if id < n {
                    let _ = spec.case(id);
                }
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn a_value_replaced_by_a_bad_token_never_panics(
        line in 0usize..13, token in 0usize..TOKENS.len()
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
    fn a_truncated_spec_never_panics(cut in 0usize..BASE.len()) {
        if BASE.is_char_boundary(cut) {
            check(&BASE[..cut]);
        }
    }

    #[test]
    fn garbage_never_panics(text in "[ -~\n]{0,200}") {
        check(&text);
    }
}

#[test]
fn the_base_spec_is_valid() {
    let spec = Spec::parse(BASE).unwrap();
    assert_eq!(spec.case_count().unwrap(), 3 * 5 * 3);
}
