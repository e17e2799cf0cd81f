//! Pictures of one structure's analysis in the [`crate::draw`] style: the statics (members
//! coloured by the load solve's member force, or by the max-margin prestress as force density
//! when nothing is loaded; supports, loads and reactions drawn) and the mode shapes (the K
//! lowest modes of small vibration about the equilibrium force densities, each shape δn
//! scaled so that its largest node displacement is 10 % of the drawing's extent and drawn over
//! the undeformed structure; where the modes cannot be computed, e.g. without string
//! stiffness or bar mass, the first-order internal mechanisms Aᵀ δn = 0 instead).

use crate::draw::{drawing_figure_of, drawing_panel, ColorBy, Drawing, Style};
use crate::error::Result;
use nalgebra::{DMatrix, Vector3};
use tensegrity_core::budget::{self, Estimate};
use tensegrity_core::Structure;
use tensegrity_io::figure::Figure;
use tensegrity_statics::cluster_columns::per_segment;
use tensegrity_statics::stiffness::{self, MassModel};
use tensegrity_statics::DofMap;
use tensegrity_statics::{Statics, StaticsReport};

/// The structure of a statics report, members coloured by force (or prestress force
/// density), reactions drawn. With `style.color_by` [`ColorBy::Kind`] the colouring is chosen
/// from what the report has; a colouring the report cannot give falls back to the other.
pub fn statics_figure(structure: &Structure, report: &StaticsReport, style: &Style) -> Figure {
    let mut d = Drawing::of(structure);
    // one value per column (a cluster's after the strings) spread onto the drawn lines (a
    // cluster's segments after the strings)
    let spread = |v: &Option<Vec<f64>>, density| {
        v.as_ref()
            .map(|v| per_segment(structure, v, density).unwrap_or_else(|| v.clone()))
    };
    d.force = spread(&report.member_force, false);
    d.force_density =
        spread(&report.force_density, true).or_else(|| spread(&report.prestress, true));
    d.reactions = report
        .reactions
        .iter()
        .flatten()
        .map(|r| (r.node, Vector3::from(r.force)))
        .collect();
    let mut style = style.clone();
    style.color_by = match (style.color_by, d.force.is_some()) {
        (ColorBy::Force, true) | (ColorBy::Kind, true) => ColorBy::Force,
        (_, _) if d.force_density.is_some() => ColorBy::ForceDensity,
        _ => ColorBy::Kind,
    };
    let what = match (style.color_by, report.member_force.is_some()) {
        (ColorBy::Force, _) => "member forces of the load solve",
        (ColorBy::ForceDensity, true) => "force densities of the load solve",
        (ColorBy::ForceDensity, false) => "max-margin prestress (max |q| = 1)",
        _ => "bars and strings",
    };
    let title = format!("{what}, {} view", style.view.name());
    drawing_figure_of(vec![drawing_panel(title, &d, &style)], 640)
}

/// The nodes moved by `shape` (free dofs, as [`DofMap`]) scaled so that the largest node
/// displacement is `amplitude`.
fn displaced(
    nodes: &[Vector3<f64>],
    dofs: &DofMap,
    shape: &[f64],
    amplitude: f64,
) -> Vec<Vector3<f64>> {
    let mut delta = vec![Vector3::zeros(); nodes.len()];
    for (&(node, axis), &v) in dofs.free.iter().zip(shape) {
        delta[node] += dofs.axis(node, axis) * v;
    }
    let largest = delta.iter().map(|d| d.norm()).fold(0.0f64, f64::max);
    let s = if largest > 0.0 {
        amplitude / largest
    } else {
        0.0
    };
    nodes.iter().zip(&delta).map(|(p, d)| p + d * s).collect()
}

/// The largest distance between two nodes along an axis.
fn extent(nodes: &[Vector3<f64>]) -> f64 {
    (0..3)
        .map(|d| {
            let (lo, hi) = nodes.iter().fold((f64::MAX, f64::MIN), |(lo, hi), p| {
                (lo.min(p[d]), hi.max(p[d]))
            });
            hi - lo
        })
        .fold(0.0, f64::max)
        .max(1e-9)
}

