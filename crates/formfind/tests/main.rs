//! The integration tests of this package, one test binary (one link instead of one per
//! file: a clean `cargo test --workspace` fits the CI machine's disk). Each file of this
//! directory is a module; run one with `cargo test --test integration FILE::`.

mod clusters;
mod design;
mod edges;
mod errors;
mod forms;
mod loads;
mod sensitivity;
