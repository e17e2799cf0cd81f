//! `formfind`: the form of a tensegrity from its connectivity ([`FormfindRequest`], a request
//! named `formfind`) — a topology file or a built-in form, one call of
//! [`formfind::form_find`] (force density, adaptive force density or dynamic relaxation),
//! then [`formfind::synthesize`]: the found self-stress scaled to the prestress level and the
//! string rest lengths that realise it at the given axial stiffness, a
//! [`tensegrity_core::Structure`] that starts in equilibrium (the scene `--out` writes).
//!
//! The report ([`FormfindReport`]) holds the found geometry (`nodes`), the force densities q
//! (tension-positive, bars then strings in topology order, as the method normalises them),
//! the statics of that self-stress (`self_stress_dim`, `prestressable`, `prestress_stable`),
//! the equilibrium residual ‖A q‖ / ‖q‖ of the found geometry (A the equilibrium matrix, so
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
use ::formfind::{FormFindError, FormFound, Method, Settings, Synthesis, Topology};
use serde::{Deserialize, Serialize};
use tensegrity_core::budget::{Estimate, Parameters};
use tensegrity_core::request::{
    exclusive, Categorized, Category, InvalidParameter, Param, Request, Rule,
};
use tensegrity_core::Structure;
use tensegrity_io::IoError;

/// The form-finding of a topology file or a built-in form, as data (defaults: the method by
/// what the topology gives, the library's prestress, stiffness, bar mass and tolerances).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FormfindRequest {
    /// The topology: a TOML file, or its text (excludes `builtin`).
    pub topology: Option<SceneSource>,
    /// A built-in form by name (`prism:3`, `octahedron`, `tower:3:2`, `grid:4`).
    pub builtin: Option<String>,
    /// The last size of the built-in, appended to its name (`prism` with n = 5: `prism:5`).
    pub n: Option<usize>,
    /// The method (`None`: `fdm` when every member has a force density, else `adaptive`).
    pub method: Option<Method>,
    /// The group whose force density `ratio` multiplies.
    pub group: Option<String>,
    /// The factor on the force density of the members of `group`.
    pub ratio: f64,
    /// Prestress level: the largest string tension (N).
    pub prestress: f64,
    /// Axial stiffness EA of the members that give none (N).
    pub stiffness: f64,
    /// Mass of each bar of the exported structure (kg).
    pub bar_mass: f64,
    /// Convergence tolerance of the iterative methods (relative residual).
    pub tolerance: f64,
    /// Iteration cap of the iterative methods.
    pub max_iterations: usize,
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
        }
    }
}

impl Request for FormfindRequest {
    const NAME: &'static str = "formfind";