/// The most mode panels [`modes_figure`] draws: a request for more draws the
/// [`MAX_MODE_PANELS`] lowest (a front end says so).
pub const MAX_MODE_PANELS: usize = 12;

/// Bytes of the SVG of one member or node drawn in a panel (a 3-prism tower of 603 nodes and
/// 1803 members: 615 kB a panel, 256 bytes an item).
pub const SVG_BYTES_PER_ITEM: f64 = 300.0;

/// The panels [`modes_figure`] draws for `k` modes asked: at most [`MAX_MODE_PANELS`].
pub fn mode_panels(k: usize) -> usize {
    k.min(MAX_MODE_PANELS)
}

/// Sustained rate of the dense SVDs of the figure's equilibrium matrix (flop/s): measured
/// 2.6·10¹⁰ on the project's 2-core VM (the mechanisms of a free tower of 200 prisms, 1809 ×
/// 1803: 5.9 s; of 300 prisms: 18.8 s), rounded down.
pub const SVD_FLOP_RATE: f64 = 2e10;

/// Flops of the dense modal analysis of n degrees of freedom per n³: the mass factor's
/// inverse, two products and the symmetric eigendecomposition with vectors (measured: 13 s
/// for n = 1809 on the project's 2-core VM at [`budget::DENSE_FLOP_RATE`]: 16.6 s estimated).
pub const MODAL_FLOPS_PER_N3: f64 = 14.0;

/// The resource estimate of [`modes_figure`] of `structure` for `k` modes, before any work:
/// the equilibrium force densities (an SVD of the n × m equilibrium matrix), then the dense
/// modes of the n free degrees of freedom where the model has what they need (string
/// stiffness and rest lengths, bar materials, masses: checked member by member, no solve),
/// else the mechanisms (a second such SVD); and the panels drawn ([`mode_panels`]),
/// [`SVG_BYTES_PER_ITEM`] a member or node each. Named `modes = k`.
///
/// ```
/// use tensegrity_core::test_models::snelson_tower_free;
/// use tensegrity_figures::structures::modes_figure_estimate;
/// let small = modes_figure_estimate(&snelson_tower_free(2).unwrap(), 1000);
/// assert!(small.work_s < 0.1 && small.output_bytes < 1e6, "{small:?}");
/// assert_eq!(small.parameters.to_string(), "modes = 1000");
/// let large = modes_figure_estimate(&snelson_tower_free(1000).unwrap(), 1000);
/// assert!(large.work_s > 600.0, "{large:?}"); // 9009 degrees of freedom, dense
/// ```
pub fn modes_figure_estimate(structure: &Structure, k: usize) -> Estimate {
    let dofs = DofMap::of(structure);
    let (n, m) = (dofs.len(), structure.n_members());
    let panels = mode_panels(k);
    let svd_s = budget::svd_flops(n, m) / SVD_FLOP_RATE;
    let masses = stiffness::lumped_masses(structure);
    let modal = stiffness::axial_stiffness(structure).is_ok()
        && (DofMap::stiffness_of(structure).free.iter()).all(|&(node, _)| masses[node] > 0.0);
    let nf = n as f64;
    let (second, memory, how) = if modal {
        let work = MODAL_FLOPS_PER_N3 * nf * nf * nf / budget::DENSE_FLOP_RATE;
        (
            work,
            64.0 * nf * nf,
            format!("the dense modes of {n} degrees of freedom"),
        )
    } else {
        let how = format!("the mechanisms of the {n} × {m} equilibrium matrix");
        (svd_s, budget::dense_statics_bytes(n, m), how)
    };
    let items = (structure.n_nodes() + m) as f64;
    let svg = panels as f64 * items * SVG_BYTES_PER_ITEM;
    Estimate::new(
        format!("the mode-shape figure ({how}, {panels} panels)"),
        format!("modes = {k}"),
    )
    .memory(memory.max(budget::dense_statics_bytes(n, m)) + svg)
    .work(svd_s + second)
    .output(svg)
}

