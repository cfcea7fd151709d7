//! Numbers in the output files (trace, batch, ball paths and work-precision CSVs): the
//! shortest decimal text that reads back to the same `f64`, and the rule that an output
//! number is finite (a NaN or infinity fails the run, naming the field, instead of being
//! written).

use crate::error::Error;
use std::fmt;

/// An `f64` displayed as the shortest decimal text that reads back to the same value:
/// `0.1`, `2.0`, `1e-10`, `-3.5e300` (Rust's `{:?}` of `f64`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shortest(pub f64);

impl fmt::Display for Shortest {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.0)
    }
}

/// `v` as [`Shortest`] text.
pub fn shortest(v: f64) -> String {
    Shortest(v).to_string()
}

/// `v` when it is finite; otherwise [`Error::NonFinite`] naming the output field (`field`
/// is called only then).
pub fn finite_output(v: f64, field: impl FnOnce() -> String) -> Result<f64, Error> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(Error::NonFinite {
            field: field(),
            value: v,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn non_finite_outputs_name_the_field() {
        assert_eq!(finite_output(1.5, String::new).unwrap(), 1.5);
        let e = finite_output(f64::NAN, || "trace column U (m/s) at t = 0".into()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "non-finite result: trace column U (m/s) at t = 0 = NaN"
        );
        assert!(finite_output(f64::NEG_INFINITY, || "x".into()).is_err());
    }
}
