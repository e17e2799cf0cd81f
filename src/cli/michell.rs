//! `tensegrity michell`: a planar or 3-D discrete Michell truss under a tip load — member
//! forces, member types, masses (thesis chapter 4, ERRATA ch. 4).
//!
//! ```text
//! tensegrity michell --complexity Q (--planar | --cylindrical DELTA | --spherical EPS)
//!     --beta B --phi P [--r0 R] [--load W0] [--azimuth A] [--polar G] [--material NAME]
//!     [--extra-strings PRESTRESS|auto] [--method recursive|global] [--json]
//! ```
//!
//! The flags are the fields of [`MichellRequest`] ([`RequestArgs`]); one library call
//! ([`MichellRequest::run`]) and the report printed ([`super::michell_text`]).

use anyhow::{Context, Result};
use michell3d::MichellRequest;

mod args;
mod grids;
pub use args::{MichellAction, MichellArgs, MichellTableArgs};
pub use grids::run_table;
use grids::{open_outputs, write_gamma_sweep, write_sign_maps};

/// Runs `tensegrity michell`: one analysis (the truss is built once and reused by the sign
/// maps and the γ sweep).
pub fn run(args: &MichellArgs) -> Result<()> {
    if let Some(MichellAction::Optimize(opt)) = &args.action {
        return super::michell_optimize::run(opt);
    }
    let _progress = guard(args)?;
    let request: MichellRequest = args.request.request()?;
    let (sign_map, gamma_sweep) = open_outputs(args)?;
    let drawing = args.figure.open("--svg", args.svg.as_deref())?;
    let run = request.run().context("michell truss analysis failed")?;
    if args.json {
        super::output::print_json(&run)?;
    } else {
        print!("{}", super::michell_text::report(&run));
    }
    if let Some(sink) = drawing {
        let nodes: Vec<_> = run
            .analysis
            .truss
            .nodes()
            .iter()
            .map(|n| n.position)
            .collect();
        let style = args
            .drawing
            .style(tensegrity_figures::draw::default_view(&nodes));
        sink.finish(&tensegrity_figures::structures::michell_figure(
            &run.analysis,
            &style,
        ))?;
    }
    if let Some(sink) = sign_map {
        write_sign_maps(args, &run.request, &run.analysis.truss, sink)?;
    }
    if let (Some(sink), Some(prestress)) = (gamma_sweep, run.request.extra_strings) {
        write_gamma_sweep(args, &run.request, &run.analysis.truss, prestress, sink)?;
    }
    Ok(())
}

/// The resource guard of `tensegrity michell` ([`super::guard`]): the sign maps, if asked for.
fn guard(args: &MichellArgs) -> Result<super::guard::Progress> {
    let members = args.map_members.len();
    super::guard::sign_map(args.map_grid, members, args.sign_map.is_some())
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(Parser, Debug)]
    struct Cli {
        #[command(flatten)]
        args: MichellArgs,
    }

    fn parse(argv: &[&str]) -> Result<MichellArgs, clap::Error> {
        let mut all = vec!["michell"];
        all.extend_from_slice(argv);
        Cli::try_parse_from(all).map(|c| c.args)
    }

    fn request(argv: &[&str]) -> MichellRequest {
        parse(argv).unwrap().request.request().unwrap()
    }

    #[test]
    fn parses_the_documented_flags() {
        let argv = "--complexity 4 --cylindrical 0.25 --beta pi/6 --phi 22.5deg --azimuth -pi/4 \
                    --polar 3pi/4 --method global --json";
        let r = request(&argv.split_whitespace().collect::<Vec<_>>());
        assert_eq!((r.complexity, r.cylindrical), (Some(4), Some(0.25)));
        assert!((r.phi.unwrap() - std::f64::consts::PI / 8.0).abs() < 1e-15);
        assert!((r.azimuth + std::f64::consts::FRAC_PI_4).abs() < 1e-15);
        assert_eq!((r.r0, r.load, r.material.as_str()), (1.0, 1000.0, "steel"));
        assert_eq!(r.method, michell3d::Method::Global);
        assert!(michell3d::analyse(&r.analysis()).is_ok());
    }

    #[test]
    fn geometry_is_required_and_exclusive() {
        let base = ["--complexity", "2", "--beta", "pi/6", "--phi", "pi/8"];
        assert!(parse(&base)
            .unwrap_err()
            .to_string()
            .contains("give one of planar"));
        let mut both = base.to_vec();
        both.extend(["--planar", "--spherical", "pi/24"]);
        let e = parse(&both).unwrap_err().to_string();
        assert!(e.contains("--planar") && e.contains("spherical"), "{e}");
        let mut planar = base.to_vec();
        planar.push("--planar");
        let r = michell3d::analyse(&request(&planar).analysis()).unwrap();
        assert_eq!(r.members.len(), 6);
        assert!(super::super::michell_text::report_text(&r).contains("planar"));
        let mut bad = base.to_vec();
        bad.extend(["--cylindrical", "0"]);
        let err = michell3d::analyse(&request(&bad).analysis()).unwrap_err();
        assert!(err.to_string().contains("delta"));
        assert!(parse(&["--planar", "--beta", "1", "--phi", "1"]).is_err());
    }
}
