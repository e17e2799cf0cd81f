//! [`IntegratorKind::build`]: a fresh integrator of a kind for a model (the one place that
//! knows every method's constructor; the methods themselves are generic over the
//! [`System`](crate::System) they advance, and are built here for [`Model`]).

use crate::ark::ImexArk;
use crate::flight::Flight;
use crate::imex::Imex;
use crate::integrator::Integrator;
use crate::kind::IntegratorKind;
use crate::model::Model;
use crate::rattle::Rattle;
use crate::rk4::Rk4;
use crate::rk45::Dopri5;
use crate::sdirk::Sdirk;
use tensegrity_core::error::{CoreError, DynamicsError};

impl IntegratorKind {
    /// A fresh integrator of this kind for `model`; `rtol` and `atol` are used by the
    /// adaptive ones only.
    pub fn build(
        self,
        model: &Model,
        rtol: f64,
        atol: f64,
    ) -> Result<Box<dyn Integrator<Model>>, CoreError> {
        let n = model.state_len();
        Ok(match self {
            Self::Rk4 => Box::new(Rk4::new(n)),
            Self::Rk45 => Box::new(Dopri5::new(n, rtol, atol)),
            Self::Rattle => Box::new(Rattle::new(model)?),
            Self::Sdirk => Box::new(Sdirk::new(model, rtol, atol)?),
            Self::Imex => Box::new(Imex::new(model)),
            Self::ImexArk => Box::new(ImexArk::new(model)),
            Self::Rk4Flight => Box::new(Flight::new(model, Box::new(Rk4::new(n)), self)),
            Self::Newmark => {
                return Err(DynamicsError::Unsupported {
                    item: "integrator = newmark".into(),
                    reason: "Newmark steps elastic models only: give the scene `[simulation] bars = \"elastic\"`, or integrate rigid bars with rk4, rk45, rattle, sdirk, imex, imex-ark or rk4-flight".into(),
                }
                .into())
            }
        })
    }
}
