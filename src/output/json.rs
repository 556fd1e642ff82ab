//! Writing the plan's JSON text quickly: the numbers of a plan are nearly all rounded to a few
//! decimals (coordinates to 1e-9 degrees, lengths to a millimetre), and such a number is
//! written from its integer count of 1e-9 with integer formatting, the same text serde_json
//! writes with its shortest-digits float formatting, at a fraction of the cost. Every other
//! number goes to serde_json's own formatting.

use crate::geometry::round_half_away;
use serde::Serialize;
use serde_json::ser::{CompactFormatter, Formatter};
use std::io;

/// Writes `value` as compact JSON text, the same text as `serde_json::to_string`.
///
/// ```
/// use furrow::output::json::to_json_string;
///
/// let value = serde_json::json!({ "at": [24.052448994, 60.25], "length_m": 27.218, "k": 1e-7 });
/// let text = to_json_string(&value)?;
/// assert_eq!(text, serde_json::to_string(&value)?);
/// assert_eq!(text, r#"{"at":[24.052448994,60.25],"k":1e-7,"length_m":27.218}"#);
/// # Ok::<(), serde_json::Error>(())
/// ```
pub fn to_json_string<T: Serialize + ?Sized>(value: &T) -> Result<String, serde_json::Error> {
    let mut bytes = Vec::with_capacity(4096);
    value.serialize(&mut serde_json::Serializer::with_formatter(
        &mut bytes,
        RoundedNumbers,
    ))?;
    // serde_json writes only UTF-8 (the strings it was given and ASCII around them): the
    // check never fails.
    String::from_utf8(bytes).map_err(|_| serde::ser::Error::custom("the JSON text is not UTF-8"))
}

/// serde_json's compact formatter, with numbers of at most nine decimals written as integers.
struct RoundedNumbers;

/// Decimals a number may have to be written by [`RoundedNumbers`] itself.
const DECIMALS: u32 = 9;
/// 10^DECIMALS.
const UNIT: u64 = 10u64.pow(DECIMALS);
/// 10^DECIMALS, as a double (exactly).
const SCALE: f64 = UNIT as f64;

impl Formatter for RoundedNumbers {
    // Not inlined: every float field of every struct written calls it, and one copy keeps the
    // module small.
    #[inline(never)]
    fn write_f64<W: ?Sized + io::Write>(&mut self, writer: &mut W, value: f64) -> io::Result<()> {
        let mut buffer = [0u8; 32];
        match write_decimal(value, &mut buffer) {
            Some(len) => writer.write_all(&buffer[..len]),
            None => CompactFormatter.write_f64(writer, value),
        }
    }
}

/// `value` written into `out` as serde_json writes it, if it is the double nearest a decimal
/// of at most [`DECIMALS`] decimals and between 1e-5 and 1e6 in size; the length written.
///
/// Such a number's shortest decimal that reads back as the same double is that decimal: a
/// double near it is less than 1e-9 from the next (below 2^23), so no decimal of fewer digits
/// reads back as it, and serde_json writes it in positional notation (from 1e-5 to below
/// 1e16), with ".0" after a whole number.
fn write_decimal(value: f64, out: &mut [u8; 32]) -> Option<usize> {
    let size = value.abs();
    if !(1e-5..1e6).contains(&size) {
        return None;
    }
    let scale = SCALE;
    // Exact where the check below holds: below 1e15 the product is within a fraction of the
    // integer, and that integer over the scale (the division rounds correctly) is the number.
    let count = round_half_away(size * scale);
    if count / scale != size {
        return None;
    }
    let count = count as u64;
    let unit = UNIT;
    let (whole, mut fraction) = (count / unit, count % unit);
    let mut len = 0;
    if value < 0.0 {
        out[0] = b'-';
        len = 1;
    }
    let mut digits = itoa::Buffer::new();
    let whole = digits.format(whole).as_bytes();
    out[len..len + whole.len()].copy_from_slice(whole);
    len += whole.len();
    out[len] = b'.';
    len += 1;
    if fraction == 0 {
        out[len] = b'0';
        return Some(len + 1);
    }
    let mut places = DECIMALS as usize;
    while fraction % 10 == 0 {
        fraction /= 10;
        places -= 1;
    }
    for k in (0..places).rev() {
        out[len + k] = b'0' + (fraction % 10) as u8;
        fraction /= 10;
    }
    Some(len + places)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn serde_text(v: f64) -> String {
        serde_json::to_string(&v).unwrap()
    }

    fn ours(v: f64) -> String {
        to_json_string(&v).unwrap()
    }

    #[test]
    fn numbers_are_written_as_serde_json_writes_them() {
        for v in [
            0.0,
            -0.0,
            1.0,
            -1.0,
            10.0,
            1e-5,
            -1e-5,
            1.5e-5,
            9.99e-6,
            1e-6,
            1e-7,
            123456.789,
            999999.999999999,
            1e6,
            2.5e6,
            1e15,
            1e16,
            24.052448994,
            60.250001492,
            -179.999999999,
            0.1,
            0.3,
            0.1 + 0.2,
            1.0 / 3.0,
            f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            359.1467,
            0.0000123,
            100.0,
        ] {
            assert_eq!(ours(v), serde_text(v), "{v:e}");
        }
    }

    #[test]
    fn a_rounded_number_takes_the_integer_way() {
        let mut buffer = [0u8; 32];
        let len = write_decimal(-24.052448994, &mut buffer).unwrap();
        assert_eq!(&buffer[..len], b"-24.052448994");
        let len = write_decimal(27.0, &mut buffer).unwrap();
        assert_eq!(&buffer[..len], b"27.0");
        // Not a decimal of nine places, or outside the range: serde_json's way.
        assert_eq!(write_decimal(1.0 / 3.0, &mut buffer), None);
        assert_eq!(write_decimal(1e-6, &mut buffer), None);
        assert_eq!(write_decimal(2e6, &mut buffer), None);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(4096))]

        #[test]
        fn rounded_numbers_are_written_as_serde_json_writes_them(
            count in -2_000_000_000_000_000i64..2_000_000_000_000_000,
            decimals in 0u32..=12,
            shift in -7i32..=7,
        ) {
            // A decimal of `decimals` places, as the output rounds them, at many sizes.
            let scale = 10f64.powi(decimals as i32);
            let v = (count as f64 / 1e3).round() / scale * 10f64.powi(shift);
            prop_assert_eq!(ours(v), serde_text(v));
            let rounded = (v * scale).round() / scale;
            prop_assert_eq!(ours(rounded), serde_text(rounded));
            // Those of nine places or fewer, in the range, take the integer way.
            if decimals <= DECIMALS && (1e-5..1e6).contains(&rounded.abs()) {
                prop_assert!(write_decimal(rounded, &mut [0u8; 32]).is_some(), "{rounded:e}");
            }
        }

        #[test]
        fn any_number_is_written_as_serde_json_writes_it(bits in any::<u64>()) {
            let v = f64::from_bits(bits);
            prop_assert_eq!(ours(v), serde_text(v));
        }
    }
}
