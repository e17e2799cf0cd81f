//! `tensegrity michell optimize (--planar | --cylindrical D | --spherical E) --radius-ratio RHO
//! [--complexity Q] [--joint-mass KG] [--material M] [--load W0] [--r0 R] [--json]`: the
//! mass-optimal discrete Michell truss for a fixed ratio ρ = r_q/r₀ (one call to
//! [`michell3d::optimize::optimize`]); the flags are the fields of [`MichellOptimizeRequest`].

use super::request_args::RequestArgs;
use anyhow::{Context, Result};
use michell3d::optimize::Optimum;
use michell3d::MichellOptimizeRequest;

/// Arguments of `tensegrity michell optimize`: the request's flags
/// ([`MichellOptimizeRequest`]: one of `--planar`, `--cylindrical`, `--spherical` and
/// `--radius-ratio` required).
#[derive(clap::Args, Debug)]
pub struct OptimizeArgs {
    #[command(flatten)]
    request: RequestArgs<MichellOptimizeRequest>,
    /// Print JSON instead of a readable report.
    #[arg(long)]
    pub json: bool,
}

/// Entry point of `tensegrity michell optimize`.
pub fn run(args: &OptimizeArgs) -> Result<()> {
    let request: MichellOptimizeRequest = args.request.request()?;
    let _progress = super::guard::estimated(&request)?;
    let o = request.run().context("Michell optimisation failed")?;
    if args.json {
        super::output::print_json(&o)?;
    } else {
        print!("{}", text(&o));
    }
    Ok(())
}

fn text(o: &Optimum) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "optimal discrete Michell truss, ρ = r_q/r₀ = {}",
        o.radius_ratio
    );
    let _ = writeln!(s, "  complexity q            {}", o.complexity);
    let _ = writeln!(s, "  beta, phi (rad)         {:.9}, {:.9}", o.beta, o.phi);
    let _ = writeln!(
        s,
        "  mass (kg)               {:.6} = members {:.6} + {} joints {:.6}",
        o.mass_kg, o.member_mass_kg, o.joints, o.joint_mass_kg
    );
    let _ = writeln!(
        s,
        "  normalised yield mass   {:.9} (continuum 2 ln(1/ρ) = {:.9})",
        o.normalized_yield_mass, o.continuum_normalized_mass
    );
    if let (Some(p), Some(r)) = (o.planar_mass_kg, o.mass_penalty) {
        let _ = writeln!(
            s,
            "  planar optimum (kg)     {p:.6}; mass penalty of the 3-D truss {r:.6}"
        );
    }
    s
}
