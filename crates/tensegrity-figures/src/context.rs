//! The context every figure's builder gets ([`Context`]): the `quick` switch, the data
//! directory the sweeps behind Figs. 3.13 and 4.18 write their CSVs into, the rolling runs
//! shared by several figures (computed once) and the [`Warning`]s recorded so far.

use crate::error::{FigureError, Result};
use crate::warning::Warning;
use std::path::PathBuf;
use std::sync::{Mutex, OnceLock};
use sweeps::{RunOptions, Silent, Spec};
use tensegrity_io::csv::Curve;
use toroid::{RollReport, ToroidError};

/// What every figure's builder gets: `quick`, where the sweeps write their CSVs, the rolling
/// runs shared by Figs. 3.10 and 3.11 (computed once), and the warnings so far.
#[derive(Debug)]
pub struct Context {
    quick: bool,
    data: PathBuf,
    rolling: OnceLock<std::result::Result<Vec<RollReport>, ToroidError>>,
    warnings: Mutex<Vec<Warning>>,
}

impl Context {
    /// A context; the sweeps' CSVs go to `data` (an existing directory).
    pub fn new(quick: bool, data: impl Into<PathBuf>) -> Self {
        Self {
            quick,
            data: data.into(),
            rolling: OnceLock::new(),
            warnings: Mutex::new(Vec::new()),
        }
    }

    /// Whether the figures use coarser grids and shorter runs.
    pub fn quick(&self) -> bool {
        self.quick
    }

    /// Records a warning for figure `number`.
    pub fn warn(&self, number: &'static str, warning: tensegrity_core::Warning) {
        let mut w = self.warnings.lock().unwrap_or_else(|e| e.into_inner());
        w.push(Warning {
            figure: number,
            warning,
        });
    }

    /// The warnings recorded, in the order they came.
    pub fn into_warnings(self) -> Vec<Warning> {
        self.warnings
            .into_inner()
            .unwrap_or_else(|e| e.into_inner())
    }

    /// Runs the sweep `spec` (TOML text) to `data/NAME.csv` and reads columns `x` and `y`
    /// back as curves, one per value of `group` (`""`: one curve).
    pub fn sweep(
        &self,
        name: &str,
        spec: &str,
        x: &str,
        y: &str,
        group: &str,
    ) -> Result<Vec<Curve>> {
        let spec = Spec::parse(spec).map_err(|source| FigureError::SweepSpec {
            name: name.to_string(),
            source: Box::new(source),
        })?;
        let path = self.data.join(format!("{name}.csv"));
        let opts = RunOptions {
            threads: Some(1),
            ..RunOptions::default()
        };
        let summary = sweeps::run(&spec, &path, &opts, &mut Silent)?;
        if summary.errors > 0 {
            return Err(FigureError::ErrorRows {
                errors: summary.errors,
                written: summary.written,
                path,
            });
        }
        let group = (!group.is_empty()).then_some(group);
        Ok(tensegrity_io::csv::read_series(&path, x, y, group)?)
    }

    /// The rolling runs shared by several figures: `run` once, its result (or error) kept.
    pub(crate) fn rolling(
        &self,
        run: impl FnOnce() -> toroid::Result<Vec<RollReport>>,
    ) -> Result<&[RollReport]> {
        match self.rolling.get_or_init(run) {
            Ok(runs) => Ok(runs),
            Err(e) => Err(e.clone().into()),
        }
    }
}
