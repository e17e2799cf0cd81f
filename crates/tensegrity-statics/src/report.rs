//! The complete statics report of one structure, as `tensegrity statics` prints it.
//!
//! One call ([`statics_report`]) runs, in order:
//!
//! 1. the SVD of the equilibrium matrix A (A q = w, q tension-positive force densities, bars
//!    then strings then clustered strings, [`crate::cluster_columns`]: every per-member
//!    array of the report, `force_density`, `member_force`, `self_stress`, `prestress` and
//!    the sizing, has that order, a cluster's force its tension t_c = q_c L_c): rank r,
//!    self-stress dimension s = columns − r, mechanisms m = dofs − r,
//!    the orthonormal self-stress basis and the smallest singular value;
//! 2. prestressability (the max-margin LP) and, when prestressable, prestress stability of the
//!    max-margin stress; internal mechanisms (first-order flexes beyond rigid-body motions);
//! 3. when the structure is loaded: the minimal-norm load solve (force densities, member
//!    forces f = q l, support reactions, residual ‖A q − w‖₂) and, when members have
//!    materials, minimum-mass sizing for those forces (strings for yield, bars for yield and
//!    Euler buckling), with a warning when a string ends up in compression. A load the
//!    structure cannot carry (relative residual above
//!    [`LOAD_RESIDUAL_TOLERANCE`](super::load::LOAD_RESIDUAL_TOLERANCE)) is the error
//!    [`tensegrity_core::error::StaticsError::LoadNotCarried`] naming the residual and
//!    the unbalanced nodes, unless [`StaticsRequest::least_squares`] asks for the
//!    least-squares answer, which is then reported with `load_carried: false` and no sizing;
//! 4. with [`StaticsRequest::modes`] = Some(k): the k lowest natural frequencies about the
//!    current state, K φ = ω² M φ with the tangent stiffness and the chosen mass model.
//!
//! Failures of the optional parts (sizing, modes) do not fail the report: they are reported
//! in its `sizing_error` and `modal_error` fields.
//!
//! The report is built in one place, [`report_from`], over any statics back-end
//! ([`StaticsBackend`]: the dense SVD, the sparse QR, the cyclic blocks);
//! [`statics_report`] chooses the back-end by [`StaticsSettings::method`]
//! ([`super::select::backend`]). The dense SVD leaves `statics_method` out; another back-end
//! names itself there ([`Factorization`]), and a rank decision it cannot certify (every
//! back-end, the dense SVD included: no clear [`SpectralGap`]), or what it does not compute,
//! is said in `statics_warning`; `spectral_gap` gives the singular values behind the decision.

use super::front::{Certification, Factorization, SelfStressBasis, StaticsBackend};
use super::prestress::Prestressability;
use super::{SpectralGap, StaticsSettings};
pub use crate::reaction::Reaction;
use crate::response::LinearResponse;
use crate::sizing::{self, Governing, SizingReport};
use crate::stiffness::{self, MassModel};
use serde::Serialize;
use tensegrity_core::error::{CoreError, Result, StaticsError};
use tensegrity_core::structure::{MemberId, Structure};
use tensegrity_derive::Columns;

/// What [`statics_report`] computes. The default is the default SVD rank tolerance, no modes
/// and the lumped mass model.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StaticsRequest {
    /// Rank tolerance and LP solver of the statics.
    pub settings: StaticsSettings,
    /// Report the k lowest natural frequencies (None: no modal analysis).
    pub modes: Option<usize>,
    /// The mass matrix of the modal analysis.
    pub mass: MassModel,
    /// Report the least-squares solution of a load the structure cannot carry (marked
    /// `load_carried: false`, without sizing) instead of failing.
    pub least_squares: bool,
}

