//! `design`: inverse form-finding ([`DesignRequest`], a request named `design`): a design
//! file (a topology with a `[design]` table, read here: `tensegrity_io::design`), then one
//! call of the library's [`::formfind::design::design`]: the force densities (within their
//! bounds, shared by groups or listed members) whose force density form minimises the
//! weighted sum of the file's goals, found by a bound-constrained quasi-Newton method on the
//! exact adjoint gradient. The report ([`DesignReport`]) holds the objective (at the start
//! and designed, each term's), the optimiser's verdict (`converged`, `stop`, iterations and
//! evaluations), the designed force densities, nodes, lengths, forces and reactions, and the
//! history; [`designed_form`] turns the designed topology into a found form and its scene
//! (the same synthesis as `formfind`).
//!
//! ```
//! use tensegrity_core::request::Request;
//! use tensegrity_engine::design::{design, DesignRequest};
//! use tensegrity_engine::SceneSource;
//! let text = "[[strings]]\nnodes = [0, 1]\nforce_density = 1.0\n\
//!             [[fixed]]\nnode = 0\nposition = [0.0, 0.0, 0.0]\n\
//!             [[loads]]\nnode = 1\nforce = [1.0, 0.0, 0.0]\n\
//!             [[design.terms]]\n[[design.terms.goals]]\nkind = \"length\"\ntarget = 2.0\n";
//! let r = DesignRequest { design: Some(SceneSource::Toml(text.into())), ..DesignRequest::default() };
//! let report = design(&r).unwrap();
//! assert!(report.designed.converged && (report.designed.length[0] - 2.0).abs() < 1e-4);
//! ```

use crate::formfind::{FormfindFailure, FormfindRequest, Formfound};
use crate::scene::SceneSource;
use ::formfind::design::{Designed, OptimizerMethod};
use ::formfind::{Method, Topology};
use serde::{Deserialize, Serialize};
use tensegrity_core::request::{InvalidParameter, Request};
use tensegrity_derive::{Columns, Params};

/// Inverse form-finding of a design file, as data (defaults: the file's optimiser settings,
/// `formfind`'s synthesis of the scene).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct DesignRequest {
    /// The design file (a topology with a `[design]` table), or its TOML text.
    #[param(
        text,
        help = "The design file (TOML: a topology with a [design] table of parameters, terms and goals), or its TOML text",
        optional
    )]
    pub design: Option<SceneSource>,
    /// The optimiser's iteration cap, replacing the file's `[design.optimizer]` one.
    #[param(count, help = "Iteration cap of the optimiser (default: the file's, else 1000)", rule = AtLeast(1.0), optional)]
    pub max_iterations: Option<usize>,
    /// The optimiser, replacing the file's `[design.optimizer] method`.
    #[param(choice = ["lbfgsb", "levenberg_marquardt"], help = "Optimiser: lbfgsb (bound-constrained quasi-Newton, any objective) or levenberg_marquardt (projected Levenberg-Marquardt on the residuals' exact Jacobian, for terms with squared or mean_squared errors: fast where L-BFGS crawls along a flat valley); default: the file's, else lbfgsb", optional)]
    pub method: Option<OptimizerMethod>,
    /// Prestress level of a designed form without loads: the largest string tension (N).
    #[param(
        number,
        unit = "N",
        help = "Prestress level of the written scene of a form without loads (a loaded form's forces are those of its loads)",
        positive
    )]
    pub prestress: f64,
    /// Axial stiffness EA of the members that give none (N).
    #[param(
        number,
        unit = "N",
        help = "Axial stiffness EA of the members that give none (the scene's rest lengths)",
        positive
    )]
    pub stiffness: f64,
    /// Mass of each bar of the written scene (kg).
    #[param(
        number,
        unit = "kg",
        help = "Mass of each bar of the written scene",
        positive
    )]
    pub bar_mass: f64,
}

impl Default for DesignRequest {
    fn default() -> Self {
        let f = FormfindRequest::default();
        Self {
            design: None,
            max_iterations: None,
            method: None,
            prestress: f.prestress,
            stiffness: f.stiffness,
            bar_mass: f.bar_mass,
        }
    }
}

impl Request for DesignRequest {
    const NAME: &'static str = "design";

    fn check(&self) -> Result<(), InvalidParameter> {
        Ok(())
    }
}

