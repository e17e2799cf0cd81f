//! # tensegrity-core
//!
//! The model and the topology-independent analyses of the tensegrity toolkit:
//!
//! - [`structure`]: nodes N (3×n), bars, strings, supports, loads, gravity, with a validating
//!   builder;
//! - [`connectivity`]: C_b, C_s, C_r and B = N C_bᵀ, S = N C_sᵀ, R = N C_rᵀ;
//! - [`statics`]: equilibrium matrix A q = w, SVD rank, self-stress, mechanisms,
//!   prestressability (LP), minimal-norm load solve with reactions; `statics::symmetry` the
//!   same for cyclically symmetric structures in O(n) (Fourier blocks per representation);
//! - [`stiffness`]: tangent stiffness, first-order flexes, prestress stability, modes;
//! - [`budget`]: memory, work and output estimated from a request's sizes, and the limits
//!   that refuse oversized requests before anything is allocated;
//! - [`validate`]: the checks of scalar parameters shared by requests, scenes and flags;
//! - [`request`]: requests as data ([`request::Request`], one [`request::Param`] per field),
//!   the shared [`request::InvalidParameter`] and the error [`request::Category`];
//! - [`angle`]: the angle forms of every front end (`30deg`, `pi/8`, radians);
//! - [`sizing`]: minimum mass of strings (yield) and bars (yield and Euler buckling);
//! - [`dynamics`]: rigid-bar dynamics N̈M + NK = W + ΩPᵀ with class-k joints, strings, gravity,
//!   ground contact, RK4 / adaptive RK45 / RATTLE integrators, monitors and a recorder;
//! - [`linalg`]: dense (SVD, symmetric eigen, small Cholesky) and sparse (ordering, Cholesky
//!   with symbolic reuse, LU) factorisations, the only module that touches the factorisation
//!   backend;
//! - `test_models` (feature `test-models`): canonical structures with reference answers.
//!
//! Sign conventions: force densities q are tension positive; the member vector is
//! `n_end − n_start`; members are numbered bars first, then strings.
#![warn(missing_docs)]
#![allow(non_snake_case)]

pub mod angle;
pub mod budget;
pub mod connectivity;
pub mod dynamics;
pub mod error;
pub mod linalg;
pub mod material;
pub mod member_id;
pub mod request;
pub mod sizing;
pub mod statics;
pub mod stiffness;
pub mod structure;
#[cfg(any(test, feature = "test-models"))]
pub mod test_models;
pub mod validate;

pub use connectivity::{Connectivity, Incidence};
pub use dynamics::{IntegratorKind, Simulation, SimulationResult, SimulationSettings};
pub use error::{
    CoreError, DynamicsError, ModelError, NumericsError, Result, StaticsError, StepHint,
};
pub use material::{Material, MaterialTable};
pub use member_id::MemberId;
pub use statics::report::{statics_report, StaticsReport, StaticsRequest};
pub use statics::{LoadSolution, Prestressability, Statics, StaticsSettings};
pub use structure::{Bar, Load, StringMember, Structure, StructureBuilder, Support};

/// The README's examples, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
