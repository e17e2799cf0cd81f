//! The shared test structures, from `tensegrity_core::test_models` (one copy for the tests,
//! the benches and the work–precision study).
#![allow(dead_code, unused_imports)]

pub use tensegrity_core::test_models::{alu, dbar_frame as dbar, snelson};
use tensegrity_core::Structure;

/// The 45° D-bar spanning `span` with one string, compressed by `load` at node 3, node 0
/// supported; all members of the benchmark aluminium.
pub fn loaded_dbar(span: f64, load: f64) -> Structure {
    tensegrity_core::test_models::loaded_dbar(span, load).unwrap()
}
