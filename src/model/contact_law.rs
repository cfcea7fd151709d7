//! A contact law: the normal force from the compression itself, Hertz's elastic force with an
//! optional damping term (docs/contact-law.md).
//!
//! The compression delta (m) of the two balls grows at the relative approach rate,
//! delta' = 2 U (delta(0) = 0), and the normal force is
//!
//! ```text
//! none           f = k delta^(3/2)
//! hunt-crossley  f = k delta^(3/2) (1 + beta delta')          beta in s/m
//! kuwabara-kono  f = k delta^(3/2) + gamma k delta^(1/2) delta'   gamma in s
//! ```
//!
//! clipped at 0 (the balls never pull). The contact ends when the force returns to zero
//! during restitution: at delta = 0 for `none` and `hunt-crossley` (its factor
//! 1 + beta delta' stays positive, docs/contact-law.md#the-end-of-the-contact), at
//! delta + gamma delta' = 0 with delta > 0 for `kuwabara-kono`. The restitution, the
//! impulse and the contact time follow from the law; the damping coefficient is a user's
//! calibration, given directly or solved from a restitution at a speed
//! ([`ContactLaw::calibrated`]).

use crate::error::{finite, Error};
use crate::integrator::law::{head_on, HeadOn};
use crate::model::material::elastic_impact;
use crate::model::params::positive;
use serde::{Deserialize, Serialize};
use std::fmt;

/// The field the stiffness is named by (as in the scene file).
pub const STIFFNESS_FIELD: &str = "contact.law.stiffness";
/// The field the damping coefficient is named by.
pub const COEFFICIENT_FIELD: &str = "contact.law.coefficient";
/// The field of the restitution a coefficient is calibrated to.
pub const RESTITUTION_FIELD: &str = "contact.law.restitution";
/// The field of the speed a coefficient is calibrated at.
pub const AT_SPEED_FIELD: &str = "contact.law.at_speed";

/// The damping term of the law.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Damping {
    /// Elastic Hertz: no damping, restitution 1.
    None,
    /// Hunt & Crossley (1975): f = k delta^(3/2) (1 + beta delta'), beta (s/m). The
    /// restitution depends on beta v alone (v the approach speed).
    HuntCrossley,
    /// Kuwabara & Kono (1987), Brilliantov et al. (1996): the viscoelastic sphere,
    /// f = k delta^(3/2) + gamma k delta^(1/2) delta', gamma (s). 1 - e grows as v^(1/5).
    KuwabaraKono,
}

impl Damping {
    /// The name as the scene file writes it.
    pub fn name(self) -> &'static str {
        match self {
            Damping::None => "none",
            Damping::HuntCrossley => "hunt-crossley",
            Damping::KuwabaraKono => "kuwabara-kono",
        }
    }

    /// The unit of the coefficient.
    pub fn unit(self) -> &'static str {
        match self {
            Damping::None => "-",
            Damping::HuntCrossley => "s/m",
            Damping::KuwabaraKono => "s",
        }
    }
}

