//! `--extra-strings auto|P` of `tensegrity michell` (§4.6–4.7): `auto` pretensions the extra
//! strings to the smallest prestress t* above which no member but the tip members changes sign
//! over the nominal load region of complexity 1; a number uses that prestress. Either way the
//! report gains `min_extra_prestress`, `critical_member`, `worst_direction` and
//! `sign_changes` (from [`michell3d::nominal_region`]).

use anyhow::{Context, Result};
use michell3d::nominal_region::{min_extra_prestress, sign_changes, ExtraPrestress};
use michell3d::{AnalysisRequest, ExtraStrings, MichellTruss};

/// The value of `--extra-strings`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ExtraStringsArg {
    /// The threshold prestress t*.
    Auto,
    /// This prestress (N).
    Prestress(f64),
}

/// Parses `auto` or a non-negative number of newtons.
pub fn parse(s: &str) -> Result<ExtraStringsArg, String> {
    if s.trim().eq_ignore_ascii_case("auto") {
        return Ok(ExtraStringsArg::Auto);
    }
    super::values::non_negative(s).map(ExtraStringsArg::Prestress)
}

/// The threshold and the sign changes of one request's extra strings.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ExtraStringsCheck {
    /// t* and where it is set.
    #[serde(flatten)]
    pub threshold: ExtraPrestress,
    /// Non-tip members that change sign over the nominal region at the prestress used.
    pub sign_changes: Vec<usize>,
}

/// Resolves `auto` (t*, or an error naming the members no prestress can hold) and checks the
/// prestress used; returns the request with its prestress set.
pub fn resolve(
    arg: ExtraStringsArg,
    request: &AnalysisRequest,
) -> Result<(AnalysisRequest, ExtraStringsCheck)> {
    let truss = MichellTruss::new(request.params)?;
    let strings = ExtraStrings::new(&truss)?;
    let threshold = min_extra_prestress(&truss, &strings, request.load, request.method)
        .context("the extra-string prestress threshold failed")?;
    let prestress = match (arg, threshold.min_extra_prestress) {
        (ExtraStringsArg::Prestress(p), _) => p,
        (ExtraStringsArg::Auto, Some(t)) => t,
        (ExtraStringsArg::Auto, None) => anyhow::bail!(
            "no extra-string prestress keeps members {:?} from changing sign over the nominal \
             region: give --extra-strings P to analyse a chosen prestress",
            threshold.unreachable
        ),
    };
    let changes = sign_changes(&truss, &strings, request.load, prestress, request.method)?;
    let request = AnalysisRequest {
        extra_strings: Some(prestress),
        ..request.clone()
    };
    Ok((
        request,
        ExtraStringsCheck {
            threshold,
            sign_changes: changes,
        },
    ))
}

/// The report's JSON with the check's keys added.
pub fn json_with(report: &impl serde::Serialize, check: &ExtraStringsCheck) -> Result<String> {
    let mut value = serde_json::to_value(report)?;
    if let (Some(map), serde_json::Value::Object(extra)) =
        (value.as_object_mut(), serde_json::to_value(check)?)
    {
        map.extend(extra);
    }
    Ok(serde_json::to_string_pretty(&value)?)
}

/// The check as text lines.
pub fn text(check: &ExtraStringsCheck) -> String {
    let t = &check.threshold;
    let mut s = match (t.min_extra_prestress, t.critical_member, t.worst_direction) {
        (Some(p), Some(m), Some([az, polar])) => format!(
            "extra strings: min prestress over the nominal region {p:.6} N (member {m}, load \
             azimuth {az:.6} rad, polar {polar:.6} rad)\n"
        ),
        (Some(p), _, _) => {
            format!("extra strings: min prestress over the nominal region {p:.6} N\n")
        }
        _ => format!(
            "extra strings: members {:?} change sign over the nominal region at any prestress\n",
            t.unreachable
        ),
    };
    s += &format!(
        "extra strings: members changing sign over the nominal region: {:?}\n",
        check.sign_changes
    );
    s
}
