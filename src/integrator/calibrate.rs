//! A contact law's head-on impact and its calibration to a restitution: methods of
//! [`ContactLaw`] that run the normal law alone with dop853 (the law itself is data, in
//! `model::contact_law`).

use crate::base::error::Error;
use crate::base::root::{illinois_update, Bound, Side};
use crate::base::validate::{finite, positive};
use crate::integrator::law::{head_on, largest_coefficient, HeadOn};
use crate::model::contact_law::{ContactLaw, Damping, AT_SPEED_FIELD, RESTITUTION_FIELD};
use crate::model::material::elastic_impact;

/// Relative tolerance of the head-on integrations of the calibration (dop853).
pub const CALIBRATION_RTOL: f64 = 1e-13;

/// |e(c) - e_target| at which the calibration is done.
const CALIBRATION_TOL: f64 = 1e-13;

/// Most doublings of the coefficient while bracketing, and most Illinois trials.
const CALIBRATION_MAX_TRIALS: usize = 200;

impl ContactLaw {
    /// The law of `damping` whose head-on impact at the relative approach speed `at_speed`
    /// (m/s) has the restitution `restitution`, for balls of reduced mass `reduced_mass`
    /// (kg): the coefficient is bracketed (doubling from the small-damping estimate) and
    /// solved by regula falsi (Illinois) on e(c) - e, each e(c) a head-on integration of the
    /// normal law alone with dop853 at rtol [`CALIBRATION_RTOL`].
    ///
    /// Errors: a restitution outside (0, 1] (1 only gives coefficient 0), a speed that is
    /// not finite and > 0, `none` with a restitution below 1, or a restitution the law does
    /// not reach.
    ///
    /// ```
    /// use billiard_contact::{ContactLaw, Damping};
    /// // Hunt-Crossley: e depends on beta v alone; at v = 1 m/s, x = beta v with e = 0.95
    /// // solves -e x - ln(1 - e x) = x - ln(1 + x) (docs/contact-law.md#the-laws).
    /// let law = ContactLaw::calibrated(4.5e8, Damping::HuntCrossley, 0.95, 1.0, 0.085)?;
    /// let x = law.coefficient() * 1.0;
    /// let residual = -0.95 * x - (-0.95 * x).ln_1p() - (x - x.ln_1p());
    /// assert!(residual.abs() < 1e-13 && (x - 0.0789).abs() < 1e-4);
    /// assert!((law.head_on(0.085, 1.0, 1e-12)?.restitution - 0.95).abs() < 1e-10);
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn calibrated(
        stiffness: f64,
        damping: Damping,
        restitution: f64,
        at_speed: f64,
        reduced_mass: f64,
    ) -> Result<Self, Error> {
        positive(AT_SPEED_FIELD, at_speed, "m/s")?;
        finite(RESTITUTION_FIELD, restitution)?;
        if !(restitution > 0.0 && restitution <= 1.0) {
            return Err(Error::invalid(
                RESTITUTION_FIELD,
                restitution,
                "in (0, 1]: a damped contact always rebounds a little",
            ));
        }
        let elastic = ContactLaw::new(stiffness, damping, 0.0)?;
        if restitution == 1.0 {
            return Ok(elastic);
        }
        if damping == Damping::None {
            return Err(Error::invalid(
                RESTITUTION_FIELD,
                format!("{restitution} with contact.law.damping = \"none\""),
                "1 (elastic Hertz); a restitution below 1 needs hunt-crossley or kuwabara-kono",
            ));
        }
        let e_of = |c: f64| -> Result<f64, Error> {
            let law = ContactLaw::new(stiffness, damping, c)?;
            Ok(head_on(&law, reduced_mass, at_speed, CALIBRATION_RTOL)?.restitution)
        };
        // The law's damping bound (integrator::law): the bracket stops at it.
        let (_, tau0) = elastic_impact(stiffness, reduced_mass, at_speed);
        let c_max = largest_coefficient(damping, at_speed, tau0);
        let c0 = elastic.small_damping_estimate(restitution, at_speed, reduced_mass);
        let (lo, hi) = bracket(&e_of, restitution, c0.min(c_max), c_max)?;
        solve_bracketed(&e_of, restitution, lo, hi)
            .and_then(|c| ContactLaw::new(stiffness, damping, c))
    }

    /// A first coefficient for the calibration: the small-damping slope 1 - e = (2/3) beta v
    /// for Hunt-Crossley; for Kuwabara-Kono the damping time gamma that is the same
    /// fraction (1 - e) of the elastic contact time's scale delta_max / v.
    fn small_damping_estimate(&self, restitution: f64, v: f64, reduced_mass: f64) -> f64 {
        let loss = 1.0 - restitution;
        match self.damping() {
            Damping::None => 0.0,
            Damping::HuntCrossley => 1.5 * loss / v,
            Damping::KuwabaraKono => {
                let (delta_max, _) = elastic_impact(self.stiffness(), reduced_mass, v);
                loss * delta_max / v
            }
        }
    }

    /// The head-on impact of this law at the relative approach speed `v` (m/s) for reduced
    /// mass `reduced_mass` (kg), the normal law integrated alone with dop853 at `rtol`:
    /// restitution, contact time, largest compression and peak force.
    pub fn head_on(&self, reduced_mass: f64, v: f64, rtol: f64) -> Result<HeadOn, Error> {
        positive("contact.law.at_speed", v, "m/s")?;
        positive("reduced_mass", reduced_mass, "kg")?;
        head_on(self, reduced_mass, v, rtol)
    }
}

