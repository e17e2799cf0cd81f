//! `tensegrity demo`: the statics of every bundled example scene, summarised.

use anyhow::Result;
use tensegrity::EXAMPLE_SCENES;
use tensegrity_core::scene::Scene;
use tensegrity_core::StaticsSettings;

/// Runs the demo on the built-in example scenes.
pub fn run() -> Result<()> {
    println!("tensegrity demo: statics of the bundled example scenes\n");
    println!(
        "{:<18} {:>5} {:>4} {:>7} {:>4} {:>11} {:>9} {:>12} {:>10}",
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
        let r = super::statics::analyse(&scene.structure, StaticsSettings::default())?;
        let prestress = if r.prestressable {
            format!("{:.4}", r.prestress_margin)
        } else {
            "no".to_string()
        };
        let mass = r.mass_kg.map_or("-".to_string(), |m| format!("{m:.6}"));
        println!(
            "{:<18} {:>5} {:>4} {:>7} {:>4} {:>11} {:>9} {:>12} {:>10}",
            name,
            r.nodes,
            r.bars,
            r.strings,
            r.rank,
            r.self_stress_dim,
            r.internal_mechanisms,
            prestress,
            mass
        );
    }
    println!(
        "\nrun `tensegrity statics examples/<scene> [--json]` for the full report of one scene"
    );
    Ok(())
}
