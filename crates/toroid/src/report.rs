//! Reports of the toroid studies, as the CLI prints them (text or JSON): the statics and
//! inertia of one wheel ([`toroid_report`]) and its tip-over figures ([`tipover_report`]).
//! The rolling report is in [`crate::roll`](mod@crate::roll).
//!
//! Every study starts from a [`WheelSpec`] (the seven parameters, the stabilising options and
//! the bar density) and a request struct whose [`Default`] is the CLI's default; the numbers
//! come from [`crate::analyse`], [`crate::prestress_design`], [`crate::rim_radius_window`] and
//! [`crate::tipover`].

use crate::analysis::{analyse, design_from, prestressed_structure, rim_radius_window};
use crate::builder::{build, build_prism, Toroid};
use crate::defaults;
use crate::error::Result;
use crate::inertia::wheel_mass;
use crate::params::{Stabilize, ToroidParams};
use crate::symmetry::SymmetryCounts;
use crate::tipover::tipover;
use serde::{Deserialize, Serialize, Serializer};
use tensegrity_core::request::InvalidParameter;
use tensegrity_core::Structure;
use tensegrity_derive::{Columns, Params};
use tensegrity_statics::SpectralGap;

/// One wheel: geometry, stabilising strings and bar mass per length. Serialised flat (the
/// seven parameters, `stabilize` as `"spokes,inner"`, `bar_density`), so a request that
/// `#[serde(flatten)]`s it reads `{"sides": 12, "stabilize": "spokes,outer", ...}`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Params)]
#[serde(from = "WheelFields", into = "WheelFields")]
pub struct WheelSpec {
    /// The seven geometric parameters.
    #[param(flatten)]
    pub params: ToroidParams,
    /// The stabilising string sets.
    #[param(
        text,
        help = "Stabilising strings: comma-separated spokes, inner, outer, or none"
    )]
    pub stabilize: Stabilize,
    /// Bar mass per length (kg/m); strings are massless.
    #[param(number, unit = "kg/m", help = "Bar mass per length", positive)]
    pub bar_density: f64,
    /// Scale the tread offset with the number of sides ([`WheelSpec::geometry`]): D is read
    /// as its value at [`defaults::SCALE_REFERENCE_SIDES`] sides and built as
    /// D · n_ref / n (the reference D = 0.1 gives D = 0.8/n), so that large wheels stay
    /// prestressable.
    #[param(
        flag,
        help = "Scale the tread offset with the sides: D_n = D·8/n (0.8/n for the reference D = 0.1), so large wheels stay prestressable"
    )]
    pub scale_with_n: bool,
}

/// The flat serde form of [`WheelSpec`]: one plain struct (no nested flatten), so that a
/// request flattening it keeps `deny_unknown_fields` working.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
struct WheelFields {
    sides: usize,
    outer_tread: f64,
    inner_tread: f64,
    offset: f64,
    outer_radius: f64,
    inner_radius: f64,
    rim_radius: f64,
    stabilize: Stabilize,
    bar_density: f64,
    scale_with_n: bool,
}

impl Default for WheelFields {
    fn default() -> Self {
        WheelSpec::default().into()
    }
}

impl From<WheelFields> for WheelSpec {
    fn from(f: WheelFields) -> Self {
        Self {
            params: ToroidParams {
                sides: f.sides,
                outer_tread: f.outer_tread,
                inner_tread: f.inner_tread,
                offset: f.offset,
                outer_radius: f.outer_radius,
                inner_radius: f.inner_radius,
                rim_radius: f.rim_radius,
            },
            stabilize: f.stabilize,
            bar_density: f.bar_density,
            scale_with_n: f.scale_with_n,
        }
    }
}

impl From<WheelSpec> for WheelFields {
    fn from(w: WheelSpec) -> Self {
        let p = w.params;
        Self {
            sides: p.sides,
            outer_tread: p.outer_tread,
            inner_tread: p.inner_tread,
            offset: p.offset,
            outer_radius: p.outer_radius,
            inner_radius: p.inner_radius,
            rim_radius: p.rim_radius,
            stabilize: w.stabilize,
            bar_density: w.bar_density,
            scale_with_n: w.scale_with_n,
        }
    }
}

impl Default for WheelSpec {
    /// The reference wheel: [`ToroidParams::REFERENCE`], spokes + inner rings, 1 kg/m bars.
    fn default() -> Self {
        Self {
            params: ToroidParams::REFERENCE,
            stabilize: Stabilize::SPOKES_INNER,
            bar_density: defaults::BAR_DENSITY,
            scale_with_n: false,
        }
    }
}