/// A coefficient bracket [lo, hi] with e(lo) >= target > e(hi): from 0 (e = 1) and
/// doubling `c0` until e falls below the target, up to the largest coefficient `c_max`
/// (a target below e(c_max) is refused).
fn bracket(
    e_of: &dyn Fn(f64) -> Result<f64, Error>,
    target: f64,
    c0: f64,
    c_max: f64,
) -> Result<(f64, f64), Error> {
    let (mut lo, mut hi) = (0.0, c0.max(f64::MIN_POSITIVE));
    for _ in 0..CALIBRATION_MAX_TRIALS {
        let e = e_of(hi)?;
        if e < target {
            return Ok((lo, hi));
        }
        if hi >= c_max {
            return Err(Error::invalid(
                RESTITUTION_FIELD,
                target,
                format!(
                    "at least {} at this speed: a smaller one needs a damping past the law's \
                     bound (contact.law.coefficient at most {})",
                    crate::base::number::sci(e, 3),
                    crate::base::number::sci(c_max, 4),
                ),
            ));
        }
        lo = hi;
        hi = (hi * 2.0).min(c_max);
    }
    Err(Error::invalid(
        RESTITUTION_FIELD,
        target,
        format!("a restitution the law reaches (none up to a coefficient of {hi:e})"),
    ))
}

/// The coefficient in [lo, hi] with e(c) = target: regula falsi with the Illinois
/// modification on g(c) = e(c) - target.
fn solve_bracketed(
    e_of: &dyn Fn(f64) -> Result<f64, Error>,
    target: f64,
    lo: f64,
    hi: f64,
) -> Result<f64, Error> {
    let mut a = Bound {
        q: lo,
        g: e_of(lo)? - target,
    };
    let mut b = Bound {
        q: hi,
        g: e_of(hi)? - target,
    };
    let mut side = Side::None;
    let mut best = if a.g.abs() < b.g.abs() { a } else { b };
    for _ in 0..CALIBRATION_MAX_TRIALS {
        if best.g.abs() <= CALIBRATION_TOL || b.q - a.q <= 4.0 * f64::EPSILON * b.q {
            break;
        }
        let c = a.q + (b.q - a.q) * (a.g / (a.g - b.g));
        let g = e_of(c)? - target;
        if g.abs() < best.g.abs() {
            best = Bound { q: c, g };
        }
        side = illinois_update(&mut a, &mut b, side, c, g);
    }
    Ok(best.q)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The calibration's first guess for Hunt-Crossley is the small-damping slope: for
    /// e = 0.999 it is within 0.2 % of the beta whose e solves the first integral
    /// -e x - ln(1 - e x) = x - ln(1 + x), x = beta v (solved here by bisection); the next
    /// order, 1 - e = (2/3) x (1 - 0.66 x), puts the slope's guess 0.1 % low at x = 1.5e-3.
    #[test]
    fn first_guess_is_the_small_damping_slope() {
        let (e, v) = (0.999, 2.0);
        let energy = |x: f64, e: f64| -e * x - (-e * x).ln_1p() - (x - x.ln_1p());
        let (mut lo, mut hi) = (1e-6, 1e-2);
        for _ in 0..200 {
            let x = 0.5 * (lo + hi);
            // Negative while x is below the root (too little damping for this e):
            // x^2 (e^2 - 1) / 2 + x^3 (e^3 + 1) / 3 + ...
            if energy(x, e) < 0.0 {
                lo = x;
            } else {
                hi = x;
            }
        }
        let beta = 0.5 * (lo + hi) / v;
        let law = ContactLaw::new(1e9, Damping::HuntCrossley, 0.0).unwrap();
        let guess = law.small_damping_estimate(e, v, 0.085);
        assert!((guess / beta - 1.0).abs() < 2e-3, "{guess} vs {beta}");
        // Kuwabara-Kono: (1 - e) delta_max / v, delta_max = (5 m* v^2 / (4 k))^(2/5).
        let law = ContactLaw::new(1e9, Damping::KuwabaraKono, 0.0).unwrap();
        let delta_max = (5.0 * 0.085 * v * v / 4e9).powf(0.4);
        let want = 1e-3 * delta_max / v;
        let got = law.small_damping_estimate(e, v, 0.085);
        assert!((got / want - 1.0).abs() < 1e-12, "{got} vs {want}");
    }

    /// The calibration refuses a restitution outside (0, 1], a speed not > 0, and a
    /// restitution below 1 without damping, naming the field.
    #[test]
    fn calibration_refuses_bad_targets() {
        for (e, v, field) in [
            (0.0, 1.0, RESTITUTION_FIELD),
            (1.1, 1.0, RESTITUTION_FIELD),
            (0.9, 0.0, AT_SPEED_FIELD),
        ] {
            match ContactLaw::calibrated(1e9, Damping::HuntCrossley, e, v, 0.085) {
                Err(Error::InvalidParameter { field: f, .. }) => assert_eq!(f, field),
                other => panic!("{e} {v}: {other:?}"),
            }
        }
        assert!(ContactLaw::calibrated(1e9, Damping::None, 0.9, 1.0, 0.085).is_err());
    }
}
