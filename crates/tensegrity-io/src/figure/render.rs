//! PNG and PDF from a figure's SVG: parsed by usvg with the embedded DejaVu Sans as its only
//! font (no system fonts), rasterised by resvg onto white at dpi/96 pixels per CSS pixel
//! (the texts outside clipped groups laid out once and kept, [`TextCache`]), or
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
///
/// The texts outside clipped groups are drawn last, each from its layout in the
/// [`TextCache`] moved to its place: laying out a text (shaping it on the font) costs more
/// than drawing it, and an animation's frames repeat their texts.
pub fn rgb(svg: &str, dpi: f64) -> Result<(Vec<u8>, (u32, u32))> {
    let (rgba, (w, h)) = rgba(svg, dpi)?;
    let mut rgb = Vec::with_capacity(3 * (w as usize) * (h as usize));
    for p in rgba.chunks_exact(4) {
        rgb.extend_from_slice(&p[..3]);
    }
    Ok((rgb, (w, h)))
}

/// [`rgb`] with each pixel's opacity after it (always 255: the page is opaque white), as
/// the rasteriser leaves it: what an encoder that reads whole pixels takes without a copy.
pub fn rgba(svg: &str, dpi: f64) -> Result<(Vec<u8>, (u32, u32))> {
    let merged = merged_polylines(svg);
    let (rest, texts) = split_texts(&merged);
    let tree = tree(&rest)?;
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
    let scale = resvg::tiny_skia::Transform::from_scale(sx, sy);
    resvg::render(&tree, scale, &mut pixmap.as_mut());
    for text in &texts {
        let laid_out = text_cache().get(&text.key)?;
        let at = scale.pre_translate(text.x as f32, text.y as f32);
        resvg::render(&laid_out, at, &mut pixmap.as_mut());
    }
    // opaque white underneath: the premultiplied RGBA is the RGB and 255
    Ok((pixmap.take(), (w, h)))
}

/// `svg` with each run of consecutive `<polyline>` lines that differ only in their points
/// (the figure writer's members of one kind: one per line, [`super::svg`]) drawn as one
/// `<path>` of as many subpaths: the same outline (each subpath stroked with its own caps
/// and joins), filled at once. The rasteriser's work per element (parsing, a stroke, a
/// fill's set-up) dominated a drawing of many short members: a rolling wheel's frame has
/// 153. Where two members of one colour overlap, their union is filled once, so the
/// anti-aliased edge inside the overlap is not blended twice. Only pictures are drawn so;
/// the SVG keeps one polyline per series.
fn merged_polylines(svg: &str) -> String {
    const HEAD: &str = "<polyline points=\"";
    let mut out = String::with_capacity(svg.len());
    // the attributes after the points of the run being merged
    let mut run: Option<&str> = None;
    for line in svg.split_inclusive('\n') {
        let parts = line
            .strip_prefix(HEAD)
            .and_then(|rest| rest.split_once('"'))
            .filter(|(points, _)| !points.is_empty());
        match (parts, run) {
            (Some((points, style)), Some(open)) if style == open => {
                subpath(&mut out, points);
            }
            (Some((points, style)), _) => {
                if let Some(open) = run {
                    out.push('"');
                    out.push_str(open);
                }
                out.push_str("<path d=\"");
                subpath(&mut out, points);
                run = Some(style);
            }
            (None, _) => {
                if let Some(open) = run.take() {
                    out.push('"');
                    out.push_str(open);
                }
                out.push_str(line);
            }
        }
    }
    if let Some(open) = run {
        out.push('"');
        out.push_str(open);
    }
    out
}

/// The points `x,y x,y …` of a polyline as the subpath `M x,y L x,y …`.
fn subpath(out: &mut String, points: &str) {
    for (k, p) in points.split(' ').enumerate() {
        out.push_str(match k {
            0 => " M",
            1 => " L",
            _ => " ",
        });
        out.push_str(p);
    }
}

/// A text taken out of an SVG: its element moved to the origin, with its fill (the key of
/// its layout), and where it goes.
#[derive(Debug, Clone, PartialEq)]
struct PlacedText {
    key: String,
    x: f64,
    y: f64,
}

/// The value of attribute `name` in the tag `tag`.
fn attribute<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let at = tag.find(&format!(" {name}=\""))? + name.len() + 3;
    let len = tag[at..].find('"')?;
    Some(&tag[at..at + len])
}

