//! The Michell commands as requests ([`tensegrity_core::request::Request`]): flat data, one
//! description per field, read by the command line, the sweeps and Python alike.
//!
//! | request | command / study | library call |
//! |---|---|---|
//! | [`MichellRequest`] | `michell` | [`MichellRequest::run`] ([`MichellAnalysis::run`]) |
//! | [`MichellOptimizeRequest`] | `michell optimize` / `michell_optimize` | [`crate::optimize::optimize`] |
//! | [`MichellTableRequest`] | `michell-table` / `michell_table` | [`crate::mass_vs_complexity`] |
//!
//! The geometry is one of `planar = true`, `cylindrical = δ` or `spherical = ε` (exactly one:
//! [`exclusive`]); the library's [`MichellParams`] holds it as an enum, so each request
//! converts ([`MichellRequest::analysis`], [`MichellOptimizeRequest::optimize_request`]).
//!
//! `extra_strings` of `michell` is a prestress (N) or `auto`: the threshold t* above which no
//! member but the tip members changes sign over the nominal load region of complexity 1
//! ([`crate::nominal_region`]); either way the report gains `min_extra_prestress`,
//! `critical_member`, `worst_direction` and `sign_changes` ([`ExtraStringsCheck`]).

use crate::complexity::{mass_vs_complexity, MassRow, FIG_4_18_DELTAS};
use crate::error::{MichellError, Result};
use crate::extra_strings::ExtraStrings;
use crate::nominal_region::{min_extra_prestress, sign_changes, ExtraPrestress};
use crate::optimize::{optimize, OptimizeRequest, Optimum};
use crate::params::{Geometry, MichellParams};
use crate::propagation::Method;
use crate::report::{AnalysisRequest, MichellAnalysis, MichellReport};
use crate::truss::MichellTruss;
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::f64::consts::PI;
use tensegrity_core::angle::{serde_angle, serde_angle_option};
use tensegrity_core::columns::{Column, Columns};
use tensegrity_core::request::{exclusive, InvalidParameter, Request};
use tensegrity_derive::{Columns, Params};

/// Default tip load w₀ (N).
pub const DEFAULT_LOAD: f64 = 1000.0;
/// Default tip radius r₀ (m).
pub const DEFAULT_R0: f64 = 1.0;
/// Default material of bars and strings.
pub const DEFAULT_MATERIAL: &str = "steel";

/// The geometry fields, as (name, value when set) for [`exclusive`].
fn geometry_given(
    planar: bool,
    cylindrical: Option<f64>,
    spherical: Option<f64>,
) -> [(&'static str, Option<String>); 3] {
    [
        ("planar", planar.then(|| "true".to_string())),
        ("cylindrical", cylindrical.map(|d| d.to_string())),
        ("spherical", spherical.map(|e| e.to_string())),
    ]
}

/// The help texts of the geometry fields every request of the truss shares.
mod help {
    /// `planar`.
    pub const PLANAR: &str = "Skelton's planar truss in the y–z plane";
    /// `cylindrical`.
    pub const CYLINDRICAL: &str =
        "3-D truss, cylindrical parameterisation with dimensionless offset δ (eq. 4.11)";
    /// `spherical`.
    pub const SPHERICAL: &str =
        "3-D truss, spherical parameterisation with angle ε (eq. 4.12), e.g. `pi/24`";
}

fn geometry_of(cylindrical: Option<f64>, spherical: Option<f64>) -> Geometry {
    match (cylindrical, spherical) {
        (Some(delta), _) => Geometry::Cylindrical { delta },
        (None, Some(epsilon)) => Geometry::Spherical { epsilon },
        (None, None) => Geometry::Planar,
    }
}

/// The prestress of the extra strings of §4.6: a value (N) or the threshold t* (`auto`).
/// Written as the number or `"auto"`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ExtraStringsPrestress {
    /// The threshold prestress t*.
    Auto,
    /// This prestress (N, ≥ 0).
    Newtons(f64),
}

impl std::str::FromStr for ExtraStringsPrestress {
    type Err = String;

    /// `auto`, or a finite prestress ≥ 0 (N).
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        if s.trim().eq_ignore_ascii_case("auto") {
            return Ok(Self::Auto);
        }
        match s.trim().parse::<f64>() {
            Ok(p) if p.is_finite() && p >= 0.0 => Ok(Self::Newtons(p)),
            _ => Err("expected `auto` or a finite prestress ≥ 0 (N)".into()),
        }
    }
}

