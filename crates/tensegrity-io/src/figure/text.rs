//! Text of figures: plain text with math marked by dollars, and text widths measured on the
//! embedded font's advances, which the layout needs to place labels and legends.
//!
//! The rule: text is drawn as written, `_` and `^` included (a column `mean_speed`, a file
//! `prism_drop.toml`), except between a pair of `$`: there `_x` or `_{xy}` is a subscript,
//! `^x` or `^{xy}` a superscript, and digits right after a Greek letter are subscripts
//! (`$F_f/F_e$`, `$λ1010$` → λ₁₀₁₀). The dollars are not drawn; `\$` is a dollar sign, and a
//! `$` with no partner is drawn as it is. Text from a user or a file goes through
//! [`literal`], so that even its dollars stay text.

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

/// `text` as plain text whatever it holds: its dollars escaped, so [`runs`] finds no math in
/// it (for text from a user or a file: column names, file names, titles given on the command
/// line).
pub fn literal(text: &str) -> String {
    text.replace('$', "\\$")
}

/// The segments of `text`: (text, is math), the dollars of the math taken off and `\$`
/// made `$`.
fn segments(text: &str) -> Vec<(Vec<char>, bool)> {
    let chars: Vec<char> = text.chars().collect();
    // the positions of the unescaped dollars
    let mut dollars = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        match chars[i] {
            '\\' if chars.get(i + 1) == Some(&'$') => i += 2,
            '$' => {
                dollars.push(i);
                i += 1
            }
            _ => i += 1,
        }
    }
    // pairs open and close math; a last dollar with no partner is text
    let pairs: Vec<(usize, usize)> = dollars.chunks_exact(2).map(|p| (p[0], p[1])).collect();
    let unescape = |s: &[char]| -> Vec<char> {
        let mut out = Vec::with_capacity(s.len());
        let mut k = 0;
        while k < s.len() {
            if s[k] == '\\' && s.get(k + 1) == Some(&'$') {
                k += 1;
            }
            out.push(s[k]);
            k += 1;
        }
        out
    };
    let mut out = Vec::new();
    let mut at = 0;
    for (open, close) in pairs {
        out.push((unescape(&chars[at..open]), false));
        out.push((chars[open + 1..close].to_vec(), true));
        at = close + 1;
    }
    out.push((unescape(&chars[at..]), false));
    out.retain(|(s, _)| !s.is_empty());
    out
}

/// The runs of `text` after the markup (math between `$` pairs only, see the module's rule):
/// (text, shift), empty runs left out.
pub fn runs(text: &str) -> Vec<(String, Shift)> {
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
    for (chars, math) in segments(text) {
        if math {
            math_runs(&chars, &mut push);
        } else {
            push(chars.into_iter().collect(), Shift::Normal);
        }
    }
    out
}

/// The runs of one piece of math, handed to `push`.
fn math_runs(chars: &[char], push: &mut impl FnMut(String, Shift)) {
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
}

/// The text of `text` after the markup, scripts inline (e.g. for a CSV or a caption).
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
            runs("$F_f/F_e$"),
            vec![
                ("F".into(), Shift::Normal),
                ("f".into(), Shift::Sub),
                ("/F".into(), Shift::Normal),
                ("e".into(), Shift::Sub)
            ]
        );
        assert_eq!(plain("$ι2$ [m]"), "ι₂ [m]");
        assert_eq!(plain("$λ1010$"), "λ₁₀₁₀");
        assert_eq!(runs("$r_{k+1}$")[1], ("k+1".into(), Shift::Sub));
        assert_eq!(runs("$10^-3$")[1], ("-3".into(), Shift::Sup));
        // a lone underscore or one after a space stays
        assert_eq!(plain("$a _ b$"), "a _ b");
        assert_eq!(plain("$_x$"), "_x");
        assert!(width("mmm", 10.0) > width("iii", 10.0));
        assert!(width("$F_f$", 10.0) < width("F_f", 10.0));
        assert!((width("ab", 10.0) - width("a", 10.0) - width("b", 10.0)).abs() < 1e-12);
    }

    #[test]
    fn text_outside_dollars_is_plain() {
        for t in ["mean_speed", "prism_drop.toml", "x^2", "σ1", "a_{b}"] {
            assert_eq!(runs(t), vec![(t.to_string(), Shift::Normal)], "{t}");
        }
        // math inside a pair of dollars, text around it
        assert_eq!(
            runs("speed of $v_x$ [m/s]"),
            vec![
                ("speed of v".into(), Shift::Normal),
                ("x".into(), Shift::Sub),
                (" [m/s]".into(), Shift::Normal)
            ]
        );
        // an odd dollar is text; an escaped one too
        assert_eq!(plain("cost $_x"), "cost $_x");
        assert_eq!(plain("$a_b$ and $ left"), "ab and $ left");
        assert_eq!(plain(r"\$a_b\$"), "$a_b$");
        // literal keeps any text as written
        for t in ["$q_{ij}$", "a$b$c_d", r"x\$y", "$"] {
            assert_eq!(plain(&literal(t)), t, "{t}");
        }
    }
}
