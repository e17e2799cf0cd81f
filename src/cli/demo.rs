//! `tensegrity demo`: the statics of every bundled example scene and the toroid wheel,
//! summarised, on built-in defaults.

use anyhow::Result;
use tensegrity::EXAMPLE_SCENES;
use tensegrity_core::StaticsSettings;
use tensegrity_io::scene::Scene;
use toroid::rolling::RigidRolling;
use toroid::ToroidParams;

/// Runs the demo.
pub fn run() -> Result<()> {
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
        let r = super::statics::analyse(&scene.structure, StaticsSettings::default())?;
        let prestress = if r.prestressable {
            format!("{:.4}", r.prestress_margin)
        } else {
            "no".to_string()
        };
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
            prestress,
            mass
        );
    }
    println!("(full report of one scene: tensegrity statics examples/<scene> [--json])\n");

    let params = ToroidParams::default();
    println!("tensegrity toroid wheel: n = 8, T 0.4, t 0.3, D 0.1, R_o 1, R_i 0.6, R_m 0.8 m, bars 1 kg/m\n");
    println!(
        "{:<18} {:>5} {:>4} {:>7} {:>11} {:>9} {:>10}",
        "stabilising", "nodes", "bars", "strings", "self-stress", "internal", "prestress"
    );
    for options in ["none", "spokes", "spokes,inner", "inner,outer"] {
        let t = toroid::build(&params, options.parse()?, 1.0)?;
        let a = toroid::analyse(&t)?;
        let prestress = if a.prestressable {
            format!("{:.4}", a.prestress_margin)
        } else {
            "no".to_string()
        };
        println!(
            "{:<18} {:>5} {:>4} {:>7} {:>11} {:>9} {:>10}",
            options,
            a.nodes,
            a.bars,
            a.strings,
            a.self_stress_dim,
            a.internal_mechanisms,
            prestress
        );
    }
    println!("\nrigid rolling down 50 deg for 5 s (the bumps shrink with n, thesis Fig. 3.10):");
    for n in [8, 12, 16, 24] {
        let t = toroid::build(&params.sides(n), "spokes,inner".parse()?, 1.0)?;
        let a = toroid::analyse(&t)?;
        let r = RigidRolling::of(&t, &a, 50f64.to_radians()).run(5.0)?;
        println!(
            "  n = {n:>2}: mass {:>7.3} kg, I1 {:>7.3} kg m^2, axle oscillation {:.5} m, mean speed {:.3} m/s",
            a.mass_kg, a.i1, r.axle_height_oscillation, r.mean_speed
        );
    }
    Ok(())
}