impl Serialize for ExtraStringsPrestress {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        match self {
            Self::Auto => s.serialize_str("auto"),
            Self::Newtons(p) => s.serialize_f64(*p),
        }
    }
}

impl<'de> Deserialize<'de> for ExtraStringsPrestress {
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        #[derive(Deserialize)]
        #[serde(untagged)]
        enum Raw {
            Number(f64),
            Text(String),
        }
        let text = match Raw::deserialize(d)? {
            Raw::Number(x) => x.to_string(),
            Raw::Text(t) => t,
        };
        text.parse().map_err(serde::de::Error::custom)
    }
}

/// `michell`: one discrete Michell truss under a tip load (thesis chapter 4).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct MichellRequest {
    /// Complexity q (required).
    #[param(count, help = "Complexity q (number of member levels; level-q nodes are supports)", rule = AtLeast(1.0), required)]
    pub complexity: Option<usize>,
    /// Skelton's planar truss.
    #[param(flag, help = help::PLANAR)]
    pub planar: bool,
    /// Cylindrical offset δ.
    #[param(number, help = help::CYLINDRICAL, optional)]
    pub cylindrical: Option<f64>,
    /// Spherical angle ε (rad).
    #[serde(with = "serde_angle_option")]
    #[param(angle, help = help::SPHERICAL, optional)]
    pub spherical: Option<f64>,
    /// Departure angle β (rad, required).
    #[serde(with = "serde_angle_option")]
    #[param(angle, help = "Departure angle β, e.g. `pi/6` or `30deg`", required)]
    pub beta: Option<f64>,
    /// Segmentation angle φ (rad, required).
    #[serde(with = "serde_angle_option")]
    #[param(angle, help = "Segmentation angle φ, e.g. `pi/8`", required)]
    pub phi: Option<f64>,
    /// Initial radius r₀ (m).
    #[param(number, unit = "m", help = "Initial radius r₀", positive)]
    pub r0: f64,
    /// Tip load magnitude w₀ (N).
    #[param(number, unit = "N", help = "Tip load magnitude w₀", positive)]
    pub load: f64,
    /// Load azimuth φ_w (rad).
    #[serde(with = "serde_angle")]
    #[param(
        angle,
        help = "Load azimuth φ_w (eq. 4.13); with the default polar angle the load is −ι̂₃"
    )]
    pub azimuth: f64,
    /// Load polar angle γ from ι̂₃ (rad).
    #[serde(with = "serde_angle")]
    #[param(angle, help = "Load polar angle γ from ι̂₃ (eq. 4.13)")]
    pub polar: f64,
    /// Material of bars and strings (a built-in name).
    #[param(
        text,
        help = "Material of bars and strings (aluminium, steel, titanium, carbon_fibre, nylon, uhmwpe)"
    )]
    pub material: String,
    /// Extra strings of §4.6 and their prestress.
    #[param(
        text,
        help = "Add the extra strings of §4.6 (q ≥ 2, 3-D), each pretensioned to this many newtons, or `auto`: to the smallest prestress above which no member but the tip members changes sign over the nominal load region of complexity 1",
        optional
    )]
    pub extra_strings: Option<ExtraStringsPrestress>,
    /// Force propagation method.
    #[param(choice = ["recursive", "global"], help = "Force propagation method")]
    pub method: Method,
}

impl Default for MichellRequest {
    /// No geometry (complexity, β, φ and one of planar/cylindrical/spherical are required);
    /// [`DEFAULT_R0`], [`DEFAULT_LOAD`] along −ι̂₃ (φ_w = 0, γ = π), [`DEFAULT_MATERIAL`], no
    /// extra strings, the recursive method.
    fn default() -> Self {
        Self {
            complexity: None,
            planar: false,
            cylindrical: None,
            spherical: None,
            beta: None,
            phi: None,
            r0: DEFAULT_R0,
            load: DEFAULT_LOAD,
            azimuth: 0.0,
            polar: PI,
            material: DEFAULT_MATERIAL.into(),
            extra_strings: None,
            method: Method::Recursive,
        }
    }
}

impl Request for MichellRequest {
    const NAME: &'static str = "michell";

    /// Exactly one of `planar`, `cylindrical`, `spherical`.
    fn check(&self) -> std::result::Result<(), InvalidParameter> {
        exclusive(
            &geometry_given(self.planar, self.cylindrical, self.spherical),
            true,
        )
    }
}

/// The threshold and the sign changes of one request's extra strings.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExtraStringsCheck {
    /// t* and where it is set.
    #[serde(flatten)]
    pub threshold: ExtraPrestress,
    /// Non-tip members that change sign over the nominal region at the prestress used.
    pub sign_changes: Vec<usize>,
}

