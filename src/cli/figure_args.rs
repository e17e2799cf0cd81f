//! The flags of every command that writes a figure: `--size WxH[px|in|cm|mm|pt]` and `--dpi`
//! ([`FigureArgs`]); and of the commands that draw a structure: `--view`, `--color-by`,
//! `--labels` ([`StructureArgs`]). The figure's format is its file's extension: `.svg`,
//! `.png` or `.pdf`.

use anyhow::{Context, Result};
use std::path::Path;
use tensegrity_figures::draw::{ColorBy, Style, View};
use tensegrity_io::figure::{PageSize, RenderOptions};
use tensegrity_io::sink::FigureSink;

/// Size and resolution of the figures a command writes.
#[derive(clap::Args, Debug, Clone)]
pub struct FigureArgs {
    /// Figure size WIDTHxHEIGHT with a unit px (default), in, cm, mm or pt, e.g. 6x4in or
    /// 16x10cm (default: each figure's own size in px). A PDF's page is this size.
    #[arg(long, value_name = "WxH", value_parser = parse_page)]
    pub size: Option<PageSize>,
    /// Resolution of PNG images and animation frames in pixels per inch (10 to 2400; default
    /// 96, one pixel per px).
    #[arg(long, value_name = "DPI")]
    pub dpi: Option<f64>,
}

fn parse_page(s: &str) -> Result<PageSize, String> {
    s.parse::<PageSize>().map_err(|e| e.to_string())
}

impl FigureArgs {
    /// The render options, checked (`--dpi` in range).
    pub fn options(&self) -> Result<RenderOptions> {
        RenderOptions::new(self.size, self.dpi).context("--dpi")
    }

    /// Opens the figure sink of `flag` at `path` (if given) with these options.
    pub fn open(&self, flag: &str, path: Option<&Path>) -> Result<Option<FigureSink>> {
        let options = self.options()?;
        super::output::open(flag, path, |p| FigureSink::open_with(p, options))
    }

    /// [`FigureArgs::open`] for a flag that always has a path.
    pub fn open_required(&self, flag: &str, path: &Path) -> Result<FigureSink> {
        let options = self.options()?;
        super::output::open_required(flag, path, |p| FigureSink::open_with(p, options))
    }
}

/// How a structure is drawn.
#[derive(clap::Args, Debug, Clone)]
pub struct StructureArgs {
    /// Projection: iso, xy, yz, xz, or AZIMUTH,ELEVATION angles (e.g. 30deg,20deg).
    #[arg(long, value_name = "VIEW", value_parser = parse_view)]
    pub view: Option<View>,
    /// Member colours: kind (bars dark, strings red), force or force-density (a diverging map
    /// with a colour bar, tension dashed; default: force where the command has forces).
    #[arg(long, value_name = "BY", value_parser = parse_color_by)]
    pub color_by: Option<ColorBy>,
    /// Number the nodes, the members, or both: nodes,members.
    #[arg(long, value_name = "LIST", value_delimiter = ',', value_parser = ["nodes", "members"])]
    pub labels: Vec<String>,
}

fn parse_view(s: &str) -> Result<View, String> {
    s.parse()
}

fn parse_color_by(s: &str) -> Result<ColorBy, String> {
    s.parse()
}

impl StructureArgs {
    /// The drawing style, `view` unless `--view` is given.
    pub fn style(&self, view: View) -> Style {
        Style {
            view: self.view.unwrap_or(view),
            color_by: self.color_by.unwrap_or_default(),
            node_labels: self.labels.iter().any(|l| l == "nodes"),
            member_labels: self.labels.iter().any(|l| l == "members"),
            ..Style::default()
        }
    }
}
