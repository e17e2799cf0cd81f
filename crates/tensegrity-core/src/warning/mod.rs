//! Warnings of a report: a result computed outside its model's assumptions, or a check it
//! failed, as data ([`Warning`], one variant per situation, with its numbers as fields).
//!
//! A warning is rendered to text in one place (its `Display`, in `render.rs`) and serialised
//! as an object `{kind, message, …fields}`: `kind` the variant's snake_case name (stable),
//! `message` the rendered text, then the variant's fields. Reading one back ignores
//! `message` (it is derived).
//!
//! ```
//! use tensegrity_core::warning::Warning;
//! let w = Warning::GroundPulled { min_normal: -2.5 };
//! assert_eq!(w.kind(), "ground_pulled");
//! assert_eq!(w.to_string(), "the ground pulled on the wheel (normal force down to -2.500 N): a real slope only pushes");
//! let v = serde_json::to_value(&w).unwrap();
//! assert_eq!(v["kind"], "ground_pulled");
//! assert_eq!(v["min_normal"], -2.5);
//! assert_eq!(v["message"], w.to_string());
//! let back: Warning = serde_json::from_value(v).unwrap();
//! assert_eq!(back, w);
//! ```

mod render;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// The invariant a drift warning is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
#[non_exhaustive]
pub enum DriftInvariant {
    /// Total energy of a conservative model.
    Energy,
    /// Total energy of a passive model, which may only fall.
    EnergyGrowth,
    /// Rigid bar lengths.
    BarLength,
    /// The linear constraints N P = D.
    Constraint,
    /// The stage equations of an implicit method (the fraction left unconverged).
    ImplicitSolve,
    /// The tangential velocity of touching contact nodes under the split IMEX (the fraction of
    /// contact node-steps whose velocity change reversed against the previous step's: a
    /// creeping contact chattering about its slaved creep).
    CreepChatter,
}

/// A side and the smallest net normal force of one rolling run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LiftOff {
    /// The wheel's number of sides n.
    pub sides: usize,
    /// The smallest net normal force of the run (N, negative).
    pub min_normal: f64,
}