/// One `michell` run: the analysis (with the truss it was computed on, for sign maps and γ
/// sweeps), the library request it ran and, with extra strings, their check. Serialises to
/// the JSON of `michell`: the report's keys, then the check's.
#[derive(Debug, Clone)]
pub struct MichellRun {
    /// The library request (the extra strings' prestress resolved).
    pub request: AnalysisRequest,
    /// The truss and its report.
    pub analysis: MichellAnalysis,
    /// The extra strings' threshold and sign changes, when they were asked for.
    pub extra: Option<ExtraStringsCheck>,
}

impl Serialize for MichellRun {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        struct Out<'a> {
            #[serde(flatten)]
            report: &'a MichellReport,
            #[serde(flatten)]
            extra: &'a Option<ExtraStringsCheck>,
        }
        Out {
            report: &self.analysis.report,
            extra: &self.extra,
        }
        .serialize(s)
    }
}

/// The report's columns ([`MichellReport`]): the keys of the extra strings' check, serialised
/// after the report's, are not result columns.
impl Columns for MichellRun {
    fn columns() -> &'static [Column] {
        MichellReport::columns()
    }
}

impl MichellRequest {
    /// The truss parameters (q = 0 and NaN angles where unset: the library refuses them).
    pub fn params(&self) -> MichellParams {
        let (q, r0) = (self.complexity.unwrap_or(0), self.r0);
        let (beta, phi) = (self.beta.unwrap_or(f64::NAN), self.phi.unwrap_or(f64::NAN));
        MichellParams {
            complexity: q,
            r0,
            beta,
            phi,
            geometry: geometry_of(self.cylindrical, self.spherical),
        }
    }

    /// The library request (an `auto` prestress left unset: [`Self::run`] resolves it).
    pub fn analysis(&self) -> AnalysisRequest {
        AnalysisRequest {
            params: self.params(),
            load: self.load,
            azimuth: self.azimuth,
            polar: self.polar,
            material: self.material.clone(),
            extra_strings: match self.extra_strings {
                Some(ExtraStringsPrestress::Newtons(p)) => Some(p),
                _ => None,
            },
            method: self.method,
        }
    }

    /// Resolves the extra strings' prestress, then analyses the truss.
    pub fn run(&self) -> Result<MichellRun> {
        let mut request = self.analysis();
        let extra = match self.extra_strings {
            Some(arg) => {
                let (prestress, check) = resolve(arg, &request)?;
                request.extra_strings = Some(prestress);
                Some(check)
            }
            None => None,
        };
        let analysis = MichellAnalysis::run(&request)?;
        Ok(MichellRun {
            request,
            analysis,
            extra,
        })
    }
}

/// Resolves `auto` (t*, or an error naming the members no prestress can hold) and checks the
/// prestress used against the nominal region.
fn resolve(
    arg: ExtraStringsPrestress,
    request: &AnalysisRequest,
) -> Result<(f64, ExtraStringsCheck)> {
    let truss = MichellTruss::new(request.params)?;
    let strings = ExtraStrings::new(&truss)?;
    let threshold = min_extra_prestress(&truss, &strings, request.load, request.method)?;
    let prestress = match (arg, threshold.min_extra_prestress) {
        (ExtraStringsPrestress::Newtons(p), _) => p,
        (ExtraStringsPrestress::Auto, Some(t)) => t,
        (ExtraStringsPrestress::Auto, None) => {
            return Err(MichellError::NoExtraPrestress {
                members: threshold.unreachable,
            })
        }
    };
    let changes = sign_changes(&truss, &strings, request.load, prestress, request.method)?;
    let check = ExtraStringsCheck {
        threshold,
        sign_changes: changes,
    };
    Ok((prestress, check))
}

