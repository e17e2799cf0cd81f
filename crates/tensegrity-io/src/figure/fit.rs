//! Text fitted to the room it has: a title, axis label or legend entry measured on the
//! embedded font ([`super::text::width`]) and, when wider than its room, first broken into
//! lines at a space (never inside `$…$` math), then set smaller (down to
//! [`MIN_SCALE`] of its size, ~7.5 pt for a 14 px title), and only then cut with `…`.
//!
//! At each size s = size × {1, 0.9, 0.8, [`MIN_SCALE`]} in turn: the whole text on one line if
//! its width ≤ `room`; else, when two lines are allowed, the split at a space that minimises
//! the wider of the two halves, if that fits. The first size where either fits wins, so a
//! figure at a journal's column width keeps its text at full size where a line break
//! suffices.

use super::text;

/// The smallest a fitted text is set, relative to its size.
pub const MIN_SCALE: f64 = 0.72;

/// A text fitted to a width: its lines (none for an empty text) and the size they are set at.
#[derive(Debug, Clone, PartialEq)]
pub struct Fitted {
    /// The lines, top to bottom.
    pub lines: Vec<String>,
    /// Font size (px).
    pub size: f64,
}

impl Fitted {
    /// The widest line's width (px).
    pub fn width(&self) -> f64 {
        self.lines
            .iter()
            .map(|l| text::width(l, self.size))
            .fold(0.0, f64::max)
    }

    /// The distance between the baselines of two lines (px).
    pub fn line_height(&self) -> f64 {
        1.15 * self.size
    }
}

/// The byte positions of the spaces of `t` outside `$…$` math (a `\$` is not a delimiter).
fn breaks(t: &str) -> Vec<usize> {
    let mut out = Vec::new();
    let mut in_math = false;
    let mut prev = '\0';
    for (i, c) in t.char_indices() {
        if c == '$' && prev != '\\' {
            in_math = !in_math;
        } else if c == ' ' && !in_math {
            out.push(i);
        }
        prev = c;
    }
    out
}

/// `t` fitted to `room` px at `size` px or smaller, on at most `max_lines` (1 or 2) lines.
///
/// ```
/// use tensegrity_io::figure::fit::{fit, MIN_SCALE};
/// let f = fit("axle height against time", 14.0, 1000.0, 2);
/// assert_eq!((f.lines.len(), f.size), (1, 14.0));
/// let f = fit("axle height against time", 14.0, 120.0, 2);
/// assert_eq!(f.lines, ["axle height", "against time"]);
/// let f = fit("axle height against time", 14.0, 30.0, 1);
/// assert!(f.lines[0].ends_with('…') && f.size == 14.0 * MIN_SCALE);
/// ```
pub fn fit(t: &str, size: f64, room: f64, max_lines: usize) -> Fitted {
    fit_at_least(t, size, 0.0, room, max_lines)
}

/// [`fit`], never set smaller than `min` px (nor than `size`): what does not fit at `min` is
/// cut there (a small page keeps its text legible, cut rather than tiny).
///
/// ```
/// use tensegrity_io::figure::fit::fit_at_least;
/// let f = fit_at_least("isometric, across [m]", 9.0, 7.92, 60.0, 1);
/// assert_eq!(f.size, 7.92);
/// assert!(f.lines[0].ends_with('…'));
/// ```
pub fn fit_at_least(t: &str, size: f64, min: f64, room: f64, max_lines: usize) -> Fitted {
    if t.is_empty() {
        return Fitted {
            lines: Vec::new(),
            size,
        };
    }
    let spaces = breaks(t);
    let smallest = (size * MIN_SCALE).max(min.min(size));
    for scale in [1.0, 0.9, 0.8, MIN_SCALE] {
        let s = (size * scale).max(smallest);
        if text::width(t, s) <= room {
            return Fitted {
                lines: vec![t.to_string()],
                size: s,
            };
        }
        if max_lines >= 2 {
            let best = spaces
                .iter()
                .map(|&i| {
                    let (a, b) = (&t[..i], t[i + 1..].trim_start());
                    (text::width(a, s).max(text::width(b, s)), a, b)
                })
                .min_by(|p, q| p.0.total_cmp(&q.0));
            if let Some((w, a, b)) = best {
                if w <= room && !a.is_empty() && !b.is_empty() {
                    return Fitted {
                        lines: vec![a.to_string(), b.to_string()],
                        size: s,
                    };
                }
            }
        }
    }
    Fitted {
        lines: vec![cut(t, &spaces, smallest, room)],
        size: smallest,
    }
}

/// `t` cut with `…` to `room` px at `size`: by characters when it holds no math, else by
/// words (so that no `$` loses its partner); the first word at least.
fn cut(t: &str, spaces: &[usize], size: f64, room: f64) -> String {
    if !t.contains('$') {
        let mut chars: Vec<char> = t.chars().collect();
        while chars.len() > 1 {
            chars.pop();
            let c: String = chars.iter().collect::<String>().trim_end().to_string() + "…";
            if text::width(&c, size) <= room {
                return c;
            }
        }
        return chars.into_iter().collect::<String>() + "…";
    }
    for &i in spaces.iter().rev() {
        let c = format!("{}…", t[..i].trim_end());
        if text::width(&c, size) <= room {
            return c;
        }
    }
    match spaces.first() {
        Some(&i) => format!("{}…", &t[..i]),
        None => t.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_break_outside_math_only() {
        assert_eq!(breaks("a $b c$ d"), vec![1, 7]);
        assert_eq!(breaks(r"cost \$ 5 $x y$"), vec![4, 7, 9]);
        // a title of math and words, too wide for one line, breaks at a word
        let t = "friction $F_f/F_e$ at the tip-over threshold";
        let f = fit(t, 14.0, 0.6 * text::width(t, 14.0), 2);
        assert_eq!(f.lines.len(), 2);
        for l in &f.lines {
            assert_eq!(l.matches('$').count() % 2, 0, "{l}");
            assert!(text::width(l, f.size) <= 0.6 * text::width(t, 14.0));
        }
    }

    #[test]
    fn what_fits_nowhere_is_set_small_and_cut() {
        let t = "isometric, across [m]";
        let room = 0.5 * text::width(t, 12.5);
        let f = fit(t, 12.5, room, 1);
        assert_eq!(f.size, 12.5 * MIN_SCALE);
        assert!(f.lines[0].ends_with('…'));
        assert!(f.width() <= room);
        // smaller first: 0.8 of the size is enough here, no cut
        let f = fit(t, 12.5, 0.85 * text::width(t, 12.5), 1);
        assert_eq!((f.size, f.lines[0].as_str()), (10.0, t));
        // math is cut by words, its dollars kept in pairs
        let f = fit("the $ι_2$ axis of the wheel", 12.0, 40.0, 1);
        assert_eq!(f.lines[0].matches('$').count() % 2, 0);
    }
}
