//! The `michell` study: the flags of `tensegrity michell` (src/cli/michell.rs) mapped onto
//! [`michell3d::AnalysisRequest`]. Exactly one of `planar = true`, `cylindrical` (δ) and
//! `spherical` (ε, an angle) chooses the geometry, as the flags do.

use super::{col, Column};
use crate::error::{Result, SweepError};
use crate::params::{param, required, Kind, ParamDef, Params};
use michell3d::{AnalysisRequest, Method, MichellParams};

/// Parameters of `michell`.
pub const PARAMS: [ParamDef; 13] = [
    required("complexity", Kind::Count, ""),
    param("planar", Kind::Flag, ""),
    param("cylindrical", Kind::Number, ""),
    param("spherical", Kind::Angle, "rad"),
    required("beta", Kind::Angle, "rad"),
    required("phi", Kind::Angle, "rad"),
    param("r0", Kind::Number, "m"),
    param("load", Kind::Number, "N"),
    param("azimuth", Kind::Angle, "rad"),
    param("polar", Kind::Angle, "rad"),
    param("material", Kind::Text, ""),
    param("extra_strings", Kind::Number, "N"),
    param("method", Kind::Text, ""),
];

/// The scalars of [`michell3d::MichellReport`] (nested objects flattened with `.`).
pub const COLUMNS: [Column; 13] = [
    col("params.complexity", ""),
    col("params.r0", "m"),
    col("params.beta", "rad"),
    col("params.phi", "rad"),
    col("params.geometry.kind", ""),
    col("params.geometry.delta", ""),
    col("params.geometry.epsilon", "rad"),
    col("method", ""),
    col("material", ""),
    col("prestress", "N"),
    col("mass_kg.yield", "kg"),
    col("mass_kg.yield_buckling", "kg"),
    col("normalized_yield_mass", ""),
];

/// `--r0` of `tensegrity michell` (m).
pub const DEFAULT_R0: f64 = 1.0;

fn geometry(p: &Params, q: usize, r0: f64, beta: f64, phi: f64) -> Result<MichellParams> {
    let planar = p.flag("planar")?.unwrap_or(false);
    match (planar, p.number("cylindrical")?, p.angle("spherical")?) {
        (true, None, None) => Ok(MichellParams::planar(q, r0, beta, phi)),
        (false, Some(delta), None) => Ok(MichellParams::cylindrical(q, r0, beta, phi, delta)),
        (false, None, Some(eps)) => Ok(MichellParams::spherical(q, r0, beta, phi, eps)),
        _ => Err(SweepError::InvalidValue {
            name: "planar/cylindrical/spherical".into(),
            value: format!(
                "{}/{}/{}",
                p.text("planar").unwrap_or_default(),
                p.text("cylindrical").unwrap_or_default(),
                p.text("spherical").unwrap_or_default()
            ),
            reason: "give exactly one of planar = true, cylindrical = δ, spherical = ε".into(),
        }),
    }
}

fn method(s: &str) -> std::result::Result<Method, &'static str> {
    match s {
        "recursive" => Ok(Method::Recursive),
        "global" => Ok(Method::Global),
        _ => Err("expected recursive or global"),
    }
}

fn need<T>(v: Option<T>, name: &'static str) -> Result<T> {
    v.ok_or(SweepError::MissingParameter {
        study: "michell",
        name,
    })
}

/// The request of `tensegrity michell`.
pub fn request(p: &Params) -> Result<AnalysisRequest> {
    let q = need(p.count("complexity")?, "complexity")?;
    let beta = need(p.angle("beta")?, "beta")?;
    let phi = need(p.angle("phi")?, "phi")?;
    let r0 = p.number("r0")?.unwrap_or(DEFAULT_R0);
    let d = AnalysisRequest::new(geometry(p, q, r0, beta, phi)?);
    Ok(AnalysisRequest {
        load: p.number("load")?.unwrap_or(d.load),
        azimuth: p.angle("azimuth")?.unwrap_or(d.azimuth),
        polar: p.angle("polar")?.unwrap_or(d.polar),
        material: p.text("material").unwrap_or(d.material.clone()),
        extra_strings: p.number("extra_strings")?.or(d.extra_strings),
        method: p.parsed("method", method)?.unwrap_or(d.method),
        ..d
    })
}