/// One warning of a report (module docs). Numbers are SI (m, s, N, J); fractions are
/// fractions, not percent.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(remote = "Self", tag = "kind", rename_all = "snake_case")]
#[non_exhaustive]
pub enum Warning {
    // --- statics and form-finding ---
    /// The self-stress admits no state with every string in tension and every bar in
    /// compression.
    NotPrestressable,
    /// The prestressed form has a mechanism the prestress does not stiffen.
    NotPrestressStable,
    /// No prestressed structure could be synthesised.
    NoPrestressedStructure {
        /// Why.
        reason: String,
    },
    /// The statics decision is not certified (e.g. a rank decision without a clear gap).
    StaticsNotCertified {
        /// Why.
        reason: String,
    },
    /// No load envelope could be computed.
    NoLoadEnvelope {
        /// Why.
        reason: String,
    },
    /// The statics of a rim body are free-body statics; the envelope, minimum prestress and
    /// mass take the rigid rim.
    RimFreeBody,
    /// A method `auto` chose in place of the one the data named (e.g. the adaptive force
    /// density method after the force density method found no form).
    MethodChosen {
        /// Why, and what it replaced.
        reason: String,
    },
    /// No cyclic symmetry: the statics fell back to the dense SVD.
    NoCyclicSymmetry {
        /// Why the symmetry was not found.
        reason: String,
    },
    /// A prestress below the minimum that carries the load envelope: strings slacken (or the
    /// bar goes into tension) under some loads of the envelope, so the mass sized at this
    /// prestress is not a sizing for the envelope.
    PrestressBelowMinimum {
        /// The prestress asked for: the bar compression (N).
        prestress: f64,
        /// The smallest bar compression that carries the envelope (N).
        minimum: f64,
        /// The envelope's tip load w₀ (N).
        load: f64,
        /// The fraction of the sampled load directions that slacken a string or put the bar
        /// in tension.
        slack_fraction: f64,
    },
    // --- rolling and contact ---
    /// A single loop of tips in one plane has no track: it tips under any lateral force.
    SingleLoopTrack,
    /// A prestress too small to keep every string taut under the wheel's weight per tip.
    SlackInContact {
        /// The smallest string tension of the prestress (N).
        min_tension: f64,
        /// The tip load the prestress carries with every string taut (N).
        capacity: f64,
        /// The tips a landing shares the weight among.
        tips: usize,
        /// The weight per landing tip, m g / tips (N).
        per_tip: f64,
        /// The smallest tension that would carry it (N).
        suggested_min_tension: f64,
    },
    /// A contact node sank below the ground by more than the tolerance.
    SankBelowGround {
        /// The deepest penetration (m).
        depth: f64,
        /// The tolerance (m).
        tolerance: f64,
    },
    /// A contact node sank below the slope by more than the tolerance: the contact is too
    /// soft for the wheel.
    SankBelowSlope {
        /// The deepest penetration (m).
        depth: f64,
        /// The tolerance (m).
        tolerance: f64,
        /// The tolerance as a fraction of the outer radius R_o.
        tolerance_fraction: f64,
    },
    /// The ground pulled on the wheel (a negative normal force).
    GroundPulled {
        /// The smallest normal force (N).
        min_normal: f64,
    },
    /// The net normal force of rolling runs went negative: the wheel would leave the slope.
    LiftOff {
        /// The model that ran (e.g. `full model`).
        model: String,
        /// The runs that lifted off.
        runs: Vec<LiftOff>,
    },
    /// The energy budget of a run does not close within its tolerance.
    EnergyBudget {
        /// The miss, relative to the budget's largest term.
        error: f64,
        /// The tolerance.
        tolerance: f64,
    },
    /// The rigid model's energy budget does not close within its tolerance.
    RigidEnergyBudget {
        /// The miss, relative.
        error: f64,
    },
    /// A simultaneous impact did not converge.
    ImpactNotConverged {
        /// When (s).
        t: f64,
        /// The sweeps it took.
        sweeps: usize,
    },
    /// An impact created energy (Newton restitution with friction).
    ImpactCreatedEnergy {
        /// When (s).
        t: f64,
        /// The energy created (J).
        energy: f64,
    },
    // --- integration ---
    /// An invariant drifted past its limit.
    Drift {
        /// Which invariant.
        invariant: DriftInvariant,
        /// The measured relative drift (for `implicit_solve`: the fraction unconverged; for
        /// `creep_chatter`: the fraction of contact node-steps that chattered).
        value: f64,
        /// The limit it passed.
        limit: f64,
        /// What to change.
        remedy: String,
    },
    /// The integration stopped before its end time.
    StoppedEarly {
        /// When it stopped (s).
        t: f64,
        /// The end time asked for (s).
        t_end: f64,
        /// Why.
        reason: String,
    },
    /// The run was interrupted by its observer.
    Interrupted {
        /// When (s).
        t: f64,
        /// The end time asked for (s).
        t_end: f64,
    },
    /// The rigid model's event loop stopped early.
    RigidStopped {
        /// When (s).
        t: f64,
        /// Why.
        reason: String,
    },
    /// A reported quantity is not a finite number: the run left double precision.
    NonFinite {
        /// The quantity.
        quantity: String,
    },
    // --- convergence under refinement ---
    /// A quantity whose error, extrapolated from its change at the companion resolution,
    /// exceeds its tolerance.
    NotConverged {
        /// The quantity.
        quantity: String,
        /// Its value at the run's resolution (absent for a measured change).
        value: Option<f64>,
        /// Its value at the companion resolution (finer, or coarser: `refinement` says).
        refined: Option<f64>,
        /// The relative change (absent when one of the two values is missing).
        relative_change: Option<f64>,
        /// The error extrapolated with the documented order (relative).
        #[serde(default)]
        estimated_error: Option<f64>,
        /// The tolerance (relative).
        tolerance: f64,
        /// The refinement (e.g. `dt / 2`).
        refinement: String,
    },
    /// An optimiser (inverse form-finding) stopped by a cap or a failed line search before
    /// its convergence rule: the best point found is reported.
    OptimizerNotConverged {
        /// Why it stopped (`iterations`, `evaluations`, `line_search`).
        stop: String,
        /// The iterations it made.
        iterations: usize,
        /// The objective at the best point.
        objective: f64,
    },
    /// An optimiser (inverse form-finding) stopped by its objective rule (the objective fell
    /// by less than `ftol` in an iteration) at a point that its gradient rule does not call
    /// stationary: the objective stalled, which on an ill-conditioned problem can lie well
    /// above the optimum.
    OptimizerStalled {
        /// The projected gradient's largest entry there.
        projected_gradient: f64,
        /// The gradient rule's tolerance.
        gtol: f64,
        /// The objective there.
        objective: f64,
    },
    /// Members whose sign-free force density changed sign in a design: the designed topology
    /// lists them as the other kind.
    MembersChangedKind {
        /// The members (bars then strings, as given).
        members: Vec<usize>,
    },
    /// The refined run gave no result: nothing is known converged.
    RefinementFailed {
        /// The refinement and why it failed.
        refinement: String,
    },
    // --- aggregates ---
    /// A warning of one run of a table (e.g. the `full` run of the wheel with n sides).
    InRun {
        /// The wheel's number of sides n.
        sides: usize,
        /// Which run.
        run: String,
        /// The run's warning.
        warning: Box<Warning>,
    },
    /// A row of a table that failed.
    RowFailed {
        /// The wheel's number of sides n.
        sides: usize,
        /// The error.
        error: String,
    },
}

