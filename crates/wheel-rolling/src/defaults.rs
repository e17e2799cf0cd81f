//! Named defaults of the rolling models: the values the front ends show as their defaults
//! and what the library uses when a request leaves them at [`Default`].
//!
//! Units are SI. They reproduce the thesis set-up of §3.2 (Figs. 3.10 and 3.11): a wheel on a
//! 50° slope, plastic impacts, μ_s = 0.8, strings of 2·10⁴ N/m and a penalty ground of
//! 10⁵ N/m per contact node, RK4 at 0.1 ms with 1 ms samples.

/// Standard gravity g (m/s²).
pub const GRAVITY: f64 = 9.81;

/// Slope of the rolling studies (degrees).
pub const INCLINE_DEG: f64 = 50.0;

/// Simulated time of a rolling run (s).
pub const ROLL_T_END: f64 = 10.0;

/// Integration step of the rolling models (s): the fixed step of the rigid model and of the
/// full model's explicit integrators (RK4, RATTLE), the largest step of the adaptive ones.
pub const ROLL_DT: f64 = 1e-4;

/// Step of the full model under IMEX with a penalty ground and the default strings (s): its
/// contact damping is implicit, so the step follows the strings and the motion; at 5·10⁻⁴ s
/// the n = 24 wheel down 50° for 10 s closes its energy budget to 7·10⁻³ (7·10⁻⁴ s misses
/// it: 1.9·10⁻²).
pub const IMEX_ROLL_DT: f64 = 5e-4;

/// Step of the full model under IMEX-ARK ([`IntegratorKind::ImexArk`](tensegrity_dynamics::IntegratorKind::ImexArk))
/// with a penalty ground and the default strings (s). On the reference pivot of
/// docs/notes/ROLLING.md (n = 8 on 30°, μ = 1.2) it follows the axle to 1.5·10⁻⁶ m before the
/// impact, where the split IMEX at [`IMEX_ROLL_DT`] is 1.1·10⁻² m off; at 5·10⁻⁴ s its
/// stage equations stall on the Stribeck weakening more often (432 of 6,514 stages).
pub const IMEX_ARK_ROLL_DT: f64 = 2.5e-4;

/// The shortest default step of the full model under IMEX (s): what [`full_dt`] gives for
/// strings of 8·10⁶ N/m and stiffer. A bound on the cost, not on the accuracy: at 10⁷ N/m on
/// 50° for 1 s this step closes the energy budget to 1.9·10⁻⁴.
pub const IMEX_MIN_DT: f64 = 2.5e-5;

/// The full model's step when the request leaves `dt` unset. IMEX on a penalty or stick
/// ground: [`IMEX_ROLL_DT`] · √([`STRING_STIFFNESS`] / k), k the string stiffness, kept
/// within [[`IMEX_MIN_DT`], [`IMEX_ROLL_DT`]]: the strings stay in IMEX's explicit part, whose
/// error grows with their frequency √k (on 50° for 3 s, 5·10⁻⁴ s misses the energy budget
/// by 1.0·10⁻² at 10⁵ N/m and 2.0·10⁻² at 2·10⁵ N/m, where at 2·10⁶ N/m it diverges within
/// 5 ms). The floor was [`ROLL_DT`] until 2026-12-03; with strings and ground of 10⁶ N/m
/// (μ = 1.2, e = 0, 3 s) 10⁻⁴ s missed the budget by 1.3·10⁻² (n = 8 on 40°) and
/// 2.5·10⁻² (n = 10 on 20°), where the scaled 7.1·10⁻⁵ s closes it to 3.3·10⁻³ and
/// 4.9·10⁻³ (n = 6 and 24 on 50°: 1.2·10⁻³, 3.5·10⁻³). IMEX-ARK on those grounds: the same
/// rule from [`IMEX_ARK_ROLL_DT`]. [`ROLL_DT`] otherwise (the thesis
/// contact stays in the explicit part).
///
/// ```
/// use tensegrity_dynamics::IntegratorKind;
/// use wheel_rolling::{defaults, ContactKind};
/// let imex = |contact, k| defaults::full_dt(IntegratorKind::Imex, contact, k);
/// assert_eq!(imex(ContactKind::Penalty, 2e4), 5e-4);
/// assert!((imex(ContactKind::Stick, 8e4) - 2.5e-4).abs() < 1e-15);
/// assert!((imex(ContactKind::Penalty, 2e6) - 5e-5).abs() < 1e-15);
/// assert_eq!(imex(ContactKind::Penalty, 1e9), defaults::IMEX_MIN_DT);
/// assert_eq!(imex(ContactKind::Thesis, 2e4), 1e-4);
/// let ark = |k| defaults::full_dt(IntegratorKind::ImexArk, ContactKind::Penalty, k);
/// assert_eq!(ark(2e4), defaults::IMEX_ARK_ROLL_DT);
/// assert!((ark(8e4) - 1.25e-4).abs() < 1e-15);
/// assert_eq!(defaults::full_dt(IntegratorKind::Rk4, ContactKind::Penalty, 2e4), 1e-4);
/// ```
pub fn full_dt(
    integrator: tensegrity_dynamics::IntegratorKind,
    contact: crate::contact_kind::ContactKind,
    string_stiffness: f64,
) -> f64 {
    match integrator {
        tensegrity_dynamics::IntegratorKind::Imex if contact.is_penalty() => {
            let scaled = IMEX_ROLL_DT * (STRING_STIFFNESS / string_stiffness).sqrt();
            if scaled.is_nan() {
                ROLL_DT
            } else {
                scaled.clamp(IMEX_MIN_DT, IMEX_ROLL_DT)
            }
        }
        tensegrity_dynamics::IntegratorKind::ImexArk if contact.is_penalty() => {
            let scaled = IMEX_ARK_ROLL_DT * (STRING_STIFFNESS / string_stiffness).sqrt();
            if scaled.is_nan() {
                ROLL_DT
            } else {
                scaled.clamp(IMEX_MIN_DT, IMEX_ARK_ROLL_DT)
            }
        }
        _ => ROLL_DT,
    }
}

