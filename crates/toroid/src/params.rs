//! The seven toroid parameters (thesis Fig. 3.2) and the stabilising options (§3.1).

use crate::error::{Result, ToroidError};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::fmt;
use std::str::FromStr;
use tensegrity_derive::Params;

/// Geometry of the toroid: n sides, outer/inner tread widths T, t, tread offset D, outer,
/// inner and rim radii R_o, R_i, R_m (all lengths in m). Serialised flat (inside a request:
/// `#[serde(flatten)]`), each field under its name; missing fields take the reference
/// wheel's value.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Params)]
#[serde(default)]
/// One [`tensegrity_core::request::Param`] per field (`#[derive(Params)]`; lengths in m).
/// `sides` has no range rule of its own: the builder refuses n < 3 in its own words.
pub struct ToroidParams {
    /// Number of sides (prisms) n ≥ 3.
    #[param(count, help = "Number of sides (prisms) n, at least 3")]
    pub sides: usize,
    /// Outer tread width T.
    #[param(number, unit = "m", help = "Outer tread width T", positive)]
    pub outer_tread: f64,
    /// Inner tread width t.
    #[param(number, unit = "m", help = "Inner tread width t", positive)]
    pub inner_tread: f64,
    /// Tread offset D (≥ 0).
    #[param(number, unit = "m", help = "Tread offset D", non_negative)]
    pub offset: f64,
    /// Outer radius R_o.
    #[param(number, unit = "m", help = "Outer radius R_o", positive)]
    pub outer_radius: f64,
    /// Inner radius R_i < R_o.
    #[param(number, unit = "m", help = "Inner radius R_i < R_o", positive)]
    pub inner_radius: f64,
    /// Rim radius R_m.
    #[param(number, unit = "m", help = "Rim radius R_m", positive)]
    pub rim_radius: f64,
}

impl Default for ToroidParams {
    /// [`ToroidParams::REFERENCE`].
    fn default() -> Self {
        Self::REFERENCE
    }
}

impl ToroidParams {
    /// The reference wheel of the thesis errata: n = 8, T = 0.4, t = 0.3, D = 0.1, R_o = 1,
    /// R_i = 0.6, R_m = 0.8.
    pub const REFERENCE: ToroidParams = ToroidParams {
        sides: 8,
        outer_tread: 0.4,
        inner_tread: 0.3,
        offset: 0.1,
        outer_radius: 1.0,
        inner_radius: 0.6,
        rim_radius: 0.8,
    };

    /// Sets the number of sides.
    ///
    /// ```
    /// use toroid::ToroidParams;
    /// let p = ToroidParams::default().sides(12).rim_radius(0.75);
    /// assert_eq!((p.sides, p.rim_radius), (12, 0.75));
    /// assert!(p.validate().is_ok());
    /// ```
    pub fn sides(mut self, n: usize) -> Self {
        self.sides = n;
        self
    }

    /// Sets the rim radius R_m.
    pub fn rim_radius(mut self, r: f64) -> Self {
        self.rim_radius = r;
        self
    }

    /// Sets the tread offset D.
    ///
    /// ```
    /// use toroid::ToroidParams;
    /// assert!(ToroidParams::default().offset(-0.1).validate().is_err());
    /// ```
    pub fn offset(mut self, d: f64) -> Self {
        self.offset = d;
        self
    }

