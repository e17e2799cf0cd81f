//! `formfind`: the form of a tensegrity from its connectivity ([`FormfindRequest`], a request
//! named `formfind`) — a topology file or a built-in form, read here (the library knows no
//! file format), then one call of the library's [`formfind::find`]: the form (force density,
//! adaptive force density or dynamic relaxation; unset, the one the topology's data call for,
//! and `auto` the only value that may fall back from one to another, with a warning), the
//! found self-stress scaled to the prestress level and the string rest lengths that realise it
//! at the given axial stiffness, a [`tensegrity_core::Structure`] that starts in equilibrium
//! (the scene `--out` writes).
//!
//! The report ([`FormfindReport`]) holds the found geometry (`nodes`), the force densities q
//! (tension-positive, bars then strings in topology order, as the method normalises them),
//! the statics of that self-stress (`self_stress_dim`, `prestressable`, `prestress_stable`;
//! only with `analyse`, null otherwise: they cost most of a large form's time), the
//! equilibrium residual ‖A q‖ / ‖q‖ of the found geometry (A the equilibrium matrix, so
//! A q = vec(N Cᵀ diag(q) C) at the free nodes) and the iterations of the method; and, at the
//! prestress level P (the largest string tension), the member forces f_k = s q_k l_k with
//! s = P / max_strings(q_k l_k) and the strings' rest lengths.
//!
//! A sweep varies the form through the request's numbers: `n` (the size of a built-in given
//! without it: `builtin = "prism"`, `n = 5` is `prism:5`) and `ratio`, the factor on the force
//! density of the members of `group`.
//!
//! ```
//! use tensegrity_core::request::Request;
//! use tensegrity_engine::formfind::FormfindRequest;
//! let r = FormfindRequest::from_values([("builtin", serde_json::json!("prism")), ("n", serde_json::json!(4))])?;
//! assert_eq!(r.builtin_name().as_deref(), Some("prism:4"));
//! assert!(FormfindRequest::from_values([("n", serde_json::json!(4))]).is_err());
//! # Ok::<(), tensegrity_core::request::InvalidParameter>(())
//! ```

use crate::scene::SceneSource;
pub use ::formfind::{design, sensitivity, FormfindReport, Formfound};
use ::formfind::{FormFindError, Method, Settings, Synthesis, Topology};
use serde::{Deserialize, Serialize};
use tensegrity_core::budget::{Estimate, Parameters};
use tensegrity_core::request::{exclusive, Categorized, Category, InvalidParameter, Request};
use tensegrity_derive::Params;
use tensegrity_io::IoError;

/// The form-finding of a topology file or a built-in form, as data (defaults: the method by
/// what the topology gives, the library's prestress, stiffness, bar mass and tolerances).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Params)]
#[serde(default, deny_unknown_fields)]
pub struct FormfindRequest {
    /// The topology: a TOML file, or its text (excludes `builtin`).
    #[param(
        text,
        help = "The topology file (TOML: bars, strings, groups, fixed nodes), or its TOML text (a value naming no file, with a line break or an `=`, and not one line ending in .toml)",
        optional
    )]
    pub topology: Option<SceneSource>,
    /// A built-in form by name (`prism:3`, `octahedron`, `tower:3:2`, `grid:4`).
    #[param(
        text,
        help = "A built-in form instead of a topology: prism:N, octahedron, tower:N:M, grid:K",
        optional
    )]
    pub builtin: Option<String>,
    /// The last size of the built-in, appended to its name (`prism` with n = 5: `prism:5`).
    #[param(count, help = "The last size of the built-in form, appended to its name (builtin prism, n 5: prism:5), for sweeps", rule = AtLeast(1.0), optional)]
    pub n: Option<usize>,
    /// The method (`None`: the one the topology's data call for, [`Method::Given`]).
    #[param(choice = ["fdm", "adaptive", "dr", "auto"], help = "Method: fdm (force density, every member's given), adaptive (force densities found from the connectivity), dr (dynamic relaxation from every member's length and stiffness) or auto (as the default, but falling back from fdm to adaptive with a warning); default: fdm when every member has a force density, dr when every member has a length, adaptive when neither is given (data given is never ignored, and fdm failing is an error)", optional)]
    pub method: Option<Method>,
    /// The group whose force density `ratio` multiplies.
    #[param(
        text,
        help = "The group of the topology whose force density `ratio` multiplies",
        optional
    )]
    pub group: Option<String>,
    /// The factor on the force density of the members of `group`.
    #[param(
        number,
        help = "Factor on the force density of the members of `group`",
        positive
    )]
    pub ratio: f64,
    /// Prestress level: the largest string tension (N).
    #[param(
        number,
        unit = "N",
        help = "Prestress level of the exported structure: the largest string tension",
        positive
    )]
    pub prestress: f64,
    /// Axial stiffness EA of the members that give none (N).
    #[param(
        number,
        unit = "N",
        help = "Axial stiffness EA of the members that give none (strings' rest lengths, dynamic relaxation)",
        positive
    )]
    pub stiffness: f64,
    /// Mass of each bar of the exported structure (kg).
    #[param(
        number,
        unit = "kg",
        help = "Mass of each bar of the exported structure",
        positive
    )]
    pub bar_mass: f64,
    /// Convergence tolerance of the iterative methods (relative residual).
    #[param(
        number,
        help = "Convergence tolerance of the iterative methods (relative residual)",
        positive
    )]
    pub tolerance: f64,
    /// Iteration cap of the iterative methods.
    #[param(count, help = "Iteration cap of the iterative methods", rule = AtLeast(1.0))]
    pub max_iterations: usize,
    /// Analyse the found form: its self-stress dimension, prestressability and prestress
    /// stability (default: not, [`::formfind::ANALYSE`]; those report fields are then null).
    #[param(
        flag,
        help = "Analyse the found form: self-stress dimension (the rank of the equilibrium matrix), prestressability (the prestress-margin LP where the force densities are no witness) and prestress stability, the costly part on a large form; without it those report fields are null"
    )]
    pub analyse: bool,
}