    fn params() -> Vec<Param> {
        vec![
            Param::text(
                "topology",
                "The topology file (TOML: bars, strings, groups, fixed nodes), or its TOML text (a value with a line break or `=`)",
            )
            .optional(),
            Param::text(
                "builtin",
                "A built-in form instead of a topology: prism:N, octahedron, tower:N:M, grid:K",
            )
            .optional(),
            Param::count(
                "n",
                "The last size of the built-in form, appended to its name (builtin prism, n 5: prism:5), for sweeps",
            )
            .rule(Rule::AtLeast(1.0))
            .optional(),
            Param::choice(
                "method",
                &["fdm", "adaptive", "dr"],
                "Method: fdm (force density, every member's given), adaptive (force densities found from the connectivity) or dr (dynamic relaxation from lengths and stiffnesses); default: fdm when every member has a force density, else adaptive",
            )
            .optional(),
            Param::text(
                "group",
                "The group of the topology whose force density `ratio` multiplies",
            )
            .optional(),
            Param::number("ratio", "", "Factor on the force density of the members of `group`")
                .positive(),
            Param::number(
                "prestress",
                "N",
                "Prestress level of the exported structure: the largest string tension",
            )
            .positive(),
            Param::number(
                "stiffness",
                "N",
                "Axial stiffness EA of the members that give none (strings' rest lengths, dynamic relaxation)",
            )
            .positive(),
            Param::number("bar_mass", "kg", "Mass of each bar of the exported structure").positive(),
            Param::number(
                "tolerance",
                "",
                "Convergence tolerance of the iterative methods (relative residual)",
            )
            .positive(),
            Param::count("max_iterations", "Iteration cap of the iterative methods")
                .rule(Rule::AtLeast(1.0)),
        ]
    }

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

/// The report of `formfind` (module docs). Member lists are bars then strings, in topology
/// order.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FormfindReport {
    /// The built-in's name, the topology file, or `topology text`.
    pub source: String,
    /// Nodes.
    pub n_nodes: usize,
    /// Bars.
    pub n_bars: usize,
    /// Strings.
    pub n_strings: usize,
    /// The method that found the form.
    pub method: Method,
    /// One [x, y, z] per node (m).
    pub nodes: Vec<[f64; 3]>,
    /// Force density q per member (N/m, tension-positive), normalised by the method.
    pub force_density: Vec<f64>,
    /// Dimension of the self-stress space of the found geometry.
    pub self_stress_dim: usize,
    /// Whether a self-stress with strings in tension and bars in compression exists.
    pub prestressable: bool,
    /// Whether the prestressed structure is stable.
    pub prestress_stable: bool,
    /// ‖A q‖ / ‖q‖ at the found geometry.
    pub residual: f64,
    /// Iterations of the method (1 for a direct solve).
    pub iterations: usize,
    /// The extent along z of the nodes the method placed (every node of a free-standing
    /// form, the free ones where nodes are held) (m).
    pub height: f64,
    /// The longest bar (m; 0 without bars).
    pub max_bar_length: f64,
    /// The prestress level of the exported structure: the largest string tension (N).
    pub prestress: f64,
    /// Member forces at that level (N, tension-positive), `null` where there is no scene.
    pub member_force: Option<Vec<f64>>,
    /// Rest length of each string of the exported structure (m), `null` where there is no
    /// scene.
    pub rest_length: Option<Vec<f64>>,
    /// What the caller should know (a form that is not prestress-stable, no scene, …).
    pub warnings: Vec<String>,
}

