//! The precision of a structure's data: how far its node coordinates may lie from the
//! values they stand for, judged from the digits they are written with.
//!
//! A coordinate x read from a file is the decimal its writer printed. Its *significant
//! digits* d(x) are the fewest (1 to 17) whose shortest decimal reads back as exactly x. A
//! structure whose coordinates need all 17 digits (or 16: the shortest round trip of most
//! computed values) was written at full precision: its data are exact to rounding in the
//! last bit. Whole numbers are exact as written and are left out of the judgement; d_max is
//! the longest count among the other values. With d_max below five the values were typed by
//! hand (`0.5`, `1.25`, `0.866`): taken as meant, exact. With 5 ≤ d_max < 16, and at least
//! two (and a quarter) of the non-whole values at d_max digits, a writer rounded them to
//! d_max digits (it prints most computed values to that count, beside short values a user
//! gave), and each coordinate may be off by half a unit in its d_max-th digit:
//!
//! > e = max_x ½ · 10^(⌊log₁₀|x|⌋ − d_max + 1)   (m)
//!
//! The statics turn e into a bound on the singular values of the equilibrium matrix that
//! rounding alone can create (`tensegrity_statics::rank`).
//!
//! ```
//! use tensegrity_core::precision::{coordinate_rounding, significant_digits};
//! assert_eq!(significant_digits(0.5), 1);
//! assert_eq!(significant_digits(-0.230392157), 9);
//! assert_eq!(significant_digits(0.1 + 0.2), 17);
//! // written to 9 digits: each coordinate may be off by half a unit in its ninth digit,
//! // the largest (2.5 → 2.50000000) by 5e-9
//! let e = coordinate_rounding([0.230392157, -0.534313725, 1.0, -2.5]);
//! assert!((e - 0.5e-8).abs() < 1e-22);
//! // computed values at full precision, or values typed by hand: exact data
//! assert_eq!(coordinate_rounding([0.1 + 0.2, 1.0 / 3.0]), 0.0);
//! assert_eq!(coordinate_rounding([0.5, 10.0, 0.866]), 0.0);
//! ```

/// From this many significant digits on, data are taken as written at full precision.
pub const FULL_PRECISION_DIGITS: u32 = 16;

/// Below this many significant digits, data are taken as typed by hand: exact as meant.
pub const MIN_ROUNDED_DIGITS: u32 = 5;

/// The fewest significant decimal digits (1 to 17) whose shortest decimal reads back as
/// exactly `x`; 0 for 0 and non-finite values.
pub fn significant_digits(x: f64) -> u32 {
    if x == 0.0 || !x.is_finite() {
        return 0;
    }
    let reads_back = |d: u32| {
        let text = format!("{:.*e}", (d - 1) as usize, x);
        text.parse::<f64>() == Ok(x)
    };
    // the shortest decimal that reads back (`{:e}` writes it) has d₀ digits; the value
    // correctly rounded to d₀ digits reads back as well but for a tie at the edge of x's
    // rounding interval, so d₀ is checked, and the search goes on above it should it fail
    // (one formatting instead of up to 17: the rank decision judges every coordinate)
    let shortest = format!("{x:e}");
    let mantissa = shortest.split('e').next().unwrap_or("");
    let d0 = mantissa
        .bytes()
        .filter(u8::is_ascii_digit)
        .count()
        .clamp(1, 17) as u32;
    (d0..=17).find(|&d| reads_back(d)).unwrap_or(17)
}

