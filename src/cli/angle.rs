//! Angles on the command line (DESIGN.md): the parser lives in the sweeps crate
//! ([`sweeps::angle::parse_angle`]) so that sweep specs and flags read angles the same way.

pub use sweeps::angle::parse_angle;
