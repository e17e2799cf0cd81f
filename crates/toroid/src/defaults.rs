//! Named defaults and policies of the toroid studies: the values the CLI shows as its
//! defaults, and what the library uses when a request leaves them at [`Default`].
//!
//! Units are SI. The rolling defaults reproduce the thesis set-up of §3.2 (Figs. 3.10 and
//! 3.11): the reference wheel (n = 8, spokes + inner rings, 1 kg/m bars) on a 50° slope.

/// Standard gravity g (m/s²) of every toroid study.
pub const GRAVITY: f64 = 9.81;

/// Bar mass per length of the reference wheel (kg/m); strings are massless.
pub const BAR_DENSITY: f64 = 1.0;

/// Slope of the rolling studies (degrees).
pub const INCLINE_DEG: f64 = 50.0;

/// Simulated time of a rolling run (s).
pub const ROLL_T_END: f64 = 10.0;

/// Integration step of the rolling models (s): the fixed RK4 step of both models.
pub const ROLL_DT: f64 = 1e-4;

/// Output (sampling) interval of the rolling models (s).
pub const ROLL_OUTPUT_DT: f64 = 1e-3;

/// Damping of the thesis contact model (§3.2.2), or normal damping of the penalty ground
/// (N·s/m).
pub const GROUND_DAMPING: f64 = 200.0;

/// Normal stiffness of the penalty ground (N/m).
pub const GROUND_STIFFNESS: f64 = 1e5;

/// Static friction coefficient μ_s of the penalty ground.
pub const STATIC_FRICTION: f64 = 0.8;

/// Normal coefficient of restitution of a contact impact (0 = plastic, as in the thesis).
pub const RESTITUTION: f64 = 0.0;

/// Kinetic over static friction, μ_k = [`KINETIC_FRICTION_RATIO`] · μ_s.
pub const KINETIC_FRICTION_RATIO: f64 = 0.75;

/// String stiffness of the full rolling model (N/m); it also decides the `auto` fidelity.
pub const STRING_STIFFNESS: f64 = 2e4;

/// Smallest string tension of the full rolling model's prestress (N).
pub const ROLL_MIN_TENSION: f64 = 20.0;

/// Smallest string tension of the prestress design that `toroid_report` shows (N).
pub const DESIGN_MIN_TENSION: f64 = 10.0;

/// The wheel sizes of thesis Fig. 3.10 (the rolling series of [`crate::rolling_series`]).
pub const FIG_3_10_SIDES: [usize; 4] = [8, 12, 16, 24];

/// The rim-radius window of a single prism is searched on
/// (`RIM_WINDOW_FROM` R_o, `RIM_WINDOW_TO` R_o).
pub const RIM_WINDOW_FROM: f64 = 0.02;

/// Upper end of the rim-radius search, as a multiple of R_o.
pub const RIM_WINDOW_TO: f64 = 1.5;

/// Grid points of the rim-radius search before bisection.
pub const RIM_WINDOW_SAMPLES: usize = 75;

/// Bisection tolerance of the rim-radius window (m).
pub const RIM_WINDOW_TOL: f64 = 1e-6;

/// Penetration tolerance of the full model's contact, as a fraction of R_o: a contact node
/// deeper than this below the slope flags the run (the wheel sank into the ground).
pub const PENETRATION_TOLERANCE: f64 = 0.01;

/// Friction regularisation velocity of the penalty ground (m/s): below it the tanh law
/// behaves as a stiff viscous stick.
pub const FRICTION_REGULARIZATION_VELOCITY: f64 = 1e-3;

/// Stribeck velocity of the penalty ground (m/s): the static → kinetic transition; a loaded
/// contact node faster than this along the slope counts as slipping.
pub const STRIBECK_VELOCITY: f64 = 1e-2;

/// Largest relative residual of the full model's energy budget that still counts as closed
/// (the budget is integrated by the trapezoidal rule at every integration step; the
/// reference wheel at the default 0.1 ms RK4 step misses by 2·10⁻³ after 2 s and 6·10⁻³
/// after 10 s of bouncing, falling with the step).
pub const ENERGY_BALANCE_TOLERANCE: f64 = 1e-2;

/// A contact pair counts as a new contact (an impact) when it loads after being off the
/// ground for at least this long (s); shorter gaps are chatter of the same contact.
pub const CONTACT_REARM_TIME: f64 = 2e-3;

/// Longest contact transient of an impact of the full model (s): the impulse is integrated
/// from touch-down until the previously loaded pairs have left the ground, at most this long.
pub const IMPACT_WINDOW: f64 = 0.05;

/// Interval of the node frames written by `tensegrity roll --vtk` (s).
pub const ROLL_FRAME_DT: f64 = 0.01;