/// `svg` without its texts that lie outside clipped or transformed groups, and those texts.
/// The figures' writer ([`super::svg`]) sets a text's place by the `x` and `y` of its
/// `<text>` (a turned one by `rotate(-90 x y)` about the same point) and its colour by an
/// enclosing `<g fill>`; a text it cannot read so stays in the SVG.
fn split_texts(svg: &str) -> (String, Vec<PlacedText>) {
    let mut rest = String::with_capacity(svg.len());
    let mut texts = Vec::new();
    // per open group: its fill (inherited) and whether it clips
    let mut groups: Vec<(String, bool)> = vec![("#000000".into(), false)];
    let mut i = 0;
    while let Some(k) = svg[i..].find('<') {
        let start = i + k;
        let tail = &svg[start..];
        let end = match tail.find('>') {
            Some(e) => start + e + 1,
            None => break,
        };
        let tag = &svg[start..end];
        if tag.starts_with("<g") {
            let (fill, clip) = groups.last().cloned().unwrap_or_default();
            let fill = attribute(tag, "fill").map_or(fill, str::to_string);
            // a clipped or transformed group keeps its texts (drawn moved, they would escape
            // the clip or miss the transform)
            let clip = clip
                || attribute(tag, "clip-path").is_some()
                || attribute(tag, "transform").is_some();
            groups.push((fill, clip));
        } else if tag.starts_with("</g") {
            groups.pop();
        } else if tag.starts_with("<text") {
            let (fill, clip) = groups.last().cloned().unwrap_or_default();
            let close = svg[end..]
                .find("</text>")
                .map(|c| end + c + "</text>".len());
            let xy = attribute(tag, "x").zip(attribute(tag, "y"));
            let xy = xy.and_then(|(x, y)| Some((x.parse::<f64>().ok()?, y.parse::<f64>().ok()?)));
            if let (false, Some(close), Some((x, y))) = (clip, close, xy) {
                let (xs, ys) = (
                    attribute(tag, "x").unwrap_or(""),
                    attribute(tag, "y").unwrap_or(""),
                );
                let moved = tag
                    .replacen(&format!(" x=\"{xs}\" y=\"{ys}\""), " x=\"0\" y=\"0\"", 1)
                    .replacen(&format!("rotate(-90 {xs} {ys})"), "rotate(-90 0 0)", 1);
                let key = format!("<g fill=\"{fill}\">{moved}{}</g>", &svg[end..close]);
                texts.push(PlacedText { key, x, y });
                rest.push_str(&svg[i..start]);
                i = close;
                continue;
            }
        }
        rest.push_str(&svg[i..end]);
        i = end;
    }
    rest.push_str(&svg[i..]);
    (rest, texts)
}

/// Texts laid out (shaped on the font, turned into outlines), each kept by its element: the
/// frames of an animation, and the panels of a figure, repeat their tick labels, axis
/// labels and legends. At most [`TextCache::CAPACITY`] are kept (then it starts again).
#[derive(Debug, Default)]
pub struct TextCache {
    laid_out: std::sync::Mutex<std::collections::HashMap<String, Arc<usvg::Tree>>>,
}

impl TextCache {
    /// The most texts kept.
    pub const CAPACITY: usize = 4096;

    /// The layout of the text `element` (a `<g fill>` around a `<text>` at the origin).
    fn get(&self, element: &str) -> Result<Arc<usvg::Tree>> {
        let lock = || self.laid_out.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(t) = lock().get(element) {
            return Ok(t.clone());
        }
        let svg = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"1\" height=\"1\" font-family=\"{FONT_FAMILY}, sans-serif\">{element}</svg>"
        );
        let laid_out = Arc::new(tree(&svg)?);
        let mut map = lock();
        if map.len() >= Self::CAPACITY {
            map.clear();
        }
        map.insert(element.to_string(), laid_out.clone());
        Ok(laid_out)
    }
}

