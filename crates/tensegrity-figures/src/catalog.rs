//! The thesis figures the project computes: [`FIGURES`], one [`FigureSpec`] per figure
//! (number, what it shows, its builder), and [`FiguresRequest`], what a front end asks of
//! the table (`quick`, `only`, `png`, `threads`).
//!
//! Each figure also says the thesis's caption (`title`) and what differs from it
//! (`differs`), which `figures` writes to its index.
//!
//! | figures | what | from |
//! |---|---|---|
//! | 2.2 | the planar D-bar of eq. 2.8–2.10 | closed form |
//! | 3.1, 3.2 | the prism's nodes; the toroid's parameters | [`toroid::prism_nodes`], [`toroid::WheelSpec::build`] |
//! | 3.3, 3.9 | toroid wheels: stabilising options; complexity 6, 24, 100 (D = 0.8/n) | [`toroid::toroid_report`] |
//! | 3.8 | the n = 8 wheel rolling, three instants | [`toroid::roll_with_frames`] |
//! | 3.10, 3.11 | axle height and contact reaction of rolling wheels | [`toroid::rolling_series`] |
//! | 3.13 | F_f/F_e against σ and ε | a `tipover` sweep ([`sweeps::run`]) |
//! | 4.1–4.3 | Michell spirals and the planar topology | eq. 4.1–4.7, [`michell3d::MichellAnalysis::run`] |
//! | 4.4, 4.6–4.13, 4.19 | force regions; planar, cylindrical and spherical trusses, extra strings | [`michell3d::MichellAnalysis::run`], [`michell3d::ExtraStrings`] |
//! | 4.14–4.16 | sign maps of the tip members | [`sweeps::grids::sign_maps`] |
//! | 4.18 | mass against complexity | two `michell` sweeps |
//! | 4.20 | member force densities over γ | [`michell3d::extra_strings::gamma_sweep`] |
//! | 5.1–5.3 | T-bar tread, wheel, extended wheel | [`tbar_wheel::drawing::polylines`] |

use crate::context::Context;
use crate::data::Drawn;
use crate::error::Result;
use crate::{chapter2, michell, tbar, wheels as wheel};
use serde::{Deserialize, Serialize};
use tensegrity_core::request::InvalidParameter;

/// A figure's builder: the figure and its data from library calls (and sweeps, whose CSVs
/// go to the context's data directory).
pub type Builder = fn(&Context) -> Result<Drawn>;

/// One thesis figure.
#[derive(Debug, Clone, Copy)]
pub struct FigureSpec {
    /// Its number in the thesis (`3.10`).
    pub number: &'static str,
    /// What it shows.
    pub description: &'static str,
    /// The thesis's caption.
    pub title: &'static str,
    /// What differs from the thesis's figure of the same number.
    pub differs: &'static str,
    build: Builder,
}

impl FigureSpec {
    const fn new(
        number: &'static str,
        description: &'static str,
        (title, differs): (&'static str, &'static str),
        build: Builder,
    ) -> Self {
        Self {
            number,
            description,
            title,
            differs,
            build,
        }
    }

    /// Builds the figure and its data.
    pub fn build(&self, ctx: &Context) -> Result<Drawn> {
        (self.build)(ctx)
    }

    /// Its file name: `fig_3_10.svg` for `3.10` (`ext` = `svg`, `png`, or `csv` for its
    /// data).
    pub fn file_name(&self, ext: &str) -> String {
        format!("fig_{}.{ext}", self.number.replace('.', "_"))
    }
}

/// The figures of the thesis the project computes.
pub const COUNT: usize = 30;

