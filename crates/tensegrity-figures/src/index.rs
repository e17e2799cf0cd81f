//! The index of a `figures` run ([`FigureIndex`]): for every figure, its thesis number and
//! caption, what it shows, the files written (the picture and its data), the command that
//! reproduces it, what differs from the thesis's figure, and whether it was built. The
//! front end writes it as `index.json` (serde) and `index.md` ([`FigureIndex::to_markdown`]);
//! it supplies the command, spelled its own way.

use crate::catalog::FigureSpec;
use serde::Serialize;

/// One figure of the index.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct IndexEntry {
    /// Its number in the thesis (`3.9`).
    pub figure: String,
    /// The thesis's caption.
    pub title: String,
    /// What it shows here.
    pub description: String,
    /// The files written, relative to the output directory: the picture, then its data.
    pub files: Vec<String>,
    /// The command that reproduces it.
    pub command: String,
    /// What differs from the thesis's figure of the same number.
    pub differs_from_thesis: String,
    /// `written` or `failed`.
    pub status: String,
    /// Why it failed, if it did.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// Where the figure's model was used outside its assumptions.
    pub warnings: Vec<tensegrity_core::Warning>,
}

impl IndexEntry {
    /// The entry of `spec`, its `files` and `command`; `error`: why it failed.
    pub fn new(
        spec: &FigureSpec,
        files: Vec<String>,
        command: String,
        error: Option<String>,
    ) -> Self {
        Self {
            figure: spec.number.to_string(),
            title: spec.title.to_string(),
            description: spec.description.to_string(),
            files,
            command,
            differs_from_thesis: spec.differs.to_string(),
            status: if error.is_none() { "written" } else { "failed" }.to_string(),
            error,
            warnings: Vec::new(),
        }
    }
}

/// The index of one `figures` run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FigureIndex {
    /// Whether the run was `quick` (coarser grids, shorter rigid-model runs).
    pub quick: bool,
    /// The figures, in the thesis's order.
    pub figures: Vec<IndexEntry>,
}

impl FigureIndex {
    /// The index as a Markdown table, one row per figure.
    ///
    /// ```
    /// use tensegrity_figures::index::{FigureIndex, IndexEntry};
    /// let spec = &tensegrity_figures::FIGURES[0];
    /// let e = IndexEntry::new(spec, vec!["fig_2_2.svg".into()], "run it".into(), None);
    /// let md = FigureIndex { quick: false, figures: vec![e] }.to_markdown();
    /// assert!(md.contains("| 2.2 | 2D D-Bar |"));
    /// ```
    pub fn to_markdown(&self) -> String {
        let cell = |s: &str| s.replace('|', "\\|").replace('\n', " ");
        let mut out = String::from("# Figures\n\n");
        if self.quick {
            out.push_str(
                "Built with `quick`: coarser grids and shorter runs on the rigid model.\n\n",
            );
        }
        out.push_str(
            "| Fig. | thesis caption | files | command | differs from the thesis | status |\n",
        );
        out.push_str("|---|---|---|---|---|---|\n");
        for e in &self.figures {
            let files: Vec<String> = e.files.iter().map(|f| format!("[{f}]({f})")).collect();
            let mut status = e.status.clone();
            if let Some(err) = &e.error {
                status.push_str(&format!(": {err}"));
            }
            for w in &e.warnings {
                status.push_str(&format!("; warning: {w}"));
            }
            out.push_str(&format!(
                "| {} | {} | {} | `{}` | {} | {} |\n",
                e.figure,
                cell(&e.title),
                files.join(", "),
                e.command,
                cell(&e.differs_from_thesis),
                cell(&status)
            ));
        }
        out
    }
}
