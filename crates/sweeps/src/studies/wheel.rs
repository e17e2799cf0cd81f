//! The toroid-wheel studies `toroid` and `tipover` (and the wheel flags `roll` shares, see
//! [`super::roll`]): the flags of `tensegrity toroid` and `tipover` (src/cli/toroid.rs)
//! mapped onto the same library requests.
//!
//! `tipover` also takes σ = R_i/R_o and ε = t/T (thesis §3.3.2, Fig. 3.13) as `sigma` and
//! `epsilon`: they set the geometry as the tip-over analysis reads it back, R_i = σ R_o and
//! t = ε T (with the case's R_o and T), so a σ × ε sweep runs real wheels; giving `sigma`
//! with `inner_radius`, or `epsilon` with `inner_tread`, is an error of that case.

use super::{col, Column};
use crate::error::{Result, SweepError};
use crate::params::{param, Kind, ParamDef, Params};
use toroid::{Stabilize, TipoverRequest, ToroidRequest, WheelSpec};

macro_rules! geometry_then {
    ($($extra:expr),* $(,)?) => {
        [
            param("sides", Kind::Count, ""),
            param("outer_tread", Kind::Number, "m"),
            param("inner_tread", Kind::Number, "m"),
            param("offset", Kind::Number, "m"),
            param("outer_radius", Kind::Number, "m"),
            param("inner_radius", Kind::Number, "m"),
            param("rim_radius", Kind::Number, "m"),
            param("stabilize", Kind::Text, ""),
            param("bar_density", Kind::Number, "kg/m"),
            $($extra),*
        ]
    };
}

/// Parameters of `toroid`.
pub const TOROID_PARAMS: [ParamDef; 13] = geometry_then![
    param("prism_only", Kind::Flag, ""),
    param("min_tension", Kind::Number, "N"),
    param("rim_window", Kind::Flag, ""),
    param("string_stiffness", Kind::Number, "N/m"),
];

/// Parameters of `tipover`.
pub const TIPOVER_PARAMS: [ParamDef; 12] = geometry_then![
    param("gravity", Kind::Number, "m/s^2"),
    param("sigma", Kind::Number, ""),
    param("epsilon", Kind::Number, ""),
];

/// The scalars of [`toroid::ToroidReport`].
pub const TOROID_COLUMNS: [Column; 11] = [
    col("nodes", ""),
    col("bars", ""),
    col("strings", ""),
    col("stabilize", ""),
    col("rank", ""),
    col("self_stress_dim", ""),
    col("prestressable", ""),
    col("prestress_margin", ""),
    col("internal_mechanisms", ""),
    col("mass_kg", "kg"),
    col("I1", "kg m^2"),
];

/// Parameters of `lean` (`tensegrity tipover --rolling`).
pub const LEAN_PARAMS: [ParamDef; 12] = geometry_then![
    param("incline", Kind::Angle, "rad"),
    param("side_slope", Kind::Angle, "rad"),
    param("t_end", Kind::Number, "s"),
];

/// The result scalars of [`toroid::rolling_lean::LeanRollingReport`] (its echo of the inputs
/// `sides`, `outer_tread`, `incline`, `side_slope` left out: they are axis or fixed values).
pub const LEAN_COLUMNS: [Column; 9] = [
    col("mass_kg", "kg"),
    col("static_critical_side_slope", "rad"),
    col("max_lean", "rad"),
    col("final_lean", "rad"),
    col("fell", ""),
    col("fall_time", "s"),
    col("downhill", "m"),
    col("max_penetration", "m"),
    col("valid", ""),
];

/// The run of `tensegrity tipover --rolling`: the wheel and the cross-sloped plane.
pub fn lean_request(p: &Params) -> Result<(WheelSpec, toroid::rolling_lean::LeanRolling)> {
    let d = toroid::rolling_lean::LeanRolling::default();
    Ok((
        wheel(p)?,
        toroid::rolling_lean::LeanRolling {
            incline: p.angle("incline")?.unwrap_or(d.incline),
            side_slope: p.angle("side_slope")?.unwrap_or(d.side_slope),
            t_end: p.number("t_end")?.unwrap_or(d.t_end),
            ..d
        },
    ))
}

