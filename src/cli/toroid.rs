//! `tensegrity toroid`: its flags are the fields of [`ToroidRequest`] ([`RequestArgs`]); one
//! library call ([`toroid::toroid_report`]) and the report printed.

use super::request_args::RequestArgs;
use anyhow::Result;
use std::path::PathBuf;
use tensegrity_io::sink::FileSink;
use toroid::{ToroidReport, ToroidRequest};

/// Arguments of `tensegrity toroid`: the request's flags ([`ToroidRequest`]) and the outputs.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("scene_strings").args(["string_stiffness"]).requires("export_scene")))]
pub struct ToroidArgs {
    #[command(flatten)]
    request: RequestArgs<ToroidRequest>,
    /// Write the structure as a scene file (for `tensegrity statics` or `simulate`); with
    /// --string-stiffness its strings are stiff and prestressed.
    #[arg(long, value_name = "FILE")]
    export_scene: Option<PathBuf>,
    /// Print JSON.
    #[arg(long)]
    json: bool,
}

/// Entry point of `tensegrity toroid`.
pub fn run_toroid(args: &ToroidArgs) -> Result<()> {
    let request: ToroidRequest = args.request.request()?;
    let _progress = super::guard::toroid(&request)?;
    let scene = super::output::open(
        "--export-scene",
        args.export_scene.as_deref(),
        FileSink::open,
    )?;
    let report = toroid::toroid_report(&request)?;
    if let Some(w) = &report.statics_warning {
        eprintln!("warning: {w}");
    }
    if let Some(sink) = scene {
        sink.finish_with(tensegrity_io::scene::to_toml(&report.structure))?;
    }
    if let (Some(path), false) = (&args.export_scene, args.json) {
        println!("wrote {}", path.display());
    }
    if args.json {
        super::output::print_json(&report)?;
    } else {
        print_toroid(&request, &report);
    }
    Ok(())
}

fn print_toroid(args: &ToroidRequest, r: &ToroidReport) {
    println!(
        "toroid n = {} ({}): {} nodes, {} bars, {} strings",
        args.wheel.params.sides, r.stabilize, r.nodes, r.bars, r.strings
    );
    println!(
        "rank {}  self-stress states {}  internal mechanisms {}",
        r.rank, r.self_stress_dim, r.internal_mechanisms
    );
    if r.prestressable {
        println!("prestressable: yes, margin {:.6}", r.prestress_margin);
    } else {
        println!("prestressable: no");
    }
    println!("mass {:.6} kg   I1 {:.6} kg m^2", r.mass_kg, r.i1);
    println!("inertia about the centre (kg m^2):");
    for row in &r.inertia {
        println!("  [{:>12.6} {:>12.6} {:>12.6}]", row[0], row[1], row[2]);
    }
    if args.rim_window {
        match r.rim_radius_window {
            Some([lo, hi]) => {
                println!("single prism prestressable for R_m in [{lo:.6}, {hi:.6}] m")
            }
            None => println!("single prism prestressable for no R_m in (0, 1.5 R_o)"),
        }
    }
    if let Some(f) = &r.prestress_member_force {
        let range = |v: &[f64]| {
            let min = v.iter().copied().fold(f64::INFINITY, f64::min);
            let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (min, max)
        };
        let (bars, strings) = (range(&f[..r.bars]), range(&f[r.bars..]));
        println!(
            "prestress design (min string tension {} N): strings {:.3}..{:.3} N, bars {:.3}..{:.3} N",
            args.min_tension, strings.0, strings.1, bars.0, bars.1
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::roll::RollArgs;
    use clap::Parser;
    use toroid::RollRequest;

    #[derive(Parser, Debug)]
    enum Cli {
        Roll(RollArgs),
        Toroid(ToroidArgs),
    }

    #[test]
    fn the_cli_defaults_are_the_library_defaults() {
        let Cli::Roll(roll) = Cli::try_parse_from(["t", "roll"]).unwrap() else {
            unreachable!()
        };
        assert_eq!(roll.request().unwrap(), RollRequest::default());
        let Cli::Toroid(t) = Cli::try_parse_from(["t", "toroid"]).unwrap() else {
            unreachable!()
        };
        assert_eq!(
            t.request.request::<ToroidRequest>().unwrap(),
            ToroidRequest::default()
        );
    }

    #[test]
    fn bad_values_are_usage_errors() {
        let err = Cli::try_parse_from(["t", "toroid", "--stabilize", "wheels"]).unwrap_err();
        assert!(err.to_string().contains("wheels"), "{err}");
        let alone = Cli::try_parse_from(["t", "toroid", "--string-stiffness", "1e4"]);
        assert!(alone.unwrap_err().to_string().contains("--export-scene"));
    }
}
