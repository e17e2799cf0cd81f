//! The resource limits a front end checks the estimates ([`crate::estimate`]) against, the
//! same for every front end: the default limits of this process ([`for_this_process`]: the
//! memory limit is min(8 GiB, 3/4 of the memory the process may use), the work and output
//! limits [`budget::DEFAULT_MAX_WORK_S`] and [`budget::DEFAULT_MAX_OUTPUT_BYTES`]), sizes as
//! people write them ([`parse_size`]: `500M`, `16Gi`), a size that admits a refused estimate
//! ([`suggest_size`]).

use tensegrity_core::budget::{self, Limits};

/// The default limits of this process: [`available_memory`] · 3/4, at most
/// [`budget::DEFAULT_MAX_MEMORY_BYTES`]; the default work and output limits.
pub fn for_this_process() -> Limits {
    Limits {
        memory_bytes: (0.75 * available_memory()).min(budget::DEFAULT_MAX_MEMORY_BYTES),
        ..Limits::default()
    }
}

/// The memory this process may use (bytes): the smallest of the cgroup limit (less its
/// usage), the address-space limit and the available memory (Linux; infinite elsewhere).
pub fn available_memory() -> f64 {
    let read = |p: &str| std::fs::read_to_string(p).ok();
    let number = |t: Option<String>| t.and_then(|t| t.trim().parse::<f64>().ok());
    let field = |file: &str, key: &str, at: usize| {
        let text = read(file)?;
        let line = text.lines().find(|l| l.starts_with(key))?;
        line.split_whitespace().nth(at)?.parse::<f64>().ok()
    };
    let mut avail = f64::INFINITY;
    if let Some(kb) = field("/proc/meminfo", "MemAvailable:", 1) {
        avail = avail.min(kb * 1024.0);
    }
    if let Some(max) = number(read("/sys/fs/cgroup/memory.max")) {
        let used = number(read("/sys/fs/cgroup/memory.current")).unwrap_or(0.0);
        avail = avail.min((max - used).max(0.0));
    }
    if let Some(v) = field("/proc/self/limits", "Max address space", 3) {
        avail = avail.min(v);
    }
    avail
}

/// A size that [`parse_size`] cannot read (the text as written).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("invalid size \"{text}\": use e.g. 500M, 16G, 2T")]
pub struct SizeError {
    /// The text given.
    pub text: String,
}

/// Parses a size (bytes): a number with an optional unit K, M, G, T (powers of 1000, or Ki,
/// Mi, Gi, Ti for powers of 1024; a trailing B is allowed).
///
/// ```
/// use tensegrity_engine::limits::parse_size;
/// assert_eq!(parse_size("16Gi"), Ok(16.0 * 1024f64.powi(3)));
/// assert_eq!(parse_size("500M"), Ok(5e8));
/// assert_eq!(parse_size("lots").unwrap_err().text, "lots");
/// ```
pub fn parse_size(s: &str) -> Result<f64, SizeError> {
    let t = s.trim().trim_end_matches(['B', 'b']);
    let at = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let units = ["", "K", "M", "G", "T"];
    let (unit, binary) = match t[at..].to_ascii_uppercase() {
        u if u.ends_with('I') => (u[..u.len() - 1].to_string(), true),
        u => (u, false),
    };
    let power = units
        .iter()
        .position(|u| *u == unit)
        .filter(|&p| p > 0 || !binary);
    match (power, t[..at].trim().parse::<f64>()) {
        (Some(p), Ok(v)) if v.is_finite() && v > 0.0 => {
            Ok(v * if binary { 1024f64 } else { 1000f64 }.powi(p as i32))
        }
        _ => Err(SizeError {
            text: s.to_string(),
        }),
    }
}

/// A size a little (10 %) above `bytes`, in the binary unit that fits (`12Gi`, `3Ti`): a
/// limit that admits an estimate of `bytes`.
pub fn suggest_size(bytes: f64) -> String {
    let (scale, unit) = [(4, "Ti"), (3, "Gi"), (2, "Mi")]
        .into_iter()
        .map(|(power, unit)| (1024f64.powi(power), unit))
        .find(|&(scale, _)| bytes >= scale)
        .unwrap_or((1024.0, "Ki"));
    let v = (bytes / scale * 1.1).ceil();
    if v.is_finite() && v < 1e15 {
        format!("{v:.0}{unit}")
    } else {
        "<more than is available>".into()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_with_decimal_and_binary_units() {
        assert_eq!(parse_size("500M").unwrap(), 5e8);
        assert_eq!(parse_size("16G").unwrap(), 16e9);
        assert_eq!(parse_size("2GiB").unwrap(), 2.0 * 1024f64.powi(3));
        assert_eq!(parse_size("1Ki").unwrap(), 1024.0);
        assert_eq!(parse_size("1234").unwrap(), 1234.0);
        for bad in ["-1G", "12Q", "G", "1i", "Ki"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_suggested_size_admits_the_estimate() {
        // 6.208e13 B = 56.46 TiB, +10 %: 63Ti
        assert_eq!(suggest_size(6.208e13), "63Ti");
        assert_eq!(suggest_size(1.5e9), "2Gi");
        assert!(parse_size(&suggest_size(3.3e10)).unwrap() > 3.3e10);
    }

    #[test]
    fn the_process_limits_are_the_defaults_at_most() {
        let l = for_this_process();
        assert!(l.memory_bytes >= 0.0 && l.memory_bytes <= budget::DEFAULT_MAX_MEMORY_BYTES);
        assert_eq!(l.work_s, budget::DEFAULT_MAX_WORK_S);
        assert_eq!(l.output_bytes, budget::DEFAULT_MAX_OUTPUT_BYTES);
    }
}