/// Runs one `lean` case.
pub fn lean_report(p: &Params) -> Result<toroid::rolling_lean::LeanRollingReport, String> {
    let (spec, run) = lean_request(p)?;
    let wheel = spec.build().map_err(|e| e.to_string())?;
    run.run(&wheel).map_err(|e| e.to_string())
}

/// The scalars of [`toroid::TipoverReport`].
pub const TIPOVER_COLUMNS: [Column; 8] = [
    col("mass_kg", "kg"),
    col("rho", ""),
    col("epsilon", ""),
    col("sigma", ""),
    col("cot_theta", ""),
    col("critical_lateral_force", "N"),
    col("normalized_friction", ""),
    col("min_friction_to_tip", ""),
];

/// The wheel of `tensegrity toroid/roll/tipover`'s geometry flags.
pub(super) fn wheel(p: &Params) -> Result<WheelSpec> {
    let d = WheelSpec::default();
    let g = d.params;
    let mut w = d;
    w.params.sides = p.count("sides")?.unwrap_or(g.sides);
    w.params.outer_tread = p.number("outer_tread")?.unwrap_or(g.outer_tread);
    w.params.inner_tread = p.number("inner_tread")?.unwrap_or(g.inner_tread);
    w.params.offset = p.number("offset")?.unwrap_or(g.offset);
    w.params.outer_radius = p.number("outer_radius")?.unwrap_or(g.outer_radius);
    w.params.inner_radius = p.number("inner_radius")?.unwrap_or(g.inner_radius);
    w.params.rim_radius = p.number("rim_radius")?.unwrap_or(g.rim_radius);
    w.stabilize = p
        .parsed("stabilize", str::parse::<Stabilize>)?
        .unwrap_or(d.stabilize);
    w.bar_density = p.number("bar_density")?.unwrap_or(d.bar_density);
    Ok(w)
}

/// The request of `tensegrity toroid`.
pub fn toroid_request(p: &Params) -> Result<ToroidRequest> {
    let d = ToroidRequest::default();
    Ok(ToroidRequest {
        wheel: wheel(p)?,
        prism_only: p.flag("prism_only")?.unwrap_or(d.prism_only),
        min_tension: p.number("min_tension")?.unwrap_or(d.min_tension),
        rim_window: p.flag("rim_window")?.unwrap_or(d.rim_window),
        string_stiffness: p.number("string_stiffness")?.or(d.string_stiffness),
    })
}

pub(super) fn choice<T: Copy>(
    options: &'static [(&'static str, T)],
) -> impl Fn(&str) -> std::result::Result<T, String> {
    move |s| {
        options
            .iter()
            .find(|(name, _)| *name == s)
            .map(|&(_, v)| v)
            .ok_or_else(|| {
                let names: Vec<&str> = options.iter().map(|(n, _)| *n).collect();
                format!("expected one of {}", names.join(", "))
            })
    }
}

/// The request of `tensegrity tipover`, with σ and ε mapped onto R_i and t.
pub fn tipover_request(p: &Params) -> Result<TipoverRequest> {
    let mut wheel = wheel(p)?;
    for (ratio, length) in [("sigma", "inner_radius"), ("epsilon", "inner_tread")] {
        let Some(x) = p.number(ratio)? else { continue };
        if p.get(length).is_some() {
            return Err(SweepError::InvalidValue {
                name: ratio.into(),
                value: x.to_string(),
                reason: format!("give `{ratio}` or `{length}`, not both"),
            });
        }
        let g = &mut wheel.params;
        match ratio {
            "sigma" => g.inner_radius = x * g.outer_radius,
            _ => g.inner_tread = x * g.outer_tread,
        }
    }
    Ok(TipoverRequest {
        wheel,
        gravity: p
            .number("gravity")?
            .unwrap_or(TipoverRequest::default().gravity),
    })
}