/// `michell optimize`: the mass-optimal truss for a given radius ratio ρ = r_q/r₀
/// ([`optimize`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct MichellOptimizeRequest {
    /// Skelton's planar truss (yield sizing).
    #[param(flag, help = help::PLANAR)]
    pub planar: bool,
    /// Cylindrical offset δ (yield + buckling sizing).
    #[param(number, help = help::CYLINDRICAL, optional)]
    pub cylindrical: Option<f64>,
    /// Spherical angle ε (rad, yield + buckling sizing).
    #[serde(with = "serde_angle_option")]
    #[param(angle, help = help::SPHERICAL, optional)]
    pub spherical: Option<f64>,
    /// ρ = r_q / r₀ in (0, 1) (required).
    #[param(
        number,
        help = "ρ = r_q / r₀ in (0, 1): the support circle over the tip radius",
        required
    )]
    pub radius_ratio: Option<f64>,
    /// The complexity q; optimised when unset (then a joint mass is needed).
    #[param(count, help = "The complexity q; optimised when left out (then joint_mass is needed)", rule = AtLeast(1.0), optional)]
    pub complexity: Option<usize>,
    /// Mass of each joint (kg).
    #[param(
        number,
        unit = "kg",
        help = "Mass of each joint, added per node",
        non_negative
    )]
    pub joint_mass: f64,
    /// Largest complexity the search tries.
    #[param(count, help = "Largest complexity the search tries")]
    pub max_complexity: usize,
    /// Material of bars and strings.
    #[param(text, help = "Material of bars and strings")]
    pub material: String,
    /// Tip load w₀ (N).
    #[param(
        number,
        unit = "N",
        help = "Tip load w₀, perpendicular to the tip radius (−ι̂₃)",
        positive
    )]
    pub load: f64,
    /// Initial (tip) radius r₀ (m).
    #[param(number, unit = "m", help = "Initial (tip) radius r₀", positive)]
    pub r0: f64,
}

impl Default for MichellOptimizeRequest {
    /// The library's defaults ([`OptimizeRequest::new`]); geometry and ρ required.
    fn default() -> Self {
        let d = OptimizeRequest::new(Geometry::Planar, f64::NAN);
        Self {
            planar: false,
            cylindrical: None,
            spherical: None,
            radius_ratio: None,
            complexity: d.complexity,
            joint_mass: d.joint_mass,
            max_complexity: d.max_complexity,
            material: d.material,
            load: d.load,
            r0: d.r0,
        }
    }
}

impl MichellOptimizeRequest {
    /// The library request.
    pub fn optimize_request(&self) -> OptimizeRequest {
        let geometry = geometry_of(self.cylindrical, self.spherical);
        OptimizeRequest {
            complexity: self.complexity,
            joint_mass: self.joint_mass,
            material: self.material.clone(),
            load: self.load,
            r0: self.r0,
            max_complexity: self.max_complexity,
            ..OptimizeRequest::new(geometry, self.radius_ratio.unwrap_or(f64::NAN))
        }
    }

    /// Runs [`optimize`].
    pub fn run(&self) -> Result<Optimum> {
        optimize(&self.optimize_request())
    }
}

impl Request for MichellOptimizeRequest {
    const NAME: &'static str = "michell_optimize";

    /// Exactly one of `planar`, `cylindrical`, `spherical`.
    fn check(&self) -> std::result::Result<(), InvalidParameter> {
        exclusive(
            &geometry_given(self.planar, self.cylindrical, self.spherical),
            true,
        )
    }
}

/// Default largest complexity of `michell-table`.
pub const TABLE_MAX_COMPLEXITY: usize = 35;

/// `michell-table` (Fig. 4.18): mass against complexity q = 2..=`max_complexity`, planar and
/// δ = 0.1, 0.25, 0.5 ([`FIG_4_18_DELTAS`]), r₀ = 1, β = π/6, φ = π/q.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct MichellTableRequest {
    /// Largest complexity (the table runs q = 2..=Q).
    #[param(count, help = "Largest complexity (the table runs q = 2..=Q, at most the 3-D families' 100)", rule = Closed(2.0, crate::params::MAX_COMPLEXITY_3D as f64))]
    pub max_complexity: usize,
    /// Tip load w₀ (N), along −ι̂₃.
    #[param(number, unit = "N", help = "Tip load w₀, along −ι̂₃", positive)]
    pub load: f64,
    /// Material of bars and strings.
    #[param(text, help = "Material of bars and strings")]
    pub material: String,
}

impl Default for MichellTableRequest {
    /// [`TABLE_MAX_COMPLEXITY`], [`DEFAULT_LOAD`], [`DEFAULT_MATERIAL`].
    fn default() -> Self {
        Self {
            max_complexity: TABLE_MAX_COMPLEXITY,
            load: DEFAULT_LOAD,
            material: DEFAULT_MATERIAL.into(),
        }
    }
}

/// The rows of `michell-table`.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct MichellTable {
    /// One row per complexity and family (planar first, then each δ).
    pub rows: Vec<MassRow>,
}

impl MichellTableRequest {
    /// The complexities of the table, 2..=`max_complexity`.
    pub fn complexities(&self) -> Vec<usize> {
        (2..=self.max_complexity).collect()
    }

