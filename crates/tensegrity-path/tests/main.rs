//! The integration tests of this package, one test binary (one link instead of one per
//! file: a clean `cargo test --workspace` fits the CI machine's disk). Each file of this
//! directory is a module; run one with `cargo test --test integration FILE::`.

mod branch;
mod clusters;
mod common;
mod drivers;
mod elastic_supports;
mod fold_skip;
mod mixed_bars;
mod prism_slack;
mod slack;
mod sparse_branch;
mod sparse_spectrum;
mod stops;
mod transient;
mod tsgfem;
mod tsgfem_dynamics;
mod von_mises;
