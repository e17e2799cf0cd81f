//! # toroid
//!
//! The 3-bar-prism tensegrity toroid of the thesis (chapter 3), used as a wheel: geometry from
//! seven parameters, stabilising string options, statics (self-stress, prestressability,
//! internal mechanisms, prestress design), mass and inertia, tip-over, and rolling down an
//! incline (with the models of the wheel-rolling crate); and the reports of these studies ([`toroid_report`], [`roll()`],
//! [`tipover_report`], [`rolling_series`]) built from request structs whose defaults are the
//! named constants of [`defaults`].
//!
//! ```
//! use toroid::{analyse, build, ToroidParams};
//! let t = build(&ToroidParams::default(), "spokes".parse().unwrap(), 1.0).unwrap();
//! let a = analyse(&t).unwrap();
//! // ERRATA 3.4: spokes alone leave one zero-energy spin per prism about its rim bar
//! assert_eq!(a.internal_mechanisms, 8);
//! ```
#![warn(missing_docs)]
#![allow(non_snake_case)]

mod analysis;
pub mod budget;
mod builder;
pub mod defaults;
mod error;
mod inertia;
mod params;
pub mod report;
pub mod request;
pub mod roll;
pub mod rolling_lean;
mod spec_mass;
mod symmetry;
mod tipover;
pub mod tipover_dynamic;

pub use analysis::{
    analyse, analyse_dense, analysis_from, design_from, prestress_design, prestressed_structure,
    prism_prestressable, rim_radius_window, PrestressDesign, ToroidAnalysis,
};
pub use builder::{build, build_prism, prism_nodes, prism_rotation, MemberLabel, Role, Toroid};
pub use error::{Result, ToroidError};
pub use inertia::{bar_inertia, bar_inertia_thesis, wheel_inertia, wheel_mass};
pub use params::{Stabilize, ToroidParams};
pub use report::{
    tipover_report, toroid_report, Stabilized, TipoverReport, TipoverRequest, ToroidReport,
    ToroidRequest, WheelSpec,
};
pub use request::{TipoverDynamicRequest, TipoverRollingRequest};
pub use roll::{
    roll, roll_observed, roll_with_frames, rolling_series, RollReport, RollRequest, ToroidWheel,
};
pub use symmetry::{toroid_symmetry, SymmetryCounts};
pub use tipover::{friction_grid, normalized_friction, tipover, TipOver};
/// The rolling models the toroid's [`roll()`] runs (re-exported: the request's enums and the
/// report's parts are wheel-rolling's).
pub use wheel_rolling::{
    self, ContactKind, FidelityChoice, FirstImpact, ImpactRecord, RollValidity,
};
