//! Issue 26, item 3: every flag of every command is validated by the same rules as its sibling
//! commands. Table-driven: the same bad value fed to every sibling that takes the flag gives
//! the same refusal (exit 2, `invalid value for --FLAG: …` with the same rule text), and the
//! requests' parameter descriptions agree on the rule of every parameter they share.
//!
//! Siblings: the rolling commands (`roll`, `tbar roll`, `tipover --dynamic`,
//! `tipover --rolling`, `fig-rolling`), the toroid wheel's commands (`toroid`, `roll`,
//! `tipover` in its three modes), the Michell-parameterised ones (`michell`,
//! `michell optimize`, `tbar`, `tbar roll`), and `simulate`'s flags against the scene's
//! `[simulation]` table.

use crate::common;

use common::scratch;
use std::collections::BTreeMap;
use tensegrity_core::request::{Param, Params};

/// The parameters of a registered command.
fn registered(name: &str) -> Vec<Param> {
    tensegrity_engine::command(name)
        .unwrap_or_else(|| panic!("no command {name}"))
        .params()
}

/// Parameters that mean the same under another name in a sibling (the T-bar's `mu_static` is
/// the toroid's `mu`).
fn canonical(name: &str) -> &str {
    match name {
        "mu_static" => "mu",
        other => other,
    }
}

/// Parameters that differ between siblings on purpose: none since the T-bar's rolling took
/// `auto` (its `fidelity` now has the choices of `roll`).
const DIFFERENT_ON_PURPOSE: &[&str] = &[];

/// Every parameter shared by two siblings of `group` has the same kind, unit and rule.
fn same_rules(group: &[(&str, Vec<Param>)]) -> Vec<String> {
    let mut seen: BTreeMap<&str, (&str, Param)> = BTreeMap::new();
    let mut differ = Vec::new();
    for (command, params) in group {
        for p in params {
            match seen.get(canonical(p.name)) {
                None => {
                    seen.insert(canonical(p.name), (command, *p));
                }
                Some((first, q)) => {
                    let same = (p.kind, p.unit, p.rule) == (q.kind, q.unit, q.rule)
                        || DIFFERENT_ON_PURPOSE.contains(&p.name);
                    if !same {
                        differ.push(format!(
                            "`{}`: {first} has {:?} {:?} [{}], {command} has {:?} {:?} [{}]",
                            p.name, q.kind, q.rule, q.unit, p.kind, p.rule, p.unit
                        ));
                    }
                }
            }
        }
    }
    differ
}

#[test]
fn sibling_requests_share_the_rule_of_every_shared_parameter() {
    let rolling = [
        ("roll", registered("roll")),
        ("tbar_roll", registered("tbar_roll")),
        ("tipover_dynamic", registered("tipover_dynamic")),
        ("tipover_rolling", registered("tipover_rolling")),
        (
            "fig_rolling",
            tensegrity_figures::rolling::FigRollingRequest::params(),
        ),
    ];
    let wheel = [
        ("toroid", registered("toroid")),
        ("roll", registered("roll")),
        ("tipover", registered("tipover")),
        ("tipover_dynamic", registered("tipover_dynamic")),
        ("tipover_rolling", registered("tipover_rolling")),
    ];
    let michell = [
        ("michell", registered("michell")),
        ("michell_optimize", registered("michell_optimize")),
        ("tbar", registered("tbar")),
        ("tbar_roll", registered("tbar_roll")),
    ];
    let mut differ = Vec::new();
    for group in [&rolling[..], &wheel[..], &michell[..]] {
        differ.extend(same_rules(group));
    }
    assert!(differ.is_empty(), "{}", differ.join("\n"));
}

/// The sibling commands with the arguments each needs to run.
fn rolling_siblings(svg: &str) -> Vec<(&'static str, Vec<String>)> {
    let v = |a: &[&str]| a.iter().map(|s| s.to_string()).collect::<Vec<_>>();
    vec![
        ("roll", v(&["roll"])),
        (
            "tbar roll",
            v(&["tbar", "roll", "--beta", "pi/6", "--cylindrical", "0.25"]),
        ),
        ("tipover --dynamic", v(&["tipover", "--dynamic"])),
        ("tipover --rolling", v(&["tipover", "--rolling"])),
        ("fig-rolling", v(&["fig-rolling", "--out", svg])),
        ("toroid", v(&["toroid"])),
        ("tipover", v(&["tipover"])),
        (
            "michell",
            v(&[
                "michell",
                "--complexity",
                "3",
                "--beta",
                "pi/6",
                "--phi",
                "pi/8",
            ]),
        ),
        (
            "michell optimize",
            v(&["michell", "optimize", "--radius-ratio", "0.25"]),
        ),
        ("tbar", v(&["tbar", "--beta", "pi/6", "--phi", "pi/8"])),
    ]
}

/// The long flags `tensegrity ARGS --help` lists.
fn flags_of(args: &[String]) -> Vec<String> {
    let mut a: Vec<&str> = args
        .iter()
        .map(String::as_str)
        .take_while(|w| !w.starts_with("--"))
        .collect();
    a.push("--help");
    let out = common::run(&a);
    String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .filter(|w| w.starts_with("--"))
        .map(|w| w.trim_end_matches(',').to_string())
        .collect()
}

