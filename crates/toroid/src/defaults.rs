//! Named defaults and policies of the toroid studies: the values the CLI shows as its
//! defaults, and what the library uses when a request leaves them at [`Default`].
//!
//! Units are SI. The rolling defaults (contact, friction, restitution, step, output interval,
//! tolerances) are wheel-rolling's ([`wheel_rolling::defaults`], re-exported here); they
//! reproduce the thesis set-up of §3.2 (Figs. 3.10 and 3.11): the reference wheel (n = 8,
//! spokes + inner rings, 1 kg/m bars) on a 50° slope.

pub use wheel_rolling::defaults::*;

/// Bar mass per length of the reference wheel (kg/m); strings are massless.
pub const BAR_DENSITY: f64 = 1.0;

/// Smallest string tension of the prestress design that `toroid_report` shows (N).
pub const DESIGN_MIN_TENSION: f64 = 10.0;

/// The rim-radius window of a single prism is searched on
/// (`RIM_WINDOW_FROM` R_o, `RIM_WINDOW_TO` R_o).
pub const RIM_WINDOW_FROM: f64 = 0.02;

/// Upper end of the rim-radius search, as a multiple of R_o.
pub const RIM_WINDOW_TO: f64 = 1.5;

/// Grid points of the rim-radius search before bisection.
pub const RIM_WINDOW_SAMPLES: usize = 75;

/// Bisection tolerance of the rim-radius window (m).
pub const RIM_WINDOW_TOL: f64 = 1e-6;

/// The number of sides at which a wheel's tread offset D is given when `scale_with_n` scales
/// it (D_n = D · 8 / n): the reference wheel's.
pub const SCALE_REFERENCE_SIDES: usize = 8;
