//! Angles on the command line (DESIGN.md): the parser of every front end
//! ([`tensegrity_core::angle::parse_angle`]).

pub use tensegrity_core::angle::parse_angle;