/// Output (sampling) interval of the rolling models (s).
pub const ROLL_OUTPUT_DT: f64 = 1e-3;

/// Interval of the node frames a front end writes as a VTK series (s).
pub const ROLL_FRAME_DT: f64 = 0.01;

/// Damping of the thesis contact model (§3.2.2), or normal damping of the penalty ground
/// (N·s/m).
pub const GROUND_DAMPING: f64 = 200.0;

/// Normal stiffness of the penalty ground per contact node (N/m).
pub const GROUND_STIFFNESS: f64 = 1e5;

/// Static friction coefficient μ_s of the ground.
pub const STATIC_FRICTION: f64 = 0.8;

/// Kinetic over static friction, μ_k = [`KINETIC_FRICTION_RATIO`] · μ_s.
pub const KINETIC_FRICTION_RATIO: f64 = 0.75;

/// Normal coefficient of restitution of a contact impact (0 = plastic, as in the thesis).
pub const RESTITUTION: f64 = 0.0;

/// String stiffness of the full rolling model (N/m); it also decides the `auto` fidelity.
pub const STRING_STIFFNESS: f64 = 2e4;

/// Smallest string tension of the full rolling model's prestress (N).
pub const ROLL_MIN_TENSION: f64 = 20.0;

/// The wheel sizes of thesis Fig. 3.10.
pub const FIG_3_10_SIDES: [usize; 4] = [8, 12, 16, 24];

/// Penetration tolerance of the full model's contact, as a fraction of R_o: a contact node
/// deeper than this below the slope flags the run (the wheel sank into the ground).
pub const PENETRATION_TOLERANCE: f64 = 0.01;

/// Friction regularisation velocity of the penalty ground (m/s): below it the tanh law
/// behaves as a stiff viscous stick.
pub const FRICTION_REGULARIZATION_VELOCITY: f64 = 1e-3;

/// Tangential spring stiffness of the stick contact over its normal stiffness, k_t / k: the
/// anchor spring that holds a stick (a node under a tangential load F < μ_s N rests at the
/// stretch F / k_t, a fraction of a millimetre for the defaults; see
/// `tensegrity_dynamics::stick`).
pub const TANGENTIAL_STIFFNESS_RATIO: f64 = 1.0;

/// Damping ratio of the stick contact's tangential spring–damper: c_t = ratio · √(2 k_t m_eff)
/// per node (1: critical for a landing pair, the stick does not ring).
pub const TANGENTIAL_DAMPING_RATIO: f64 = 1.0;

/// Stribeck velocity of the penalty ground (m/s): the static → kinetic transition; a contact
/// whose load-weighted slip speed Σ f_n |v_t| / Σ f_n is faster than this along the slope
/// counts as slipping.
pub const STRIBECK_VELOCITY: f64 = 1e-2;

/// Largest relative residual of the full model's energy budget that still counts as closed
/// (the budget is integrated by the trapezoidal rule at every integration step; the
/// reference toroid at the default 0.1 ms RK4 step misses by 2·10⁻³ after 2 s and 6·10⁻³
/// after 10 s of bouncing, falling with the step).
pub const ENERGY_BALANCE_TOLERANCE: f64 = 1e-2;

/// Largest relative residual of the rigid model's energy budget that still counts as closed
/// (it closes to ~10⁻¹² at the default step).
pub const RIGID_ENERGY_BALANCE_TOLERANCE: f64 = 1e-6;

/// A contact pair counts as a new contact (an impact) when it loads after being off the
/// ground for at least this long (s); shorter gaps are chatter of the same contact. (The pair
/// that carried the wheel before a flight needs [`IMPACT_WINDOW`]: a sliding pivot's hops.)
pub const CONTACT_REARM_TIME: f64 = 2e-3;

/// Longest contact transient of an impact of the full model (s): the impulse is integrated
/// from touch-down until the previously loaded pairs have left the ground, at most this long.
pub const IMPACT_WINDOW: f64 = 0.05;

/// Relative tolerance of the adaptive integrators (rk45, sdirk) in a rolling run: positions
/// to about 1 µm on a metre-sized wheel.
pub const ADAPTIVE_RTOL: f64 = 1e-6;

/// Absolute tolerance of the adaptive integrators in a rolling run.
pub const ADAPTIVE_ATOL: f64 = 1e-8;

/// Below this deformation measure m g / (k R_o) the `auto` fidelity considers the rigid
/// model (see [`crate::fidelity`]).
pub const RIGID_THRESHOLD: f64 = 1e-3;

/// Convergence tolerances τ of the rolling headline quantities (relative; a quantity is
/// converged when it moves by at most τ/2 at the refined resolution, see
/// [`crate::convergence`]): the first impact's time and ω⁻.
pub const CONVERGENCE_FIRST_IMPACT: f64 = 0.01;
/// … the mean speed and the mean axle height (means over the run).
pub const CONVERGENCE_MEAN: f64 = 0.02;
/// … the final speed (one state at the end).
pub const CONVERGENCE_FINAL_SPEED: f64 = 0.02;
/// … the axle-height oscillation and the number of impacts (counts and spreads).
pub const CONVERGENCE_SPREAD: f64 = 0.1;
/// … the airborne and slip fractions (absolute: their scale is 1).
pub const CONVERGENCE_FRACTION: f64 = 0.02;