impl WheelSpec {
    /// The geometry rules across the wheel's parameters (n ≥ 3, R_i < R_o, …) as an
    /// [`InvalidParameter`] naming the parameter, for the requests' `check`: every request
    /// of the wheel (`roll`, `tipover --dynamic`, `--rolling`) refuses the same wheel the same
    /// way, before anything is built.
    pub fn check(&self) -> std::result::Result<(), InvalidParameter> {
        match self.params.validate() {
            Ok(()) => Ok(()),
            Err(crate::ToroidError::InvalidParameter(p)) => Err(p),
            Err(e) => Err(InvalidParameter::raw(
                "sides",
                self.params.sides,
                e.to_string(),
            )),
        }
    }

    /// The reference wheel with `n` sides.
    pub fn with_sides(n: usize) -> Self {
        let mut w = Self::default();
        w.params.sides = n;
        w
    }

    /// The geometry built: [`Self::params`], with `scale_with_n` the tread offset scaled
    /// with the number of sides, D_n = D · n_ref / n (n_ref =
    /// [`defaults::SCALE_REFERENCE_SIDES`] = 8; the reference D = 0.1 gives D = 0.8/n). The
    /// treads T, t and the radii are kept: with D alone scaled the prestressability margin
    /// stays positive to n = 1000 (measured: 0.00195 at n = 100, 1.4·10⁻⁵ at n = 1000,
    /// against 0 for D = 0.1 at n = 100).
    ///
    /// ```
    /// use toroid::WheelSpec;
    /// let mut w = WheelSpec::with_sides(100);
    /// assert_eq!(w.geometry().offset, 0.1);
    /// w.scale_with_n = true;
    /// assert!((w.geometry().offset - 0.008).abs() < 1e-15);
    /// assert_eq!(w.params.offset, 0.1); // the request keeps what was asked
    /// ```
    pub fn geometry(&self) -> ToroidParams {
        let mut p = self.params;
        if self.scale_with_n && p.sides > 0 {
            p.offset *= defaults::SCALE_REFERENCE_SIDES as f64 / p.sides as f64;
        }
        p
    }

    /// Builds the toroid (of [`Self::geometry`]).
    pub fn build(&self) -> Result<Toroid> {
        build(&self.geometry(), self.stabilize, self.bar_density)
    }
}

/// What [`toroid_report`] analyses (the request of `toroid`, see [`crate::request`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct ToroidRequest {
    /// The wheel.
    #[serde(flatten)]
    pub wheel: WheelSpec,
    /// Analyse a single prism (six nodes, K6) instead of the whole wheel.
    #[param(
        flag,
        help = "Analyse a single prism (six nodes, K6) instead of the whole wheel"
    )]
    pub prism_only: bool,
    /// Minimum string tension of the prestress design (N).
    #[param(
        number,
        unit = "N",
        help = "Minimum string tension of the prestress design",
        positive
    )]
    pub min_tension: f64,
    /// Also search the rim radii R_m for which a single prism is prestressable.
    #[param(
        flag,
        help = "Also search the rim radii R_m for which a single prism is prestressable"
    )]
    pub rim_window: bool,
    /// Give every string of [`ToroidReport::structure`] this stiffness (N/m) and the rest
    /// length that realises the prestress design (needs a prestressable toroid).
    #[param(
        number,
        unit = "N/m",
        help = "Give every string of the exported structure this stiffness and the rest length that realises the prestress design",
        positive,
        optional
    )]
    pub string_stiffness: Option<f64>,
}

impl Default for ToroidRequest {
    /// The reference wheel, a 10 N prestress design, no rim window, no string stiffness.
    fn default() -> Self {
        Self {
            wheel: WheelSpec::default(),
            prism_only: false,
            min_tension: defaults::DESIGN_MIN_TENSION,
            rim_window: false,
            string_stiffness: None,
        }
    }
}

/// What a [`ToroidReport`] analysed: a wheel with its stabilising options, or one prism.
/// Serialised as text: the options (`"spokes,inner"`) or `"prism"`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stabilized {
    /// The whole wheel with these stabilising string sets.
    Wheel(Stabilize),
    /// A single prism (six nodes, K6).
    Prism,
}

impl std::fmt::Display for Stabilized {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stabilized::Wheel(s) => s.fmt(f),
            Stabilized::Prism => f.write_str("prism"),
        }
    }
}

