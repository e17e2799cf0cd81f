//! `tensegrity tbar --mass-sweep`: the mass price of the omnidirectional load envelope against
//! the 3-D Michell truss of the same (r₀, β, φ, δ/ε, q), over complexities and offsets, for
//! single treads with the rigid rim ([`tbar_wheel::mass::mass_sweep`]). The same study runs
//! in parallel through `tensegrity sweep` (study `tbar`, e.g. examples/sweeps/tbar_q_delta.toml).

use anyhow::Result;
use tbar_wheel::mass::{mass_sweep, MassRow};
use tbar_wheel::TbarRequest;

/// Runs the sweep around the parameters of `req` and prints it (table or JSON).
pub fn run(req: &TbarRequest, complexities: &[usize], deltas: &[f64], json: bool) -> Result<()> {
    let rows = mass_sweep(
        &req.params,
        complexities,
        deltas,
        req.load,
        req.ea,
        &req.material,
    );
    if json {
        super::output::print_json(&rows)?;
    } else {
        print_rows(&rows, req);
    }
    Ok(())
}

fn print_rows(rows: &[MassRow], req: &TbarRequest) {
    println!(
        "T-bar tread against the Michell truss, w0 = {} N from every direction, {}",
        req.load, req.material
    );
    println!("  q  delta   min prestress [N]  T-bar mass [kg]  Michell mass [kg]  ratio");
    for r in rows {
        match (r.min_prestress, &r.mass) {
            (Some(p), Some(m)) => println!(
                "{:>3} {:>6} {:>19.6} {:>16.6e} {:>18.6e} {:>6.3}",
                r.complexity, r.delta, p, m.mass_kg, m.michell_mass_kg, m.mass_ratio
            ),
            _ => println!(
                "{:>3} {:>6}  no envelope: {}",
                r.complexity,
                r.delta,
                r.note.as_deref().unwrap_or("-")
            ),
        }
    }
}