/// The report of `design`: the design file and the library's result.
#[derive(Debug, Clone, PartialEq, Serialize, Columns)]
pub struct DesignReport {
    /// The design file, or `design text`.
    pub source: String,
    /// The result: objective, verdict, designed force densities and form, history.
    #[serde(flatten)]
    pub designed: Designed,
    /// What the caller should know: an optimiser that did not converge, members that
    /// changed kind.
    pub warnings: Vec<tensegrity_core::Warning>,
}

impl DesignRequest {
    /// The topology and the design problem of the file asked for, and its label.
    pub fn problem(
        &self,
    ) -> Result<(Topology, ::formfind::design::DesignSpec, String), FormfindFailure> {
        let (topology, mut spec, source) = match &self.design {
            Some(SceneSource::Path(p)) => {
                let (t, s) = tensegrity_io::design::from_path(p)?;
                (t, s, p.display().to_string())
            }
            Some(SceneSource::Toml(text)) => {
                let (t, s) = tensegrity_io::design::from_str_named(text, "design text")?;
                (t, s, "design text".to_string())
            }
            Some(SceneSource::Data(_)) => {
                let reason = "a design is a file or its TOML text, not structure data";
                return Err(InvalidParameter::raw("design", "structure data", reason).into());
            }
            None => {
                let reason = "give a design file (a topology with a [design] table)";
                return Err(InvalidParameter::raw("design", "(unset)", reason).into());
            }
        };
        if let Some(n) = self.max_iterations {
            spec.optimizer.max_iterations = n;
        }
        if let Some(m) = self.method {
            spec.optimizer.method = m;
        }
        Ok((topology, spec, source))
    }
}

/// Runs `design`: the report (the registry's library call).
pub fn design(request: &DesignRequest) -> Result<DesignReport, FormfindFailure> {
    let (topology, spec, source) = request.problem()?;
    let designed = ::formfind::design::design(&topology, &spec).map_err(|e| match e {
        // a problem naming what the topology lacks: an error of the file, which it names
        e @ ::formfind::FormFindError::InvalidTopology { .. } => {
            FormfindFailure::Io(tensegrity_io::IoError::InvalidTopology {
                file: source.clone(),
                line: None,
                source: Box::new(e),
            })
        }
        e => e.into(),
    })?;
    let mut warnings = Vec::new();
    if !designed.converged {
        warnings.push(tensegrity_core::Warning::OptimizerNotConverged {
            stop: designed.stop.to_string(),
            iterations: designed.iterations,
            objective: designed.objective,
        });
    }
    // (Levenberg–Marquardt's objective rule takes only a nearly undamped Gauss–Newton step,
    // near a minimum of its sum of squares: the cable net within 2·10⁻⁶ of its optimum,
    // its projected gradient 3·10⁻⁶ against gtol 10⁻⁸; L-BFGS-B's stalls 13 % above it)
    if designed.converged && !designed.stationary && designed.method == "lbfgsb" {
        warnings.push(tensegrity_core::Warning::OptimizerStalled {
            projected_gradient: designed.projected_gradient,
            gtol: spec.optimizer.gtol,
            objective: designed.objective,
        });
    }
    if !designed.changed_kind.is_empty() {
        warnings.push(tensegrity_core::Warning::MembersChangedKind {
            members: designed.changed_kind.clone(),
        });
    }
    Ok(DesignReport {
        source,
        designed,
        warnings,
    })
}

/// The designed topology form-found by the force density method and synthesised as
/// `formfind` does (the prestress, stiffness and bar mass of `request`): the scene of the
/// designed structure, ready for `statics` and `simulate`.
pub fn designed_form(
    request: &DesignRequest,
    report: &DesignReport,
) -> Result<Formfound, FormfindFailure> {
    let f = FormfindRequest {
        method: Some(Method::Fdm),
        prestress: request.prestress,
        stiffness: request.stiffness,
        bar_mass: request.bar_mass,
        ..FormfindRequest::default()
    };
    f.run_on(report.designed.topology.clone(), report.source.clone())
}

#[cfg(test)]
mod tests {
    use super::*;
    use tensegrity_core::request::check_description;

    #[test]
    fn the_request_describes_its_fields() {
        check_description::<DesignRequest>().unwrap();
        let e = design(&DesignRequest::default()).unwrap_err().to_string();
        assert!(e.contains("give a design file"), "{e}");
    }
}
