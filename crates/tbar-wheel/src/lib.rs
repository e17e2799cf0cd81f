//! # tbar-wheel
//!
//! The T-bar tread and wheel of thesis chapter 5, built on the 3-D Michell parameters of
//! chapter 4 (implemented with the corrections of ERRATA 4.x and 5.x):
//!
//! - [`params`]: [`TbarParams`] (Michell q, r₀, β, φ, δ/ε; [`BarBase`]; [`Layout`]: tread,
//!   wheel of π/φ treads, extended wheel) and their validation;
//! - [`geometry`]: the four-offspring lattice with merged tuples, the radial bar, the rigid rim
//!   supports, the wheel and extended wheel ([`TbarGeometry`]);
//! - [`statics`]: rank, self-stress dimension, mechanisms and prestressability margin through
//!   the core's statics front ([`tensegrity_statics::StaticsBackend`]): the cyclic
//!   blocks for a wheel (O(n) in the treads), the dense SVD for a tread;
//! - [`envelope`]: the omnidirectional load envelope (minimum prestress by an LP over the
//!   self-stress space, critical member and direction, slack map);
//! - [`brute`]: an independent brute-force check of the minimum prestress;
//! - [`mass`]: minimum-mass sizing for the envelope against the 3-D Michell truss;
//! - [`drawing`]: polylines of Figs. 5.1–5.3 (side and top views) for the io figure module;
//! - [`report`]: one complete analysis for the CLI ([`tbar_report`]);
//! - [`symmetry`]: the Cₙ descriptor of the wheel (n = π/φ treads about ι̂₁), which sends
//!   every wheel analysis of [`report`] (both rims, wheels and extended wheels) through the
//!   core's symmetry-adapted blocks.
//!
//! - [`rim`]: the rim body (a ring of bars with a hub, class-k joints) replacing the rigid
//!   rim's supports, and its prestressability LP;
//! - [`standing`]: the single loop against the extended wheel with a free rim body, free and
//!   standing on the ground (the thesis's "unstable in the ι̂₂ι̂₃ plane");
//! - [`rolling`]: mass properties, out-of-plane tip-over, and the rolling polygon for
//!   wheel-rolling's reduced rigid model;
//! - [`rolling_full`]: the wheel as a free, prestressed, massive structure with its contact
//!   nodes and starting pose ([`rolling_full::FullWheel`], a [`wheel_rolling::Wheel`]) for
//!   wheel-rolling's full tensegrity model;
//! - [`roll`]: the T-bar side of `tbar roll` ([`TbarRollRequest`], the rows' T-bar columns
//!   and the report types; the engine crate adds the toroid column).
#![warn(missing_docs)]

pub mod brute;
pub mod drawing;
pub mod envelope;
pub mod error;
pub mod geometry;
pub mod mass;
mod mass_sweep;
pub mod params;
pub mod report;
pub mod request;
pub mod rim;
pub mod roll;
pub mod rolling;
pub mod rolling_full;
pub mod standing;
pub mod statics;
pub mod symmetry;

pub use error::{Result, TbarError};
pub use geometry::TbarGeometry;
pub use mass_sweep::{MASS_SWEEP_COMPLEXITIES, MASS_SWEEP_OFFSETS};
pub use params::{BarBase, Layout, RimMode, TbarParams};
pub use report::{tbar_report, tbar_report_dense, TbarReport, TbarRequest};
pub use request::TbarStaticRequest;
pub use roll::{TbarRollReport, TbarRollRequest, TbarRollRow};