/// Every figure, in the thesis's order.
pub const FIGURES: [FigureSpec; COUNT] = [
    FigureSpec::new(
        "2.2",
        "planar D-bar (eq. 2.8–2.10), L = 2 m, h = 0.5 m",
        ("2D D-Bar", "L = 2 m and h = 0.5 m chosen (the thesis keeps them symbolic); members drawn as lines, not arrows"),
        chapter2::fig_2_2,
    ),
    FigureSpec::new(
        "3.1",
        "3-bar prism node positions n1…n6",
        ("3-Bar Prism Node Positions", "n6 = [0, R_m tan(π/n), −R_m] as corrected (ERRATA 3.1; the thesis prints −R_i); a drawing of the reference prism (n = 8), not a sketch"),
        wheel::fig_3_1,
    ),
    FigureSpec::new(
        "3.2",
        "toroid parameters on the reference wheel",
        ("3-Bar Toroid Parameters", "the radii drawn as circles and the values in the legend and data, not dimension arrows"),
        wheel::fig_3_2,
    ),
    FigureSpec::new(
        "3.3",
        "toroid stabilising options (1,2), (1,3), (2,3)",
        ("3-Bar Toroid Extra String Options", "isometric views; the prestress design's member forces and margin added in the data"),
        wheel::fig_3_3,
    ),
    FigureSpec::new(
        "3.8",
        "n = 8 wheel rolling, three instants",
        ("3-Bar Wheel at t = 0; t = 1.5; t = 3 seconds", "this project's rolling model (auto fidelity; the rigid model for 0, 0.25, 0.5 s with quick), drawn from the run's own node frames in the incline's frame"),
        wheel::fig_3_8,
    ),
    FigureSpec::new(
        "3.9",
        "wheels of complexity 6, 24, 100 (D = 0.8/n)",
        ("3-Bar Wheels of Complexity (left to right) 6, 24, 100", "tread offset scaled, D = 0.8/n (scale_with_n): with the reference D = 0.1 the n = 100 wheel is not prestressable (margin 0); margins in the data"),
        wheel::fig_3_9,
    ),
    FigureSpec::new(
        "3.10",
        "axle height of n = 8, 12, 16, 24 wheels on 50°",
        ("Axle ι3 Displacement for n = 8, 12, 16, 24, φ = 50°", "height above the incline less its mean, 2 s; this project's contact model and fidelity policy"),
        wheel::fig_3_10,
    ),
    FigureSpec::new(
        "3.11",
        "contact reaction of n = 8, 16 wheels",
        ("Reaction Force History for n = 8, 16", "the net normal force on the slope, 2 s; this project's contact model and fidelity policy"),
        wheel::fig_3_11,
    ),
    FigureSpec::new(
        "3.13",
        "F_f/F_e against σ and ε (tipover sweep)",
        ("Normalized Friction as a function of σ and ε", "one curve per ε against σ instead of a colour map; eq. 3.29 as corrected (ERRATA 3.13), from real wheels"),
        wheel::fig_3_13,
    ),
    FigureSpec::new(
        "4.1",
        "Michell spiral of complexity 4 with its radii",
        ("Michell Spiral of Complexity 4, φ = π/8, β = π/6", "computed from eq. 4.1–4.7 (Skelton's sketch has angle annotations)"),
        michell::fig_4_1,
    ),
    FigureSpec::new(
        "4.2",
        "Michell spirals of order 0…4",
        ("Michell Spiral of Complexity 0, 1, 2, 3, and 4, φ = π/8, β = π/6", "none in content; one colour per order"),
        michell::fig_4_2,
    ),
    FigureSpec::new(
        "4.3",
        "planar Michell topology of complexity 4",
        ("Michell Topology of Complexity 4, φ = π/8, β = π/6", "none in content"),
        michell::fig_4_3,
    ),
    FigureSpec::new(
        "4.4",
        "planar q = 4: spiral families and force regions",
        ("Michell Topology of Complexity 4, Force Regions of Interest", "the regions drawn as fans of load directions at the tip; the data holds the forces under the load along −ι3 (θ00 = 3π/2)"),
        michell::fig_4_4,
    ),
    FigureSpec::new(
        "4.6",
        "cylindrical q = 4, δ = 0.25: side and top",
        ("3D Michell Topology of Complexity 4 - Side and Top View, φ = π/8, β = π/6, δ = r0/4", "members coloured by force sign under a 1 kN tip load along −ι3"),
        michell::fig_4_6,
    ),
    FigureSpec::new(
        "4.7",
        "cylindrical q = 4, δ = 0.25: isometric",
        ("3D Michell Truss of Complexity 4 - Isometric View, β = π/6, δ = r0/4", "φ = π/8 as in Fig. 4.6; members coloured by force sign"),
        michell::fig_4_7,
    ),
    FigureSpec::new(
        "4.8",
        "spherical q = 1, ε = π/12",
        ("Sketch of Segmentation Angle, ε", "a computed truss (q = 1, φ = π/16) instead of a sketch"),
        michell::fig_4_8,
    ),
    FigureSpec::new(
        "4.9",
        "spherical q = 2, ε = π/12: x–y, coloured by height class",
        ("XY View of 3D Michell Topology of Complexity 2; β = π/6, φ = π/16; ε = π/12", "colours: height class Z = U − D per node, mean Z per member (own palette)"),
        michell::fig_4_9,
    ),
    FigureSpec::new(
        "4.10",
        "spherical q = 2, ε = π/12: isometric",
        ("3D Michell Truss of Complexity 2; β = π/6, φ = π/16; ε = π/12", "members coloured by force sign"),
        michell::fig_4_10,
    ),
    FigureSpec::new(
        "4.11",
        "spherical q = 4, ε = π/12: y–z and x–y",
        ("3D Michell Truss of Complexity 4 - YZ and XY View; β = π/6, φ = π/10; ε = π/12", "members coloured by force sign"),
        michell::fig_4_11,
    ),
    FigureSpec::new(
        "4.12",
        "spherical q = 4, ε = π/12: isometric",
        ("3D Michell Truss of Complexity 4; β = π/6, φ = π/10; ε = π/12", "members coloured by force sign"),
        michell::fig_4_12,
    ),
    FigureSpec::new(
        "4.13",
        "cylindrical q = 1: tip members in tension and compression",
        ("3D Truss, q = 1, Red = Tension, Blue = Compression", "δ = 0.25 and φ = π/8 chosen (the thesis states none); the force densities of eq. 4.18–4.20 in the data"),
        michell::fig_4_13,
    ),
    FigureSpec::new(
        "4.14",
        "sign map of λ1010",
        ("Sign of λ1010 as a Function of φ, γ", "γ over [0, π] (the polar angle; the thesis sweeps [0, 2π], ERRATA 4.22)"),
        michell::fig_4_14,
    ),
    FigureSpec::new(
        "4.15",
        "sign map of λ1001",
        ("Sign of λ1001 as a Function of φ, γ", "γ over [0, π] (ERRATA 4.22)"),
        michell::fig_4_15,
    ),
    FigureSpec::new(
        "4.16",
        "sign map of λ0100",
        ("Sign of λ0100 as a Function of φ, γ", "γ over [0, π] (ERRATA 4.22); eq. 4.23 as corrected (ERRATA 4.13)"),
        michell::fig_4_16,
    ),
    FigureSpec::new(
        "4.18",
        "mass against complexity (michell sweeps)",
        ("Mass of 2D and 3D truss, δ = [0, 0.1, 0.25, 0.5]", "steel, yield and Euler buckling, w0 = 1 kN, φ = π/q"),
        michell::fig_4_18,
    ),
    FigureSpec::new(
        "4.19",
        "extra strings, q = 2 and 3",
        ("Extra Strings on 3D Michell Truss of Complexity 2 and 3", "isometric views, cylindrical δ = 0.25"),
        michell::fig_4_19,
    ),
    FigureSpec::new(
        "4.20",
        "member force densities over γ, low and high prestress",
        ("Force Density of Members. Top: low pre-stress; Bottom: high pre-stress", "cylindrical q = 2, δ = 0.25; 10 N and 5 kN in the extra strings (the thesis states no levels); panels side by side"),
        michell::fig_4_20,
    ),
    FigureSpec::new(
        "5.1",
        "T-bar tread",
        ("Single Tread of T-Bar Wheel", "q = 1 (the thesis draws q = 2, which `tbar` reports not prestressable: with every lattice member a string only q = 1 treads are; q = 1 is the smallest prestressable tread), cylindrical, β = π/6, φ = π/8, δ = 0.25"),
        tbar::fig_5_1,
    ),
    FigureSpec::new(
        "5.2",
        "T-bar wheel",
        ("T-Bar Wheel", "q = 1 (the thesis draws q = 2, which `tbar` reports not prestressable: with every lattice member a string only q = 1 treads are; q = 1 is the smallest prestressable tread), cylindrical, β = π/6, φ = π/8, δ = 0.25"),
        tbar::fig_5_2,
    ),
    FigureSpec::new(
        "5.3",
        "extended T-bar wheel",
        ("Extended T-Bar Wheel", "q = 1 (the thesis draws q = 2, which `tbar` reports not prestressable: with every lattice member a string only q = 1 treads are; q = 1 is the smallest prestressable tread), cylindrical, β = π/6, φ = π/8, δ = 0.25; a copy 0.5 m along ι1"),
        tbar::fig_5_3,
    ),
];