impl Serialize for Stabilized {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// The statics, mass and inertia of one toroid; serialises to the JSON of `tensegrity toroid`.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct ToroidReport {
    /// Node count.
    pub nodes: usize,
    /// Bar count.
    pub bars: usize,
    /// String count.
    pub strings: usize,
    /// The stabilising options (`"spokes,inner"`, …), or `"prism"` for a single prism.
    pub stabilize: Stabilized,
    /// Rank of the equilibrium matrix.
    pub rank: usize,
    /// Dimension of the self-stress space.
    pub self_stress_dim: usize,
    /// Whether a self-stress tensions every string and compresses every bar.
    pub prestressable: bool,
    /// The prestressability LP margin.
    pub prestress_margin: f64,
    /// First-order flexes beyond the rigid-body motions.
    pub internal_mechanisms: usize,
    /// Total bar mass (kg).
    #[column(unit = "kg")]
    pub mass_kg: f64,
    /// Inertia tensor about the wheel centre (kg m²), row-major.
    pub inertia: [[f64; 3]; 3],
    /// I₁ about the rolling axis (kg m²).
    #[serde(rename = "I1")]
    #[column(unit = "kg m^2")]
    pub i1: f64,
    /// Member forces of the prestress design (N, tension positive, bars then strings), when
    /// prestressable.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prestress_member_force: Option<Vec<f64>>,
    /// The rim radii [R_m,min, R_m,max] (m) of single-prism prestressability, when searched
    /// and found.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rim_radius_window: Option<[f64; 2]>,
    /// Self-stress states and internal mechanisms per representation of the wheel's Cₙ
    /// symmetry (the symmetry-adapted analysis); absent for a single prism.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[column(skip)]
    pub symmetry: Option<SymmetryCounts>,
    /// The singular values on either side of the rank tolerance behind the counts (the
    /// narrowest block's of the symmetry-adapted analysis).
    #[column(nested)]
    pub spectral_gap: SpectralGap,
    /// Set (else `null`) when the rank decision has no clear gap: a singular value within a
    /// factor 10 of the tolerance, so rank, self-stress dimension and mechanisms are uncertain.
    pub statics_warning: Option<String>,
    /// The analysed structure (with stiff, prestressed strings when the request gives a
    /// string stiffness), for export; not serialised.
    #[serde(skip)]
    pub structure: Structure,
}

/// Builds and analyses one toroid (or prism): counts, prestress, flexes, mass, inertia, the
/// prestress design and, on request, the rim-radius window.
///
/// ```
/// use toroid::{toroid_report, ToroidRequest};
/// let r = toroid_report(&ToroidRequest::default()).unwrap();
/// assert_eq!((r.nodes, r.internal_mechanisms), (42, 0));
/// let f = r.prestress_member_force.unwrap();
/// let min_string = f[r.bars..].iter().copied().fold(f64::INFINITY, f64::min);
/// assert!((min_string - 10.0).abs() < 1e-9);
/// ```
pub fn toroid_report(request: &ToroidRequest) -> Result<ToroidReport> {
    let p = request.wheel.geometry();
    let t = if request.prism_only {
        build_prism(&p, request.wheel.bar_density)?
    } else {
        request.wheel.build()?
    };
    let a = analyse(&t)?;
    // with a string stiffness, a toroid that is not prestressable fails here (no design)
    let design = if a.prestressable || request.string_stiffness.is_some() {
        Some(design_from(&t, &a, request.min_tension)?)
    } else {
        None
    };
    let structure = match (request.string_stiffness, &design) {
        (Some(k), Some(d)) => prestressed_structure(&t, d, k)?,
        _ => t.structure.clone(),
    };
    let window = if request.rim_window {
        rim_radius_window(
            &p,
            defaults::RIM_WINDOW_FROM * p.outer_radius,
            defaults::RIM_WINDOW_TO * p.outer_radius,
            defaults::RIM_WINDOW_SAMPLES,
            defaults::RIM_WINDOW_TOL,
        )?
    } else {
        None
    };
    Ok(ToroidReport {
        nodes: a.nodes,
        bars: a.bars,
        strings: a.strings,
        stabilize: if request.prism_only {
            Stabilized::Prism
        } else {
            Stabilized::Wheel(t.stabilize)
        },
        rank: a.rank,
        self_stress_dim: a.self_stress_dim,
        prestressable: a.prestressable,
        prestress_margin: a.prestress_margin,
        internal_mechanisms: a.internal_mechanisms,
        mass_kg: a.mass_kg,
        inertia: std::array::from_fn(|i| std::array::from_fn(|j| a.inertia[(i, j)])),
        i1: a.i1,
        prestress_member_force: design.map(|d| d.member_force.iter().copied().collect()),
        rim_radius_window: window.map(|(lo, hi)| [lo, hi]),
        symmetry: SymmetryCounts::of(&a.representations),
        spectral_gap: a.spectral_gap,
        statics_warning: a.statics_warning.clone(),
        structure,
    })
}

