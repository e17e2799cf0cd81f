//! The integration tests of this package, one test binary (one link instead of one per
//! file: a clean `cargo test --workspace` fits the CI machine's disk). Each file of this
//! directory is a module; run one with `cargo test --test integration FILE::`. But
//! `interrupt.rs`: the interrupt flag is process-wide, so it is a test binary of its own
//! (`--test interrupt`).

mod examples;
mod merge_memory;
mod merge_spec;
mod merge_stream;
mod shards;
mod spec_fuzz;
mod sweeps;
