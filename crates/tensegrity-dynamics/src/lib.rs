//! Rigid-bar tensegrity dynamics N̈M + NK = W + ΩPᵀ (Skelton/Goyal, thesis ch. 2 with
//! ERRATA 2.1–2.8).
//!
//! # Equations
//!
//! * Class-1 node dynamics, bar by bar (J = m_b/12, current length l):
//!   J b̈ = ½(f₂ − f₁) − (1/(2l²)) b bᵀ(f₂ − f₁) − (J/l²) b ‖ḃ‖², m_b r̈ = f₁ + f₂; equivalently
//!   N̈M + NK = F with M = C_bᵀĴC_b + C_rᵀm̂C_r, K = C_sᵀγ̂C_s − C_bᵀλ̂C_b and
//!   λ̂ = −Ĵ l̂⁻²⌊ḂᵀḂ⌋ − ½ l̂⁻²⌊BᵀFC_bᵀ⌋.
//! * Forces F = W − Sγ̂C_s + ΩPᵀ: loads, gravity m_b g/2 at each bar end, strings
//!   γ = max(0, k(1 − s0/‖s‖) + c sᵀṡ/‖s‖²) when ‖s‖ > s0 (else 0), ground contact
//!   ([`forces`]), and the constraint forces ΩPᵀ.
//! * Class-k joints and supports: class-1 copies with N P = D; Ω from the closed form
//!   [(PᵀM⁻¹P)⊗I₃ − ¼ Σ_k (J_k l_k²)⁻¹ (h_k h_kᵀ)⊗(b_k b_kᵀ)] vec Ω = vec(D̈ − N̈₀P),
//!   h_k = Pᵀc_k, solved with a sparse Cholesky factorisation whose symbolic part is reused
//!   ([`model`], `omega`); for a few jointed bars the same system is solved in joint space
//!   (N P = D eliminated exactly, one multiplier per bar: `omega::joint_space`).
//!
//! # Integrators
//!
//! [`Rk4`] (fixed step, MOTES parity), [`Dopri5`] (adaptive 5(4), dense output, events),
//! [`Rattle`] (constraint-preserving, symplectic, 2nd order) and [`Sdirk`] (adaptive,
//! L-stable, 3rd order, Newton with a finite-difference Jacobian: stiff strings and stiff or
//! dissipative contact at the step the rigid-body motion needs), [`Imex`] and [`ImexArk`]
//! (the ground's stiff part implicit) and [`Flight`], all behind the [`Integrator`]
//! trait ([`integrator`]) that the one driver loop of [`Simulation::run`] steps. The methods are
//! written against the system they advance ([`System`]: state and right-hand side;
//! [`ConstrainedSystem`]: the constraints, their projection and RATTLE's pieces;
//! [`ContactSystem`]: the contact split), which [`Model`] implements, and take their
//! coefficients from one [`Tableau`] type ([`tableau`]); what each method is (order, implicit
//! parts, events, purpose) is [`IntegratorKind::facts`]. Sign changes
//! of event functions are located by [`events`]; RK states can be projected back onto the
//! constraints ([`SimulationSettings::project`]). Every run reports its work counters
//! ([`IntegratorStats`]); `work_precision` (feature `test-models`) measures error against
//! time on the test models.
//!
//! # Example
//!
//! ```
//! use tensegrity_core::{Bar, Structure, Support};
//! use tensegrity_dynamics::{IntegratorKind, Simulation, SimulationSettings};
//! // A pendulum: one 1 kg bar pinned at the origin, released horizontally.
//! let s = Structure::builder()
//!     .nodes([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]])
//!     .bar(Bar::new(0, 1).mass(1.0))
//!     .support(Support::pinned(0))
//!     .gravity([0.0, 0.0, -9.81])
//!     .build()
//!     .unwrap();
//! let settings = SimulationSettings {
//!     t_end: 0.3,
//!     integrator: IntegratorKind::Rk45,
//!     ..Default::default()
//! };
//! let r = Simulation::new(&s, settings).unwrap().run().unwrap();
//! assert!(r.final_nodes[0].norm() < 1e-12); // the pin holds
//! assert!(r.energy_drift < 1e-7);
//! ```

pub mod anchor;
pub mod ark;
pub mod cluster_forces;
pub mod constraints;
mod contact_split;
pub mod convergence;
pub mod drift;
pub mod estimate;
pub mod events;
mod factory;
pub mod flight;
pub mod forces;
pub mod identify;
pub mod imex;
pub mod integrator;
pub mod kind;
pub mod model;
pub mod monitors;
mod omega;
pub mod rattle;
pub mod recorder;
pub mod report;
pub mod rk4;
pub mod rk45;
pub mod sdirk;
pub mod sensitivity;
pub mod simulation;
pub mod stepper;
pub mod stick;
pub mod strings;
pub mod system;
pub mod tableau;
#[cfg(any(test, feature = "test-models"))]
pub mod test_models;
#[cfg(any(test, feature = "test-models"))]
pub mod work_precision;

pub use anchor::Anchor;
pub use ark::ImexArk;
pub use constraints::ConstraintSet;
pub use convergence::{Convergence, QuantityConvergence};
pub use drift::{DriftLimits, DriftQuantity, DriftWarning};
pub use events::{Event, EventFn, EventHit, StateView};
pub use flight::Flight;
pub use forces::{Ground, GroundModel};
pub use imex::Imex;
pub use integrator::{Integrator, IntegratorStats, StepOutcome};
pub use kind::{Implicit, IntegratorFacts, IntegratorKind};
pub use model::{LoadFn, Model, NodeRef, RestLengthFn, Workspace};
pub use monitors::Monitor;
pub use rattle::Rattle;
pub use recorder::{Quantities, Recorder, Sample, SampleSink};
pub use report::SimulationReport;
pub use rk4::Rk4;
pub use rk45::Dopri5;
pub use sdirk::{Sdirk, SdirkStats};
pub use simulation::{Simulation, SimulationResult, SimulationSettings};
pub use stepper::{Action, Actuator, ActuatorTarget, Stepper, StepperState};
pub use strings::StringLaw;
pub use system::{ConstrainedSystem, ContactSystem, System};
pub use tableau::Tableau;

/// The README's examples, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
