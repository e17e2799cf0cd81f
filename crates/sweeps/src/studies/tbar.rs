//! The `tbar` study: the flags of `tensegrity tbar` (src/cli/tbar.rs) mapped onto
//! [`tbar_wheel::TbarRequest`]. `cylindrical` (δ) or `spherical` (ε, an angle) chooses the
//! parameterisation; `wheel = true` or `extended = OFFSET` the layout; `bar_base` is `rim`
//! (default) or `chord`; `rim` is `fixed` (default) or `body`.

use super::{col, Column};
use crate::error::{Result, SweepError};
use crate::params::{param, required, Kind, ParamDef, Params};
use michell3d::MichellParams;
use tbar_wheel::{BarBase, Layout, RimMode, TbarParams, TbarRequest};

/// Parameters of `tbar`.
pub const PARAMS: [ParamDef; 15] = [
    param("complexity", Kind::Count, ""),
    required("beta", Kind::Angle, "rad"),
    required("phi", Kind::Angle, "rad"),
    param("cylindrical", Kind::Number, ""),
    param("spherical", Kind::Angle, "rad"),
    param("r0", Kind::Number, "m"),
    param("wheel", Kind::Flag, ""),
    param("extended", Kind::Number, "m"),
    param("bar_base", Kind::Text, ""),
    param("rim", Kind::Text, ""),
    param("load", Kind::Number, "N"),
    param("ea", Kind::Number, "N"),
    param("prestress", Kind::Number, "N"),
    param("directions", Kind::Count, ""),
    param("material", Kind::Text, ""),
];

/// The scalars of [`tbar_wheel::TbarReport`] (nested objects flattened with `.`; the keys
/// of every layout and parameterisation).
pub const COLUMNS: [Column; 44] = [
    col("params.michell.complexity", ""),
    col("params.michell.r0", "m"),
    col("params.michell.beta", "rad"),
    col("params.michell.phi", "rad"),
    col("params.michell.geometry.kind", ""),
    col("params.michell.geometry.delta", ""),
    col("params.michell.geometry.epsilon", "rad"),
    col("params.bar_base", ""),
    col("params.layout.kind", ""),
    col("params.layout.offset", "m"),
    col("params.rim", ""),
    col("nodes", ""),
    col("bars", ""),
    col("rim", ""),
    col("rim_bars", ""),
    col("strings", ""),
    col("treads", ""),
    col("rank", ""),
    col("self_stress_dim", ""),
    col("mechanisms", ""),
    col("internal_mechanisms", ""),
    col("statics_method", ""),
    col("prestressable", ""),
    col("prestress_margin", ""),
    col("load", "N"),
    col("ea", "N"),
    col("min_prestress", "N"),
    col("critical_member.member", ""),
    col("critical_member.kind", ""),
    col("critical_member.index", ""),
    col("critical_member.tread", ""),
    col("critical_member.azimuth", "rad"),
    col("critical_member.polar", "rad"),
    col("prestress", "N"),
    col("slack_fraction", ""),
    col("bar_always_compressed", ""),
    col("min_strings_carrying", ""),
    col("bar_always_carries", ""),
    col("mass_kg", "kg"),
    col("mass.material", ""),
    col("mass.mass_kg", "kg"),
    col("mass.yield_mass_kg", "kg"),
    col("mass.michell_mass_kg", "kg"),
    col("mass.mass_ratio", ""),
];

/// `--r0` of `tensegrity tbar` (m).
pub const DEFAULT_R0: f64 = 1.0;

fn need<T>(v: Option<T>, name: &'static str) -> Result<T> {
    v.ok_or(SweepError::MissingParameter {
        study: "tbar",
        name,
    })
}

fn bar_base(s: &str) -> std::result::Result<BarBase, &'static str> {
    match s {
        "rim" => Ok(BarBase::Rim),
        "chord" => Ok(BarBase::Chord),
        _ => Err("expected rim or chord"),
    }
}

fn rim(s: &str) -> std::result::Result<RimMode, &'static str> {
    match s {
        "fixed" => Ok(RimMode::Fixed),
        "body" => Ok(RimMode::Body),
        _ => Err("expected fixed or body"),
    }
}

fn michell(p: &Params) -> Result<MichellParams> {
    let q = p.count("complexity")?.unwrap_or(1);
    let beta = need(p.angle("beta")?, "beta")?;
    let phi = need(p.angle("phi")?, "phi")?;
    let r0 = p.number("r0")?.unwrap_or(DEFAULT_R0);
    match (p.number("cylindrical")?, p.angle("spherical")?) {
        (Some(delta), None) => Ok(MichellParams::cylindrical(q, r0, beta, phi, delta)),
        (None, Some(eps)) => Ok(MichellParams::spherical(q, r0, beta, phi, eps)),
        (c, s) => Err(SweepError::InvalidValue {
            name: "cylindrical/spherical".into(),
            value: format!("{c:?}/{s:?}"),
            reason: "give exactly one of cylindrical = δ, spherical = ε".into(),
        }),
    }
}

/// The request of `tensegrity tbar`.
pub fn request(p: &Params) -> Result<TbarRequest> {
    let layout = match (p.number("extended")?, p.flag("wheel")?.unwrap_or(false)) {
        (Some(offset), _) => Layout::Extended { offset },
        (None, true) => Layout::Wheel,
        (None, false) => Layout::Tread,
    };
    let base = p.parsed("bar_base", bar_base)?.unwrap_or(BarBase::Rim);
    let rim = p.parsed("rim", rim)?.unwrap_or(RimMode::Fixed);
    let d = TbarRequest::new(
        TbarParams::tread(michell(p)?)
            .with_layout(layout)
            .with_bar_base(base)
            .with_rim(rim),
    );
    Ok(TbarRequest {
        load: p.number("load")?.unwrap_or(d.load),
        ea: p.number("ea")?.unwrap_or(d.ea),
        prestress: p.number("prestress")?.or(d.prestress),
        directions: p.count("directions")?.unwrap_or(d.directions),
        material: p.text("material").unwrap_or(d.material.clone()),
        ..d
    })
}
