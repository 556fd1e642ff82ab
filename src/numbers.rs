//! Numbers in messages, written without the standard library's float formatting.
//!
//! Writing an `f64` with `{}`, `{:?}` or `{:.1}` compiles the standard library's float
//! formatting (Grisu and Dragon4 with their tables, about 20 KB of WebAssembly) into the
//! planner's module. [`Shortest`] writes the shortest text that reads back to the number with
//! the formatter the JSON output already uses (zmij, through serde_json); [`Decimals`] rounds
//! to a number of decimals and writes the integer and its fraction with the integer formatting
//! the module already holds; [`Position`] writes a point as `[x, y]`.
//!
//! ```
//! use furrow::numbers::{Decimals, Position, Shortest};
//!
//! assert_eq!(Decimals(12.345, 1).to_string(), "12.3");
//! assert_eq!(Decimals(-0.05, 1).to_string(), "-0.1");
//! assert_eq!(Shortest(6.0).to_string(), "6");
//! assert_eq!(Shortest(0.25).to_string(), "0.25");
//! assert_eq!(Position([24.05, 60.5]).to_string(), "[24.05, 60.5]");
//! ```

use std::fmt;

/// A number rounded half away from zero to `.1` decimals (at most 9), as `{:.N}` writes it up
/// to 10¹⁵; larger ones are written as integers, non-finite ones as `NaN`, `inf` and `-inf`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Decimals(pub f64, pub u8);

/// Beyond this magnitude a number is written without a fraction (its scaled value would lose
/// integer precision).
const LARGEST_WITH_FRACTION: f64 = 1e15;

impl fmt::Display for Decimals {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let Decimals(x, decimals) = *self;
        if !x.is_finite() {
            return Shortest(x).fmt(f);
        }
        let decimals = decimals.min(9);
        let scale = 10u64.pow(u32::from(decimals));
        let magnitude = x.abs();
        if magnitude >= LARGEST_WITH_FRACTION {
            let sign = if x < 0.0 { "-" } else { "" };
            return write!(f, "{sign}{}", magnitude.round() as u64);
        }
        let scaled = (magnitude * scale as f64).round() as u64;
        let sign = if x < 0.0 && scaled != 0 { "-" } else { "" };
        let (whole, fraction) = (scaled / scale, scaled % scale);
        if decimals == 0 {
            write!(f, "{sign}{whole}")
        } else {
            let width = usize::from(decimals);
            write!(f, "{sign}{whole}.{fraction:0width$}")
        }
    }
}

/// A number as the shortest text that reads back to it: `6`, `0.25`, `1e-9`; `NaN`, `inf` and
/// `-inf` when not finite.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shortest(pub f64);

impl fmt::Display for Shortest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x.is_nan() {
            return f.write_str("NaN");
        }
        if x.is_infinite() {
            return f.write_str(if x > 0.0 { "inf" } else { "-inf" });
        }
        if x == x.trunc() && x.abs() < LARGEST_WITH_FRACTION {
            // As the standard formatting writes integers: `123456789`, not `1.23456789e8`.
            let sign = if x.is_sign_negative() && x != 0.0 {
                "-"
            } else {
                ""
            };
            return write!(f, "{sign}{}", x.abs() as u64);
        }
        let mut buffer = zmij::Buffer::new();
        let text = buffer.format_finite(x);
        f.write_str(text)
    }
}

/// A point as `[x, y]`, each coordinate by [`Shortest`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Position(pub [f64; 2]);

impl fmt::Display for Position {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [x, y] = self.0;
        write!(f, "[{}, {}]", Shortest(x), Shortest(y))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn decimals_write_as_the_standard_formatting_does() {
        for (x, n, text) in [
            (0.0, 1, "0.0"),
            (-0.0, 1, "0.0"),
            (-0.04, 1, "0.0"),
            (1.25, 0, "1"),
            (2.5, 0, "3"),
            (1234.5678, 2, "1234.57"),
            (-7.0, 3, "-7.000"),
            (0.001, 3, "0.001"),
            (1e16, 2, "10000000000000000"),
            (f64::NAN, 1, "NaN"),
            (f64::NEG_INFINITY, 1, "-inf"),
        ] {
            assert_eq!(Decimals(x, n).to_string(), text, "{x:e} to {n}");
        }
    }

    #[test]
    fn shortest_writes_integers_without_a_fraction() {
        for (x, text) in [
            (6.0, "6"),
            (0.25, "0.25"),
            (-3.5, "-3.5"),
            (100.0, "100"),
            (123456789012.0, "123456789012"),
            (-0.0, "0"),
            (0.1 + 0.2, "0.30000000000000004"),
            (f64::INFINITY, "inf"),
        ] {
            assert_eq!(Shortest(x).to_string(), text);
        }
    }

    proptest! {
        /// The text reads back to the number rounded to its decimals, and to within a unit of
        /// the last decimal of what the standard formatting writes (which may round a tie the
        /// other way).
        #[test]
        fn decimals_read_back_within_half_a_unit(x in -1e9f64..1e9, n in 0u8..7) {
            let text = Decimals(x, n).to_string();
            let back: f64 = text.parse().unwrap();
            let unit = 10f64.powi(-i32::from(n));
            prop_assert!((back - x).abs() <= unit / 2.0 + x.abs() * 1e-15, "{x} as {text}");
            let standard = format!("{x:.*}", usize::from(n));
            let theirs: f64 = standard.parse().unwrap();
            prop_assert!(
                (back - theirs).abs() <= unit * 1.001 + x.abs() * 4e-16,
                "{text} against {standard}"
            );
        }

        /// The shortest text reads back to the very number.
        #[test]
        fn shortest_reads_back_exactly(x in proptest::num::f64::NORMAL | proptest::num::f64::ZERO) {
            let text = Shortest(x).to_string();
            prop_assert_eq!(text.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{}", text);
        }
    }
}
