//! # michell3d
//!
//! Discrete Michell trusses (thesis chapter 4, implemented with the corrections of ERRATA ch. 4
//! and the conventions of DESIGN.md):
//!
//! - Skelton's planar truss (q, r₀, β, φ; a = sin β / sin(β+φ), c = sin φ / sin(β+φ)) and the
//!   3-D truss with the cylindrical (δ) or spherical (ε) parameterisation: [`MichellParams`],
//!   [`MichellTruss`] (four-index nodes (U, D, L, R) with identical tuples merged; children
//!   (U+1,D,L+1,R), (U+1,D,L,R+1), (U,D+1,L,R); member vector n_parent − n_child; level-q
//!   supports);
//! - force propagation ([`propagate`], dispatching on [`Method`]) by the recursive method of
//!   joints ([`propagate_recursive`], one fixed-size solve per node) and, independently, by a
//!   global solve of the assembled equilibrium, eliminated level by level with sparse LUs
//!   ([`global::solve_global`]); tension-positive force densities
//!   ([`ForceSolution`]);
//! - tip loads w₀[cos φ sin γ, sin φ sin γ, cos γ] ([`tip_load`]) and sign maps over (φ, γ)
//!   ([`signmap`]);
//! - member types from the force sign, minimum mass for yield and buckling ([`sizing`]), the
//!   planar closed forms ([`planar`]) and the mass–complexity table of Fig. 4.18
//!   ([`complexity`]);
//! - extra strings with prestress and the γ sweep of Fig. 4.20 ([`extra_strings`]);
//! - one complete analysis for the CLI ([`analyse`]).
//!
//! ```
//! use michell3d::*;
//! use std::f64::consts::{FRAC_PI_6, PI};
//!
//! // A 3-D cylindrical truss, q = 4, φ = π/4, δ = 0.25, under 1 kN along −ι̂₃.
//! let truss = MichellTruss::new(MichellParams::cylindrical(4, 1.0, FRAC_PI_6, PI / 4.0, 0.25))?;
//! assert_eq!(truss.nodes().len(), 35);
//! assert_eq!(truss.members().len(), 60);
//! let loads = NodalLoads::tip(tip_load(1000.0, 0.0, PI)?);
//! let rec = propagate(&truss, &loads, Method::Recursive)?;
//! let glo = propagate(&truss, &loads, Method::Global)?;
//! for (a, b) in rec.force_density.iter().zip(&glo.force_density) {
//!     assert!((a - b).abs() < 1e-9 * a.abs().max(1.0));
//! }
//! // Reactions balance the load.
//! let total: nalgebra::Vector3<f64> = rec.reactions.iter().sum();
//! assert!((total + tip_load(1000.0, 0.0, PI)?).norm() < 1e-8);
//! # Ok::<(), MichellError>(())
//! ```
#![warn(missing_docs)]

pub mod complexity;
pub mod error;
pub mod extra_strings;
pub mod global;
pub mod loads;
pub mod nodes;
pub mod nominal_region;
pub mod optimize;
pub mod params;
pub mod planar;
pub mod propagation;
pub mod recursive;
pub mod report;
pub mod request;
pub mod signmap;
pub mod sizing;
pub mod solution;
pub mod truss;

pub use complexity::{mass_rows, mass_vs_complexity, MassRow};
pub use error::{MichellError, Result};
pub use extra_strings::{
    gamma_sweep, solve_prestressed, ExtraStrings, GammaSweep, GammaSweepRow, SweepMember,
};
pub use loads::{in_plane_load, tip_load, NodalLoads};
pub use nodes::NodeTuple;
pub use params::{Geometry, MichellParams};
pub use propagation::{propagate, propagate_recursive, ForceSolution, Method};
pub use report::{analyse, AnalysisRequest, MichellAnalysis, MichellReport};
pub use request::{
    ExtraStringsCheck, ExtraStringsPrestress, MichellOptimizeRequest, MichellRequest, MichellRun,
    MichellTable, MichellTableRequest,
};
pub use signmap::{sign_map_rows, sign_maps, AngleGrid, SignMap, SignMapBasis, SignMapRow};
pub use sizing::{normalized_yield_mass, size_members, MemberKind, TrussSizing};
pub use truss::{Branch, Member, MichellTruss, Node};
