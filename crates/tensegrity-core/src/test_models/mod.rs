//! Canonical structures with their reference answers, shared by the unit and integration
//! tests, the benches and the work–precision study.
//!
//! Compiled into the crate's own tests, and for other crates behind the cargo feature
//! `test-models`. One file per model; every model documents where its reference numbers come
//! from (a closed form, a published value, or an invariant of the method).
//!
//! | model | function | reference answer |
//! |---|---|---|
//! | D-bar (thesis §2.2.1) | [`dbar`], [`dbar_frame`], [`loaded_dbar`], [`partly_supported_dbar`] | one self-stress; C of eq. 2.8–2.10; hand-calculated forces |
//! | Snelson prism | [`snelson_prism`], [`snelson`] | self-stress only at twist π/2 − π/p ([`snelson_twist`]); q ratios 1 : 1 : √3 : −√3 |
//! | double pendulum | [`double_pendulum`] | published tip at t = 5 s ([`DOUBLE_PENDULUM_TIP_5S`]) |
//! | MOTES D-bar | [`motes_dbar`] | N P = D and bar lengths kept over 5000 RK4 steps |
//! | dropped prism | [`dropped_prism`], `tensegrity_dynamics::test_models::dropped_prism_ground` | rest penetration m g / (3 k) per foot ([`dropped_prism_penetration`]) |
//! | spinning bar | [`spinning_bar`] | exact rotation ([`spinning_bar_exact`]) |
//! | double-layer lattice | [`double_layer_grid`] | sparse statics scaling; dense agreement |
//! | six-bar icosahedron | [`six_bar`], [`six_bar_nodes`] | self-equilibrium with bar force density −(3/2) q (closed form at a node) |
//! | chains and towers | [`dbar_chain`], [`prism_stack`], [`snelson_tower`], [`snelson_tower_free`] | size scaling for benches |

mod chains;
mod dbar;
mod double_pendulum;
mod dropped_prism;
mod lattice;
mod motes_dbar;
mod motes_prism;
mod six_bar;
mod snelson;
mod spinning_bar;

pub use chains::{dbar_chain, prism_stack, snelson_tower, snelson_tower_free};
pub use dbar::{
    alu, bar_pinned_at_both_ends, dbar, dbar_frame, loaded_dbar, partly_supported_dbar,
};
pub use double_pendulum::{double_pendulum, DOUBLE_PENDULUM_G, DOUBLE_PENDULUM_TIP_5S};
pub use dropped_prism::{dropped_prism, dropped_prism_penetration, DROPPED_PRISM_G};
pub use lattice::double_layer_grid;
pub use motes_dbar::{motes_anchor_dbar, motes_dbar, MOTES_DBAR_DT, MOTES_DBAR_STEPS};
pub use motes_prism::motes_anchor_prism;
pub use six_bar::{six_bar, six_bar_nodes};
pub use snelson::{oscillating_prism, snelson, snelson_prism, snelson_twist, PrismParams};
pub use spinning_bar::{spinning_bar, spinning_bar_exact};