/// The rounding e (same unit as the values) of values written to a common number of
/// significant digits (module docs); 0 when they are written at full precision
/// ([`FULL_PRECISION_DIGITS`] or more), typed by hand (fewer than [`MIN_ROUNDED_DIGITS`]),
/// or show no sign of a writer's rounding: fewer than two, or fewer than a quarter, of the
/// values that are not whole numbers carry the longest count of digits d_max (a writer that
/// rounds gives most computed values d_max digits, beside the short values a user gave, such
/// as a boundary at ±0.75; whole numbers are left out, they are exact as written — a chain at
/// x = 0, 1, …, 17999 is not "rounded to five digits").
pub fn coordinate_rounding(values: impl IntoIterator<Item = f64> + Clone) -> f64 {
    let fractional: Vec<u32> = values
        .clone()
        .into_iter()
        .filter(|x| x.is_finite() && x.fract() != 0.0)
        .map(significant_digits)
        .collect();
    let d_max = fractional.iter().copied().max().unwrap_or(0);
    let at_max = fractional.iter().filter(|&&d| d == d_max).count();
    let rounded = (MIN_ROUNDED_DIGITS..FULL_PRECISION_DIGITS).contains(&d_max)
        && at_max >= 2
        && 4 * at_max >= fractional.len();
    if !rounded {
        return 0.0;
    }
    values
        .into_iter()
        .filter(|x| *x != 0.0 && x.is_finite())
        .map(|x| 0.5 * 10f64.powi(x.abs().log10().floor() as i32 - d_max as i32 + 1))
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_rounded_to_d_digits_has_d_digits() {
        let x = std::f64::consts::PI;
        for d in 1..=15 {
            let rounded: f64 = format!("{:.*e}", d - 1, x).parse().unwrap();
            // trailing zeros make the count smaller, never larger
            assert!(significant_digits(rounded) <= d as u32, "{d}: {rounded}");
        }
        assert_eq!(significant_digits(1.23456789), 9);
        assert_eq!(significant_digits(x), 16);
        assert_eq!(significant_digits(f64::NAN), 0);
    }

    /// The count from the shortest decimal equals the definition's search from one digit up
    /// (the fewest digits whose correctly rounded decimal reads back), on values rounded to
    /// every digit count, at every scale, at powers of two (whose rounding interval is
    /// lopsided) and on bit patterns spread over the doubles.
    #[test]
    fn the_count_from_the_shortest_decimal_equals_the_search_from_one_digit() {
        let search = |x: f64| {
            (1..=17u32)
                .find(|&d| format!("{:.*e}", (d - 1) as usize, x).parse::<f64>() == Ok(x))
                .unwrap_or(17)
        };
        let mut values = vec![0.1, 0.5, 1.0 / 3.0, 2.0f64.sqrt(), 9.5, 1e-300, 1.7e308];
        for k in -60..60 {
            values.push(2f64.powi(k));
            values.push(-(2f64.powi(k)) * 0.7);
        }
        for d in 0..17 {
            for base in [std::f64::consts::PI, std::f64::consts::E, 0.123456789012345] {
                for scale in [1e-9, 1e-3, 1.0, 1e4, 1e12] {
                    values.push(format!("{:.*e}", d, base * scale).parse().unwrap());
                }
            }
        }
        // a multiplicative hash walks over bit patterns of finite doubles
        let mut bits: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..2000 {
            bits = bits.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
            let x = f64::from_bits(bits >> 2 | 0x3000_0000_0000_0000);
            values.push(x);
        }
        for x in values {
            if x != 0.0 && x.is_finite() {
                assert_eq!(significant_digits(x), search(x), "{x:e}");
            }
        }
    }

    #[test]
    fn the_rounding_is_half_a_unit_of_the_last_digit_of_the_largest_value() {
        // 5 digits: 123.45 may be off by 0.005, 0.0012345 by 5e-8: the largest counts
        let e = coordinate_rounding([123.45, 0.0012345, 0.0]);
        assert!((e - 0.005).abs() < 1e-15, "{e}");
        // every true value lies within e of its rounding
        let exact = [1.0 / 3.0, 2.0f64.sqrt(), -7.0 / 11.0];
        let rounded: Vec<f64> = exact
            .iter()
            .map(|x| format!("{x:.8e}").parse().unwrap())
            .collect();
        let e = coordinate_rounding(rounded.iter().copied());
        for (x, r) in exact.iter().zip(&rounded) {
            assert!((x - r).abs() <= e, "{x} {r} {e}");
        }
        assert_eq!(coordinate_rounding(std::iter::empty::<f64>()), 0.0);
    }

    #[test]
    fn whole_numbers_and_a_few_long_values_are_no_rounding() {
        // a chain at x = 0 … 17999 with y = 0.5: five-digit whole numbers are exact
        let chain: Vec<f64> = (0..18000)
            .flat_map(|i| [i as f64, 0.5 * (i % 2) as f64])
            .collect();
        assert_eq!(coordinate_rounding(chain.iter().copied()), 0.0);
        // one long value among hand-typed ones is no writer's rounding
        assert_eq!(coordinate_rounding([0.5, 0.25, 1.5, 0.75, 0.123456]), 0.0);
        // a grid's whole x, y and a boundary at ±0.75 beside z rounded to nine digits
        let net = [
            1.0,
            2.0,
            -0.230392157,
            3.0,
            1.0,
            -0.534313725,
            0.0,
            2.0,
            -0.0490196078,
            0.75,
            -0.75,
            0.75,
            -0.75,
            0.75,
        ];
        assert!((coordinate_rounding(net) - 5e-9).abs() < 1e-20);
    }
}
