//! The integration tests of this package, one test binary (one link instead of one per
//! file: a clean `cargo test --workspace` fits the CI machine's disk). Each file of this
//! directory is a module; run one with `cargo test --test integration FILE::`.

mod drift_warnings;
mod dynamics_basic;
mod dynamics_chatter;
mod dynamics_clusters;
mod dynamics_contact;
mod dynamics_features;
mod dynamics_flight;
mod dynamics_orders;
mod dynamics_stick;
mod dynamics_stiff;
mod integrator_stats;
mod sensitivity;
mod stepper;
