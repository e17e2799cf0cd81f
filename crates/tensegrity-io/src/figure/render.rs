//! PNG and PDF from a figure's SVG: parsed by usvg with the embedded DejaVu Sans as its only
//! font (no system fonts), rasterised by resvg onto white at dpi/96 pixels per CSS pixel, or
//! converted by svg2pdf to a one-page PDF whose page is the figure's size at 72 points per inch
//! (text stays text, with the font subset embedded; the SVG for a PDF carries its size in
//! points, [`super::svg::write_points`]).

use super::{FONT, FONT_FAMILY};
use crate::error::{IoError, Result};
use std::sync::{Arc, OnceLock};

/// The largest PNG the renderer makes, in pixels (width × height).
pub const MAX_PIXELS: f64 = 100e6;

fn options() -> &'static usvg::Options<'static> {
    static OPTIONS: OnceLock<usvg::Options<'static>> = OnceLock::new();
    OPTIONS.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(FONT.to_vec());
        db.set_sans_serif_family(FONT_FAMILY);
        usvg::Options {
            font_family: FONT_FAMILY.to_string(),
            fontdb: Arc::new(db),
            ..usvg::Options::default()
        }
    })
}

fn drawing_error(e: impl std::fmt::Display) -> IoError {
    IoError::Drawing {
        message: e.to_string(),
    }
}

/// The parsed SVG.
fn tree(svg: &str) -> Result<usvg::Tree> {
    usvg::Tree::from_str(svg, options()).map_err(drawing_error)
}

/// The SVG rasterised at `dpi` (96: one pixel per CSS pixel) on white: RGB bytes, row-major,
/// and the size in pixels (the SVG's size × dpi / 96, rounded).
pub fn rgb(svg: &str, dpi: f64) -> Result<(Vec<u8>, (u32, u32))> {
    let tree = tree(svg)?;
    let scale = dpi / 96.0;
    let size = tree.size();
    let (w, h) = (
        (size.width() as f64 * scale).round(),
        (size.height() as f64 * scale).round(),
    );
    if w < 1.0 || h < 1.0 || w * h > MAX_PIXELS {
        return Err(IoError::InvalidFigureSize {
            text: format!("{w} × {h} pixels"),
            reason: "a PNG must have between 1 and 100 million pixels: lower the size or the dpi",
        });
    }
    let (w, h) = (w as u32, h as u32);
    let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h)
        .ok_or_else(|| drawing_error(format!("no {w} × {h} image")))?;
    pixmap.fill(resvg::tiny_skia::Color::WHITE);
    let (sx, sy) = (w as f32 / size.width(), h as f32 / size.height());
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::from_scale(sx, sy),
        &mut pixmap.as_mut(),
    );
    // opaque white underneath: the premultiplied RGBA is the RGB
    let rgb = pixmap
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    Ok((rgb, (w, h)))
}

/// The SVG as a one-page PDF whose page is the SVG's size read as points (one user unit a
/// point: [`super::svg::write_points`] writes a figure so). The conversion runs at 72 dpi, so
/// svg2pdf adds no scale of its own: at any other dpi svg2pdf 0.13 scales the drawing but not
/// the pattern matrices of its gradients, and a colour bar's stops land in the wrong places.
pub fn pdf(svg: &str) -> Result<Vec<u8>> {
    let tree = tree(svg)?;
    svg2pdf::to_pdf(
        &tree,
        svg2pdf::ConversionOptions::default(),
        svg2pdf::PageOptions { dpi: 72.0 },
    )
    .map_err(drawing_error)
}
