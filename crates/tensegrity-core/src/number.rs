//! Numbers in messages: [`short_number`] writes a value as a person reads it (shared by the
//! errors and the parameter checks, so both spell a value alike).

/// A number as a person reads it: plain decimals for ordinary magnitudes, scientific
/// notation for tiny or huge ones (`1e-300`, not three hundred zeros).
///
/// ```
/// use tensegrity_core::number::short_number;
/// assert_eq!(short_number(-5.0), "-5");
/// assert_eq!(short_number(1.5), "1.5");
/// assert_eq!(short_number(1e-300), "1e-300");
/// assert_eq!(short_number(f64::NAN), "NaN");
/// ```
pub fn short_number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e15).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}
