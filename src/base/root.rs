//! The scalar root finder's step shared by the crate's root finders (the stop of sliding,
//! a contact law's stop and its calibration): regula falsi with the Illinois modification.

/// One end of the bracket: the abscissa q (here the impulse fraction; the time or a law's
/// coefficient for the other root finders of the crate) and the function g there.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Bound {
    pub(crate) q: f64,
    pub(crate) g: f64,
}

/// The end of the bracket the last trial replaced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Side {
    None,
    Low,
    High,
}

/// Replaces the end of the bracket on the side of the trial (q, g), and halves the value at
/// the other end when that end is kept twice in a row (the Illinois modification, which
/// stops the retained end from stalling the secant). Returns the side replaced.
pub(crate) fn illinois_update(lo: &mut Bound, hi: &mut Bound, last: Side, q: f64, g: f64) -> Side {
    if g > 0.0 {
        *lo = Bound { q, g };
        if last == Side::Low {
            hi.g *= 0.5;
        }
        Side::Low
    } else {
        *hi = Bound { q, g };
        if last == Side::High {
            lo.g *= 0.5;
        }
        Side::High
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Illinois step on g(q) = 1 - 4 q on [0, 1] (root 1/4): the secant's first trial
    /// is the root itself, and a kept end has its value halved.
    #[test]
    fn illinois_halves_the_end_kept_twice() {
        let mut lo = Bound { q: 0.0, g: 1.0 };
        let mut hi = Bound { q: 1.0, g: -3.0 };
        let q = lo.q + (hi.q - lo.q) * (lo.g / (lo.g - hi.g));
        assert_eq!(q, 0.25);
        // Two trials above the root in a row: the high end is kept twice, its g halved.
        let side = illinois_update(&mut lo, &mut hi, Side::None, 0.2, 0.2);
        assert_eq!((side, lo.q, hi.g), (Side::Low, 0.2, -3.0));
        let side = illinois_update(&mut lo, &mut hi, side, 0.24, 0.04);
        assert_eq!((side, lo.q, hi.g), (Side::Low, 0.24, -1.5));
        // A trial below the root replaces the high end; the low end is not halved.
        let side = illinois_update(&mut lo, &mut hi, side, 0.26, -0.04);
        assert_eq!((side, hi.q, lo.g), (Side::High, 0.26, 0.04));
    }
}
