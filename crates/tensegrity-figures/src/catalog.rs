//! The thesis figures the project computes: [`FIGURES`], one [`FigureSpec`] per figure
//! (number, what it shows, its builder), and [`FiguresRequest`], what a front end asks of
//! the table (`quick`, `only`, `png`, `threads`).
//!
//! | figures | what | from |
//! |---|---|---|
//! | 3.3, 3.9 | toroid wheels: stabilising options; complexity 6, 24, 100 | [`toroid::WheelSpec::build`] |
//! | 3.8 | the n = 8 wheel rolling, three instants | [`toroid::roll`] |
//! | 3.10, 3.11 | axle height and contact reaction of rolling wheels | [`toroid::rolling_series`] |
//! | 3.13 | F_f/F_e against σ and ε | a `tipover` sweep ([`sweeps::run`]) |
//! | 4.2–4.12, 4.19 | planar, cylindrical and spherical Michell trusses, extra strings | [`michell3d::MichellAnalysis::run`], [`michell3d::ExtraStrings`] |
//! | 4.14–4.16 | sign maps of the tip members | [`sweeps::grids::sign_maps`] |
//! | 4.18 | mass against complexity | two `michell` sweeps |
//! | 4.20 | member forces over γ | [`michell3d::extra_strings::gamma_sweep`] |
//! | 5.1–5.3 | T-bar tread, wheel, extended wheel | [`tbar_wheel::drawing::polylines`] |

use crate::driver::Context;
use crate::error::Result;
use crate::{michell, tbar, wheels as wheel};
use serde::{Deserialize, Serialize};
use tensegrity_core::request::InvalidParameter;
use tensegrity_io::figure::Figure;

/// A figure's builder: the figure from library calls (and sweeps, whose CSVs go to the
/// context's data directory).
pub type Builder = fn(&Context) -> Result<Figure>;

/// One thesis figure.
#[derive(Debug, Clone, Copy)]
pub struct FigureSpec {
    /// Its number in the thesis (`3.10`).
    pub number: &'static str,
    /// What it shows.
    pub description: &'static str,
    build: Builder,
}

impl FigureSpec {
    const fn new(number: &'static str, description: &'static str, build: Builder) -> Self {
        Self {
            number,
            description,
            build,
        }
    }

    /// Builds the figure.
    pub fn build(&self, ctx: &Context) -> Result<Figure> {
        (self.build)(ctx)
    }

    /// Its file name: `fig_3_10.svg` for `3.10` (`ext` = `svg` or `png`).
    pub fn file_name(&self, ext: &str) -> String {
        format!("fig_{}.{ext}", self.number.replace('.', "_"))
    }
}

/// Every figure, in the thesis's order.
pub const FIGURES: [FigureSpec; 24] = [
    FigureSpec::new(
        "3.3",
        "toroid stabilising options (1,2), (1,3), (2,3)",
        wheel::fig_3_3,
    ),
    FigureSpec::new("3.8", "n = 8 wheel rolling, three instants", wheel::fig_3_8),
    FigureSpec::new("3.9", "wheels of complexity 6, 24, 100", wheel::fig_3_9),
    FigureSpec::new(
        "3.10",
        "axle height of n = 8, 12, 16, 24 wheels on 50°",
        wheel::fig_3_10,
    ),
    FigureSpec::new(
        "3.11",
        "contact reaction of n = 8, 16 wheels",
        wheel::fig_3_11,
    ),
    FigureSpec::new(
        "3.13",
        "F_f/F_e against σ and ε (tipover sweep)",
        wheel::fig_3_13,
    ),
    FigureSpec::new("4.2", "planar Michell spirals, q = 1…4", michell::fig_4_2),
    FigureSpec::new("4.4", "planar q = 4: force regions", michell::fig_4_4),
    FigureSpec::new(
        "4.6",
        "cylindrical q = 4, δ = 0.25: side and top",
        michell::fig_4_6,
    ),
    FigureSpec::new(
        "4.7",
        "cylindrical q = 4, δ = 0.25: isometric",
        michell::fig_4_7,
    ),
    FigureSpec::new("4.8", "spherical q = 1, ε = π/12", michell::fig_4_8),
    FigureSpec::new("4.9", "spherical q = 2, ε = π/12: x–y", michell::fig_4_9),
    FigureSpec::new(
        "4.10",
        "spherical q = 2, ε = π/12: isometric",
        michell::fig_4_10,
    ),
    FigureSpec::new(
        "4.11",
        "spherical q = 4, ε = π/12: y–z and x–y",
        michell::fig_4_11,
    ),
    FigureSpec::new(
        "4.12",
        "spherical q = 4, ε = π/12: isometric",
        michell::fig_4_12,
    ),
    FigureSpec::new("4.14", "sign map of λ1010", michell::fig_4_14),
    FigureSpec::new("4.15", "sign map of λ1001", michell::fig_4_15),
    FigureSpec::new("4.16", "sign map of λ0100", michell::fig_4_16),
    FigureSpec::new(
        "4.18",
        "mass against complexity (michell sweeps)",
        michell::fig_4_18,
    ),
    FigureSpec::new("4.19", "extra strings, q = 2 and 3", michell::fig_4_19),
    FigureSpec::new(
        "4.20",
        "member forces over γ, low and high prestress",
        michell::fig_4_20,
    ),
    FigureSpec::new("5.1", "T-bar tread", tbar::fig_5_1),
    FigureSpec::new("5.2", "T-bar wheel", tbar::fig_5_2),
    FigureSpec::new("5.3", "extended T-bar wheel", tbar::fig_5_3),
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
        assert_eq!(FIGURES[3].file_name("png"), "fig_3_10.png");
        let all = FiguresRequest::default().selected().unwrap();
        assert_eq!(all.len(), 24);
        let e = FiguresRequest {
            only: vec!["3.10".into(), "x".into()],
            ..Default::default()
        }
        .selected()
        .unwrap_err();
        assert!(e
            .to_string()
            .starts_with("only = \"x\": no figure x (known: 3.3, 3.8,"));
    }

    #[test]
    fn the_request_reads_its_serde_form() {
        let r: FiguresRequest =
            serde_json::from_str(r#"{"quick": true, "only": ["4.2"], "threads": 2}"#).unwrap();
        assert!(r.quick && !r.png && r.workers() == 2 && r.only == ["4.2"]);
        assert!(serde_json::from_str::<FiguresRequest>(r#"{"fast": true}"#).is_err());
    }
}
