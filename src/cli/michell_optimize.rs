//! `tensegrity michell optimize (--planar | --cylindrical D | --spherical E) --radius-ratio RHO
//! [--complexity Q] [--joint-mass KG] [--material M] [--load W0] [--r0 R] [--json]`: the
//! mass-optimal discrete Michell truss for a fixed ratio ρ = r_q/r₀ (one call to
//! [`michell3d::optimize::optimize`]).

use crate::cli::angle::parse_angle;
use anyhow::{Context, Result};
use clap::ArgGroup;
use michell3d::optimize::{optimize, OptimizeRequest, Optimum};
use michell3d::Geometry;

/// Arguments of `tensegrity michell optimize`.
#[derive(clap::Args, Debug)]
#[command(group(
    ArgGroup::new("family")
        .required(true)
        .args(["planar", "cylindrical", "spherical"])
))]
pub struct OptimizeArgs {
    /// Skelton's planar truss (yield sizing).
    #[arg(long)]
    pub planar: bool,
    /// 3-D truss, cylindrical offset δ (yield + buckling sizing).
    #[arg(long, value_name = "D", allow_hyphen_values = true, value_parser = super::values::finite)]
    pub cylindrical: Option<f64>,
    /// 3-D truss, spherical angle ε, e.g. `pi/24` (yield + buckling sizing).
    #[arg(long, value_name = "E", value_parser = parse_angle, allow_hyphen_values = true)]
    pub spherical: Option<f64>,
    /// ρ = r_q / r₀ in (0, 1): the support circle over the tip radius.
    #[arg(long, value_name = "RHO", value_parser = super::values::finite)]
    pub radius_ratio: f64,
    /// The complexity q; optimised when left out (then --joint-mass is needed).
    #[arg(long, value_name = "Q")]
    pub complexity: Option<usize>,
    /// Mass of each joint (kg), added per node.
    #[arg(long, value_name = "KG", default_value_t = 0.0, value_parser = super::values::non_negative)]
    pub joint_mass: f64,
    /// Largest complexity the search tries.
    #[arg(long, value_name = "Q", default_value_t = 60)]
    pub max_complexity: usize,
    /// Material of bars and strings.
    #[arg(long, value_name = "M", default_value = "steel")]
    pub material: String,
    /// Tip load w₀ (N), perpendicular to the tip radius (−ι̂₃).
    #[arg(long, value_name = "W0", default_value_t = 1000.0, value_parser = super::values::positive)]
    pub load: f64,
    /// Initial (tip) radius r₀ (m).
    #[arg(long, value_name = "R", default_value_t = 1.0, value_parser = super::values::positive)]
    pub r0: f64,
    /// Print JSON instead of a readable report.
    #[arg(long)]
    pub json: bool,
}

impl OptimizeArgs {
    /// The request the arguments describe.
    pub fn request(&self) -> OptimizeRequest {
        let geometry = match (self.cylindrical, self.spherical) {
            (Some(delta), _) => Geometry::Cylindrical { delta },
            (None, Some(epsilon)) => Geometry::Spherical { epsilon },
            (None, None) => Geometry::Planar,
        };
        OptimizeRequest {
            complexity: self.complexity,
            joint_mass: self.joint_mass,
            material: self.material.clone(),
            load: self.load,
            r0: self.r0,
            max_complexity: self.max_complexity,
            ..OptimizeRequest::new(geometry, self.radius_ratio)
        }
    }
}

/// Entry point of `tensegrity michell optimize`.
pub fn run(args: &OptimizeArgs) -> Result<()> {
    let o = optimize(&args.request()).context("Michell optimisation failed")?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&o)?);
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
