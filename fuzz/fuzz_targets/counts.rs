//! Fuzz target: counts (issue 42). The other targets mutate text, which seldom yields a huge
//! number; this one builds inputs around fuzzed counts — a topology's `n_nodes` and member
//! count, a sweep axis's length and span, the size of a built-in form, a toroid's sides —
//! and runs them the way the front ends do: read, estimate, and run only what the estimate
//! admits within small limits. Any count must be refused by name or estimated before
//! anything of its size is allocated: an abort, an out-of-memory (libFuzzer's
//! `-rss_limit_mb`), a panic or a slow input is a finding.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sweeps::Spec;
use tensegrity_core::budget::Limits;

/// What a case may cost to be run here (an estimate above it is refused, as a front end
/// refuses it over its limits).
const LIMITS: Limits = Limits {
    memory_bytes: 256.0 * 1024.0 * 1024.0,
    work_s: 0.05,
    output_bytes: 1e6,
};

fn count(bytes: &[u8]) -> u64 {
    let mut b = [0u8; 8];
    for (i, x) in bytes.iter().take(8).enumerate() {
        b[i] = *x;
    }
    // many small counts and a few huge ones
    let raw = u64::from_le_bytes(b);
    match b[7] % 4 {
        0 => raw % 64,
        1 => raw % 100_000,
        2 => raw % 10_000_000_000_000,
        _ => raw,
    }
}

/// A topology of `n_nodes` nodes and a chain of `members` strings (at most 64 written).
fn topology(n_nodes: u64, members: u64) -> String {
    let mut text = format!("n_nodes = {n_nodes}\nfixed = [0]\n");
    for k in 0..members.min(64) {
        text.push_str(&format!(
            "[[strings]]\nnodes = [{k}, {}]\nforce_density = 1.0\n",
            k + 1
        ));
    }
    text
}

/// Reads, estimates and (when admitted) runs a topology.
fn run_topology(text: &str) {
    let Ok(t) = tensegrity_io::topology::from_str_named(text, "fuzz.toml") else {
        return;
    };
    let settings = formfind::Settings::default();
    if LIMITS.check(&formfind::estimate(&t, &settings)).is_ok() {
        let _ = formfind::form_find(&t, &settings);
    }
}

/// Parses a sweep spec, counts and estimates its first and last cases, and runs the first
/// when admitted.
fn run_spec(text: &str) {
    let Ok(spec) = Spec::parse(text) else {
        return;
    };
    let Ok(n) = spec.case_count() else {
        return;
    };
    for id in [0, n.saturating_sub(1)] {
        if let Ok(params) = spec.case(id).params {
            let _ = spec.study.estimate(params);
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&kind, rest)) = data.split_first() else {
        return;
    };
    let a = count(rest);
    let b = count(rest.get(8..).unwrap_or(&[]));
    match kind % 5 {
        0 => run_topology(&topology(a, b)),
        // a sweep axis of `a` values over a span of `b`
        1 => run_spec(&format!(
            "study = \"toroid\"\n[axes]\nouter_radius = {{ from = 1.0, to = {}.0, steps = {a} }}\n",
            b.max(2)
        )),
        // a built-in form of size a (and b)
        2 => run_spec(&format!(
            "study = \"formfind\"\n[fixed]\nbuiltin = \"{}\"\n",
            match b % 3 {
                0 => format!("prism:{a}"),
                1 => format!("grid:{a}"),
                _ => format!("tower:{a}:{}", b % 1000),
            }
        )),
        // a toroid of `a` sides, a Michell truss and a T-bar of complexity `a`
        3 => run_spec(&format!(
            "study = \"{}\"\n[fixed]\n{} = {a}\n",
            ["toroid", "michell", "tbar"][(b % 3) as usize],
            ["sides", "complexity", "complexity"][(b % 3) as usize]
        )),
        // an axis of `a` explicit steps of a count parameter
        _ => run_spec(&format!(
            "study = \"formfind\"\n[fixed]\nbuiltin = \"prism\"\n[axes]\nn = {{ from = 3, to = {}, step = 1 }}\n",
            a.max(3)
        )),
    }
});
