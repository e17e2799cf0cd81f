//! `tensegrity demo`: the statics of every bundled example scene and the toroid wheel,
//! summarised, on built-in defaults (library calls only); `--json`: the same as one object
//! (`scenes`, `wheels`, `rolling`, each a list of rows with the commands' own keys).

use anyhow::Result;
use serde_json::{json, Value};
use tensegrity::EXAMPLE_SCENES;
use tensegrity_io::scene::Scene;
use tensegrity_statics::{statics_report, StaticsRequest};
use toroid::{FidelityChoice, RollRequest, ToroidRequest, WheelSpec};

/// Arguments of `tensegrity demo`.
#[derive(clap::Args, Debug)]
pub struct DemoArgs {
    /// Print the results as one JSON object instead of tables.
    #[arg(long)]
    pub json: bool,
}

/// Runs the demo.
pub fn run(args: &DemoArgs) -> Result<()> {
    let text = !args.json;
    let report = json!({
        "scenes": scenes(text)?,
        "wheels": wheels(text)?,
        "rolling": rolling(text)?,
    });
    if args.json {
        super::output::print_json(&report)?;
    }
    Ok(())
}

fn margin(prestressable: bool, margin: f64) -> String {
    if prestressable {
        format!("{margin:.4}")
    } else {
        "no".to_string()
    }
}

fn scenes(text: bool) -> Result<Vec<Value>> {
    let mut rows = Vec::new();
    text.then(|| {
        println!("tensegrity demo: statics of the bundled example scenes\n");
        println!(
            "{:<18} {:>5} {:>4} {:>7} {:>4} {:>11} {:>9} {:>10} {:>10}",
            "scene",
            "nodes",
            "bars",
            "strings",
            "rank",
            "self-stress",
            "internal",
            "prestress",
            "mass [kg]"
        )
    });
    for (name, toml) in EXAMPLE_SCENES {
        let scene = Scene::from_str_named(toml, name)?;
        let r = statics_report(&scene.structure, &StaticsRequest::default())?;
        let mass = r.mass_kg.map_or("-".to_string(), |m| format!("{m:.6}"));
        rows.push(
            json!({"scene": name, "nodes": r.nodes, "bars": r.bars, "strings": r.strings,
            "rank": r.rank, "self_stress_dim": r.self_stress_dim,
            "internal_mechanisms": r.internal_mechanisms, "prestressable": r.prestressable,
            "prestress_margin": r.prestress_margin, "mass_kg": r.mass_kg}),
        );
        if !text {
            continue;
        }
        println!(
            "{:<18} {:>5} {:>4} {:>7} {:>4} {:>11} {:>9} {:>10} {:>10}",
            name,
            r.nodes,
            r.bars,
            r.strings,
            r.rank,
            r.self_stress_dim,
            r.internal_mechanisms,
            margin(r.prestressable, r.prestress_margin),
            mass
        );
    }
    text.then(|| {
        println!("(full report of one scene: tensegrity statics examples/<scene> [--json])\n")
    });
    Ok(rows)
}

fn wheels(text: bool) -> Result<Vec<Value>> {
    let mut rows = Vec::new();
    if text {
        println!("tensegrity toroid wheel: n = 8, T 0.4, t 0.3, D 0.1, R_o 1, R_i 0.6, R_m 0.8 m, bars 1 kg/m\n");
        println!(
            "{:<18} {:>5} {:>4} {:>7} {:>11} {:>9} {:>10}",
            "stabilising", "nodes", "bars", "strings", "self-stress", "internal", "prestress"
        );
    }
    for options in ["none", "spokes", "spokes,inner", "inner,outer"] {
        let request = ToroidRequest {
            wheel: WheelSpec {
                stabilize: options.parse()?,
                ..WheelSpec::default()
            },
            ..ToroidRequest::default()
        };
        let a = toroid::toroid_report(&request)?;
        rows.push(
            json!({"stabilize": options, "nodes": a.nodes, "bars": a.bars,
            "strings": a.strings, "self_stress_dim": a.self_stress_dim,
            "internal_mechanisms": a.internal_mechanisms, "prestressable": a.prestressable,
            "prestress_margin": a.prestress_margin}),
        );
        if !text {
            continue;
        }
        println!(
            "{:<18} {:>5} {:>4} {:>7} {:>11} {:>9} {:>10}",
            options,
            a.nodes,
            a.bars,
            a.strings,
            a.self_stress_dim,
            a.internal_mechanisms,
            margin(a.prestressable, a.prestress_margin)
        );
    }
    Ok(rows)
}