/// Everything `tensegrity statics` reports; serialises to its JSON.
#[derive(Debug, Clone, PartialEq, Serialize, Columns, Default)]
pub struct StaticsReport {
    /// Number of nodes.
    pub nodes: usize,
    /// Number of bars.
    pub bars: usize,
    /// Number of strings.
    pub strings: usize,
    /// Number of clustered strings (left out of the JSON when 0); their entries follow the
    /// strings' in every per-member array (`cluster 0`, …; [`crate::cluster_columns`]).
    #[serde(skip_serializing_if = "is_zero")]
    #[column(skip)]
    pub clusters: usize,
    /// Rank of the equilibrium matrix.
    pub rank: usize,
    /// Dimension of the self-stress space.
    pub self_stress_dim: usize,
    /// First-order mechanisms (rigid-body motions included when unsupported).
    pub mechanisms: usize,
    /// Internal mechanisms: mechanisms beyond the rigid-body motions the supports allow.
    pub internal_mechanisms: usize,
    /// Whether a self-stress puts every string in tension and every bar in compression.
    pub prestressable: bool,
    /// The prestressability LP margin (0 when not prestressable).
    pub prestress_margin: f64,
    /// Prestress stability with the max-margin stress (only when prestressable).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prestress_stable: Option<bool>,
    /// Orthonormal self-stress basis (force densities), members bars, strings, then clusters.
    pub self_stress: Vec<Vec<f64>>,
    /// Set when `self_stress` is left empty although the space is not: why (its dimension
    /// and size; see [`SELF_STRESS_LIST_MAX`](super::sparse::SELF_STRESS_LIST_MAX)).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[column(skip)]
    pub self_stress_omitted: Option<String>,
    /// The max-margin self-stress (force densities) scaled to max|q| = 1 (only when
    /// prestressable).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prestress: Option<Vec<f64>>,
    /// Smallest singular value of the equilibrium matrix.
    pub smallest_singular_value: f64,
    /// Absolute rank tolerance used.
    pub rank_tolerance: f64,
    /// The rounding of the node coordinates the rank decision discounted (m; [`crate::rank`]):
    /// judged from their digits, or the `input_precision` times the largest coordinate; 0
    /// for data at full precision or under a user's rank tolerance.
    #[column(unit = "m")]
    pub input_rounding: f64,
    /// Force densities for the loads (N/m, tension positive).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub force_density: Option<Vec<f64>>,
    /// Member forces for the loads (N, tension positive).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub member_force: Option<Vec<f64>>,
    /// Support reactions.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reactions: Option<Vec<Reaction>>,
    /// ‖A q − w‖₂ (N).
    #[serde(skip_serializing_if = "Option::is_none")]
    #[column(unit = "N")]
    pub residual: Option<f64>,
    /// Whether the loads are carried (relative residual within the tolerance); false only
    /// with [`StaticsRequest::least_squares`].
    #[serde(skip_serializing_if = "Option::is_none")]
    pub load_carried: Option<bool>,
    /// Nodes left unbalanced by a load that is not carried.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unbalanced_nodes: Option<Vec<usize>>,
    /// Total minimum mass for the loads (kg), when members have materials.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[column(unit = "kg")]
    pub mass_kg: Option<f64>,
    /// Minimum radius of each member for the loads (m), when sized.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub member_radius_m: Option<Vec<f64>>,
    /// Minimum mass of each member for the loads (kg), when sized.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub member_mass_kg: Option<Vec<f64>>,
    /// Failure mode setting each member's size: `yield`, `buckling` or `unloaded`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub governing: Option<Vec<Governing>>,
    /// Set when the mass was computed but the design is not buildable as is (strings in
    /// compression).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sizing_warning: Option<String>,
    /// The lowest natural frequencies (Hz) about the current state, with modes requested: the
    /// K lowest modes of nonzero frequency, the zero modes skipped (the modes the `--modes`
    /// figure draws).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub natural_frequencies_hz: Option<Vec<f64>>,
    /// With modes: how many zero-frequency modes (rigid-body motions the supports allow,
    /// mechanisms the prestress does not stiffen; |ω²| ≤
    /// [`stiffness::ZERO_MODE_TOLERANCE`] · max |ω²|) were skipped before
    /// `natural_frequencies_hz`.
    #[serde(skip_serializing_if = "Option::is_none")]
    #[column(skip)]
    pub zero_modes_skipped: Option<usize>,
    /// Why the modes could not be computed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub modal_error: Option<String>,
    /// Why the mass could not be computed, when members have materials but sizing failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sizing_error: Option<String>,
    /// Set when another back-end than the dense SVD answered: `sparse_qr` (the sparse
    /// rank-revealing QR; `smallest_singular_value` is then an estimate: an upper bound ≤
    /// `rank_tolerance` when A is rank deficient, an inverse-iteration estimate otherwise) or
    /// `cyclic` (the symmetry-adapted blocks).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub statics_method: Option<Factorization>,
    /// Set when the rank decision could not be certified (see
    /// [`SparseStatics`](super::SparseStatics) and
    /// [`CyclicStatics`](super::symmetry::CyclicStatics)), or when the back-end left
    /// something out (the cyclic back-end: only the symmetric self-stresses, no prestress
    /// stability).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub statics_warning: Option<String>,
    /// The singular values on either side of the rank tolerance behind the rank decision
    /// ([`SpectralGap`]; the narrowest block's for the cyclic back-end). A decision without a
    /// clear gap (a value within a factor 10 of the tolerance) is flagged in `statics_warning`.
    #[column(nested)]
    pub spectral_gap: SpectralGap,
    /// The linear response at the scene's geometry (small displacements: node displacements,
    /// member force changes, reactions; [`crate::response`]), when asked or driven by a
    /// support's prescribed displacement; added by the caller that knows the displacements
    /// ([`crate::response::linear_response`]), not by [`statics_report`].
    #[serde(skip_serializing_if = "Option::is_none")]
    #[column(skip)]
    pub linear_response: Option<LinearResponse>,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// Runs every statics analysis of one structure (see the module documentation).
///
/// ```
/// use tensegrity_statics::report::{statics_report, StaticsRequest};
/// use tensegrity_core::{Bar, StringMember, Structure};
/// let s = Structure::builder()
///     .nodes([[0.0, 0.0, 0.0], [1.0, 0.5, 0.0], [1.0, -0.5, 0.0], [2.0, 0.0, 0.0]])
///     .bar(Bar::new(0, 1)).bar(Bar::new(0, 2)).bar(Bar::new(1, 3)).bar(Bar::new(2, 3))
///     .string(StringMember::new(0, 3)).string(StringMember::new(1, 2))
///     .build()
///     .unwrap();
/// let r = statics_report(&s, &StaticsRequest::default()).unwrap();
/// assert_eq!((r.self_stress_dim, r.prestressable), (1, true));
/// assert!(r.force_density.is_none()); // no loads, no load solve
/// ```
pub fn statics_report(structure: &Structure, request: &StaticsRequest) -> Result<StaticsReport> {
    let backend = super::select::backend(structure, request.settings)?;
    let sparse = backend.kind() == Factorization::SparseQr;
    match report_from(backend.as_ref(), request) {
        // a sparse result that fails its own check (a load solve that leaves a residual, an
        // LP that stalls: a Levy dome of 4,080 members) is answered by the dense SVD where
        // the automatic choice allows it within the limits, and the report says so
        Err(e)
            if sparse
                && failed_check(&e)
                && super::select::dense_fallback(structure, &request.settings) =>
        {
            let dense = super::Statics::with_settings(structure, request.settings)?;
            let mut report = report_from(&dense, request)?;
            let note = format!(
                "the sparse QR's answer failed its check ({}); the dense SVD answered",
                first_words(&e)
            );
            report.statics_warning = Some(match report.statics_warning.take() {
                Some(w) => format!("{note}; {w}"),
                None => note,
            });
            Ok(report)
        }
        // without the dense answer, say that it is the sparse factorisation's check that
        // failed (not that the structure is a mechanism) and what the dense one would cost
        Err(e)
            if sparse
                && failed_check(&e)
                && request.settings.method == super::StaticsMethod::Auto =>
        {
            Err(StaticsError::SparseCheckFailed {
                failure: first_words(&e),
                dense_work_s: super::select::dense_work_s(structure),
            }
            .into())
        }
        r => r,
    }
}

/// Whether `e` is a result that failed its own numerical check (not an input error).
fn failed_check(e: &CoreError) -> bool {
    matches!(
        e,
        CoreError::Statics(StaticsError::LoadNotCarried { .. }) | CoreError::Numerics(_)
    )
}

/// The message of `e` up to its first `;` (the residual, not the node list and remedy).
fn first_words(e: &CoreError) -> String {
    let text = e.to_string();
    text.split(';').next().unwrap_or(&text).to_string()
}

/// The statics report from any back-end: counts, self-stress, prestressability and
/// mechanisms; the load solve when the structure is loaded; the modes when asked.
pub fn report_from(
    backend: &dyn StaticsBackend,
    request: &StaticsRequest,
) -> Result<StaticsReport> {
    let structure = backend.structure();
    let mut report = base_report(backend)?;
    let settings = &request.settings;
    if settings.rank_tolerance.is_none() {
        report.input_rounding = crate::rank::input_rounding(structure, settings.input_precision);
    }
    if structure.is_loaded() {
        let sol = backend.solve_loads()?;
        add_load_solve(structure, sol, request.least_squares, &mut report)?;
    }
    if let Some(k) = request.modes {
        add_modes(structure, k, request.mass, &mut report);
    }
    Ok(report)
}

/// Counts, self-stress, prestressability and mechanisms; the optional parts left empty.
fn base_report(backend: &dyn StaticsBackend) -> Result<StaticsReport> {
    let structure = backend.structure();
    let mut notes = Vec::new();
    // a back-end may leave the margin of a very large structure out (nested dissection)
    let pre = match backend.prestressability() {
        Ok(pre) => pre,
        Err(e @ CoreError::Unsupported { .. }) => {
            notes.push(format!(
                "prestressability not computed (prestressable and prestress_margin are not answers): {e}"
            ));
            Prestressability::none(super::n_columns(structure))
        }
        Err(e) => return Err(e),
    };
    notes.extend(crate::cluster_columns::friction_note(structure));
    let internal_mechanisms = backend.internal_mechanisms()?;
    if let Certification::NotCertified { reason } = backend.certification() {
        notes.push(reason);
    }
    let prestress_stable = if pre.prestressable {
        match backend.prestress_stability(&pre.stress) {
            Ok(s) => Some(s.stable),
            Err(e @ CoreError::Unsupported { .. }) => {
                notes.push(format!("prestress stability not tested: {e}"));
                None
            }
            Err(e) => return Err(e),
        }
    } else {
        None
    };
    let basis = backend.self_stress();
    if let SelfStressBasis::Symmetric { basis, dim } = &basis {
        notes.push(format!(
            "self_stress lists the {} fully symmetric states of the {dim}-dimensional self-stress space",
            basis.ncols()
        ));
    }
    let self_stress_omitted = match &basis {
        SelfStressBasis::Omitted { dim, basis } => Some(format!(
            "the {dim}-dimensional self-stress basis of {} members ({} numbers) is not listed: above {} numbers its orthonormalisation would dominate the analysis (the dense SVD method lists it at any size)",
            basis.nrows(),
            dim * basis.nrows(),
            super::sparse::SELF_STRESS_LIST_MAX
        )),
        _ => None,
    };
    let kind = backend.kind();
    Ok(StaticsReport {
        self_stress_omitted,
        nodes: structure.n_nodes(),
        bars: structure.n_bars(),
        strings: structure.n_strings(),
        clusters: structure.clusters().len(),
        rank: backend.rank(),
        self_stress_dim: backend.self_stress_dim(),
        mechanisms: backend.mechanisms(),
        internal_mechanisms,
        prestressable: pre.prestressable,
        prestress_margin: pre.margin,
        prestress_stable,
        self_stress: basis
            .matrix()
            .column_iter()
            .map(|c| c.iter().copied().collect())
            .collect(),
        prestress: pre
            .prestressable
            .then(|| pre.stress.iter().copied().collect()),
        smallest_singular_value: backend.smallest_singular_value(),
        rank_tolerance: backend.tolerance(),
        statics_method: (kind != Factorization::Svd).then_some(kind),
        statics_warning: (!notes.is_empty()).then(|| notes.join("; ")),
        spectral_gap: backend.spectral_gap(),
        // the load solve, sizing and modes are added by their own steps
        ..StaticsReport::default()
    })
}

/// The minimal-norm load solve and, when members have materials and the load is carried, the
/// sizing for it.
fn add_load_solve(
    structure: &Structure,
    sol: super::LoadSolution,
    least_squares: bool,
    report: &mut StaticsReport,
) -> Result<()> {
    let carried = sol.load_carried();
    if !carried && !least_squares {
        return Err(StaticsError::LoadNotCarried {
            residual: sol.residual,
            relative_residual: sol.relative_residual,
            nodes: sol.unbalanced.iter().map(|(n, _)| *n).collect(),
        }
        .into());
    }
    report.load_carried = Some(carried);
    if !carried {
        report.unbalanced_nodes = Some(sol.unbalanced.iter().map(|(n, _)| *n).collect());
    }
    let has_materials = (0..structure.n_members())
        .any(|k| structure.member_material(structure.member_id(k)).is_some())
        || structure.clusters().iter().any(|c| c.material.is_some());
    if has_materials && carried {
        match sizing::size_structure_lenient(structure, &sol.member_force) {
            Ok((s, compressed)) => add_sizing(&s, &compressed, report),
            Err(e) => report.sizing_error = Some(e.to_string()),
        }
    }
    report.force_density = Some(sol.force_density.iter().copied().collect());
    report.member_force = Some(sol.member_force.iter().copied().collect());
    report.reactions = Some(
        sol.reactions
            .iter()
            .zip(structure.supports())
            .map(|((_, r), support)| Reaction::of(support, r))
            .collect(),
    );
    report.residual = Some(sol.residual);
    Ok(())
}

/// Copies a sizing into the report, with a warning naming the compressed strings.
fn add_sizing(s: &SizingReport, compressed: &[MemberId], report: &mut StaticsReport) {
    let names: Vec<String> = (compressed.iter().map(|id| id.to_string()))
        .chain(s.compressed_clusters.iter().map(|c| format!("cluster {c}")))
        .collect();
    if !names.is_empty() {
        report.sizing_warning = Some(format!(
            "the minimal-norm solution puts {} in compression; sized for yield on |force|, but a string (or cluster) cannot carry compression: add prestress (a self-stress) or make it a bar",
            names.join(", ")
        ));
    }
    report.mass_kg = Some(s.total_mass);
    report.member_radius_m = Some(s.members.iter().map(|m| m.radius).collect());
    report.member_mass_kg = Some(s.members.iter().map(|m| m.mass).collect());
    report.governing = Some(s.members.iter().map(|m| m.governing).collect());
}

/// The `k` lowest nonzero natural frequencies about the equilibrium force densities, and how
/// many zero modes were skipped before them ([`stiffness::Modes::nonzero`]).
fn add_modes(structure: &Structure, k: usize, mass: MassModel, report: &mut StaticsReport) {
    let modes = stiffness::equilibrium_force_densities(structure)
        .and_then(|(q, _)| stiffness::modal_analysis_with(structure, &q, mass));
    match modes {
        Ok(m) => {
            let nonzero = m.nonzero();
            report.zero_modes_skipped = Some(m.eigenvalues.len() - nonzero.len());
            report.natural_frequencies_hz = Some(
                nonzero
                    .iter()
                    .take(k)
                    .map(|&i| m.frequencies_hz[i])
                    .collect(),
            )
        }
        Err(e) => report.modal_error = Some(e.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tensegrity_core::material::Material;
    use tensegrity_core::structure::{Bar, StringMember, Support};

    /// The loaded D-bar of `examples/dbar_loaded.toml`: a 45° D-bar spanning 2 m, aluminium,
    /// node 0 supported, 10 kN pushing node 3 towards it (published minimum mass 8.858023 kg).
    fn loaded_dbar() -> Structure {
        Structure::builder()
            .material("alu", Material::new(2700.0, 60e9, 110e6))
            .nodes([
                [0.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [1.0, -1.0, 0.0],
                [2.0, 0.0, 0.0],
            ])
            .bar(Bar::new(0, 1).material("alu"))
            .bar(Bar::new(0, 2).material("alu"))
            .bar(Bar::new(1, 3).material("alu"))
            .bar(Bar::new(2, 3).material("alu"))
            .string(StringMember::new(1, 2).material("alu"))
            .support(Support::pinned(0))
            .load(3, [-1.0e4, 0.0, 0.0])
            .build()
            .unwrap()
    }

    /// A planar four-bar linkage (three bars between two pinned ground points), aluminium,
    /// pushed sideways by 1 kN at a knee: a mechanism for that load.
    fn pushed_linkage() -> Structure {
        Structure::builder()
            .material("alu", Material::new(2700.0, 60e9, 110e6))
            .nodes([
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                [1.0, 0.0, 1.0],
                [1.0, 0.0, 0.0],
            ])
            .bar(Bar::new(0, 1).material("alu"))
            .bar(Bar::new(1, 2).material("alu"))
            .bar(Bar::new(2, 3).material("alu"))
            .support(Support::pinned(0))
            .support(Support::pinned(3))
            .load(1, [1000.0, 0.0, 0.0])
            .build()
            .unwrap()
    }

    #[test]
    fn a_load_the_mechanism_cannot_carry_is_an_error_naming_residual_and_nodes() {
        // least squares: the top bar takes f = 500 N, leaving 500 N unbalanced at both knees,
        // residual √2 · 500 N
        let err = statics_report(&pushed_linkage(), &StaticsRequest::default()).unwrap_err();
        match err {
            CoreError::Statics(StaticsError::LoadNotCarried {
                residual, nodes, ..
            }) => {
                assert!((residual - 500.0 * 2f64.sqrt()).abs() < 1e-6, "{residual}");
                assert_eq!(nodes, vec![1, 2]);
            }
            other => panic!("{other}"),
        }
        let request = StaticsRequest {
            least_squares: true,
            ..Default::default()
        };
        let r = statics_report(&pushed_linkage(), &request).unwrap();
        assert_eq!(r.load_carried, Some(false));
        assert_eq!(r.unbalanced_nodes, Some(vec![1, 2]));
        assert!((r.member_force.as_ref().unwrap()[1] + 500.0).abs() < 1e-6);
        assert!(r.mass_kg.is_none() && r.governing.is_none(), "no sizing");
    }

    #[test]
    fn the_loaded_dbar_report_has_forces_reactions_and_sizing() {
        let r = statics_report(&loaded_dbar(), &StaticsRequest::default()).unwrap();
        assert_eq!((r.rank, r.self_stress_dim, r.prestressable), (5, 0, false));
        let f = r.member_force.as_ref().unwrap();
        assert!((f[4] - 1e4).abs() < 1e-6, "{f:?}");
        assert!((f[0] + 1e4 / 2f64.sqrt()).abs() < 1e-6, "{f:?}");
        let rc = &r.reactions.as_ref().unwrap()[0];
        assert_eq!(rc.node, 0);
        assert!((rc.force[0] - 1e4).abs() < 1e-6);
        assert!(r.residual.unwrap() < 1e-8);
        assert_eq!(
            (r.load_carried, r.unbalanced_nodes.as_ref()),
            (Some(true), None)
        );
        let gov = r.governing.as_ref().unwrap();
        assert_eq!((gov[0], gov[4]), (Governing::Buckling, Governing::Yield));
        let mass = r.mass_kg.unwrap();
        assert!((mass - 8.858023).abs() < 5e-7, "{mass}");
        let total: f64 = r.member_mass_kg.as_ref().unwrap().iter().sum();
        assert!((total - r.mass_kg.unwrap()).abs() < 1e-12);
        assert!(r.natural_frequencies_hz.is_none() && r.modal_error.is_none());
    }

    #[test]
    fn modes_without_stiffness_are_reported_as_an_error_not_a_failure() {
        let request = StaticsRequest {
            modes: Some(3),
            ..StaticsRequest::default()
        };
        let r = statics_report(&loaded_dbar(), &request).unwrap();
        assert!(r.natural_frequencies_hz.is_none());
        assert!(r.modal_error.is_some());
    }
}
