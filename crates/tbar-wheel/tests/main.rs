//! The integration tests of this package, one test binary (one link instead of one per
//! file: a clean `cargo test --workspace` fits the CI machine's disk). Each file of this
//! directory is a module; run one with `cargo test --test integration FILE::`.

mod cyclic_report;
mod envelope;
mod geometry;
mod mass;
mod rim;
mod rolling_full;
mod symmetry;