fn text_cache() -> &'static TextCache {
    static CACHE: OnceLock<TextCache> = OnceLock::new();
    CACHE.get_or_init(TextCache::default)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::{Figure, Panel, RenderOptions, Series};

    /// The SVG drawn by resvg in one piece, its texts laid out in place.
    fn whole(svg: &str) -> Vec<u8> {
        let tree = tree(svg).unwrap();
        let size = tree.size();
        let (w, h) = (size.width().round() as u32, size.height().round() as u32);
        let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h).unwrap();
        pixmap.fill(resvg::tiny_skia::Color::WHITE);
        let (sx, sy) = (w as f32 / size.width(), h as f32 / size.height());
        let scale = resvg::tiny_skia::Transform::from_scale(sx, sy);
        resvg::render(&tree, scale, &mut pixmap.as_mut());
        pixmap
            .data()
            .chunks_exact(4)
            .flat_map(|p| [p[0], p[1], p[2]])
            .collect()
    }

    #[test]
    fn texts_drawn_from_the_cache_match_the_whole_drawing() {
        let line = Panel::new("$F_f/F_e$ over $λ1010$", "x [m]", "y$^2$ [m²]")
            .series(Series::new(
                "mean_speed",
                vec![(0.0, 0.0), (1.0, 2.0), (2.0, 1.5)],
            ))
            .series(Series::new("$σ_1$", vec![(0.0, 1.0), (2.0, 0.2)]));
        let figures = [
            Figure::new(vec![line.clone()]),
            Figure::new(vec![line.clone(), line]).mark_invalid("drifted: 3 % of the energy"),
        ];
        for figure in figures {
            let svg = figure.to_svg_with(&RenderOptions::default()).unwrap();
            let (rest, texts) = split_texts(&svg);
            // every text of the figure was taken out (none is clipped here)
            assert_eq!(texts.len(), svg.matches("<text").count());
            assert!(!rest.contains("<text"));
            assert!(texts.iter().any(|t| t.key.contains("rotate(-90 0 0)")));
            assert!(
                texts.iter().any(|t| t.key.contains("fill=\"#d00000\""))
                    || figure.invalid.is_none()
            );
            // drawn twice (with a warm cache the second time), each as one piece
            for _ in 0..2 {
                let (cached, _) = rgb(&svg, 96.0).unwrap();
                let direct = whole(&svg);
                assert_eq!(cached.len(), direct.len());
                // the same pixels: a text moved to the origin and drawn back is the same
                let differ = cached.iter().zip(&direct).filter(|(a, b)| a != b).count();
                assert_eq!(differ, 0, "{differ} of {} bytes differ", cached.len());
            }
        }
    }

    #[test]
    fn members_of_one_kind_are_drawn_as_one_path_with_the_same_pixels() {
        // eight separate members of one colour and width (a wheel's strings), one of
        // another width, a one-point series: no two share a pixel
        let mut panel = Panel::new("members", "x [m]", "y [m]");
        for k in 0..8 {
            let x = k as f64;
            panel = panel.series(
                Series::new("", vec![(x, 0.0), (x + 0.4, 1.0), (x, 2.0)])
                    .with_color((200, 30, 30))
                    .with_width(1.0),
            );
        }
        panel = panel
            .series(
                Series::new("", vec![(0.0, 3.0), (7.0, 3.0)])
                    .with_color((200, 30, 30))
                    .with_width(3.0),
            )
            .series(Series::new("", vec![(3.0, 4.0), (3.0, 4.0)]).with_color((0, 0, 200)));
        let svg = Figure::new(vec![panel])
            .to_svg_with(&RenderOptions::default())
            .unwrap();
        let merged = merged_polylines(&svg);
        assert_eq!(svg.matches("<polyline").count(), 10);
        assert_eq!(merged.matches("<polyline").count(), 0);
        // the eight thin ones, the thick one, the dot
        assert_eq!(merged.matches("<path d=\"").count(), 3);
        assert_eq!(merged.matches(" M").count(), 10);
        assert_eq!(merged.matches("stroke-width=\"1\"").count(), 1);
        // the rest of the drawing unchanged
        let strip = |s: &str| -> String {
            s.lines()
                .filter(|l| !l.starts_with("<polyline") && !l.starts_with("<path d="))
                .collect()
        };
        assert_eq!(strip(&svg), strip(&merged));
        // the same pixels as each member drawn on its own (their pixels are apart)
        let (drawn, _) = rgb(&svg, 96.0).unwrap();
        let direct = whole(&svg);
        let differ = drawn.iter().zip(&direct).filter(|(a, b)| a != b).count();
        assert_eq!(differ, 0, "{differ} of {} bytes differ", drawn.len());
    }

    #[test]
    fn a_clipped_text_stays_in_the_drawing() {
        let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"20\" height=\"20\"><g clip-path=\"url(#c)\"><text x=\"1\" y=\"9\" font-size=\"9\">a</text></g><g transform=\"scale(2)\"><text x=\"1\" y=\"9\" font-size=\"9\">c</text></g><text x=\"2\" y=\"19\" font-size=\"9\" text-anchor=\"end\" transform=\"rotate(-90 2 19)\">b</text></svg>";
        let (rest, texts) = split_texts(svg);
        assert!(rest.contains(">a</text>") && rest.contains(">c</text>"));
        assert!(!rest.contains(">b</text>"));
        assert_eq!(texts.len(), 1);
        assert_eq!((texts[0].x, texts[0].y), (2.0, 19.0));
        assert!(
            texts[0].key.contains(" x=\"0\" y=\"0\"") && texts[0].key.contains("rotate(-90 0 0)")
        );
    }
}
