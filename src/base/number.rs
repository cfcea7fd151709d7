//! Numbers in the output files (trace, batch, ball paths and work-precision CSVs): the
//! shortest decimal text that reads back to the same `f64`, and the rule that an output
//! number is finite (a NaN or infinity fails the run, naming the field, instead of being
//! written). And numbers for people (the summaries): [`si`] with an SI prefix (`250 µs`),
//! [`decimal`] plain (`0.255`), [`sci`] for scaled errors (`8.1e-12`), never with an
//! exponent `e0`.

use std::fmt;

/// An `f64` displayed as the shortest decimal text that reads back to the same value:
/// `0.1`, `2.0`, `1e-10`, `-3.5e300` (Rust's `{:?}` of `f64`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Shortest(pub f64);

impl fmt::Display for Shortest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.0)
    }
}

/// `v` as [`Shortest`] text.
pub(crate) fn shortest(v: f64) -> String {
    Shortest(v).to_string()
}

/// `value` rounded to `digits` significant digits (at least 1): its decimal digits (sign
/// left out) and the power of ten of the first, as Rust's `{:e}` writes them.
fn significant(value: f64, digits: usize) -> (String, i32) {
    let text = format!("{:.*e}", digits.max(1) - 1, value.abs());
    let (mantissa, exp) = text.split_once('e').unwrap_or((&text, "0"));
    (mantissa.replace('.', ""), exp.parse().unwrap_or(0))
}

/// The digits `d1 d2 ...` (first digit times 10^`point`) with the decimal point placed, and
/// trailing zeros after it removed: ("2500", 2) -> "250", ("1561453", 0) -> "1.561453".
fn place_point(digits: &str, point: i32) -> String {
    let text = if point < 0 {
        format!("0.{}{digits}", "0".repeat((-point - 1) as usize))
    } else {
        let whole = point as usize + 1;
        let padded = format!("{digits:0<whole$}");
        let (int, frac) = padded.split_at(whole);
        format!("{int}.{frac}")
    };
    let text = text.trim_end_matches('0');
    text.trim_end_matches('.').to_string()
}

/// `value` with `digits` significant digits in scientific notation, for scaled errors:
/// `8.1e-12`, `0` for zero, and no exponent `e0` (`1.2`).
pub(crate) fn sci(value: f64, digits: usize) -> String {
    if value == 0.0 || !value.is_finite() {
        return if value == 0.0 {
            "0".into()
        } else {
            value.to_string()
        };
    }
    let text = format!("{:.*e}", digits.max(1) - 1, value);
    text.strip_suffix("e0").map(str::to_string).unwrap_or(text)
}

/// `value` with `digits` significant digits as a plain decimal (trailing zeros dropped):
/// `0.255`, `-1.831742421`, `0` for zero; in [`sci`] notation outside 1e-4 <= |value| <
/// 1e7, where a plain decimal would be all zeros or too long to read.
pub(crate) fn decimal(value: f64, digits: usize) -> String {
    if value == 0.0 || !value.is_finite() {
        return sci(value, digits);
    }
    let (d, exp) = significant(value, digits);
    if !(-4..7).contains(&exp) {
        let text = sci(value, digits);
        return match text.split_once('e') {
            Some((m, e)) if m.contains('.') => {
                format!("{}e{e}", m.trim_end_matches('0').trim_end_matches('.'))
            }
            _ => text,
        };
    }
    let sign = if value < 0.0 { "-" } else { "" };
    format!("{sign}{}", place_point(&d, exp))
}

/// SI prefixes from pico to giga, by power of ten.
const PREFIXES: [(i32, &str); 8] = [
    (9, "G"),
    (6, "M"),
    (3, "k"),
    (0, ""),
    (-3, "m"),
    (-6, "µ"),
    (-9, "n"),
    (-12, "p"),
];

/// `value` in `unit` with an SI prefix that puts 1 to 999 before the point, `digits`
/// significant digits, trailing zeros dropped: `si(2.5e-4, "s", 5)` is `250 µs`,
/// `si(1.561453, "s", 7)` is `1.561453 s`. Zero is `0 s`; values beyond the prefixes
/// (below 1 p, from 1000 G) keep their exponent ([`decimal`]).
pub(crate) fn si(value: f64, unit: &str, digits: usize) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{} {unit}", sci(value, digits));
    }
    let (d, exp) = significant(value, digits);
    match PREFIXES.iter().find(|(p, _)| exp >= *p) {
        Some((p, prefix)) if exp < 12 => {
            let sign = if value < 0.0 { "-" } else { "" };
            format!("{sign}{} {prefix}{unit}", place_point(&d, exp - p))
        }
        _ => format!("{} {unit}", decimal(value, digits)),
    }
}

