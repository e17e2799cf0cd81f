//! The physical size of a figure and the resolution of its PNG: `WxH` with a unit suffix
//! (`px` — 1/96 in, the default —, `in`, `cm`, `mm`, `pt` — 1/72 in), e.g. `6x4in`,
//! `16x10cm`, `800x600`.

use crate::error::{IoError, Result};

/// A length unit of a [`PageSize`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Unit {
    /// CSS pixel, 1/96 in.
    #[default]
    Px,
    /// Inch.
    In,
    /// Centimetre.
    Cm,
    /// Millimetre.
    Mm,
    /// Point, 1/72 in.
    Pt,
}

impl Unit {
    /// CSS pixels per unit.
    pub fn px(self) -> f64 {
        match self {
            Unit::Px => 1.0,
            Unit::In => 96.0,
            Unit::Cm => 96.0 / 2.54,
            Unit::Mm => 96.0 / 25.4,
            Unit::Pt => 96.0 / 72.0,
        }
    }

    /// The suffix, as SVG writes it (none for pixels, SVG's user unit).
    pub fn suffix(self) -> &'static str {
        match self {
            Unit::Px => "",
            Unit::In => "in",
            Unit::Cm => "cm",
            Unit::Mm => "mm",
            Unit::Pt => "pt",
        }
    }
}

/// A figure's width and height in a unit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PageSize {
    /// Width, in `unit`.
    pub width: f64,
    /// Height, in `unit`.
    pub height: f64,
    /// The unit.
    pub unit: Unit,
}

impl PageSize {
    /// Width and height in CSS pixels.
    pub fn px(&self) -> (f64, f64) {
        (self.width * self.unit.px(), self.height * self.unit.px())
    }

    /// Width and height in PDF points (1/72 in).
    pub fn points(&self) -> (f64, f64) {
        let (w, h) = self.px();
        (w * 0.75, h * 0.75)
    }
}

impl std::str::FromStr for PageSize {
    type Err = IoError;

    /// `WxH[unit]`: two positive numbers, e.g. `6x4in`, `16x10cm`, `800x600` (pixels).
    fn from_str(text: &str) -> Result<Self> {
        let bad = |reason| IoError::InvalidFigureSize {
            text: text.to_string(),
            reason,
        };
        let t = text.trim().to_ascii_lowercase();
        let units = [
            ("px", Unit::Px),
            ("in", Unit::In),
            ("cm", Unit::Cm),
            ("mm", Unit::Mm),
            ("pt", Unit::Pt),
        ];
        let (body, unit) = units
            .iter()
            .find_map(|&(s, u)| t.strip_suffix(s).map(|b| (b, u)))
            .unwrap_or((t.as_str(), Unit::Px));
        let (w, h) = body.split_once('x').ok_or_else(|| {
            bad("expected WIDTHxHEIGHT with an optional unit px, in, cm, mm or pt, e.g. 6x4in")
        })?;
        let num = |s: &str| {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v > 0.0)
        };
        match (num(w), num(h)) {
            (Some(width), Some(height)) => Ok(Self {
                width,
                height,
                unit,
            }),
            _ => Err(bad("width and height must be positive numbers")),
        }
    }
}

/// How a figure is rendered: its size (its own when `None`) and the resolution of PNG images
/// and animation frames.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    /// The physical size (`None`: the figure's own, in pixels).
    pub size: Option<PageSize>,
    /// PNG pixels per inch (96: one pixel per CSS pixel). SVG and PDF are vector formats and
    /// ignore it.
    pub dpi: f64,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            size: None,
            dpi: 96.0,
        }
    }
}

impl RenderOptions {
    /// The options with a size, a dpi or both, checked: the dpi must lie in [10, 2400].
    pub fn new(size: Option<PageSize>, dpi: Option<f64>) -> Result<Self> {
        let dpi = dpi.unwrap_or(96.0);
        if !(10.0..=2400.0).contains(&dpi) {
            return Err(IoError::InvalidFigureSize {
                text: format!("{dpi} dpi"),
                reason: "the resolution must lie between 10 and 2400 dpi",
            });
        }
        Ok(Self { size, dpi })
    }

    /// Parses a size text and a dpi (either may be absent).
    pub fn parse(size: Option<&str>, dpi: Option<f64>) -> Result<Self> {
        let size = size.map(str::parse::<PageSize>).transpose()?;
        Self::new(size, dpi)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_units_and_bad_ones_are_named() {
        let s: PageSize = "6x4in".parse().unwrap();
        assert_eq!(s.px(), (576.0, 384.0));
        assert_eq!(s.points(), (432.0, 288.0));
        let s: PageSize = "800x600".parse().unwrap();
        assert_eq!((s.unit, s.px()), (Unit::Px, (800.0, 600.0)));
        let s: PageSize = "25.4X10mm".parse().unwrap();
        assert!((s.px().0 - 96.0).abs() < 1e-12);
        for bad in ["6x", "x4", "6-4in", "0x4", "-1x3cm", "nanx3"] {
            let e = bad.parse::<PageSize>().unwrap_err().to_string();
            assert!(e.contains(bad), "{e}");
        }
        assert!(RenderOptions::new(None, Some(0.0)).is_err());
        assert_eq!(RenderOptions::parse(None, None).unwrap().dpi, 96.0);
    }
}
