//! Values far outside the range of any ball game, most likely a unit slip (a radius in
//! millimetres, a mass in grams, a duration in microseconds): the scene's values are
//! checked and a warning names the field, the value, the range and the unit that brings it
//! back into range. The run is not refused: the model holds for any positive values.

use crate::base::fields::DURATION_FIELD;
use crate::base::fields::YOUNGS_MODULUS_FIELD;
use crate::base::number::decimal;

/// A quantity, the range it takes in ball games (generously: from a marble to a bowling
/// ball, from a steel ball's contact to a beach ball's), and the unit slips to look for.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Plausible {
    /// The field, as in the scene file.
    pub field: &'static str,
    /// Its SI unit.
    pub unit: &'static str,
    /// The range of any ball game, in `unit`: [low, high].
    pub range: (f64, f64),
    /// Units a value may have been given in by mistake: name, symbol, size in `unit`.
    pub slips: &'static [(&'static str, &'static str, f64)],
}

/// Lengths given in millimetres or centimetres.
const LENGTH_SLIPS: &[(&str, &str, f64)] =
    &[("millimetres", "mm", 1e-3), ("centimetres", "cm", 1e-2)];

/// `balls.mass`: a table-tennis ball is 2.7 g, a bowling ball 7.3 kg.
pub(crate) const MASS: Plausible = Plausible {
    field: "balls.mass",
    unit: "kg",
    range: (1e-3, 20.0),
    slips: &[("grams", "g", 1e-3)],
};

/// `balls.radius`: a small marble's is about 6 mm, a basketball's 0.12 m.
pub(crate) const RADIUS: Plausible = Plausible {
    field: "balls.radius",
    unit: "m",
    range: (5e-3, 0.5),
    slips: LENGTH_SLIPS,
};

/// `contact.profile.duration`: steel balls touch for some 10 us, billiard balls for 200 us,
/// inflated balls for about 10 ms.
pub(crate) const DURATION: Plausible = Plausible {
    field: DURATION_FIELD,
    unit: "s",
    range: (1e-6, 0.1),
    slips: &[("milliseconds", "ms", 1e-3), ("microseconds", "µs", 1e-6)],
};

/// `balls.youngs_modulus`: rubber's is about 1 MPa, steel's 200 GPa.
pub(crate) const YOUNGS_MODULUS: Plausible = Plausible {
    field: YOUNGS_MODULUS_FIELD,
    unit: "Pa",
    range: (1e5, 1e12),
    slips: &[("gigapascals", "GPa", 1e9), ("megapascals", "MPa", 1e6)],
};

impl Plausible {
    fn in_range(&self, v: f64) -> bool {
        (self.range.0..=self.range.1).contains(&v)
    }

    /// The unit slip that brings `value` into range: (name, symbol, size); `None` when the
    /// value is in range or no slip fits.
    pub(crate) fn slip(&self, value: f64) -> Option<(&'static str, &'static str, f64)> {
        if self.in_range(value) {
            return None;
        }
        self.slips
            .iter()
            .copied()
            .find(|(_, _, size)| self.in_range(value * size))
    }

    /// The warning for `value`, `None` when it is in range.
    pub(crate) fn warning(&self, value: f64) -> Option<String> {
        if self.in_range(value) {
            return None;
        }
        let (lo, hi) = self.range;
        let likely = self
            .slip(value)
            .map(|(name, symbol, size)| {
                format!(
                    ": {name} meant? ({value} {symbol} = {} {})",
                    decimal(value * size, 6),
                    self.unit
                )
            })
            .unwrap_or_default();
        Some(format!(
            "{} = {value} {unit} lies far outside the range of any ball game ({} to {} \
             {unit}){likely}",
            self.field,
            decimal(lo, 3),
            decimal(hi, 3),
            unit = self.unit
        ))
    }
}