impl Warning {
    /// The stable snake_case name of the variant (the `kind` of its JSON).
    pub fn kind(&self) -> &'static str {
        use Warning as W;
        match self {
            W::NotPrestressable => "not_prestressable",
            W::NotPrestressStable => "not_prestress_stable",
            W::NoPrestressedStructure { .. } => "no_prestressed_structure",
            W::StaticsNotCertified { .. } => "statics_not_certified",
            W::NoLoadEnvelope { .. } => "no_load_envelope",
            W::RimFreeBody => "rim_free_body",
            W::NoCyclicSymmetry { .. } => "no_cyclic_symmetry",
            W::MethodChosen { .. } => "method_chosen",
            W::PrestressBelowMinimum { .. } => "prestress_below_minimum",
            W::SingleLoopTrack => "single_loop_track",
            W::SlackInContact { .. } => "slack_in_contact",
            W::SankBelowGround { .. } => "sank_below_ground",
            W::SankBelowSlope { .. } => "sank_below_slope",
            W::GroundPulled { .. } => "ground_pulled",
            W::LiftOff { .. } => "lift_off",
            W::EnergyBudget { .. } => "energy_budget",
            W::RigidEnergyBudget { .. } => "rigid_energy_budget",
            W::ImpactNotConverged { .. } => "impact_not_converged",
            W::ImpactCreatedEnergy { .. } => "impact_created_energy",
            W::Drift { .. } => "drift",
            W::StoppedEarly { .. } => "stopped_early",
            W::Interrupted { .. } => "interrupted",
            W::RigidStopped { .. } => "rigid_stopped",
            W::NonFinite { .. } => "non_finite",
            W::NotConverged { .. } => "not_converged",
            W::RefinementFailed { .. } => "refinement_failed",
            W::InRun { .. } => "in_run",
            W::RowFailed { .. } => "row_failed",
            W::OptimizerNotConverged { .. } => "optimizer_not_converged",
            W::OptimizerStalled { .. } => "optimizer_stalled",
            W::MembersChangedKind { .. } => "members_changed_kind",
        }
    }

    /// This warning as one of run `run` of the wheel with `sides` sides.
    pub fn in_run(self, sides: usize, run: impl Into<String>) -> Warning {
        Warning::InRun {
            sides,
            run: run.into(),
            warning: Box::new(self),
        }
    }
}

/// The warnings' texts joined with `; ` (for one-line messages).
pub fn joined(warnings: &[Warning]) -> String {
    let texts: Vec<String> = warnings.iter().map(ToString::to_string).collect();
    texts.join("; ")
}

/// The derived form (tag and fields) of a warning, to flatten beside its message.
struct Tagged<'a>(&'a Warning);

impl Serialize for Tagged<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        // the inherent function derived with `remote = "Self"`: tag and fields
        Warning::serialize(self.0, s)
    }
}

