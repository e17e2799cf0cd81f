//! # wheel-rolling
//!
//! Rolling of any wheel down an incline, for the topology crates (the toroid, the T-bar
//! wheel) that describe their wheel through [`Wheel`]:
//!
//! - [`rigid`]: the reduced rigid model — the wheel's contact polygon ([`Polygon`]: n
//!   vertices on radius R_o, mass m, I₁) as a hybrid system with unilateral contact: pivot
//!   (I₁ + m R_o²) θ̈ = m g R_o sin(θ + φ), Coulomb slip, ballistic flight, resting or sliding
//!   sides, impacts with Newton restitution and a Coulomb impulse, events located to
//!   round-off and an energy budget E(t) − E(0) = −(impact and friction losses) that closes to
//!   ~10⁻¹²;
//! - [`full`]: the full model — a prestressed wheel ([`WheelScene`]: rigid massive bars,
//!   elastic strings, its contact groups, in its starting pose) in the core's constrained
//!   dynamics N̈M + NK = W + ΩPᵀ on a tilted gravity g₀(0, sin φ, −cos φ), against a penalty
//!   ground N = max(0, k δ − c δ̇) with regularised Coulomb friction (or the thesis contact),
//!   every step monitored for validity, the budget E(t) − E(0) = W_nc(t) and impacts;
//! - [`contact`]: the contact kinds and the penalty damping c = ζ(e) √(2 k m_eff) with
//!   ζ = −ln e / √(π² + ln² e) and m_eff = 1/(1/m + R_o² sin²(π/n)/I₁);
//! - [`validity`]: the record both models fill ([`RollValidity`], [`ImpactRecord`]);
//! - [`sample`] and [`summary`]: the sampled history, its summary ([`RunSummary`]) and one
//!   wheel's run as a comparison shows it ([`WheelRun`]);
//! - [`fidelity`]: the one fidelity decision ([`Decision`], [`Plan`]) used by the run and by
//!   its estimate: `auto` is rigid when ε = m g/(k R_o) < 10⁻³, the models agree within
//!   their uncertainty on the scene's class (the measured table [`fidelity::MEASURED`]) and
//!   the rigid run is valid, else full;
//! - [`estimate`]: resource estimates of rigid and full runs from sizes, and of a plan;
//! - [`settings`]: [`RollSettings`], the serde settings every rolling request flattens, and
//!   the resolved [`RunSpec`];
//! - [`observer`]: the hook that receives every sample and frame as it is made and may stop
//!   the run ([`Observer`]);
//! - [`run`]: [`roll_wheel`], one run of any [`Wheel`] under the decision;
//! - [`convergence`]: [`roll_checked`], the run and its repetition at a companion step
//!   (twice it where that serves, else half of it) side by side, from a start turned by
//!   10⁻⁶ rad, each headline quantity compared, and a twin only where one moved;
//! - [`ensemble`]: K copies from perturbed starting poses in parallel, the mean and 95 %
//!   interval of every headline quantity against the other model;
//! - [`frames`]: the rigid model's node frames; [`defaults`]: the named defaults.
//!
//! ```
//! use wheel_rolling::{roll_wheel, FidelityChoice, Polygon, RunSpec};
//! // an octagon of 12 kg and I₁ = 7.5 kg m² down 50° for one second, rigid model
//! let octagon = Polygon { sides: 8, outer_radius: 1.0, mass: 12.0, i1: 7.5 };
//! let spec = RunSpec { fidelity: FidelityChoice::Rigid, t_end: 1.0, ..RunSpec::default() };
//! let run = roll_wheel(&octagon, &spec, &[], None).unwrap();
//! assert!(run.result.mean_speed > 0.0 && run.result.validity.valid());
//! ```
#![warn(missing_docs)]

pub mod contact;
mod contact_kind;
pub mod convergence;
pub mod defaults;
pub mod ensemble;
mod error;
pub mod estimate;
pub mod fidelity;
mod fidelity_choice;
mod frame;
pub mod frames;
pub mod full;
pub mod observer;
mod polygon;
pub mod rigid;
pub mod run;
pub mod sample;
pub mod settings;
pub mod summary;
pub mod validity;

pub use contact::{ContactKind, ContactModel, GroundContact};
pub use convergence::roll_checked;
pub use ensemble::Ensemble;
pub use error::{strict_check, Result, RollingError};
pub use fidelity::{Decision, Fidelity, FidelityChoice, Plan};
pub use full::{FullRolling, FullRun, WheelFrame, WheelScene};
pub use observer::{Flow, Observer};
pub use rigid::{Polygon, RigidRolling, RigidRun};
pub use run::{roll_decided, roll_wheel, Rolled, Wheel};
pub use sample::{RollingResult, RollingSample};
pub use settings::{RollSettings, RunSpec};
pub use summary::{FirstImpact, RunSummary, WheelRun};
pub use tensegrity_core::request::RunChecks;
pub use tensegrity_dynamics::{Convergence, QuantityConvergence};
pub use validity::{ImpactRecord, RollValidity};
