//! The `roll` study: the flags of `tensegrity roll` (src/cli/roll.rs) mapped onto
//! [`toroid::RollRequest`], and the scalars of [`toroid::RollReport`]'s JSON as columns
//! (validity included: `valid`, `min_normal_force`, `airborne_fraction`, `slip_fraction`,
//! `max_penetration`, `energy_balance_error`, and the first impact as `first_impact.t`,
//! `first_impact.omega_before`, `first_impact.omega_after`, empty when there is none).
//! `fig-rolling` runs its wheels through this study.

use super::wheel::{choice, wheel};
use super::{col, Column};
use crate::error::Result;
use crate::params::{param, Kind, ParamDef, Params};
use toroid::RollRequest;
use wheel_rolling::{ContactKind, FidelityChoice, RollSettings};

/// Parameters of `roll`.
pub const ROLL_PARAMS: [ParamDef; 20] = geometry_then![
    param("incline", Kind::Angle, "rad"),
    param("t_end", Kind::Number, "s"),
    param("dt", Kind::Number, "s"),
    param("fidelity", Kind::Text, ""),
    param("contact", Kind::Text, ""),
    param("ground_damping", Kind::Number, "N s/m"),
    param("ground_stiffness", Kind::Number, "N/m"),
    param("mu", Kind::Number, ""),
    param("restitution", Kind::Number, ""),
    param("string_stiffness", Kind::Number, "N/m"),
    param("min_tension", Kind::Number, "N"),
];

/// The scalars of [`toroid::RollReport`], in its key order.
pub const ROLL_COLUMNS: [Column; 29] = [
    col("fidelity", ""),
    col("fidelity_reason", ""),
    col("contact", ""),
    col("sides", ""),
    col("incline_rad", "rad"),
    col("t_end", "s"),
    col("mass_kg", "kg"),
    col("I1", "kg m^2"),
    col("mu", ""),
    col("restitution", ""),
    col("ground_damping", "N s/m"),
    col("valid", ""),
    col("impacts", ""),
    col("first_impact.t", "s"),
    col("first_impact.omega_before", "rad/s"),
    col("first_impact.omega_after", "rad/s"),
    col("axle_height_oscillation", "m"),
    col("mean_axle_height", "m"),
    col("mean_speed", "m/s"),
    col("final_speed", "m/s"),
    col("max_reaction", "N"),
    col("min_normal_force", "N"),
    col("airborne_fraction", ""),
    col("slip_fraction", ""),
    col("max_penetration", "m"),
    col("energy_balance_error", ""),
    col("lift_off_time", "s"),
    col("required_friction", ""),
    col("mean_slip_speed", "m/s"),
];

const FIDELITY: [(&str, FidelityChoice); 3] = [
    ("rigid", FidelityChoice::Rigid),
    ("full", FidelityChoice::Full),
    ("auto", FidelityChoice::Auto),
];

const CONTACT: [(&str, ContactKind); 2] = [
    ("thesis", ContactKind::Thesis),
    ("penalty", ContactKind::Penalty),
];

/// The request of `tensegrity roll`.
pub fn roll_request(p: &Params) -> Result<RollRequest> {
    let d = RollRequest::default();
    let ds = d.settings;
    Ok(RollRequest {
        wheel: wheel(p)?,
        settings: RollSettings {
            incline: p.angle("incline")?.unwrap_or(ds.incline),
            dt: p.number("dt")?.unwrap_or(ds.dt),
            ground_damping: p.number("ground_damping")?.or(ds.ground_damping),
            ground_stiffness: p.number("ground_stiffness")?.unwrap_or(ds.ground_stiffness),
            restitution: p.number("restitution")?.unwrap_or(ds.restitution),
            string_stiffness: p.number("string_stiffness")?.unwrap_or(ds.string_stiffness),
            ..ds
        },
        t_end: p.number("t_end")?.unwrap_or(d.t_end),
        fidelity: p
            .parsed("fidelity", choice(&FIDELITY))?
            .unwrap_or(d.fidelity),
        contact: p.parsed("contact", choice(&CONTACT))?.unwrap_or(d.contact),
        mu: p.number("mu")?.unwrap_or(d.mu),
        min_tension: p.number("min_tension")?.unwrap_or(d.min_tension),
        ..d
    })
}