fn rolling(text: bool) -> Result<Vec<Value>> {
    text.then(|| println!("\nrolling down 50 deg from rest on a side (thesis Fig. 3.10; * = not valid, see `tensegrity roll`):"));
    let rigid = RollRequest {
        fidelity: FidelityChoice::Rigid,
        t_end: 5.0,
        ..RollRequest::default()
    };
    let mut runs = toroid::rolling_series(&rigid, &toroid::defaults::FIG_3_10_SIDES)?;
    // the full model is slower: the reference wheel only, for 2 s, at half its default step
    // (there every headline quantity but the final speed converges)
    let mut full = RollRequest {
        fidelity: FidelityChoice::Full,
        t_end: 2.0,
        ..RollRequest::default()
    };
    full.settings.dt = Some(DEMO_FULL_DT);
    runs.push(toroid::roll(&full)?);
    let rows = runs
        .iter()
        .map(|r| {
            json!({"fidelity": r.fidelity.name(), "sides": r.sides,
        "t_end": r.t_end, "mass_kg": r.mass_kg, "i1": r.i1,
        "mean_axle_height": r.summary.mean_axle_height, "mean_speed": r.summary.mean_speed,
        "airborne_fraction": r.summary.airborne_fraction, "valid": r.summary.valid,
        "chaotic": r.summary.convergence.as_ref().map(|c| c.chaotic()),
        "warnings": r.summary.warnings})
        })
        .collect();
    if !text {
        return Ok(rows);
    }
    print_rows(&runs);
    for r in runs.iter().filter(|r| !r.summary.valid) {
        let why: Vec<String> = r.summary.warnings.iter().map(short).collect();
        println!("  * n = {}: {}", r.sides, why.join("; "));
    }
    Ok(rows)
}

/// One line per rolling run, `~` after a number that is a chaotic single draw, and the line
/// that explains the mark.
fn print_rows(runs: &[toroid::RollReport]) {
    for r in runs {
        let draw = |name: &str| if chaotic(r, name) { "~" } else { " " };
        println!(
            "  {:<5} n = {:>2}, {} s: mass {:>7.3} kg, I1 {:>7.3} kg m^2, mean axle height {:.4} m{}, mean speed {:.3} m/s{}, airborne {:>5.1} %{}{}",
            format!("{:?}", r.fidelity).to_lowercase(),
            r.sides,
            r.t_end,
            r.mass_kg,
            r.i1,
            r.summary.mean_axle_height,
            draw("mean_axle_height"),
            r.summary.mean_speed,
            draw("mean_speed"),
            100.0 * r.summary.airborne_fraction,
            draw("airborne_fraction").trim_end(),
            if r.summary.valid { "" } else { " *" }
        );
    }
    if runs.iter().any(|r| {
        ["mean_axle_height", "mean_speed", "airborne_fraction"]
            .iter()
            .any(|q| chaotic(r, q))
    }) {
        println!("  ~ a single draw of the chaotic hops (a start turned by 1e-6 rad moves it): `tensegrity roll` prints the 95 % interval of another run, `--ensemble 8` a tighter one");
    }
}

/// The step of the demo's full-model row (s): half the full model's default.
const DEMO_FULL_DT: f64 = 1.25e-4;

/// Whether the convergence check found `quantity` of run `r` chaotic (a single draw).
fn chaotic(r: &toroid::RollReport, quantity: &str) -> bool {
    r.summary.convergence.as_ref().is_some_and(|c| {
        c.quantities.iter().any(|q| {
            q.name == quantity && q.status == tensegrity_dynamics::convergence::Status::Chaotic
        })
    })
}

/// A warning in a few words (the demo's rows stay one line each; `roll` gives the full text).
fn short(w: &tensegrity_core::Warning) -> String {
    use tensegrity_core::Warning as W;
    match w {
        W::NotConverged {
            quantity,
            relative_change: Some(r),
            ..
        } => format!("{quantity} moved {:.1} % at the refined step", 100.0 * r),
        W::NotConverged { quantity, .. } => format!("{quantity} changed at the refined step"),
        other => other.kind().replace('_', " "),
    }
}
