//! `tensegrity demo`: the statics of every bundled example scene and the toroid wheel,
//! summarised, on built-in defaults (library calls only).

use anyhow::Result;
use tensegrity::EXAMPLE_SCENES;
use tensegrity_core::{statics_report, StaticsRequest};
use tensegrity_io::scene::Scene;
use toroid::{FidelityChoice, RollRequest, ToroidRequest, WheelSpec};

/// Runs the demo.
pub fn run() -> Result<()> {
    scenes()?;
    wheels()?;
    rolling()
}

fn margin(prestressable: bool, margin: f64) -> String {
    if prestressable {
        format!("{margin:.4}")
    } else {
        "no".to_string()
    }
}

fn scenes() -> Result<()> {
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
    );
    for (name, text) in EXAMPLE_SCENES {
        let scene = Scene::from_str_named(text, name)?;
        let r = statics_report(&scene.structure, &StaticsRequest::default())?;
        let mass = r.mass_kg.map_or("-".to_string(), |m| format!("{m:.6}"));
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
    println!("(full report of one scene: tensegrity statics examples/<scene> [--json])\n");
    Ok(())
}

fn wheels() -> Result<()> {
    println!("tensegrity toroid wheel: n = 8, T 0.4, t 0.3, D 0.1, R_o 1, R_i 0.6, R_m 0.8 m, bars 1 kg/m\n");
    println!(
        "{:<18} {:>5} {:>4} {:>7} {:>11} {:>9} {:>10}",
        "stabilising", "nodes", "bars", "strings", "self-stress", "internal", "prestress"
    );
    for options in ["none", "spokes", "spokes,inner", "inner,outer"] {
        let request = ToroidRequest {
            wheel: WheelSpec {
                stabilize: options.parse()?,
                ..WheelSpec::default()
            },
            ..ToroidRequest::default()
        };
        let a = toroid::toroid_report(&request)?;
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
    Ok(())
}

fn rolling() -> Result<()> {
    println!("\nrolling down 50 deg from rest on a side (thesis Fig. 3.10; * = not valid, see `tensegrity roll`):");
    let rigid = RollRequest {
        fidelity: FidelityChoice::Rigid,
        t_end: 5.0,
        ..RollRequest::default()
    };
    let mut runs = toroid::rolling_series(&rigid, &toroid::defaults::FIG_3_10_SIDES)?;
    // the full model is slower: the reference wheel only, for 2 s
    let full = RollRequest {
        fidelity: FidelityChoice::Full,
        t_end: 2.0,
        ..RollRequest::default()
    };
    runs.push(toroid::roll(&full)?);
    for r in &runs {
        println!(
            "  {:<5} n = {:>2}, {} s: mass {:>7.3} kg, I1 {:>7.3} kg m^2, mean axle height {:.4} m, mean speed {:.3} m/s, airborne {:>5.1} %{}",
            format!("{:?}", r.fidelity).to_lowercase(),
            r.sides,
            r.t_end,
            r.mass_kg,
            r.i1,
            r.summary.mean_axle_height,
            r.summary.mean_speed,
            100.0 * r.summary.airborne_fraction,
            if r.summary.valid { "" } else { " *" }
        );
    }
    for r in runs.iter().filter(|r| !r.summary.valid) {
        println!("  * n = {}: {}", r.sides, r.summary.warnings.join("; "));
    }
    Ok(())
}
