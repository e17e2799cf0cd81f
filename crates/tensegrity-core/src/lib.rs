//! # tensegrity-core
//!
//! What every layer of the tensegrity toolkit shares (the analyses live in their own crates:
//! `tensegrity-statics` for the equilibrium matrix, prestress, stiffness and sizing,
//! `tensegrity-dynamics` for rigid-bar dynamics, `tensegrity-linalg` for the factorisations):
//!
//! - [`structure`]: nodes N (3×n), bars, strings, supports, loads, gravity, with a validating
//!   builder;
//! - [`connectivity`]: C_b, C_s, C_r and B = N C_bᵀ, S = N C_sᵀ, R = N C_rᵀ;
//! - [`budget`]: memory, work and output estimated from a request's sizes, and the limits
//!   that refuse oversized requests before anything is allocated;
//! - [`validate`]: the checks of scalar parameters shared by requests, scenes and flags;
//! - [`request`]: requests as data ([`request::Request`], one [`request::Param`] per field),
//!   the shared [`request::InvalidParameter`] and the error [`request::Category`];
//! - [`columns`]: the scalar result columns of a report ([`columns::Column`]), declared on
//!   its fields with `#[derive(Columns)]` (crate `tensegrity-derive`);
//! - [`precision`]: the rounding of node coordinates judged from their digits;
//! - [`angle`]: the angle forms of every front end (`30deg`, `pi/8`, radians);
//! - [`material`]: materials and the built-in table;
//! - [`warning`]: [`Warning`], the warnings of every report as data (`{kind, message, …}`);
//! - [`error`]: [`CoreError`] and its concerns (model, statics, dynamics, numerics), shared
//!   by every layer;
//! - `test_models` (feature `test-models`): canonical structures with reference answers.
//!
//! Sign conventions: force densities q are tension positive; the member vector is
//! `n_end − n_start`; members are numbered bars first, then strings.
#![warn(missing_docs)]
#![allow(non_snake_case)]

// the derive macros of tensegrity-derive name this crate by its path
extern crate self as tensegrity_core;

pub mod angle;
pub mod budget;
pub mod capstan;
pub mod cluster;
pub mod columns;
pub mod connectivity;
pub mod error;
pub mod material;
pub mod member_id;
pub mod number;
pub mod precision;
pub mod request;
pub mod structure;
#[cfg(any(test, feature = "test-models"))]
pub mod test_models;
pub mod validate;
pub mod warning;

pub use cluster::Cluster;
pub use connectivity::{Connectivity, Incidence};
pub use error::{
    CoreError, DynamicsError, ModelError, NumericsError, Result, StaticsError, StepHint,
};
pub use material::{Material, MaterialTable};
pub use member_id::MemberId;
pub use structure::{Bar, Load, StringMember, Structure, StructureBuilder, Support};
pub use warning::Warning;

/// The README's examples, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
