//! `tbar --export-scene`, `--vtk` and `--svg`: their sinks are opened before the analysis and
//! filled with the structure and its drawing afterwards.

use super::TbarArgs;
use crate::cli::output;
use anyhow::Result;
use tbar_wheel::{TbarGeometry, TbarRequest};
use tensegrity_figures::draw::{drawing_figure_of, drawing_panel, Drawing, View};
use tensegrity_io::sink::{FigureSink, FileSink};

/// The sinks of `--export-scene`, `--vtk` and `--svg`.
pub struct Outputs {
    scene: Option<FileSink>,
    vtk: Option<FileSink>,
    svg: Option<FigureSink>,
    views: Vec<View>,
    style: tensegrity_figures::draw::Style,
}

/// Opens the output flags given, before any work.
pub fn open(args: &TbarArgs) -> Result<Outputs> {
    Ok(Outputs {
        scene: output::open(
            "--export-scene",
            args.export_scene.as_deref(),
            FileSink::open,
        )?,
        vtk: output::open("--vtk", args.vtk.as_deref(), FileSink::open)?,
        svg: args.figure.open("--svg", args.svg.as_deref())?,
        views: match args.drawing.view {
            Some(v) => vec![v],
            None => vec![View::Side, View::Top],
        },
        style: args.drawing.style(View::Side),
    })
}

impl Outputs {
    /// Writes the structure (scene, VTK) and the drawing of `req` into the opened sinks; the
    /// VTK carries `forces` (N, bars first: the minimum-prestress state) as cell data.
    pub fn write(self, req: &TbarRequest, forces: Option<&[f64]>) -> Result<()> {
        if self.scene.is_none() && self.vtk.is_none() && self.svg.is_none() {
            return Ok(());
        }
        let g = TbarGeometry::new(req.params)?;
        let s = g.structure()?;
        if let Some(sink) = self.scene {
            sink.finish_with(tensegrity_io::scene::to_toml(&s))?;
        }
        if let Some(sink) = self.vtk {
            let data = tensegrity_io::vtk::FrameData {
                member_forces: forces,
                ..Default::default()
            };
            sink.finish_with(tensegrity_io::vtk::vtu_with(&s, s.nodes(), &data))?;
        }
        if let Some(sink) = self.svg {
            let drawing = Drawing::of(&s);
            let panels = self
                .views
                .iter()
                .map(|&view| {
                    let style = tensegrity_figures::draw::Style {
                        view,
                        ..self.style.clone()
                    };
                    drawing_panel(format!("T-bar, {} view", view.name()), &drawing, &style)
                })
                .collect();
            sink.finish(&drawing_figure_of(panels, 460))?;
        }
        Ok(())
    }
}
