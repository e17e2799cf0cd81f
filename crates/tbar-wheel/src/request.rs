//! The static T-bar command as a request ([`tensegrity_core::request::Request`]): flat data,
//! one description per field, read by the command line (`tensegrity tbar --wheel …`), the
//! sweeps (`study = "tbar"`) and Python alike.
//!
//! The library's [`TbarRequest`] holds the geometry as [`TbarParams`] (the Michell parameters
//! with their geometry enum, the layout enum): [`TbarStaticRequest::request`] converts. One of
//! `cylindrical = δ` and `spherical = ε` chooses the parameterisation ([`exclusive`]);
//! `extended = OFFSET` builds the extended wheel (it takes precedence over `wheel`).

use crate::envelope::{DEFAULT_DIRECTIONS, DEFAULT_EA, DEFAULT_LOAD, MAX_DIRECTIONS};
use crate::error::Result;
use crate::mass::DEFAULT_MATERIAL;
use crate::params::{BarBase, Layout, RimMode, TbarParams};
use crate::report::{tbar_report, TbarReport, TbarRequest};
use michell3d::{Geometry, MichellParams};
use serde::{Deserialize, Serialize};
use tensegrity_core::angle::serde_angle_option;
use tensegrity_core::request::{exclusive, InvalidParameter, Request};
use tensegrity_derive::Params;

/// Default complexity q of a T-bar tread.
pub const DEFAULT_COMPLEXITY: usize = 1;
/// Default tip radius r₀ (m).
pub const DEFAULT_R0: f64 = 1.0;

/// `tbar`: the T-bar tread, wheel or extended wheel of thesis chapter 5 (statics, load
/// envelope, mass; [`tbar_report`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct TbarStaticRequest {
    /// Complexity q (lattice levels; level q lies on the rim).
    #[param(count, help = "Complexity q (lattice levels; level q lies on the rim)", rule = AtLeast(1.0))]
    pub complexity: usize,
    /// Departure angle β (rad, required).
    #[serde(with = "serde_angle_option")]
    #[param(angle, help = "Departure angle β (e.g. `pi/6`, `30deg`)", required)]
    pub beta: Option<f64>,
    /// Segmentation angle φ (rad, required); a wheel needs π/φ integer.
    #[serde(with = "serde_angle_option")]
    #[param(
        angle,
        help = "Segmentation angle φ; a wheel needs π/φ integer",
        required
    )]
    pub phi: Option<f64>,
    /// Cylindrical parameterisation with offset δ.
    #[param(
        number,
        help = "Cylindrical parameterisation with offset δ (dimensionless, eq. 4.11)",
        optional
    )]
    pub cylindrical: Option<f64>,
    /// Spherical parameterisation with angle ε (rad).
    #[serde(with = "serde_angle_option")]
    #[param(
        angle,
        help = "Spherical parameterisation with angle ε (eq. 4.12)",
        optional
    )]
    pub spherical: Option<f64>,
    /// Tip radius r₀ (m).
    #[param(number, unit = "m", help = "Tip radius r₀", positive)]
    pub r0: f64,
    /// Build the wheel: π/φ treads every 2φ about ι̂₁.
    #[param(flag, help = "Build the wheel: π/φ treads every 2φ about ι̂₁")]
    pub wheel: bool,
    /// Build the extended wheel: the wheel and a copy translated by this offset (m) along ι̂₁.
    #[param(
        number,
        unit = "m",
        help = "Build the extended wheel: the wheel and a copy translated by this offset along ι̂₁",
        optional
    )]
    pub extended: Option<f64>,
    /// Base of the radial bar.
    #[param(choice = ["rim", "chord"], help = "Base of the radial bar")]
    pub bar_base: BarBase,
    /// Rigid rim (`fixed`) or a free rim body of bars with a hub (`body`).
    #[param(choice = ["fixed", "body"], help = "Rim: rigid supports (`fixed`) or a free rim body of bars with a hub (`body`)")]
    pub rim: RimMode,
    /// Tip load magnitude w₀ (N) of the load envelope.
    #[param(
        number,
        unit = "N",
        help = "Tip load magnitude w₀ of the load envelope",
        positive
    )]
    pub load: f64,
    /// Axial stiffness EA of every member (N).
    #[param(
        number,
        unit = "N",
        help = "Axial stiffness EA of every member",
        positive
    )]
    pub ea: f64,
    /// Bar compression P (N) of the slack map.
    #[param(
        number,
        unit = "N",
        help = "Bar compression P of the slack map",
        positive,
        optional
    )]
    pub prestress: Option<f64>,
    /// Directions of the slack map.
    #[param(count, help = "Directions of the slack map (quasi-uniform sphere)", rule = Closed(1.0, MAX_DIRECTIONS as f64))]
    pub directions: usize,
    /// Material of the sizing.
    #[param(text, help = "Material of the sizing (built-in table)")]
    pub material: String,
}

