//! Parameters of a T-bar tread, wheel or extended wheel, and their validation.
//!
//! The lattice uses the 3-D Michell parameters of chapter 4 ([`MichellParams`]: complexity q,
//! r₀, β, φ and δ (cylindrical, eq. 4.11) or ε (spherical, eq. 4.12); r_l = r₀aˡ with
//! a = sin β / sin(β+φ)), validated by michell3d (ERRATA 4.7–4.9, 4.12). The T-bar adds
//!
//! - the base of the radial bar ([`BarBase`]): the rim point [0, r_q, 0] (default) or the
//!   chord point [0, r_q cos φ, 0] (ERRATA 5.2: the thesis leaves it unspecified);
//! - the layout ([`Layout`]): one tread, the wheel of π/φ treads every 2φ about ι̂₁ (π/φ must
//!   be an integer), or the extended wheel (a second wheel translated along ι̂₁ by an offset).
//!
//! - the rim ([`RimMode`]): rigid (every rim node (level q) and every bar base a pinned
//!   support, the default) or a free rim body of bars (a ring and a hub, see
//!   [`crate::rim`]) for free-body analysis and dynamics.

use crate::error::{invalid, Result, TbarError};
use michell3d::MichellParams;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;
use tensegrity_derive::Columns;

/// Largest complexity accepted (a tread has (q+1)(q+2)(2q+3)/6 lattice nodes: 3 311 at q = 20).
pub const MAX_COMPLEXITY: usize = 20;
/// Most treads accepted around one wheel (π/φ); the statics of a wheel are O(treads) through
/// its cyclic symmetry, and [`crate::geometry::MAX_NODES`] bounds the structure's size.
pub const MAX_TREADS: usize = 3600;
/// Relative tolerance of "π/φ is an integer".
pub const TREAD_COUNT_TOL: f64 = 1e-9;

/// Where the radial bar starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BarBase {
    /// The rim point [0, r_q, 0] on the rim cylinder (the choice of ERRATA 5.2). For even q
    /// it is the lattice node (q/2, q/2, q/2, q/2): the two are one node.
    #[default]
    Rim,
    /// The chord point [0, r_q cos φ, 0]: the midpoint of the chord between the rim points at
    /// ±φ, supported with the rim.
    Chord,
}

impl BarBase {
    /// `"rim"` or `"chord"`.
    pub fn as_str(&self) -> &'static str {
        match self {
            BarBase::Rim => "rim",
            BarBase::Chord => "chord",
        }
    }
}

/// How the rim is modelled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum RimMode {
    /// A rigid rim: every rim node and bar base is a pinned support (the default).
    #[default]
    Fixed,
    /// A rim body of bars with a hub and no support (free body, see [`crate::rim`]).
    Body,
}

impl RimMode {
    /// `"fixed"` or `"body"`.
    pub fn as_str(&self) -> &'static str {
        match self {
            RimMode::Fixed => "fixed",
            RimMode::Body => "body",
        }
    }
}

/// One tread, the wheel, or the extended wheel.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Columns)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Layout {
    /// A single tread (Fig. 5.1).
    #[default]
    Tread,
    /// π/φ treads every 2φ about ι̂₁, neighbours sharing coincident nodes (Fig. 5.2).
    Wheel,
    /// The wheel and a copy translated by `offset` along ι̂₁ (Fig. 5.3).
    Extended {
        /// Translation of the copy along ι̂₁ (m).
        #[column(unit = "m")]
        offset: f64,
    },
}

impl Layout {
    /// `"tread"`, `"wheel"` or `"extended wheel"` (used in messages).
    pub fn name(&self) -> &'static str {
        match self {
            Layout::Tread => "tread",
            Layout::Wheel => "wheel",
            Layout::Extended { .. } => "extended wheel",
        }
    }
}

/// Everything that defines the geometry of a T-bar structure.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Columns)]
pub struct TbarParams {
    /// The 3-D Michell parameters of the lattice (q, r₀, β, φ, δ or ε).
    #[column(nested)]
    pub michell: MichellParams,
    /// The base of the radial bar.
    pub bar_base: BarBase,
    /// Tread, wheel or extended wheel.
    #[column(nested)]
    pub layout: Layout,
    /// Rigid rim (supports) or rim body.
    pub rim: RimMode,
}

impl TbarParams {
    /// A single tread with the bar based on the rim.
    pub fn tread(michell: MichellParams) -> Self {
        Self {
            michell,
            bar_base: BarBase::Rim,
            layout: Layout::Tread,
            rim: RimMode::Fixed,
        }
    }

    /// The same parameters with another rim model.
    pub fn with_rim(self, rim: RimMode) -> Self {
        Self { rim, ..self }
    }

    /// The same parameters with another layout.
    pub fn with_layout(self, layout: Layout) -> Self {
        Self { layout, ..self }
    }

    /// The same parameters with another bar base.
    pub fn with_bar_base(self, bar_base: BarBase) -> Self {
        Self { bar_base, ..self }
    }

    /// Complexity q.
    pub fn complexity(&self) -> usize {
        self.michell.complexity
    }

    /// Rim radius r_q = r₀a^q.
    pub fn rim_radius(&self) -> f64 {
        self.michell.radius(self.complexity())
    }

    /// Treads around one wheel: 1 for a tread, π/φ otherwise (validated).
    pub fn treads_per_wheel(&self) -> Result<usize> {
        match self.layout {
            Layout::Tread => Ok(1),
            Layout::Wheel | Layout::Extended { .. } => treads_for(self.michell.phi),
        }
    }

    /// Number of wheels: 2 for the extended wheel, 1 otherwise.
    pub fn copies(&self) -> usize {
        match self.layout {
            Layout::Extended { .. } => 2,
            _ => 1,
        }
    }

    /// Checks every parameter; the error names the first offending one.
    pub fn validate(&self) -> Result<()> {
        self.michell.validate()?;
        let q = self.complexity();
        if q > MAX_COMPLEXITY {
            return Err(invalid(
                "complexity",
                q as f64,
                format!("must be at most {MAX_COMPLEXITY} (a tread has (q+1)(q+2)(2q+3)/6 nodes)"),
            ));
        }
        self.treads_per_wheel()?;
        if let Layout::Extended { offset } = self.layout {
            if !offset.is_finite() || offset == 0.0 {
                return Err(invalid(
                    "extended",
                    offset,
                    "the offset of the copy along ι̂₁ must be finite and non-zero",
                ));
            }
        }
        Ok(())
    }
}

/// π/φ as an integer number of treads, or a clear error.
///
/// ```
/// use tbar_wheel::params::treads_for;
/// assert_eq!(treads_for(std::f64::consts::PI / 8.0).unwrap(), 8);
/// assert!(treads_for(0.3).is_err());
/// ```
pub fn treads_for(phi: f64) -> Result<usize> {
    let ratio = PI / phi;
    let n = ratio.round();
    if !ratio.is_finite() || (ratio - n).abs() > TREAD_COUNT_TOL * ratio || n < 2.0 {
        return Err(invalid(
            "phi",
            phi,
            format!(
                "a wheel repeats the tread every 2φ, so π/φ must be an integer ≥ 2; got π/φ = {ratio}"
            ),
        ));
    }
    if n > MAX_TREADS as f64 {
        return Err(TbarError::TooLarge {
            what: "treads per wheel (π/φ)",
            size: n as usize,
            limit: MAX_TREADS,
        });
    }
    Ok(n as usize)
}