    /// The material of the table's sizing.
    pub fn material(&self) -> Result<tensegrity_core::Material> {
        let table = tensegrity_core::MaterialTable::builtin();
        Ok(*table.lookup(&self.material, "material")?)
    }

    /// The table, sequentially (the command line fans the complexities out on threads).
    pub fn run(&self) -> Result<MichellTable> {
        let rows = mass_vs_complexity(
            &self.complexities(),
            &FIG_4_18_DELTAS,
            self.load,
            &self.material()?,
        )?;
        Ok(MichellTable { rows })
    }
}

impl Request for MichellTableRequest {
    const NAME: &'static str = "michell_table";
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;
    use tensegrity_core::request::check_description;

    #[test]
    fn every_request_describes_its_fields() {
        check_description::<MichellRequest>().unwrap();
        check_description::<MichellOptimizeRequest>().unwrap();
        check_description::<MichellTableRequest>().unwrap();
    }

    fn base() -> Vec<(&'static str, serde_json::Value)> {
        vec![
            ("complexity", json!(3)),
            ("beta", json!("pi/6")),
            ("phi", json!("pi/8")),
        ]
    }

    #[test]
    fn exactly_one_geometry_and_every_required_field() {
        let e = MichellRequest::from_values(base()).unwrap_err();
        assert!(e.to_string().contains("give one of planar"), "{e}");
        let mut two = base();
        two.extend([("planar", json!(true)), ("cylindrical", json!(0.1))]);
        let e = MichellRequest::from_values(two).unwrap_err().to_string();
        assert!(e.contains("planar") && e.contains("cylindrical"), "{e}");
        let e = MichellRequest::from_values([("planar", json!(true))]).unwrap_err();
        assert_eq!(e.to_string(), "complexity = (unset): must be given");
        let mut r = base();
        r.extend([("spherical", json!("pi/24")), ("method", json!("global"))]);
        let r = MichellRequest::from_values(r).unwrap();
        let (b, f) = (PI / 6.0, PI / 8.0);
        assert_eq!(
            r.params(),
            MichellParams::spherical(3, 1.0, b, f, PI / 24.0)
        );
        assert_eq!(r.analysis().method, Method::Global);
        assert_eq!((r.load, r.material.as_str()), (1000.0, "steel"));
    }

    #[test]
    fn the_run_is_the_analysis_and_auto_extra_strings_hold_every_sign() {
        let mut v = base();
        v.extend([("cylindrical", json!(0.25))]);
        let r = MichellRequest::from_values(v.clone()).unwrap();
        let run = r.run().unwrap();
        let direct = crate::analyse(&r.analysis()).unwrap();
        assert_eq!(
            serde_json::to_value(&run).unwrap(),
            serde_json::to_value(&direct).unwrap()
        );
        v.push(("extra_strings", json!("auto")));
        let auto = MichellRequest::from_values(v).unwrap().run().unwrap();
        let check = auto.extra.as_ref().unwrap();
        let t = check.threshold.min_extra_prestress.unwrap();
        assert_eq!(auto.request.extra_strings, Some(t));
        assert!(check.sign_changes.is_empty());
        let json = serde_json::to_value(&auto).unwrap();
        assert_eq!(json["prestress"], json["min_extra_prestress"]);
        let bad = MichellRequest::from_values([("extra_strings", json!("lots"))]).unwrap_err();
        assert_eq!(bad.name, "extra_strings");
    }

    #[test]
    fn optimize_and_table_convert() {
        let r = MichellOptimizeRequest::from_values([
            ("planar", json!(true)),
            ("radius_ratio", json!(0.25)),
            ("complexity", json!(4)),
        ])
        .unwrap();
        let o = r.run().unwrap();
        let a = 0.25f64.powf(0.25);
        assert!((o.normalized_yield_mass - 4.0 * (1.0 / a - a)).abs() < 1e-9);
        let t = MichellTableRequest::from_values([("max_complexity", json!(3))]).unwrap();
        assert_eq!(t.run().unwrap().rows.len(), 2 * 4);
        assert!(MichellTableRequest::from_values([("max_complexity", json!(1))]).is_err());
        // the 3-D families end at q = 100: refused before any row is computed
        let e = MichellTableRequest::from_values([("max_complexity", json!(10000))]).unwrap_err();
        assert_eq!(e.name, "max_complexity");
        assert!(MichellTableRequest::from_values([("max_complexity", json!(100))]).is_ok());
    }
}