/// Everything a `formfind` run makes: the topology, the found form, the structure realising
/// its prestress (when it can be synthesised) and the report.
#[derive(Debug, Clone)]
pub struct Formfound {
    /// The topology found.
    pub topology: Topology,
    /// The library's result.
    pub found: FormFound,
    /// The prestressed structure (`None` where the synthesis failed: the report says why).
    pub structure: Option<Structure>,
    /// The report.
    pub report: FormfindReport,
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
            (None, Some(name)) => (::formfind::builtin(&name)?, name),
            (None, None) => {
                let reason = "give a topology file or a `builtin` form";
                return Err(InvalidParameter::raw("topology", "(unset)", reason).into());
            }
        };
        if let Some(g) = &self.group {
            scale_group(&mut topology, g, self.ratio)?;
        }
        Ok((topology, source))
    }

    /// The settings of the library's form-finding (an unset method: [`Method::Auto`]).
    pub fn settings(&self) -> Settings {
        Settings {
            method: self.method.unwrap_or(Method::Auto),
            tolerance: self.tolerance,
            max_iterations: self.max_iterations,
            stiffness: self.stiffness,
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

    /// Runs the form-finding and the synthesis (module docs).
    pub fn run(&self) -> Result<Formfound, FormfindFailure> {
        let (topology, source) = self.topology()?;
        self.run_on(topology, source)
    }

    /// Runs the form-finding and the synthesis of a topology already read.
    pub fn run_on(&self, topology: Topology, source: String) -> Result<Formfound, FormfindFailure> {
        let found = ::formfind::form_find(&topology, &self.settings())?;
        let mut warnings = Vec::new();
        if !found.prestressable {
            warnings.push("the self-stress is not prestressable: no state with every string in tension and every bar in compression".to_string());
        } else if !found.prestress_stable {
            warnings.push(
                "the prestressed form is not stable: a mechanism is not stiffened by the prestress"
                    .to_string(),
            );
        }
        let synthesis = self.synthesis();
        let synthesised = ::formfind::rest_lengths(&topology, &found, &synthesis)
            .and_then(|r| Ok((::formfind::synthesize(&topology, &found, &synthesis)?, r)));
        let (structure, rest) = match synthesised {
            Ok((s, r)) => (Some(s), Some(r)),
            Err(e) => {
                warnings.push(format!("no prestressed structure: {e}"));
                (None, None)
            }
        };
        let report = FormfindReport {
            source,
            n_nodes: topology.n_nodes,
            n_bars: topology.bars.len(),
            n_strings: topology.strings.len(),
            method: found.method,
            nodes: found.node_rows(),
            force_density: found.force_density.clone(),
            self_stress_dim: found.self_stress_dim,
            prestressable: found.prestressable,
            prestress_stable: found.prestress_stable,
            residual: found.residual,
            iterations: found.iterations,
            height: extent_z(&topology, &found),
            max_bar_length: topology
                .bars
                .iter()
                .map(|b| (found.nodes[b.nodes[1]] - found.nodes[b.nodes[0]]).norm())
                .fold(0.0, f64::max),
            prestress: self.prestress,
            member_force: rest.as_ref().map(|r| r.tension.clone()),
            rest_length: rest.map(|r| r.rest_length),
            warnings,
        };
        Ok(Formfound {
            topology,
            found,
            structure,
            report,
        })
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

/// Multiplies the force density of group `name` (the group's own and its members') by
/// `ratio`; an unknown group, or one without a force density, is refused naming `group`.
fn scale_group(topology: &mut Topology, name: &str, ratio: f64) -> Result<(), InvalidParameter> {
    let Some(group) = topology.groups.get_mut(name) else {
        let known: Vec<&str> = topology.groups.keys().map(String::as_str).collect();
        let reason = format!(
            "no such group in the topology (groups: {})",
            known.join(", ")
        );
        return Err(InvalidParameter::text("group", name, reason));
    };
    let mut scaled = false;
    if let Some(q) = &mut group.force_density {
        *q *= ratio;
        scaled = true;
    }
    for m in topology.bars.iter_mut().chain(topology.strings.iter_mut()) {
        if let (Some(q), Some(g)) = (&mut m.force_density, &m.group) {
            if g == name {
                *q *= ratio;
                scaled = true;
            }
        }
    }
    if !scaled {
        let reason = "the group has no force density to scale";
        return Err(InvalidParameter::text("group", name, reason));
    }
    Ok(())
}

/// The extent along z of the nodes that are not held.
fn extent_z(topology: &Topology, found: &FormFound) -> f64 {
    let mut held = vec![false; found.nodes.len()];
    for f in &topology.fixed {
        held[f.node] = true;
    }
    let z = (0..found.nodes.len())
        .filter(|&i| !held[i])
        .map(|i| found.nodes[i].z);
    z.clone().fold(f64::NEG_INFINITY, f64::max) - z.fold(f64::INFINITY, f64::min)
}

/// The library's estimate of finding the form of `topology` ([`::formfind::estimate`]: the
/// method's solve and the statics of the form, from the sizes), named by what the request
/// gives: `builtin = grid:40`, `n = 40` or `topology = FILE`.
pub fn estimate_of(request: &FormfindRequest, topology: &Topology, source: &str) -> Estimate {
    let mut e = ::formfind::estimate(topology, &request.settings());
    e.parameters = match (request.n, &request.builtin) {
        (Some(n), Some(_)) => Parameters::default().and("n", n),
        (None, Some(_)) => Parameters::default().and("builtin", source),
        _ => Parameters::default().and("topology", source),
    };
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
        scale_group(&mut t, "v", 1.5).unwrap();
        assert_eq!(t.groups["v"].force_density, Some(3.0));
        let e = scale_group(&mut t, "w", 1.5).unwrap_err();
        assert!(e.to_string().contains("groups: v"), "{e}");
        t.groups.get_mut("v").unwrap().force_density = None;
        let e = scale_group(&mut t, "v", 1.5).unwrap_err();
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
