//! Text of figures: the small markup of labels (`_x`, `_{xy}` subscripts, `^x`, `^{xy}`
//! superscripts, digits after a Greek letter subscripted) and text widths measured on the
//! embedded font's advances, which the layout needs to place labels and legends.

use std::sync::OnceLock;

/// Where a run of text sits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shift {
    /// On the baseline.
    Normal,
    /// Lowered, smaller.
    Sub,
    /// Raised, smaller.
    Sup,
}

/// The size of sub- and superscripts relative to the text.
pub const SCRIPT_SCALE: f64 = 0.72;

fn is_greek(c: char) -> bool {
    ('\u{391}'..='\u{3c9}').contains(&c)
}

/// Unicode subscript of an ASCII digit.
fn subscript_digit(c: char) -> char {
    char::from_u32(0x2080 + (c as u32 - '0' as u32)).unwrap_or(c)
}

/// Unicode superscript of an ASCII digit or sign.
pub fn superscript(c: char) -> char {
    match c {
        '1' => '¹',
        '2' => '²',
        '3' => '³',
        '0' | '4'..='9' => char::from_u32(0x2070 + (c as u32 - '0' as u32)).unwrap_or(c),
        '-' | '−' => '⁻',
        '+' => '⁺',
        _ => c,
    }
}

/// The runs of `text` after the markup: (text, shift), empty runs left out.
pub fn runs(text: &str) -> Vec<(String, Shift)> {
    let chars: Vec<char> = text.chars().collect();
    let mut out: Vec<(String, Shift)> = Vec::new();
    let mut push = |s: String, shift: Shift| {
        if s.is_empty() {
            return;
        }
        match out.last_mut() {
            Some((last, sh)) if *sh == shift => last.push_str(&s),
            _ => out.push((s, shift)),
        }
    };
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        let script = match c {
            '_' => Some(Shift::Sub),
            '^' => Some(Shift::Sup),
            _ => None,
        };
        let prev_ok = i > 0 && !chars[i - 1].is_whitespace();
        if let (Some(shift), true) = (script, prev_ok) {
            if chars.get(i + 1) == Some(&'{') {
                if let Some(len) = chars[i + 2..].iter().position(|&c| c == '}') {
                    push(chars[i + 2..i + 2 + len].iter().collect(), shift);
                    i += len + 3;
                    continue;
                }
            } else if let Some(&n) = chars.get(i + 1) {
                if n.is_alphanumeric() || n == '-' || n == '−' {
                    // a signed exponent keeps its digits: 10^-3
                    let mut end = i + 2;
                    if !n.is_alphanumeric() || n.is_ascii_digit() {
                        while end < chars.len() && chars[end].is_ascii_digit() {
                            end += 1;
                        }
                    }
                    push(chars[i + 1..end].iter().collect(), shift);
                    i = end;
                    continue;
                }
            }
        }
        if c.is_ascii_digit() && i > 0 && is_greek(chars[i - 1]) {
            let mut s = String::new();
            while i < chars.len() && chars[i].is_ascii_digit() {
                s.push(subscript_digit(chars[i]));
                i += 1;
            }
            push(s, Shift::Normal);
            continue;
        }
        push(c.to_string(), Shift::Normal);
        i += 1;
    }
    out
}

/// The plain text of `text` after the markup (scripts inline).
#[cfg(test)]
pub fn plain(text: &str) -> String {
    runs(text).into_iter().map(|(s, _)| s).collect()
}

/// Advance widths of the embedded font, in ems, by character (`None`: not in the font).
fn advance(c: char) -> f64 {
    static FACE: OnceLock<Option<(ttf_parser::Face<'static>, f64)>> = OnceLock::new();
    let face = FACE.get_or_init(|| {
        ttf_parser::Face::parse(super::FONT, 0).ok().map(|f| {
            let em = f.units_per_em() as f64;
            (f, em)
        })
    });
    face.as_ref()
        .and_then(|(f, em)| {
            f.glyph_index(c)
                .and_then(|g| f.glyph_hor_advance(g))
                .map(|a| a as f64 / em)
        })
        .unwrap_or(0.6)
}

/// The width of `text` (after the markup) at font size `size` (pixels).
pub fn width(text: &str, size: f64) -> f64 {
    runs(text)
        .iter()
        .map(|(s, shift)| {
            let scale = if *shift == Shift::Normal {
                1.0
            } else {
                SCRIPT_SCALE
            };
            s.chars().map(advance).sum::<f64>() * size * scale
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_makes_scripts_and_greek_subscripts() {
        assert_eq!(
            runs("F_f/F_e"),
            vec![
                ("F".into(), Shift::Normal),
                ("f".into(), Shift::Sub),
                ("/F".into(), Shift::Normal),
                ("e".into(), Shift::Sub)
            ]
        );
        assert_eq!(plain("ι2 [m]"), "ι₂ [m]");
        assert_eq!(plain("λ1010"), "λ₁₀₁₀");
        assert_eq!(runs("r_{k+1}")[1], ("k+1".into(), Shift::Sub));
        assert_eq!(runs("10^-3")[1], ("-3".into(), Shift::Sup));
        // a lone underscore or one after a space stays
        assert_eq!(plain("a _ b"), "a _ b");
        assert_eq!(plain("_x"), "_x");
        assert!(width("mmm", 10.0) > width("iii", 10.0));
        assert!((width("ab", 10.0) - width("a", 10.0) - width("b", 10.0)).abs() < 1e-12);
    }
}