impl Default for FormfindRequest {
    fn default() -> Self {
        let (settings, synthesis) = (Settings::default(), Synthesis::default());
        FormfindRequest {
            topology: None,
            builtin: None,
            n: None,
            method: None,
            group: None,
            ratio: 1.0,
            prestress: synthesis.prestress,
            stiffness: synthesis.stiffness,
            bar_mass: synthesis.bar_mass,
            tolerance: settings.tolerance,
            max_iterations: settings.max_iterations,
            analyse: settings.analyse,
        }
    }
}

impl Request for FormfindRequest {
    const NAME: &'static str = "formfind";

    /// At most one of `topology` and `builtin` (one is needed to run: [`Self::topology`]);
    /// `n` sizes a built-in; a `ratio` other than 1 scales a `group`.
    fn check(&self) -> Result<(), InvalidParameter> {
        let topology = self.topology.as_ref().map(|t| t.to_string());
        exclusive(
            &[("topology", topology), ("builtin", self.builtin.clone())],
            false,
        )?;
        if let (Some(n), None) = (self.n, &self.builtin) {
            return Err(InvalidParameter::raw(
                "n",
                n,
                "sizes a built-in form: give `builtin` too",
            ));
        }
        if self.ratio != 1.0 && self.group.is_none() {
            let reason = "multiplies the force density of a group: give `group` too";
            return Err(InvalidParameter::new("ratio", self.ratio, reason));
        }
        Ok(())
    }
}