/// What a front end asks of the figure table.
///
/// ```
/// use tensegrity_figures::FiguresRequest;
/// let r = FiguresRequest { only: vec!["fig_3_10".into(), "4.18".into(), "3.10".into()], ..Default::default() };
/// let chosen: Vec<&str> = r.selected().unwrap().iter().map(|f| f.number).collect();
/// assert_eq!(chosen, ["3.10", "4.18"]); // in the table's order, each once
/// assert_eq!(r.extension(), "svg");
/// let bad = FiguresRequest { only: vec!["9.9".into()], ..Default::default() };
/// assert!(bad.selected().unwrap_err().to_string().contains("no figure 9.9"));
/// ```
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FiguresRequest {
    /// Coarser grids and shorter runs on the reduced rigid rolling model: a smoke test in
    /// seconds.
    pub quick: bool,
    /// Only these figures, by number (`3.10`) or file stem (`fig_3_10`); empty: all.
    pub only: Vec<String>,
    /// PNG images (embedded font) instead of SVG.
    pub png: bool,
    /// Figures built at once (unset: one per core).
    pub threads: Option<usize>,
}

impl FiguresRequest {
    /// The figures `only` selects, in the table's order, each once; an unknown number is an
    /// [`InvalidParameter`] of `only` that lists the known ones.
    pub fn selected(&self) -> Result<Vec<&'static FigureSpec>> {
        let mut chosen = Vec::new();
        for n in &self.only {
            let number = n.trim().trim_start_matches("fig_").replace('_', ".");
            let Some(i) = FIGURES.iter().position(|f| f.number == number) else {
                let all: Vec<&str> = FIGURES.iter().map(|f| f.number).collect();
                let reason = format!("no figure {number} (known: {})", all.join(", "));
                return Err(InvalidParameter::text("only", n, reason).into());
            };
            chosen.push(i);
        }
        if self.only.is_empty() {
            chosen = (0..FIGURES.len()).collect();
        }
        // one file per figure: a figure named twice is built once
        chosen.sort_unstable();
        chosen.dedup();
        Ok(chosen.into_iter().map(|i| &FIGURES[i]).collect())
    }

    /// The figures' file extension: `png` or `svg`.
    pub fn extension(&self) -> &'static str {
        if self.png {
            "png"
        } else {
            "svg"
        }
    }

    /// The workers: `threads`, or one per core.
    pub fn workers(&self) -> usize {
        self.threads
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()))
            .max(1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_figure_has_one_number_and_its_file_name() {
        let mut numbers: Vec<&str> = FIGURES.iter().map(|f| f.number).collect();
        numbers.dedup();
        assert_eq!(numbers.len(), FIGURES.len());
        assert_eq!(FIGURES[6].file_name("png"), "fig_3_10.png");
        let all = FiguresRequest::default().selected().unwrap();
        assert_eq!(all.len(), COUNT);
        let e = FiguresRequest {
            only: vec!["3.10".into(), "x".into()],
            ..Default::default()
        }
        .selected()
        .unwrap_err();
        assert!(e
            .to_string()
            .starts_with("only = \"x\": no figure x (known: 2.2, 3.1, 3.2,"));
    }

    #[test]
    fn the_request_reads_its_serde_form() {
        let r: FiguresRequest =
            serde_json::from_str(r#"{"quick": true, "only": ["4.2"], "threads": 2}"#).unwrap();
        assert!(r.quick && !r.png && r.workers() == 2 && r.only == ["4.2"]);
        assert!(serde_json::from_str::<FiguresRequest>(r#"{"fast": true}"#).is_err());
    }
}
