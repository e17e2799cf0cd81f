//! # tensegrity
//!
//! A toolkit for tensegrity mechanics: statics, stiffness, minimum-mass sizing and dynamics of
//! bar-and-string structures, plus the topologies of the thesis (toroid wheel, discrete Michell
//! truss, T-bar wheel).
//!
//! This crate is a thin facade over the workspace crates and hosts the `tensegrity` binary.
//!
//! ```
//! use tensegrity::core::{Bar, StringMember, Structure};
//! use tensegrity::statics::Statics;
//! // a planar D-bar (thesis §2.2.1): 4 bars, 2 strings, one self-stress
//! let s = Structure::builder()
//!     .nodes([[0.0, 0.0, 0.0], [1.0, 0.5, 0.0], [1.0, -0.5, 0.0], [2.0, 0.0, 0.0]])
//!     .bar(Bar::new(0, 1)).bar(Bar::new(0, 2)).bar(Bar::new(1, 3)).bar(Bar::new(2, 3))
//!     .string(StringMember::new(0, 3)).string(StringMember::new(1, 2))
//!     .build()
//!     .unwrap();
//! assert_eq!(Statics::new(&s).unwrap().self_stress_dim(), 1);
//! ```
#![warn(missing_docs)]

pub use michell3d;
pub use sweeps;
pub use tbar_wheel;
pub use tensegrity_core as core;
pub use tensegrity_dynamics as dynamics;
pub use tensegrity_io as io;
pub use tensegrity_linalg as linalg;
pub use tensegrity_statics as statics;
pub use toroid;

/// The example scenes shipped with the toolkit, as `(file name, TOML text)`.
pub const EXAMPLE_SCENES: &[(&str, &str)] = &[
    ("dbar.toml", include_str!("../examples/dbar.toml")),
    (
        "dbar_loaded.toml",
        include_str!("../examples/dbar_loaded.toml"),
    ),
    ("prism.toml", include_str!("../examples/prism.toml")),
    ("tbar.toml", include_str!("../examples/tbar.toml")),
    ("tower.toml", include_str!("../examples/tower.toml")),
];

/// The README's Rust examples, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;

/// The Rust examples of the library guide, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../docs/guide/library.md")]
struct LibraryGuideDoctests;