/// The `k` lowest mode shapes of nonzero frequency, the zero modes skipped as the statics
/// report skips them (titles `mode i: f = … Hz`, i counted over all modes, so `mode 7` of a
/// free structure follows its six rigid-body modes), or the first `k` internal
/// mechanisms where the modes cannot be computed; at most [`MAX_MODE_PANELS`] of them
/// ([`mode_panels`]); an error when neither exists.
pub fn modes_figure(
    structure: &Structure,
    k: usize,
    mass: MassModel,
    style: &Style,
) -> Result<Figure> {
    let modes = stiffness::equilibrium_force_densities(structure)
        .and_then(|(q, _)| stiffness::modal_analysis_with(structure, &q, mass));
    // the modes move the nodes of elastic supports, the mechanisms do not
    let dofs = match &modes {
        Ok(_) => DofMap::stiffness_of(structure),
        Err(_) => DofMap::of(structure),
    };
    let (shapes, titles): (DMatrix<f64>, Vec<String>) = match modes {
        Ok(m) => {
            // zero modes (rigid-body motions the supports allow) are not drawn, as the
            // report does not list them: the panels are its natural_frequencies_hz
            let kept = m.nonzero();
            let titles = kept
                .iter()
                .map(|&i| format!("mode {}: f = {:.4} Hz", i + 1, m.frequencies_hz[i]))
                .collect();
            (m.shapes.select_columns(kept.iter()), titles)
        }
        Err(modal) => {
            let flexes = Statics::new(structure)?.flexes()?;
            if flexes.internal.ncols() == 0 {
                return Err(modal.into());
            }
            let titles = (0..flexes.internal.ncols())
                .map(|i| format!("mechanism {} (modes: {modal})", i + 1))
                .collect();
            (flexes.internal, titles)
        }
    };
    let amplitude = 0.1 * extent(structure.nodes());
    let base = Drawing::of(structure);
    let style = Style {
        color_by: ColorBy::Kind,
        ..style.clone()
    };
    let panels = (0..mode_panels(k).min(shapes.ncols()))
        .map(|i| {
            let col: Vec<f64> = shapes.column(i).iter().copied().collect();
            let d = Drawing {
                nodes: displaced(structure.nodes(), &dofs, &col, amplitude),
                reference: Some(structure.nodes().to_vec()),
                loads: Vec::new(),
                ..base.clone()
            };
            let mut panel = drawing_panel(titles[i].clone(), &d, &style);
            if i > 0 {
                // one legend, on the first panel
                panel.series.iter_mut().for_each(|s| s.label.clear());
                panel.marks.iter_mut().for_each(|m| m.label.clear());
            }
            panel
        })
        .collect();
    Ok(drawing_figure_of(panels, 420))
}

/// A Michell truss of an analysis drawn in `style`: members coloured by force (tension
/// dashed), the supports (level-q nodes), the tip load at the level-0 node.
pub fn michell_figure(analysis: &michell3d::MichellAnalysis, style: &Style) -> Figure {
    let truss = &analysis.truss;
    let report = &analysis.report;
    let nodes: Vec<Vector3<f64>> = truss.nodes().iter().map(|n| n.position).collect();
    let tip = truss.nodes().iter().position(|n| n.tuple.level() == 0);
    let d = Drawing {
        bars: Vec::new(),
        strings: truss
            .members()
            .iter()
            .map(|m| [m.parent, m.child])
            .collect(),
        force: Some(report.members.iter().map(|m| m.force).collect()),
        force_density: Some(report.members.iter().map(|m| m.force_density).collect()),
        supports: (0..nodes.len()).filter(|&i| truss.is_support(i)).collect(),
        loads: tip
            .map(|t| vec![(t, Vector3::from(report.load))])
            .unwrap_or_default(),
        nodes,
        ..Drawing::default()
    };
    let style = Style {
        color_by: match style.color_by {
            ColorBy::Kind => ColorBy::Force,
            other => other,
        },
        // every member is one kind here: bars and strings are told apart by their sign
        string_width: 2.0,
        ..style.clone()
    };
    let p = &report.params;
    let title = format!(
        "Michell truss, q = {}, {} view",
        p.complexity,
        style.view.name()
    );
    drawing_figure_of(vec![drawing_panel(title, &d, &style)], 640)
}