/// The same bad value fed to every sibling that takes the flag is refused the same way: exit
/// 2, nothing computed, `invalid value for FLAG: RULE` with one RULE text for all of them.
#[test]
fn every_sibling_refuses_the_same_bad_value_the_same_way() {
    let dir = scratch("siblings", "flags");
    let svg = dir.join("x.svg").display().to_string();
    let siblings = rolling_siblings(&svg);
    let flags: Vec<Vec<String>> = siblings.iter().map(|(_, a)| flags_of(a)).collect();
    let bad: &[(&str, &str)] = &[
        ("--restitution", "2"),
        ("--restitution", "-0.1"),
        ("--incline", "90deg"),
        ("--incline", "-1deg"),
        ("--t-end", "0"),
        ("--t-end", "-1"),
        ("--t-end", "nan"),
        ("--t-end", "inf"),
        ("--dt", "0"),
        ("--dt", "-1e-3"),
        ("--mu", "-1"),
        ("--mu-static", "-1"),
        ("--string-stiffness", "0"),
        ("--ground-stiffness", "0"),
        ("--ground-damping", "-5"),
        ("--gravity", "0"),
        ("--gravity", "-9.81"),
        ("--min-tension", "0"),
        ("--output-dt", "0"),
        ("--side-slope", "90deg"),
        ("--sides", "2"),
        ("--outer-radius", "-1"),
        ("--inner-radius", "1.5"),
        ("--outer-tread", "0"),
        ("--bar-density", "0"),
        ("--treads", "2"),
        ("--complexity", "0"),
        ("--cylindrical", "nan"),
        ("--r0", "0"),
    ];
    let mut differ = Vec::new();
    let mut checked = 0;
    for (flag, value) in bad {
        let mut rules: BTreeMap<String, Vec<&str>> = BTreeMap::new();
        for ((name, args), have) in siblings.iter().zip(&flags) {
            if !have.iter().any(|f| f == flag) {
                continue;
            }
            let mut a: Vec<&str> = args.iter().map(String::as_str).collect();
            match a.iter().position(|w| w == flag) {
                Some(i) => a[i + 1] = value, // a flag the sibling needs anyway
                None => a.extend([*flag, *value]),
            }
            let out = common::run(&a);
            let err = String::from_utf8_lossy(&out.stderr).to_string();
            if err.contains("required arguments were not provided") {
                continue; // the flag needs another (toroid's `--export-scene` options)
            }
            assert_eq!(out.status.code(), Some(2), "{a:?}: {err}");
            assert!(out.stdout.is_empty(), "{a:?} printed a report");
            let prefix = format!("error: invalid value for {flag}: ");
            let rule = err
                .lines()
                .next()
                .and_then(|l| l.strip_prefix(&prefix))
                .unwrap_or_else(|| panic!("{a:?}: not `{prefix}…`: {err}"));
            if rule.contains("does not apply to") {
                continue; // a flag of another mode of `tipover`: refused as such
            }
            rules.entry(rule.to_string()).or_default().push(name);
            checked += 1;
        }
        if rules.len() > 1 {
            differ.push(format!("{flag} {value}: {rules:?}"));
        }
    }
    assert!(differ.is_empty(), "{}", differ.join("\n"));
    assert!(
        checked >= 60,
        "only {checked} (command, flag) pairs checked"
    );
}

/// `simulate`'s flags and the scene's `[simulation]` keys take the same rules: a bad value
/// is refused both ways (exit 2), the flag by its name, the key by its name and line.
#[test]
fn simulate_flags_and_scene_settings_take_the_same_rules() {
    let dir = scratch("siblings", "simulate");
    let base = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/prism_drop.toml"),
    )
    .unwrap();
    for (key, flag, value) in [
        ("t_end", "--t-end", "0"),
        ("t_end", "--t-end", "-1"),
        ("dt", "--dt", "0"),
        ("dt", "--dt", "-1e-3"),
        ("rtol", "--rtol", "0"),
        ("atol", "--atol", "-1"),
        ("output_interval", "--output-interval", "0"),
    ] {
        let by_flag = common::run(&["simulate", "examples/prism_drop.toml", flag, value]);
        let err = String::from_utf8_lossy(&by_flag.stderr);
        assert_eq!(by_flag.status.code(), Some(2), "{flag} {value}: {err}");
        assert!(err.contains(flag), "{flag} {value}: {err}");
        // the same value in the scene's table (the key replaced or added)
        let mut text = String::new();
        let mut set = false;
        for line in base.lines() {
            if line.starts_with(&format!("{key} =")) {
                text += &format!("{key} = {value}\n");
                set = true;
            } else {
                text += line;
                text.push('\n');
                if line == "[simulation]" && !base.contains(&format!("\n{key} =")) {
                    text += &format!("{key} = {value}\n");
                    set = true;
                }
            }
        }
        assert!(set, "{key}");
        let scene = dir.join(format!("{key}.toml"));
        std::fs::write(&scene, text).unwrap();
        let by_scene = common::run(&["simulate", scene.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&by_scene.stderr);
        assert_eq!(by_scene.status.code(), Some(2), "{key} = {value}: {err}");
        assert!(err.contains(key), "{key} = {value}: {err}");
    }
}