impl fmt::Display for Damping {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The law of the normal force: stiffness, damping and its coefficient (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ContactLaw {
    stiffness: f64,
    damping: Damping,
    coefficient: f64,
}

/// Relative tolerance of the head-on integrations of the calibration (dop853).
pub const CALIBRATION_RTOL: f64 = 1e-13;

/// |e(c) - e_target| at which the calibration is done.
const CALIBRATION_TOL: f64 = 1e-13;

/// Most doublings of the coefficient while bracketing, and most Illinois trials.
const CALIBRATION_MAX_TRIALS: usize = 200;

impl ContactLaw {
    /// A validated law: `stiffness` k (N / m^(3/2)) finite and > 0, `coefficient` finite and
    /// >= 0 (beta in s/m for `hunt-crossley`, gamma in s for `kuwabara-kono`; 0 for `none`).
    ///
    /// ```
    /// use billiard_contact::{ContactLaw, Damping};
    /// let law = ContactLaw::new(4.5e8, Damping::HuntCrossley, 0.1)?;
    /// // f = k delta^1.5 (1 + beta delta'): at delta = 1e-4 m closing at 1 m/s.
    /// let f = 4.5e8 * 1e-6 * (1.0 + 0.1);
    /// assert!((law.force(1e-4, 1.0) - f).abs() < 1e-12 * f);
    /// assert_eq!(law.force(-1e-9, 1.0), 0.0); // apart: no force
    /// assert!(ContactLaw::new(4.5e8, Damping::None, 0.1).is_err());
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn new(stiffness: f64, damping: Damping, coefficient: f64) -> Result<Self, Error> {
        positive(STIFFNESS_FIELD, stiffness, "N/m^1.5")?;
        finite(COEFFICIENT_FIELD, coefficient)?;
        if coefficient < 0.0 {
            return Err(Error::invalid(
                COEFFICIENT_FIELD,
                coefficient,
                format!(
                    ">= 0 {} (a damping that does not add energy)",
                    damping.unit()
                ),
            ));
        }
        if damping == Damping::None && coefficient != 0.0 {
            return Err(Error::invalid(
                COEFFICIENT_FIELD,
                format!("{coefficient} with contact.law.damping = \"none\""),
                "no coefficient with damping \"none\" (choose hunt-crossley or kuwabara-kono)",
            ));
        }
        Ok(ContactLaw {
            stiffness,
            damping,
            coefficient,
        })
    }

    /// Elastic Hertz of stiffness k (N / m^(3/2)).
    pub fn elastic(stiffness: f64) -> Result<Self, Error> {
        ContactLaw::new(stiffness, Damping::None, 0.0)
    }

    /// Stiffness k (N / m^(3/2)).
    pub fn stiffness(&self) -> f64 {
        self.stiffness
    }

    /// The damping term.
    pub fn damping(&self) -> Damping {
        self.damping
    }

    /// The damping coefficient: beta (s/m), gamma (s), or 0.
    pub fn coefficient(&self) -> f64 {
        self.coefficient
    }

    /// The normal force f (N) at compression `delta` (m) closing at `delta_dot` (m/s),
    /// clipped at 0: no force while apart (delta <= 0) and no pull.
    #[inline]
    pub fn force(&self, delta: f64, delta_dot: f64) -> f64 {
        if delta <= 0.0 {
            return 0.0;
        }
        let root = delta.sqrt();
        let k = self.stiffness;
        let f = match self.damping {
            Damping::None => k * delta * root,
            Damping::HuntCrossley => k * delta * root * (1.0 + self.coefficient * delta_dot),
            Damping::KuwabaraKono => k * root * (delta + self.coefficient * delta_dot),
        };
        f.max(0.0)
    }

    /// The rate df/dt (N/s) of the unclipped force along the motion, at compression `delta`
    /// (m > 0), rate `delta_dot` (m/s) and acceleration delta'' = -f / m* (`reduced_mass` m*
    /// in kg): its zero is the peak force. Under `kuwabara-kono` it is +inf at delta <= 0:
    /// the damped force rises as sqrt(delta) from first touch, and a positive rate keeps the
    /// start of contact from reading as the peak (gamma = 0 included).
    #[inline]
    pub fn force_rate(&self, delta: f64, delta_dot: f64, reduced_mass: f64) -> f64 {
        let d = delta.max(0.0);
        let root = d.sqrt();
        let (k, c, w) = (self.stiffness, self.coefficient, delta_dot);
        let accel = -self.force(delta, delta_dot) / reduced_mass;
        match self.damping {
            Damping::None => 1.5 * k * root * w,
            Damping::HuntCrossley => k * (1.5 * root * w * (1.0 + c * w) + d * root * c * accel),
            Damping::KuwabaraKono if d > 0.0 => {
                k * (1.5 * root * w + c * (0.5 * w * w / root + root * accel))
            }
            Damping::KuwabaraKono => f64::INFINITY,
        }
    }

    /// The separation function (m): positive while the balls press on each other, zero
    /// where the force returns to zero during restitution. delta for `none` and
    /// `hunt-crossley`, delta + gamma delta' for `kuwabara-kono`.
    #[inline]
    pub fn separation(&self, delta: f64, delta_dot: f64) -> f64 {
        match self.damping {
            Damping::None | Damping::HuntCrossley => delta,
            Damping::KuwabaraKono => delta + self.coefficient * delta_dot,
        }
    }

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
        let c0 = elastic.small_damping_estimate(restitution, at_speed, reduced_mass);
        let (lo, hi) = bracket(&e_of, restitution, c0)?;
        solve_bracketed(&e_of, restitution, lo, hi)
            .and_then(|c| ContactLaw::new(stiffness, damping, c))
    }

    /// A first coefficient for the calibration: the small-damping slope 1 - e = (2/3) beta v
    /// for Hunt-Crossley; for Kuwabara-Kono the damping time gamma that is the same
    /// fraction (1 - e) of the elastic contact time's scale delta_max / v.
    fn small_damping_estimate(&self, restitution: f64, v: f64, reduced_mass: f64) -> f64 {
        let loss = 1.0 - restitution;
        match self.damping {
            Damping::None => 0.0,
            Damping::HuntCrossley => 1.5 * loss / v,
            Damping::KuwabaraKono => {
                let (delta_max, _) = elastic_impact(self.stiffness, reduced_mass, v);
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
/// doubling `c0` until e falls below the target.
fn bracket(
    e_of: &dyn Fn(f64) -> Result<f64, Error>,
    target: f64,
    c0: f64,
) -> Result<(f64, f64), Error> {
    let (mut lo, mut hi) = (0.0, c0.max(f64::MIN_POSITIVE));
    for _ in 0..CALIBRATION_MAX_TRIALS {
        if e_of(hi)? < target {
            return Ok((lo, hi));
        }
        lo = hi;
        hi *= 2.0;
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
    use crate::integrator::stop_event::{illinois_update, Bound, Side};
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

    #[test]
    fn refuses_bad_laws() {
        for (k, d, c, field) in [
            (0.0, Damping::None, 0.0, STIFFNESS_FIELD),
            (f64::NAN, Damping::None, 0.0, STIFFNESS_FIELD),
            (1e9, Damping::HuntCrossley, -0.1, COEFFICIENT_FIELD),
            (1e9, Damping::KuwabaraKono, f64::INFINITY, COEFFICIENT_FIELD),
            (1e9, Damping::None, 1e-3, COEFFICIENT_FIELD),
        ] {
            match ContactLaw::new(k, d, c) {
                Err(Error::InvalidParameter { field: f, .. }) => assert_eq!(f, field),
                other => panic!("{k} {d} {c}: {other:?}"),
            }
        }
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

    /// The Kuwabara-Kono force vanishes at delta + gamma delta' = 0 and is clipped beyond.
    #[test]
    fn kuwabara_kono_separates_at_the_force_zero() {
        let law = ContactLaw::new(1e9, Damping::KuwabaraKono, 1e-5).unwrap();
        let delta = 1e-5;
        let w = -delta / 1e-5;
        assert_eq!(law.separation(delta, w), 0.0);
        assert!(law.force(delta, w).abs() < 1e-9);
        assert_eq!(law.force(delta, 1.5 * w), 0.0);
    }

    /// Kuwabara-Kono's rate at first touch: +inf (the sqrt(delta) rise), not 0.5 w^2 / 0
    /// times gamma, which is NaN for gamma = 0 or w = 0.
    #[test]
    fn kuwabara_kono_rate_at_first_touch_is_infinite() {
        for gamma in [0.0, 2e-6] {
            let law = ContactLaw::new(1e9, Damping::KuwabaraKono, gamma).unwrap();
            for w in [0.0, 0.5] {
                assert_eq!(law.force_rate(0.0, w, 0.085), f64::INFINITY, "{gamma} {w}");
            }
        }
    }

    /// df/dt against a central difference of f along the motion delta(t), delta'(t).
    #[test]
    fn force_rate_is_the_derivative_along_the_motion() {
        let m = 0.085;
        for law in [
            ContactLaw::elastic(1e9).unwrap(),
            ContactLaw::new(1e9, Damping::HuntCrossley, 0.2).unwrap(),
            ContactLaw::new(1e9, Damping::KuwabaraKono, 2e-6).unwrap(),
        ] {
            let (d, w) = (5e-5, 0.3);
            let a = -law.force(d, w) / m;
            let h = 1e-9;
            let f = |t: f64| law.force(d + w * t + 0.5 * a * t * t, w + a * t);
            let fd = (f(h) - f(-h)) / (2.0 * h);
            let rate = law.force_rate(d, w, m);
            assert!((rate - fd).abs() < 1e-5 * rate.abs(), "{rate} vs {fd}");
        }
    }
}