/// Why `formfind` gave no form.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FormfindFailure {
    /// A value the request refuses.
    #[error(transparent)]
    InvalidParameter(#[from] InvalidParameter),
    /// The topology file could not be read, or is invalid.
    #[error(transparent)]
    Io(#[from] IoError),
    /// The form-finding or the synthesis failed.
    #[error(transparent)]
    FormFind(#[from] FormFindError),
}

impl Categorized for FormfindFailure {
    /// A bad value or topology is bad input; the library's error keeps its category.
    fn category(&self) -> Category {
        match self {
            Self::InvalidParameter(_) => Category::Input,
            Self::Io(e) => e.category(),
            Self::FormFind(e) => e.category(),
        }
    }
}

impl FormfindRequest {
    /// The built-in's full name (`n` appended), if a built-in is asked for.
    pub fn builtin_name(&self) -> Option<String> {
        let name = self.builtin.as_deref()?;
        Some(match self.n {
            Some(n) => format!("{name}:{n}"),
            None => name.to_string(),
        })
    }

    /// The topology asked for, with `ratio` applied to `group`, and its label.
    pub fn topology(&self) -> Result<(Topology, String), FormfindFailure> {
        let (mut topology, source) = match (&self.topology, self.builtin_name()) {
            (Some(SceneSource::Path(p)), _) => (
                tensegrity_io::topology::from_path(p)?,
                p.display().to_string(),
            ),
            (Some(SceneSource::Toml(text)), _) => (
                tensegrity_io::topology::from_str_named(text, "topology text")?,
                "topology text".to_string(),
            ),
            (Some(SceneSource::Data(_)), _) => {
                let reason = "a topology is a file or its TOML text, not structure data";
                return Err(InvalidParameter::raw("topology", "structure data", reason).into());
            }
            (None, Some(name)) => (::formfind::builtin(&name)?, name),
            (None, None) => {
                let reason = "give a topology file or a `builtin` form";
                return Err(InvalidParameter::raw("topology", "(unset)", reason).into());
            }
        };
        if let Some(g) = &self.group {
            ::formfind::scale_group(&mut topology, g, self.ratio)?;
        }
        Ok((topology, source))
    }

    /// The settings of the library's form-finding (an unset method: [`Method::Given`], the
    /// one the topology's data call for, with no fallback).
    pub fn settings(&self) -> Settings {
        Settings {
            method: self.method.unwrap_or(Method::Given),
            tolerance: self.tolerance,
            max_iterations: self.max_iterations,
            stiffness: self.stiffness,
            analyse: self.analyse,
        }
    }

    /// What the synthesis makes of a found form.
    pub fn synthesis(&self) -> Synthesis {
        Synthesis {
            prestress: self.prestress,
            stiffness: self.stiffness,
            bar_mass: self.bar_mass,
        }
    }

    /// The force density form of the topology asked for, factored for its exact derivatives
    /// ([`::formfind::sensitivity`]: held nodes, the topology's force densities and point
    /// loads), for a front end that differentiates it (Python's `FormSensitivity`).
    pub fn sensitivity(&self) -> Result<sensitivity::FdmSensitivity, FormfindFailure> {
        let (topology, _) = self.topology()?;
        Ok(sensitivity::FdmSensitivity::given(&topology)?)
    }

    /// Dynamic relaxation's form of the topology asked for (held nodes, rest lengths and
    /// stiffnesses; this request's tolerance, iterations and default stiffness), its tangent
    /// stiffness factored for its exact derivatives ([`::formfind::sensitivity::DrSensitivity`]),
    /// for a front end that differentiates it (Python's `RelaxedSensitivity`).
    pub fn relaxed_sensitivity(&self) -> Result<sensitivity::DrSensitivity, FormfindFailure> {
        let (topology, _) = self.topology()?;
        Ok(sensitivity::DrSensitivity::find(
            &topology,
            &self.settings(),
        )?)
    }

    /// Runs the form-finding and the synthesis (module docs).
    pub fn run(&self) -> Result<Formfound, FormfindFailure> {
        let (topology, source) = self.topology()?;
        self.run_on(topology, source)
    }

    /// Runs the form-finding and the synthesis of a topology already read
    /// ([`::formfind::find`]).
    pub fn run_on(&self, topology: Topology, source: String) -> Result<Formfound, FormfindFailure> {
        Ok(::formfind::find(
            topology,
            source,
            &self.settings(),
            &self.synthesis(),
        )?)
    }
}

/// Runs `formfind` under a front end's check of its estimate: the topology read (a file) or
/// built (a built-in: its size is capped by the library, [`::formfind::MAX_GRID`] and the
/// like, so building it is cheap), its estimate ([`estimate_of`]) handed to `admit` (a front
/// end's limits: an error refuses the run, the value it returns — a progress indicator —
/// lives while the form is found), then the form found.
pub fn admitted<G, E: From<FormfindFailure>>(
    request: &FormfindRequest,
    admit: impl FnOnce(Option<Estimate>) -> Result<G, E>,
) -> Result<Formfound, E> {
    let (topology, source) = request.topology()?;
    let _admitted = admit(Some(estimate_of(request, &topology, &source)))?;
    Ok(request.run_on(topology, source)?)
}

/// Runs `formfind`: the report (the registry's library call).
pub fn formfind(request: &FormfindRequest) -> Result<FormfindReport, FormfindFailure> {
    Ok(request.run()?.report)
}

/// The library's estimate of finding the form of `topology` ([`::formfind::estimate`]: the
/// method that will run and the statics of the form, from the sizes), named by what the
/// request gives: `builtin = grid:40`, `n = 40` or `topology = FILE`, and `max_iterations`
/// where an iterative method's cap drives the work.
pub fn estimate_of(request: &FormfindRequest, topology: &Topology, source: &str) -> Estimate {
    let mut e = ::formfind::estimate(topology, &request.settings());
    let mut named = match (request.n, &request.builtin) {
        (Some(n), Some(_)) => Parameters::default().and("n", n),
        (None, Some(_)) => Parameters::default().and("builtin", source),
        _ => Parameters::default().and("topology", source),
    };
    if e.parameters
        .0
        .iter()
        .any(|(name, _)| name == "max_iterations")
    {
        named = named.and("max_iterations", request.max_iterations);
    }
    e.parameters = named;
    e
}

/// The resource estimate of a request (the registry's, for sweeps): the topology read or
/// built, then [`estimate_of`].
pub fn estimate(request: &FormfindRequest) -> Result<Option<Estimate>, FormfindFailure> {
    let (topology, source) = request.topology()?;
    Ok(Some(estimate_of(request, &topology, &source)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;
    use tensegrity_core::request::check_description;

    #[test]
    fn the_request_describes_its_fields_and_checks_its_sources() {
        check_description::<FormfindRequest>().unwrap();
        let r =
            FormfindRequest::from_values([("builtin", json!("prism:3")), ("method", json!("fdm"))])
                .unwrap();
        assert_eq!(r.method, Some(Method::Fdm));
        // one of topology and builtin, the one needed when the form is asked for
        let none = FormfindRequest::from_values([("prestress", json!(5.0))]).unwrap();
        let e = none.topology().unwrap_err().to_string();
        assert!(
            e.contains("give a topology file or a `builtin` form"),
            "{e}"
        );
        let both = [
            ("builtin", json!("octahedron")),
            ("topology", json!("a.toml")),
        ];
        let e = FormfindRequest::from_values(both).unwrap_err();
        assert!(e.to_string().contains("excludes"), "{e}");
        let e = FormfindRequest::from_values([("topology", json!("a.toml")), ("n", json!(3))])
            .unwrap_err();
        assert_eq!(e.name, "n");
        let e =
            FormfindRequest::from_values([("builtin", json!("prism:3")), ("ratio", json!(2.0))])
                .unwrap_err();
        assert_eq!(e.name, "ratio");
        let e = FormfindRequest::from_values([
            ("builtin", json!("prism:3")),
            ("method", json!("newton")),
        ])
        .unwrap_err();
        assert_eq!(e.name, "method");
        let e = FormfindRequest::from_values([
            ("builtin", json!("prism:3")),
            ("prestress", json!(-1.0)),
        ])
        .unwrap_err();
        assert_eq!(e.name, "prestress");
        let text =
            FormfindRequest::from_values([("topology", json!("[[bars]]\nnodes = [0, 1]\n"))])
                .unwrap();
        assert!(matches!(text.topology, Some(SceneSource::Toml(_))));
    }

    #[test]
    fn a_group_is_scaled_and_an_unknown_one_named() {
        let text = "[groups.v]\nforce_density = 2.0\n[[bars]]\nnodes = [0, 1]\nforce_density = -1.0\n\
                    [[strings]]\nnodes = [1, 2]\ngroup = \"v\"\n[[strings]]\nnodes = [2, 0]\nforce_density = 1.0\n";
        let mut t = tensegrity_io::topology::from_str_named(text, "t").unwrap();
        ::formfind::scale_group(&mut t, "v", 1.5).unwrap();
        assert_eq!(t.groups["v"].force_density, Some(3.0));
        let e = ::formfind::scale_group(&mut t, "w", 1.5).unwrap_err();
        assert!(e.to_string().contains("groups: v"), "{e}");
        t.groups.get_mut("v").unwrap().force_density = None;
        let e = ::formfind::scale_group(&mut t, "v", 1.5).unwrap_err();
        assert!(e.to_string().contains("no force density"), "{e}");
    }

    #[test]
    fn the_estimate_is_named_by_the_request_and_grows_with_the_form() {
        let grid = |n| FormfindRequest {
            builtin: Some("grid".into()),
            n: Some(n),
            ..Default::default()
        };
        let (small, large) = (
            estimate(&grid(4)).unwrap().unwrap(),
            estimate(&grid(300)).unwrap().unwrap(),
        );
        assert_eq!(large.parameters.to_string(), "n = 300");
        assert!(
            large.work_s > 100.0 * small.work_s && large.memory_bytes > 100.0 * small.memory_bytes
        );
        let named = FormfindRequest {
            builtin: Some("prism:3".into()),
            ..Default::default()
        };
        assert_eq!(
            estimate(&named).unwrap().unwrap().parameters.to_string(),
            "builtin = prism:3"
        );
        // an iterative method's estimate names the cap that drives it
        let chain =
            "[[bars]]\nnodes = [0, 1]\n[[bars]]\nnodes = [1, 2]\n[[strings]]\nnodes = [0, 2]\n";
        let adaptive = FormfindRequest {
            topology: Some(SceneSource::parse(chain)),
            max_iterations: 500,
            ..Default::default()
        };
        let e = estimate(&adaptive).unwrap().unwrap();
        assert_eq!(
            e.parameters.to_string(),
            "topology = topology text, max_iterations = 500"
        );
        assert!(
            e.what.starts_with("the adaptive force density iteration"),
            "{}",
            e.what
        );
        // a built-in the library refuses is the run's error, named
        let bad = FormfindRequest {
            builtin: Some("grid:100000".into()),
            ..Default::default()
        };
        assert!(estimate(&bad)
            .unwrap_err()
            .to_string()
            .contains("grid:100000"));
    }
}
