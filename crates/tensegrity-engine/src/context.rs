//! What the cases of one sweep share ([`Context`]): the reference run of each scene of the
//! work–precision study (the `integrators` command), computed once, and the front end's
//! resource limits.

use std::sync::OnceLock;
use tensegrity_core::budget::Limits;
use tensegrity_dynamics::simulation::SimulationResult;
use tensegrity_dynamics::work_precision::{self, run_one, Scene};
use tensegrity_dynamics::IntegratorKind;

/// The RK45 reference of the study (rtol 10⁻¹³), as `bench work-precision` runs it.
const REFERENCE_RTOL: f64 = 1e-13;

/// What the cases of one sweep share: the reference run of each scene, computed once, by the
/// first case that needs it; and the front end's resource limits, for a run that checks them
/// again once it knows more than its estimate did (the sparse statics, once its rank is known).
#[derive(Debug)]
pub struct Context {
    /// One slot per scene of [`work_precision::scenes`].
    references: Vec<OnceLock<Result<SimulationResult, String>>>,
    /// The limits the runs keep to after their estimate, if any.
    limits: Option<Limits>,
}

impl Default for Context {
    fn default() -> Self {
        Self {
            references: work_precision::scenes()
                .iter()
                .map(|_| OnceLock::new())
                .collect(),
            limits: None,
        }
    }
}

impl Context {
    /// A context whose runs keep to `limits` also where they check again after their
    /// estimate (a sweep's or a Python call's limits).
    ///
    /// ```
    /// use tensegrity_core::budget::Limits;
    /// let ctx = tensegrity_engine::Context::within(Limits::default());
    /// assert_eq!(ctx.limits(), Some(&Limits::default()));
    /// assert_eq!(tensegrity_engine::Context::default().limits(), None);
    /// ```
    pub fn within(limits: Limits) -> Self {
        Self {
            limits: Some(limits),
            ..Self::default()
        }
    }

    /// The limits of [`Context::within`], if any.
    pub fn limits(&self) -> Option<&Limits> {
        self.limits.as_ref()
    }

    /// The reference run of scene `index` of [`work_precision::scenes`], run on first use.
    pub(crate) fn reference(
        &self,
        index: usize,
        scene: &Scene,
    ) -> Result<&SimulationResult, String> {
        self.references[index]
            .get_or_init(|| {
                run_one(scene, IntegratorKind::Rk45, REFERENCE_RTOL, 1)
                    .map(|(r, _)| r)
                    .map_err(|e| format!("reference run of {}: {e}", scene.name))
            })
            .as_ref()
            .map_err(Clone::clone)
    }
}
