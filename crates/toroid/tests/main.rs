//! The integration tests of this package, one test binary (one link instead of one per
//! file: a clean `cargo test --workspace` fits the CI machine's disk). Each file of this
//! directory is a module; run one with `cargo test --test integration FILE::`.

mod builder_identity;
mod fidelity_classes;
mod roll_crossval;
mod rolling;
mod rolling_ark;
mod rolling_convergence;
mod rolling_full;
mod rolling_full_validity;
mod rolling_lean;
mod rolling_pivot;
mod rolling_stick;
mod scale_with_n;
mod symmetry;
mod tipover_dynamic;
mod toroid;
mod wheel_scene;
