//! The integration tests of this package, one test binary (one link instead of one per
//! file: a clean `cargo test --workspace` fits the CI machine's disk). Each file of this
//! directory is a module; run one with `cargo test --test integration FILE::`.

mod closed_forms_q1;
mod common;
mod counts;
mod extra_strings;
mod fig_4_18;
mod global_levels;
mod nominal_region;
mod optimize;
mod planar;
mod projection;
mod recursion_vs_global;
mod report;
mod validation;