impl Default for TbarStaticRequest {
    /// A [`DEFAULT_COMPLEXITY`] tread of radius [`DEFAULT_R0`] on the rim, rigid rim; the
    /// envelope's [`DEFAULT_LOAD`], [`DEFAULT_EA`], [`DEFAULT_DIRECTIONS`], no slack map,
    /// [`DEFAULT_MATERIAL`]. β, φ and the parameterisation are required.
    fn default() -> Self {
        Self {
            complexity: DEFAULT_COMPLEXITY,
            beta: None,
            phi: None,
            cylindrical: None,
            spherical: None,
            r0: DEFAULT_R0,
            wheel: false,
            extended: None,
            bar_base: BarBase::Rim,
            rim: RimMode::Fixed,
            load: DEFAULT_LOAD,
            ea: DEFAULT_EA,
            prestress: None,
            directions: DEFAULT_DIRECTIONS,
            material: DEFAULT_MATERIAL.into(),
        }
    }
}

impl TbarStaticRequest {
    /// The geometry (NaN angles where unset: the library refuses them).
    pub fn params(&self) -> TbarParams {
        let michell = MichellParams {
            complexity: self.complexity,
            r0: self.r0,
            beta: self.beta.unwrap_or(f64::NAN),
            phi: self.phi.unwrap_or(f64::NAN),
            geometry: match (self.cylindrical, self.spherical) {
                (_, Some(epsilon)) => Geometry::Spherical { epsilon },
                (delta, None) => Geometry::Cylindrical {
                    delta: delta.unwrap_or(0.0),
                },
            },
        };
        let layout = match (self.extended, self.wheel) {
            (Some(offset), _) => Layout::Extended { offset },
            (None, true) => Layout::Wheel,
            (None, false) => Layout::Tread,
        };
        TbarParams::tread(michell)
            .with_layout(layout)
            .with_bar_base(self.bar_base)
            .with_rim(self.rim)
    }

    /// The library request.
    pub fn request(&self) -> TbarRequest {
        TbarRequest {
            load: self.load,
            ea: self.ea,
            prestress: self.prestress,
            directions: self.directions,
            material: self.material.clone(),
            ..TbarRequest::new(self.params())
        }
    }

    /// Runs [`tbar_report`].
    pub fn run(&self) -> Result<TbarReport> {
        tbar_report(&self.request())
    }
}

impl Request for TbarStaticRequest {
    const NAME: &'static str = "tbar";

    /// Exactly one of `cylindrical`, `spherical`.
    fn check(&self) -> std::result::Result<(), InvalidParameter> {
        exclusive(
            &[
                ("cylindrical", self.cylindrical.map(|d| d.to_string())),
                ("spherical", self.spherical.map(|e| e.to_string())),
            ],
            true,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;
    use tensegrity_core::request::check_description;

    #[test]
    fn the_request_describes_its_fields() {
        check_description::<TbarStaticRequest>().unwrap();
    }

    #[test]
    fn values_map_onto_the_library_request() {
        let base = [("beta", json!("pi/6")), ("phi", json!("pi/8"))];
        let with = |extra: &[(&'static str, serde_json::Value)]| {
            let mut all = base.to_vec();
            all.extend_from_slice(extra);
            TbarStaticRequest::from_values(all)
        };
        assert!(with(&[]).unwrap_err().to_string().contains("give one of"));
        let both = with(&[("cylindrical", json!(0.25)), ("spherical", json!(0.1))]);
        assert!(both.unwrap_err().to_string().contains("excludes spherical"));
        let r = with(&[
            ("spherical", json!("pi/12")),
            ("extended", json!(0.5)),
            ("bar_base", json!("chord")),
            ("rim", json!("body")),
        ])
        .unwrap();
        let p = r.params();
        assert_eq!(p.layout, Layout::Extended { offset: 0.5 });
        assert_eq!((p.bar_base, p.rim), (BarBase::Chord, RimMode::Body));
        assert_eq!(
            p.michell.geometry,
            Geometry::Spherical {
                epsilon: std::f64::consts::PI / 12.0
            }
        );
        // the q = 1 tread of the tbar-wheel tests: min_prestress = 3.2357686 w0
        let t = with(&[("cylindrical", json!(0.25)), ("prestress", json!(5.0))]).unwrap();
        let report = t.run().unwrap();
        assert!((report.min_prestress.unwrap() - 3.235768601).abs() < 1e-8);
        assert_eq!(report.prestress, Some(5.0));
    }
}