/// For balls that do not touch (|p_B - p_A| = `distance`, r_A + r_B = `contact_distance`,
/// m, named `contact_term`: "2r" for identical balls): the unit slip that explains it, as a
/// clause to append to the error (empty when none does): the radius of identical balls that
/// looks like millimetres, or positions that do.
pub(crate) fn not_touching_hint(
    distance: f64,
    contact_distance: f64,
    contact_term: &str,
) -> String {
    let r = contact_distance / 2.0;
    let near = |a: f64, b: f64| (a / b - 1.0).abs() < 1e-2;
    let identical = contact_term == "2r";
    if let Some((name, symbol, size)) = RADIUS.slip(r).filter(|_| identical) {
        let fits = if near(distance, contact_distance * size) {
            ": the positions fit that radius"
        } else {
            ""
        };
        return format!(
            "; balls.radius = {r} m looks like {name} ({r} {symbol} = {} m){fits}",
            decimal(r * size, 6)
        );
    }
    for (name, _, size) in RADIUS.slips {
        if near(distance * size, contact_distance) {
            return format!(
                "; the positions look like {name} (|p_B - p_A| is {contact_term} in {name})"
            );
        }
    }
    String::new()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The slips: 170 kg (grams), 28.575 m (millimetres), 200 s (microseconds:
    /// 200 ms = 0.2 s is still out of range), 5.4 Pa (gigapascals); values of real balls
    /// pass.
    #[test]
    fn unit_slips_are_named() {
        assert_eq!(MASS.slip(170.0), Some(("grams", "g", 1e-3)));
        assert_eq!(RADIUS.slip(28.575).map(|s| s.0), Some("millimetres"));
        assert_eq!(RADIUS.slip(2.8575).map(|s| s.0), Some("centimetres"));
        assert_eq!(DURATION.slip(200.0).map(|s| s.0), Some("microseconds"));
        assert_eq!(DURATION.slip(0.25).map(|s| s.0), Some("milliseconds"));
        assert_eq!(YOUNGS_MODULUS.slip(5.4).map(|s| s.0), Some("gigapascals"));
        for (p, v) in [
            (MASS, 0.17),
            (MASS, 0.0027),
            (MASS, 7.26),
            (RADIUS, 0.028575),
            (DURATION, 2.5e-4),
            (YOUNGS_MODULUS, 5.4e9),
        ] {
            assert_eq!(p.warning(v), None, "{}", p.field);
        }
        let w = MASS.warning(170.0).unwrap();
        assert!(w.ends_with("grams meant? (170 g = 0.17 kg)"), "{w}");
        // Far out with no slip that fits: the range alone.
        let w = MASS.warning(1e9).unwrap();
        assert!(w.ends_with("(0.001 to 20 kg)"), "{w}");
    }

    /// Radius 28.575 (mm meant) with positions in metres: 2r = 57.15 against a distance of
    /// 0.05715; positions in mm with the radius in metres: the other way round.
    #[test]
    fn not_touching_names_the_slip() {
        let h = not_touching_hint(0.05715, 57.15, "2r");
        assert!(
            h.contains("balls.radius = 28.575 m looks like millimetres")
                && h.contains("positions fit"),
            "{h}"
        );
        let h = not_touching_hint(57.15, 0.05715, "2r");
        assert!(h.contains("the positions look like millimetres"), "{h}");
        assert_eq!(not_touching_hint(0.07, 0.06, "2r"), "");
        // Unequal balls: no single radius to blame; positions in mm still show.
        assert_eq!(not_touching_hint(0.05715, 57.15, "r_A + r_B"), "");
        let h = not_touching_hint(57.15, 0.05715, "r_A + r_B");
        assert!(h.contains("is r_A + r_B in millimetres"), "{h}");
    }

    /// The examples of the documentation of `Plausible::warning`.
    #[test]
    fn warning_examples() {
        assert_eq!(RADIUS.warning(0.028575), None);
        assert_eq!(
            RADIUS.warning(28.575).unwrap(),
            "balls.radius = 28.575 m lies far outside the range of any ball game (0.005 to \
             0.5 m): millimetres meant? (28.575 mm = 0.028575 m)"
        );
    }
}
