//! Rounding to the nearest integer, half away from zero: [`f64::round`] without the library
//! call it is in WebAssembly (which has only round-half-to-even among its instructions). The
//! output rounds every coordinate it writes.

/// `x` rounded to the nearest integer, half away from zero: the same number as
/// [`f64::round`] for every input (NaN and infinities included), by a truncation.
///
/// ```
/// use furrow::geometry::round_half_away;
///
/// for x in [2.5, -2.5, 0.49999999999999994, 1.5, -0.2, 4503599627370497.0] {
///     assert_eq!(round_half_away(x).to_bits(), x.round().to_bits());
/// }
/// ```
#[inline]
pub fn round_half_away(x: f64) -> f64 {
    let t = x.trunc();
    // Below 2^52 the fraction `x - t` is exact; above it `x` is an integer and the fraction 0.
    if (x - t).abs() >= 0.5 {
        t + x.signum()
    } else {
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn special_values_round_as_the_library_rounds() {
        for x in [
            0.0,
            -0.0,
            0.5,
            -0.5,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            f64::MIN_POSITIVE,
            -1e-300,
            4503599627370495.5,
        ] {
            assert_eq!(round_half_away(x).to_bits(), x.round().to_bits(), "{x}");
        }
        assert!(round_half_away(f64::NAN).is_nan());
    }

    proptest! {
        #![proptest_config(crate::seeded::config(4096))]
        #[test]
        fn the_same_as_round(bits in any::<u64>(), scaled in -1e12..1e12f64) {
            for x in [f64::from_bits(bits), scaled, scaled.trunc() + 0.5, scaled.trunc() - 0.5] {
                if !x.is_nan() {
                    prop_assert_eq!(round_half_away(x).to_bits(), x.round().to_bits(), "{}", x);
                }
            }
        }
    }
}