impl Serialize for Warning {
    /// `{kind, …fields, message}` (module docs).
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        struct WithMessage<'a> {
            #[serde(flatten)]
            warning: Tagged<'a>,
            message: String,
        }
        WithMessage {
            warning: Tagged(self),
            message: self.to_string(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Warning {
    /// The object of [`Serialize`]; `message` is ignored (it is rendered from the fields).
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Warning::deserialize(d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_is_its_serde_tag_and_round_trips() {
        let inner = Warning::Drift {
            invariant: DriftInvariant::BarLength,
            value: 1e-3,
            limit: 1e-6,
            remedy: "use a smaller `dt`".into(),
        };
        let all = vec![
            Warning::NotPrestressable,
            Warning::NotPrestressStable,
            Warning::NoPrestressedStructure { reason: "r".into() },
            Warning::StaticsNotCertified { reason: "r".into() },
            Warning::NoLoadEnvelope { reason: "r".into() },
            Warning::RimFreeBody,
            Warning::NoCyclicSymmetry { reason: "r".into() },
            Warning::MethodChosen { reason: "r".into() },
            Warning::PrestressBelowMinimum {
                prestress: 1.0,
                minimum: 3.2,
                load: 1.0,
                slack_fraction: 0.9,
            },
            Warning::SingleLoopTrack,
            Warning::SlackInContact {
                min_tension: 1.0,
                capacity: 2.0,
                tips: 3,
                per_tip: 4.0,
                suggested_min_tension: 2.0,
            },
            Warning::SankBelowGround {
                depth: 0.1,
                tolerance: 0.01,
            },
            Warning::SankBelowSlope {
                depth: 0.1,
                tolerance: 0.01,
                tolerance_fraction: 0.02,
            },
            Warning::GroundPulled { min_normal: -1.0 },
            Warning::LiftOff {
                model: "full model".into(),
                runs: vec![LiftOff {
                    sides: 5,
                    min_normal: -3.0,
                }],
            },
            Warning::EnergyBudget {
                error: 0.1,
                tolerance: 0.01,
            },
            Warning::RigidEnergyBudget { error: 0.1 },
            Warning::ImpactNotConverged { t: 1.0, sweeps: 50 },
            Warning::ImpactCreatedEnergy {
                t: 1.0,
                energy: 0.5,
            },
            inner.clone(),
            Warning::StoppedEarly {
                t: 1.0,
                t_end: 2.0,
                reason: "r".into(),
            },
            Warning::Interrupted { t: 1.0, t_end: 2.0 },
            Warning::RigidStopped {
                t: 1.0,
                reason: "r".into(),
            },
            Warning::NotConverged {
                quantity: "mean_speed".into(),
                value: Some(1.0),
                refined: Some(1.1),
                relative_change: Some(0.1),
                estimated_error: Some(0.2),
                tolerance: 0.02,
                refinement: "dt / 2".into(),
            },
            Warning::NonFinite {
                quantity: "mean_speed".into(),
            },
            Warning::RefinementFailed {
                refinement: "r".into(),
            },
            inner.in_run(5, "full"),
            Warning::RowFailed {
                sides: 5,
                error: "e".into(),
            },
            Warning::OptimizerNotConverged {
                stop: "iterations".into(),
                iterations: 10,
                objective: 0.5,
            },
            Warning::OptimizerStalled {
                projected_gradient: 3e-4,
                gtol: 1e-5,
                objective: 8e-4,
            },
            Warning::MembersChangedKind {
                members: vec![0, 3],
            },
        ];
        for w in all {
            let v = serde_json::to_value(&w).unwrap();
            assert_eq!(v["kind"], w.kind(), "{v}");
            assert_eq!(v["message"], w.to_string(), "{v}");
            let back: Warning = serde_json::from_value(v.clone()).unwrap();
            assert_eq!(back, w, "{v}");
        }
    }

    #[test]
    fn a_nested_warning_carries_its_own_kind_and_message() {
        let w = Warning::GroundPulled { min_normal: -2.0 }.in_run(7, "full");
        let v = serde_json::to_value(&w).unwrap();
        assert_eq!(v["sides"], 7);
        assert_eq!(v["warning"]["kind"], "ground_pulled");
        assert!(v["message"]
            .as_str()
            .unwrap()
            .starts_with("n = 7, full: the ground pulled"));
    }
}