/// What [`tipover_report`] analyses (the request of `tipover`, see [`crate::request`]).
///
/// σ = R_i/R_o and ε = t/T (thesis §3.3.2, Fig. 3.13) may be given instead of the inner
/// radius and tread: they set R_i = σ R_o and t = ε T of the wheel ([`Self::wheel_spec`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct TipoverRequest {
    /// The wheel.
    #[serde(flatten)]
    pub wheel: WheelSpec,
    /// Gravity (m/s²).
    #[param(number, unit = "m/s^2", help = "Gravity", positive)]
    pub gravity: f64,
    /// σ = R_i/R_o: sets the inner radius to σ R_o.
    #[param(
        number,
        help = "σ = R_i/R_o: sets inner_radius = σ outer_radius",
        optional
    )]
    pub sigma: Option<f64>,
    /// ε = t/T: sets the inner tread to ε T.
    #[param(number, help = "ε = t/T: sets inner_tread = ε outer_tread", optional)]
    pub epsilon: Option<f64>,
}

impl Default for TipoverRequest {
    /// The reference wheel under [`defaults::GRAVITY`], no σ or ε.
    fn default() -> Self {
        Self {
            wheel: WheelSpec::default(),
            gravity: defaults::GRAVITY,
            sigma: None,
            epsilon: None,
        }
    }
}

impl TipoverRequest {
    /// The wheel analysed: [`Self::wheel`] with R_i = σ R_o and t = ε T where σ, ε are given.
    ///
    /// ```
    /// use toroid::TipoverRequest;
    /// let r = TipoverRequest { sigma: Some(0.5), epsilon: Some(0.25), ..Default::default() };
    /// let p = r.wheel_spec().params;
    /// assert_eq!((p.inner_radius, p.inner_tread), (0.5, 0.1));
    /// ```
    pub fn wheel_spec(&self) -> WheelSpec {
        let mut w = self.wheel;
        if let Some(s) = self.sigma {
            w.params.inner_radius = s * w.params.outer_radius;
        }
        if let Some(e) = self.epsilon {
            w.params.inner_tread = e * w.params.outer_tread;
        }
        w
    }
}

/// Tip-over figures of one wheel; serialises to the JSON of `tensegrity tipover`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Columns)]
pub struct TipoverReport {
    /// Wheel (bar) mass (kg).
    #[column(unit = "kg")]
    pub mass_kg: f64,
    /// ρ = T/R_o.
    pub rho: f64,
    /// ε = t/T.
    pub epsilon: f64,
    /// σ = R_i/R_o.
    pub sigma: f64,
    /// cot θ of the contact bar with the ground.
    pub cot_theta: f64,
    /// Lateral axle force at which the wheel tips (N).
    #[column(unit = "N")]
    pub critical_lateral_force: f64,
    /// F_f/F_e at the threshold (eq. 3.29).
    pub normalized_friction: f64,
    /// Smallest static friction coefficient for which the wheel tips before sliding.
    pub min_friction_to_tip: f64,
}

/// Builds the wheel and returns its tip-over figures (thesis §3.3.2, ERRATA 3.12–3.15).
///
/// ```
/// use toroid::{tipover_report, TipoverRequest};
/// let r = tipover_report(&TipoverRequest::default()).unwrap();
/// // ρ = 0.4, ε = 0.75, σ = 0.6: F_f/F_e = −(σ + ε)/(1 − σ) = −3.375
/// assert!((r.normalized_friction + 3.375).abs() < 1e-12);
/// assert!((r.critical_lateral_force - 0.5 * r.mass_kg * 9.81 * 0.4).abs() < 1e-12);
/// ```
pub fn tipover_report(request: &TipoverRequest) -> Result<TipoverReport> {
    let t = request.wheel_spec().build()?;
    let mass = wheel_mass(&t.structure);
    let r = tipover(&t.params, mass, request.gravity)?;
    Ok(TipoverReport {
        mass_kg: mass,
        rho: r.rho,
        epsilon: r.epsilon,
        sigma: r.sigma,
        cot_theta: r.cot_theta,
        critical_lateral_force: r.critical_lateral_force,
        normalized_friction: r.normalized_friction,
        min_friction_to_tip: r.min_friction_to_tip,
    })
}
