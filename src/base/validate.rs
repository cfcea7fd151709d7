//! The checks every validating constructor starts with, and the check of every output
//! the crate writes: a value is finite (and positive) or an error names its field.

use crate::base::error::Error;

/// Checks that `value` is finite, naming `field` otherwise.
pub(crate) fn finite(field: &str, value: f64) -> Result<f64, Error> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(field, value, "a finite number"))
    }
}

/// Checks that `value` is finite and > 0 (in `unit`), naming `field` otherwise.
pub(crate) fn positive(field: &str, value: f64, unit: &str) -> Result<f64, Error> {
    finite(field, value)?;
    if value <= 0.0 {
        return Err(Error::invalid(field, value, format!("> 0 {unit}")));
    }
    Ok(value)
}

/// `v` when it is finite; otherwise [`Error::NonFinite`] naming the output field (`field`
/// is called only then).
pub(crate) fn finite_output(v: f64, field: impl FnOnce() -> String) -> Result<f64, Error> {
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
    fn non_finite_outputs_name_the_field() {
        assert_eq!(finite_output(1.5, String::new).unwrap(), 1.5);
        let e = finite_output(f64::NAN, || "trace column U (m/s) at t = 0".into()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "non-finite result: trace column U (m/s) at t = 0 = NaN"
        );
        assert!(finite_output(f64::NEG_INFINITY, || "x".into()).is_err());
    }

    #[test]
    fn invalid_names_field_value_and_range() {
        let e = finite("balls.mass", f64::NAN).unwrap_err();
        let Error::InvalidParameter {
            field,
            value,
            expected,
        } = &e
        else {
            panic!("{e:?}");
        };
        assert_eq!((field.as_str(), value.as_str()), ("balls.mass", "NaN"));
        assert_eq!(expected, "a finite number");
        assert_eq!(e.to_string(), "balls.mass = NaN: a finite number");
    }
}