/// `n` and the noun in the singular or the plural: `count(1, "row", "rows")` is "1 row",
/// `count(7, "bounce", "bounces")` is "7 bounces".
pub(crate) fn count(n: u64, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

/// `text` with every number written out in full as a person reads it: a decimal numeral
/// whose value lies outside 1e-4 <= |v| < 1e16 (with a point) or that has more than 20
/// digits (without) is replaced by its shortest round-trip form in scientific notation
/// (`1e300`, `5e-324`, `-1.25e-7`); every other numeral, and all other text, is kept as it
/// is. Rust's `{}` of an `f64` never uses an exponent, so an error naming `1e300` would
/// otherwise spell out 301 digits.
pub(crate) fn readable_numbers(text: &str) -> String {
    let bytes = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < bytes.len() {
        let starts_number = bytes[i].is_ascii_digit() && (i == 0 || !is_word_byte(bytes[i - 1]));
        if !starts_number {
            let next = text[i..].chars().next().map_or(1, char::len_utf8);
            out.push_str(&text[i..i + next]);
            i += next;
            continue;
        }
        let mut j = i;
        while j < bytes.len() && bytes[j].is_ascii_digit() {
            j += 1;
        }
        let point = j + 1 < bytes.len() && bytes[j] == b'.' && bytes[j + 1].is_ascii_digit();
        if point {
            j += 1;
            while j < bytes.len() && bytes[j].is_ascii_digit() {
                j += 1;
            }
        }
        let numeral = &text[i..j];
        let long = if point { true } else { numeral.len() > 20 };
        match numeral.parse::<f64>() {
            Ok(v) if long && v.is_finite() && format!("{v:?}").contains('e') => {
                out.push_str(&format!("{v:?}"));
            }
            _ => out.push_str(numeral),
        }
        i = j;
    }
    out
}

/// Whether `b` continues a word or a numeral (so a digit after it does not start one).
fn is_word_byte(b: u8) -> bool {
    b.is_ascii_alphanumeric() || b == b'_' || b == b'.'
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rust's `{}` writes 1e300 as 1 followed by 300 zeros and 5e-324 as 323 zeros then 5
    /// (324 digits after the point): both come back as their shortest forms; numbers in the
    /// plain range, integers up to 20 digits, names with digits and exponents already
    /// written are kept.
    #[test]
    fn long_numerals_in_messages_become_readable() {
        let big = format!("{}", 1e300);
        let tiny = format!("{}", 5e-324);
        assert_eq!((big.len(), tiny.len()), (301, 326));
        assert_eq!(
            readable_numbers(&format!("mass = {tiny} kg, radius = {big} m")),
            "mass = 5e-324 kg, radius = 1e300 m"
        );
        assert_eq!(
            readable_numbers(&format!("x = -{}", 1.25e-7)),
            "x = -1.25e-7"
        );
        // 20 digits (u64::MAX has 20) are kept; 21 are a float's.
        assert_eq!(
            readable_numbers(&u64::MAX.to_string()),
            "18446744073709551615"
        );
        assert_eq!(readable_numbers(&format!("{}", 1e20)), "1e20");
        let kept = "--chunk = 1000000000000: at most 1048576; u_x = 0.0001, 1e-9, a_px2 7.5";
        assert_eq!(readable_numbers(kept), kept);
        assert_eq!(readable_numbers("µ 0.5 ✓"), "µ 0.5 ✓");
    }

    #[test]
    fn shortest_reads_back_exactly() {
        // The texts below are the shortest decimals that round to these doubles: 0.1 is
        // the double nearest 1/10; 1e-10 needs its exponent; whole numbers keep ".0".
        assert_eq!(shortest(0.1), "0.1");
        assert_eq!(shortest(2.0), "2.0");
        assert_eq!(shortest(1e-10), "1e-10");
        assert_eq!(shortest(-0.0), "-0.0");
        let third = 1.0 / 3.0;
        assert_eq!(shortest(third), "0.3333333333333333");
        assert_eq!(shortest(third).parse::<f64>().unwrap(), third);
    }

    /// Numbers for people: the prefix changes where rounding carries to 1000 (999.9996 us
    /// to 4 digits is 1 ms), small and large values keep an exponent, never `e0`.
    #[test]
    fn numbers_for_people() {
        assert_eq!(si(9.999996e-4, "s", 4), "1 ms");
        assert_eq!(si(2.0e-4, "s", 5), "200 µs");
        assert_eq!(si(1.0, "s", 7), "1 s");
        assert_eq!(si(0.0123, "m", 3), "12.3 mm");
        assert_eq!(si(3.0e-15, "J", 3), "3e-15 J");
        assert_eq!(decimal(1.653930, 7), "1.65393");
        assert_eq!(decimal(123456.0, 3), "123000");
        assert_eq!(decimal(1.0e-4, 3), "0.0001");
        assert_eq!(decimal(1.25e7, 3), "1.25e7");
        assert_eq!(sci(-2.5, 2), "-2.5");
        assert_eq!(count(1, "row", "rows"), "1 row");
        assert_eq!(count(0, "row", "rows"), "0 rows");
        assert_eq!(sci(1.0e-17, 2), "1.0e-17");
        for v in [1.0, 2.5e-4, 1.561453, 46.0, 0.5, 1e-4] {
            for text in [si(v, "s", 7), decimal(v, 7), sci(v, 2)] {
                assert!(!text.contains("e0"), "{v}: {text}");
            }
        }
    }

    /// The examples of the documentation of `sci`.
    #[test]
    fn sci_examples() {
        assert_eq!(sci(8.14e-12, 2), "8.1e-12");
        assert_eq!(sci(0.0, 2), "0");
        assert_eq!(sci(1.23, 2), "1.2");
    }

    /// The examples of the documentation of `decimal`.
    #[test]
    fn decimal_examples() {
        assert_eq!(decimal(2.55e-1, 10), "0.255");
        assert_eq!(decimal(-8.434340058e-3, 4), "-0.008434");
        assert_eq!(decimal(3.5e-9, 3), "3.5e-9");
    }

    /// The examples of the documentation of `si`.
    #[test]
    fn si_examples() {
        assert_eq!(si(2.5e-4, "s", 5), "250 µs");
        assert_eq!(si(4.641968e-2, "s", 7), "46.41968 ms");
        assert_eq!(si(2.642307e-3, "m", 7), "2.642307 mm");
        assert_eq!(si(0.0, "J", 4), "0 J");
        assert_eq!(si(-1500.0, "N", 4), "-1.5 kN");
    }
}
