//! `sweep plot`: one result column of a sweep's CSV against another, one curve per value of
//! a group column, rows filtered by exact texts; error rows left out. A column of angles
//! written with their unit (`30deg`, `pi/6`: the axes of angle parameters such as `incline`)
//! is plotted in degrees and its axis says so. Column names, group values and the file name
//! are drawn as plain text ([`tensegrity_io::figure::literal`]: `mean_speed` keeps its
//! underscore); a title or axis label given by the caller is drawn as given, math only between
//! `$` pairs.

use crate::error::Result;
use serde::Serialize;
use std::path::PathBuf;
use tensegrity_io::csv::{column_is_angle, read_series_where};
use tensegrity_io::figure::{literal, Figure, Panel, Scale, Series};

/// What to plot.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SweepPlot {
    /// The sweep's CSV.
    pub results: PathBuf,
    /// The x column.
    pub x: String,
    /// The y column.
    pub y: String,
    /// One curve per value of this column.
    pub group: Option<String>,
    /// Only rows whose column holds exactly this text.
    pub filter: Vec<(String, String)>,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// The title (default: the CSV's file name).
    pub title: Option<String>,
    /// The x-axis label (default: the x column, `[deg]` for angles).
    pub x_label: Option<String>,
    /// The y-axis label (default: the y column, `[deg]` for angles).
    pub y_label: Option<String>,
}

/// One curve of the plot.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlotCurve {
    /// The group's value (empty without a group).
    pub label: String,
    /// Points on it.
    pub points: usize,
}

/// What was plotted (the `--json` of `sweep plot`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PlotReport {
    /// The sweep's CSV.
    pub results: String,
    /// The x column.
    pub x: String,
    /// The y column.
    pub y: String,
    /// The group column, if any.
    pub group: Option<String>,
    /// The x column holds angles, plotted in degrees.
    pub x_in_degrees: bool,
    /// The y column holds angles, plotted in degrees.
    pub y_in_degrees: bool,
    /// The curves.
    pub curves: Vec<PlotCurve>,
    /// Points in all.
    pub points: usize,
}

impl SweepPlot {
    /// The figure and what it shows; a plot with no point is an error naming the columns.
    pub fn build(&self) -> Result<(Figure, PlotReport)> {
        let filter: Vec<(&str, &str)> = self
            .filter
            .iter()
            .map(|(c, v)| (c.as_str(), v.as_str()))
            .collect();
        let curves = read_series_where(
            &self.results,
            &self.x,
            &self.y,
            self.group.as_deref(),
            &filter,
        )?;
        let path = self.results.display().to_string();
        if curves.is_empty() {
            return Err(crate::FigureError::EmptyPlot {
                path: self.results.clone(),
                x: self.x.clone(),
                y: self.y.clone(),
            });
        }
        let x_deg = column_is_angle(&self.results, &self.x)?;
        let y_deg = column_is_angle(&self.results, &self.y)?;
        let label = |given: &Option<String>, c: &str, deg: bool| match (given, deg) {
            (Some(given), _) => given.clone(),
            (None, true) => format!("{} [deg]", literal(c)),
            (None, false) => literal(c),
        };
        let title = self.title.clone().unwrap_or_else(|| {
            let name = self.results.file_name();
            literal(&name.map_or(String::new(), |n| n.to_string_lossy().into_owned()))
        });
        let mut panel = Panel::new(
            title,
            label(&self.x_label, &self.x, x_deg),
            label(&self.y_label, &self.y, y_deg),
        );
        let scale = |log: bool| if log { Scale::Log } else { Scale::Linear };
        (panel.x_scale, panel.y_scale) = (scale(self.log_x), scale(self.log_y));
        let group = self.group.as_deref().unwrap_or("");
        let mut report = PlotReport {
            results: path,
            x: self.x.clone(),
            y: self.y.clone(),
            group: self.group.clone(),
            x_in_degrees: x_deg,
            y_in_degrees: y_deg,
            curves: Vec::new(),
            points: 0,
        };
        for (label, points) in curves {
            report.points += points.len();
            report.curves.push(PlotCurve {
                label: label.clone(),
                points: points.len(),
            });
            let label = match group.is_empty() {
                true => literal(&label),
                false => literal(&format!("{group} = {label}")),
            };
            panel = panel.series(Series::new(label, points).with_markers());
        }
        Ok((Figure::new(vec![panel]), report))
    }
}