    /// Checks every parameter; the error names the first offending one.
    ///
    /// ```
    /// use toroid::ToroidParams;
    /// let bad = ToroidParams { inner_radius: 1.2, ..ToroidParams::default() };
    /// assert!(bad.validate().unwrap_err().to_string().contains("inner_radius"));
    /// ```
    pub fn validate(&self) -> Result<()> {
        if self.sides < 3 {
            return Err(ToroidError::InvalidParameter(
                tensegrity_core::request::InvalidParameter::new(
                    "sides",
                    self.sides as f64,
                    "a toroid needs at least 3 sides",
                ),
            ));
        }
        for (name, value) in [
            ("outer_tread", self.outer_tread),
            ("inner_tread", self.inner_tread),
            ("outer_radius", self.outer_radius),
            ("inner_radius", self.inner_radius),
            ("rim_radius", self.rim_radius),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(ToroidError::InvalidParameter(
                    tensegrity_core::request::InvalidParameter::new(
                        name,
                        value,
                        "must be a positive length",
                    ),
                ));
            }
        }
        if !(self.offset.is_finite() && self.offset >= 0.0) {
            return Err(ToroidError::InvalidParameter(
                tensegrity_core::request::InvalidParameter::new(
                    "offset",
                    self.offset,
                    "must be a non-negative length",
                ),
            ));
        }
        if self.inner_radius >= self.outer_radius {
            return Err(ToroidError::InvalidParameter(
                tensegrity_core::request::InvalidParameter::new(
                    "inner_radius",
                    self.inner_radius,
                    format!("must be smaller than outer_radius = {}", self.outer_radius),
                ),
            ));
        }
        Ok(())
    }
}

/// Which stabilising string sets are added (any combination, including none). Serialised as
/// its text form, e.g. `"spokes,inner"` or `"none"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Stabilize {
    /// Option 1: an axle bar and spokes from every rim node to both axle ends.
    pub spokes: bool,
    /// Option 2: inner tread rings n4_k–n4_{k+1}, n5_k–n5_{k+1}.
    pub inner: bool,
    /// Option 3: outer tread rings n1_k–n1_{k+1}, n2_k–n2_{k+1}.
    pub outer: bool,
}

impl Stabilize {
    /// No stabilising strings.
    pub const NONE: Stabilize = Stabilize {
        spokes: false,
        inner: false,
        outer: false,
    };

    /// Spokes and inner rings: first-order rigid (ERRATA 3.4), the reference wheel of the
    /// rolling studies.
    ///
    /// ```
    /// use toroid::Stabilize;
    /// assert_eq!(Stabilize::SPOKES_INNER.to_string(), "spokes,inner");
    /// ```
    pub const SPOKES_INNER: Stabilize = Stabilize {
        spokes: true,
        inner: true,
        outer: false,
    };
}

impl FromStr for Stabilize {
    type Err = ToroidError;

    /// Parses a comma-separated list such as `spokes,inner` or `none`.
    ///
    /// ```
    /// use toroid::Stabilize;
    /// let s: Stabilize = "spokes,inner".parse().unwrap();
    /// assert!(s.spokes && s.inner && !s.outer);
    /// assert_eq!("none".parse::<Stabilize>().unwrap(), Stabilize::NONE);
    /// assert!("wheels".parse::<Stabilize>().is_err());
    /// ```
    fn from_str(s: &str) -> Result<Self> {
        let mut out = Stabilize::NONE;
        for word in s.split(',').map(str::trim).filter(|w| !w.is_empty()) {
            match word {
                "spokes" => out.spokes = true,
                "inner" => out.inner = true,
                "outer" => out.outer = true,
                "none" => {}
                other => {
                    return Err(ToroidError::UnknownStabilizeOption {
                        option: other.to_string(),
                    })
                }
            }
        }
        Ok(out)
    }
}

impl Serialize for Stabilize {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

impl<'de> Deserialize<'de> for Stabilize {
    /// From the text form (`"spokes,inner"`, `"none"`).
    ///
    /// ```
    /// use toroid::Stabilize;
    /// let s: Stabilize = serde_json::from_str("\"spokes,outer\"").unwrap();
    /// assert!(s.spokes && s.outer && !s.inner);
    /// assert_eq!(serde_json::to_string(&Stabilize::SPOKES_INNER).unwrap(), "\"spokes,inner\"");
    /// assert!(serde_json::from_str::<Stabilize>("\"wheels\"").is_err());
    /// ```
    fn deserialize<D: Deserializer<'de>>(d: D) -> std::result::Result<Self, D::Error> {
        let text = String::deserialize(d)?;
        text.parse().map_err(serde::de::Error::custom)
    }
}

impl fmt::Display for Stabilize {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let names: Vec<&str> = [
            (self.spokes, "spokes"),
            (self.inner, "inner"),
            (self.outer, "outer"),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
        .collect();
        if names.is_empty() {
            write!(f, "none")
        } else {
            write!(f, "{}", names.join(","))
        }
    }
}
