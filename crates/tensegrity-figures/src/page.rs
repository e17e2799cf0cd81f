//! The render options of a run of thesis figures checked before any figure is computed
//! ([`check_options`]): a size given for every figure must fit each chosen figure's panels
//! (the rule of [`Figure::page_px`]: each panel at least 72 × 72 px, the figure at most
//! 20000 px a side), and a PNG at that size and resolution at most
//! [`render::MAX_PIXELS`]. Each figure's panels side by side are [`panels`] (a table checked
//! against every figure built, in this crate's tests).

use crate::catalog::FigureSpec;
use crate::error::Result;
use tensegrity_core::request::InvalidParameter;
use tensegrity_io::figure::{render, Figure, Panel, RenderOptions, MIN_PANEL_PX};
use tensegrity_io::IoError;

/// Panels side by side in the thesis figure numbered `number` (1 unless listed).
pub fn panels(number: &str) -> usize {
    match number {
        "3.3" | "3.8" | "3.9" => 3,
        "3.1" | "3.2" | "4.6" | "4.8" | "4.11" | "4.13" | "4.19" | "4.20" | "5.1" | "5.3" => 2,
        _ => 1,
    }
}

/// Checks `options` against every figure of `chosen` before any is computed (module docs):
/// a size that one of them cannot take is refused as `size` (`dpi` for a PNG of too many
/// pixels), naming the figure and its panels.
///
/// ```
/// use tensegrity_figures::page::check_options;
/// use tensegrity_figures::FIGURES;
/// use tensegrity_io::figure::RenderOptions;
/// let all: Vec<_> = FIGURES.iter().collect();
/// let tiny = RenderOptions::parse(Some("1x1"), None).unwrap();
/// let e = check_options(&all, &tiny, false).unwrap_err();
/// assert!(e.to_string().starts_with("size = \"1x1\""), "{e}");
/// // 200 px is wide enough for one panel, not for Fig. 3.3's three
/// let narrow = RenderOptions::parse(Some("200x300"), None).unwrap();
/// let one: Vec<_> = FIGURES.iter().filter(|f| f.number == "2.2").collect();
/// assert!(check_options(&one, &narrow, false).is_ok());
/// let e = check_options(&all, &narrow, false).unwrap_err();
/// assert!(e.to_string().contains("Fig. 3.3"), "{e}");
/// assert!(e.to_string().ends_with("the smallest size it is drawn at is 216x300"), "{e}");
/// let huge = RenderOptions::parse(Some("10000x10000"), Some(2400.0)).unwrap();
/// assert!(check_options(&one, &huge, false).is_ok());
/// assert!(check_options(&one, &huge, true).is_err());
/// ```
pub fn check_options(chosen: &[&FigureSpec], options: &RenderOptions, png: bool) -> Result<()> {
    let Some(size) = options.size else {
        return Ok(());
    };
    let text = format!("{}x{}{}", size.width, size.height, size.unit.suffix());
    for f in chosen {
        let n = panels(f.number);
        let probe = Figure::new(vec![Panel::new("", "", ""); n]);
        if let Err(e) = probe.page_px(options) {
            let rule = match e {
                IoError::InvalidFigure { reason } => reason.to_string(),
                e => e.to_string(),
            };
            let mut reason = format!("{rule} (Fig. {} has {n} panel(s) side by side)", f.number);
            let (w, h) = size.px();
            let (min_w, min_h) = (MIN_PANEL_PX * n as f64, MIN_PANEL_PX);
            if w < min_w || h < min_h {
                // the smallest size that takes it, in the unit given, rounded up
                let up = |v: f64| (v / size.unit.px() * 100.0).ceil() / 100.0;
                let (sw, sh) = (up(w.max(min_w)), up(h.max(min_h)));
                let unit = size.unit.suffix();
                reason = format!("{reason}: the smallest size it is drawn at is {sw}x{sh}{unit}");
            }
            return Err(InvalidParameter::text("size", &text, reason).into());
        }
    }
    let (w, h) = size.px();
    let scale = options.dpi / 96.0;
    let pixels = (w * scale).round() * (h * scale).round();
    if png && pixels > render::MAX_PIXELS {
        let reason = format!(
            "a PNG of {text} at {} dpi has {pixels:.3e} pixels, more than {:.0e}: lower the size or the dpi",
            options.dpi,
            render::MAX_PIXELS
        );
        return Err(InvalidParameter::new("dpi", options.dpi, reason).into());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Context, FIGURES};

    /// The table of panels is what every figure draws (quick: the same panels, coarser data).
    #[test]
    fn the_panel_table_is_each_figures_own() {
        let dir = std::env::temp_dir().join(format!("tensegrity-page-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let ctx = Context::new(true, dir.clone());
        for f in &FIGURES {
            let drawn = f.build(&ctx).unwrap();
            assert_eq!(
                drawn.figure.panels.len(),
                panels(f.number),
                "Fig. {}",
                f.number
            );
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
