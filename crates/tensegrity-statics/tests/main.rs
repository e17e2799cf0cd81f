//! The integration tests of this package, one test binary (one link instead of one per
//! file: a clean `cargo test --workspace` fits the CI machine's disk). Each file of this
//! directory is a module; run one with `cargo test --test integration FILE::`.

mod clusters;
mod common;
mod margin;
mod nested_statics;
mod properties;
mod response;
mod sensitivity;
mod sizing;
mod sparse_statics;
mod sparse_statics_scaling;
mod statics;
mod statics_front;
mod stiffness;
mod supports;
mod symmetry;
