//! Prescribed normal-force profiles f(t) over the contact (0, tau).
//!
//! Every profile is stored normalised: with s = t / tau,
//!
//! ```text
//! f(t) = (P / tau) phi(s),      p(t) = integral_0^t f = P Phi(s),      Phi(1) = 1,
//! ```
//!
//! so a profile delivers exactly the impulse P whatever its shape, and the integrator
//! works in the scaled time s. `Phi` is exact (analytic, or tabulated to round-off): it is
//! what the exact time-resolved solution needs (while sliding, the state at time t is the
//! closed form at impulse p(t): docs/model.md#the-exact-state-during-the-contact).
//!
//! | shape | phi(s) | Phi(s) |
//! |---|---|---|
//! | `half-sine` | (pi/2) sin(pi s) | sin^2(pi s / 2) |
//! | `sine-power` (exponent n) | sin^n(pi s) pi / B((n+1)/2, 1/2) | I_{sin^2(pi s)}((n+1)/2, 1/2) / 2 for s <= 1/2 |
//! | `hertz` | elastic Hertz impact, f ~ delta^(3/2) | (1 - delta'(t)/delta'(0)) / 2 |
//! | `rectangle` | 1 | s |
//! | `tabulated` | linear between (time, force) points | exact trapezoids |

pub mod beta;
mod half_sine;
mod hertz;
mod rectangle;
mod sine_power;
mod tabulated;

pub use half_sine::HalfSine;
pub use hertz::Hertz;
pub use rectangle::Rectangle;
pub use sine_power::SinePower;
pub use tabulated::{parse_table, Tabulated};

use crate::error::Error;
use crate::model::params::positive;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// A normal-force profile over the contact, normalised as in the module docs.
pub trait ForceProfile {
    /// Contact duration tau (s).
    fn duration(&self) -> f64;

    /// Normalised force phi(s) = f(s tau) tau / P (dimensionless) for s in [0, 1], the
    /// limit from inside at the ends; 0 outside [0, 1]. Integrates to 1 over [0, 1].
    fn shape(&self, s: f64) -> f64;

    /// Normalised cumulative impulse Phi(s) = p(s tau) / P in [0, 1]: 0 for s <= 0, 1 for
    /// s >= 1, non-decreasing.
    fn cumulative(&self, s: f64) -> f64;

    /// The smallest s in [0, 1] with Phi(s) = q, q in [0, 1]: the time (scaled) at which
    /// the impulse reaches q P. The default is a safeguarded Newton iteration on `cumulative`.
    fn time_at_cumulative(&self, q: f64) -> f64 {
        invert_cumulative(self, q)
    }

    /// Scaled times in (0, 1), sorted, where phi is not smooth (kinks, jumps): the
    /// integrators step exactly to them.
    fn breakpoints(&self) -> &[f64] {
        &[]
    }

    /// The exponent n of the ends, for a pulse that is analytic inside (0, 1) and grows like
    /// s^n from both ends with n not an integer (phi ~ s^n near 0 and ~ (1 - s)^n near 1):
    /// there the force's higher derivatives are infinite, and the integrator smooths the
    /// ends by a change of the time variable (or, with that off, grades its steps toward
    /// them; docs/model.md#time-stepping). `None` (the default) when the ends are smooth
    /// or are where the integration starts and stops anyway.
    fn end_power(&self) -> Option<f64> {
        None
    }

    /// Force f(t) (N) for a total impulse `impulse` P (N s).
    fn force(&self, t: f64, impulse: f64) -> f64 {
        impulse / self.duration() * self.shape(t / self.duration())
    }

    /// Cumulative impulse p(t) (N s) for a total impulse `impulse` P (N s).
    fn impulse_until(&self, t: f64, impulse: f64) -> f64 {
        impulse * self.cumulative(t / self.duration())
    }
}

/// Safeguarded Newton iteration (bisection fallback) for Phi(s) = q on [0, 1].
pub fn invert_cumulative<P: ForceProfile + ?Sized>(profile: &P, q: f64) -> f64 {
    if q <= 0.0 {
        return 0.0;
    }
    if q >= 1.0 {
        return 1.0;
    }
    let (mut lo, mut hi) = (0.0_f64, 1.0_f64);
    let mut s = q; // exact for a rectangle, a fair start for the rest
    for _ in 0..200 {
        let r = profile.cumulative(s) - q;
        if r == 0.0 {
            break;
        }
        if r < 0.0 {
            lo = s;
        } else {
            hi = s;
        }
        if hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
        let d = profile.shape(s);
        let newton = s - r / d;
        s = if d > 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
    }
    // The smallest time: a zero-force plateau at level q resolves to its start.
    if profile.cumulative(lo) >= q {
        lo
    } else {
        s
    }
}

/// The built-in profiles, selected by name in scene files.
#[derive(Debug, Clone, PartialEq)]
pub enum Profile {
    /// f ~ sin(pi t / tau).
    HalfSine(HalfSine),
    /// Elastic Hertz impact, f ~ delta^(3/2).
    Hertz(Hertz),
    /// f ~ sin^n(pi t / tau).
    SinePower(SinePower),
    /// Constant force.
    Rectangle(Rectangle),
    /// Linear interpolation of a (time, force) table.
    Tabulated(Tabulated),
}

macro_rules! delegate {
    ($self:ident, $p:ident => $e:expr) => {
        match $self {
            Profile::HalfSine($p) => $e,
            Profile::Hertz($p) => $e,
            Profile::SinePower($p) => $e,
            Profile::Rectangle($p) => $e,
            Profile::Tabulated($p) => $e,
        }
    };
}

impl ForceProfile for Profile {
    fn duration(&self) -> f64 {
        delegate!(self, p => p.duration())
    }
    #[inline]
    fn shape(&self, s: f64) -> f64 {
        delegate!(self, p => p.shape(s))
    }
    fn cumulative(&self, s: f64) -> f64 {
        delegate!(self, p => p.cumulative(s))
    }
    fn time_at_cumulative(&self, q: f64) -> f64 {
        delegate!(self, p => p.time_at_cumulative(q))
    }
    fn breakpoints(&self) -> &[f64] {
        delegate!(self, p => p.breakpoints())
    }
    fn end_power(&self) -> Option<f64> {
        delegate!(self, p => p.end_power())
    }
}

impl Profile {
    /// The profile's kind.
    pub fn kind(&self) -> ProfileKind {
        match self {
            Profile::HalfSine(_) => ProfileKind::HalfSine,
            Profile::Hertz(_) => ProfileKind::Hertz,
            Profile::SinePower(_) => ProfileKind::SinePower,
            Profile::Rectangle(_) => ProfileKind::Rectangle,
            Profile::Tabulated(_) => ProfileKind::Tabulated,
        }
    }

    /// The profile's name as written in scene files.
    pub fn name(&self) -> &'static str {
        self.kind().name()
    }
}

/// The kinds of built-in profiles, by the names scene files give them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ProfileKind {
    /// `half-sine`.
    HalfSine,
    /// `hertz`.
    Hertz,
    /// `sine-power`.
    SinePower,
    /// `rectangle`.
    Rectangle,
    /// `tabulated`.
    Tabulated,
}

impl ProfileKind {
    /// All kinds, in the order of the work-precision figure's panels.
    pub const ALL: [ProfileKind; 5] = [
        ProfileKind::HalfSine,
        ProfileKind::Hertz,
        ProfileKind::SinePower,
        ProfileKind::Rectangle,
        ProfileKind::Tabulated,
    ];

    /// The name in scene files, reports and CSVs.
    pub fn name(&self) -> &'static str {
        match self {
            ProfileKind::HalfSine => "half-sine",
            ProfileKind::Hertz => "hertz",
            ProfileKind::SinePower => "sine-power",
            ProfileKind::Rectangle => "rectangle",
            ProfileKind::Tabulated => "tabulated",
        }
    }
}

/// The field a profile's duration is named by in errors (as in the scene file).
pub const DURATION_FIELD: &str = "contact.profile.duration";

/// Checks a contact duration tau (s): finite and > 0.
fn valid_duration(duration: f64) -> Result<f64, Error> {
    positive(DURATION_FIELD, duration, "s")
}

/// Default exponent of `sine-power` (sin^1.5, the common approximation of a Hertz pulse).
pub const DEFAULT_SINE_POWER_EXPONENT: f64 = 1.5;

/// A profile as written in a scene file (`[contact.profile]`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "kebab-case", deny_unknown_fields)]
pub enum ProfileSpec {
    /// `shape = "half-sine"`.
    HalfSine {
        /// Contact duration (s).
        duration: f64,
    },
    /// `shape = "hertz"`; without `duration` the balls' material sets it.
    Hertz {
        /// Contact duration (s); `None`: from the material.
        #[serde(default)]
        duration: Option<f64>,
    },
    /// `shape = "sine-power"`, `exponent` (default 1.5); without `duration` the balls'
    /// material sets it (the Hertz contact time).
    SinePower {
        /// Contact duration (s); `None`: from the material.
        #[serde(default)]
        duration: Option<f64>,
        /// Exponent n > 0 of sin^n.
        #[serde(default)]
        exponent: Option<f64>,
    },
    /// `shape = "rectangle"`.
    Rectangle {
        /// Contact duration (s).
        duration: f64,
    },
    /// `shape = "tabulated"`, `file` relative to the scene; `duration` stretches the
    /// table's time axis (default: the table's own span).
    Tabulated {
        /// CSV file with header `time,force`.
        file: PathBuf,
        /// Contact duration (s); default the table's span.
        #[serde(default)]
        duration: Option<f64>,
    },
}

impl ProfileSpec {
    /// The duration the scene gives (s), if any.
    pub fn duration(&self) -> Option<f64> {
        match self {
            ProfileSpec::HalfSine { duration } | ProfileSpec::Rectangle { duration } => {
                Some(*duration)
            }
            ProfileSpec::Hertz { duration }
            | ProfileSpec::SinePower { duration, .. }
            | ProfileSpec::Tabulated { duration, .. } => *duration,
        }
    }

    /// Whether the shape may take its duration from the balls' material: `hertz`, and
    /// `sine-power` (the common approximation of the Hertz pulse).
    pub fn takes_material_duration(&self) -> bool {
        matches!(
            self,
            ProfileSpec::Hertz { .. } | ProfileSpec::SinePower { .. }
        )
    }

    /// Builds the profile; `base` is the directory relative file names are resolved in.
    /// Errors name the scene's field (`contact.profile.duration`, `.exponent`, `.file`);
    /// `hertz` and `sine-power` without a duration need [`ProfileSpec::build_with`].
    pub fn build(&self, base: &Path) -> Result<Profile, Error> {
        self.build_with(base, None)
    }

    /// Builds the profile with `derived` (s) as the duration of a `hertz` or `sine-power`
    /// spec that gives none (the Hertz contact time of the balls' material).
    pub fn build_with(&self, base: &Path, derived: Option<f64>) -> Result<Profile, Error> {
        let material_duration = |given: &Option<f64>| {
            given.or(derived).ok_or_else(|| {
                Error::invalid(
                    DURATION_FIELD,
                    "missing",
                    "> 0 s, or the balls' material (balls.youngs_modulus and \
                     balls.poisson_ratio), from which hertz and sine-power take the contact time",
                )
            })
        };
        Ok(match self {
            ProfileSpec::HalfSine { duration } => Profile::HalfSine(HalfSine::new(*duration)?),
            ProfileSpec::Hertz { duration } => {
                Profile::Hertz(Hertz::new(material_duration(duration)?)?)
            }
            ProfileSpec::SinePower { duration, exponent } => Profile::SinePower(SinePower::new(
                material_duration(duration)?,
                exponent.unwrap_or(DEFAULT_SINE_POWER_EXPONENT),
            )?),
            ProfileSpec::Rectangle { duration } => Profile::Rectangle(Rectangle::new(*duration)?),
            ProfileSpec::Tabulated { file, duration } => {
                Profile::Tabulated(Tabulated::from_csv_file(&base.join(file), *duration)?)
            }
        })
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Every constructor refuses a duration that is not finite and > 0, naming the field,
    /// the value and the range, and accepts a positive one.
    #[test]
    fn constructors_validate_the_duration() {
        let table = [(0.0, 1.0), (1.0, 1.0)];
        let src = Path::new("t.csv");
        for bad in [0.0, -2.5e-4, f64::NAN, f64::INFINITY] {
            let results: [Result<(), Error>; 5] = [
                HalfSine::new(bad).map(drop),
                Hertz::new(bad).map(drop),
                Rectangle::new(bad).map(drop),
                SinePower::new(bad, 1.5).map(drop),
                Tabulated::new(&table, Some(bad), src).map(drop),
            ];
            for r in results {
                match r {
                    Err(Error::InvalidParameter {
                        field,
                        value,
                        expected,
                    }) => {
                        assert_eq!(field, "contact.profile.duration");
                        assert_eq!(value, bad.to_string());
                        let range = if bad.is_finite() {
                            "> 0 s"
                        } else {
                            "a finite number"
                        };
                        assert_eq!(expected, range);
                    }
                    other => panic!("duration {bad}: {other:?}"),
                }
            }
        }
        assert_eq!(HalfSine::new(2.5e-4).unwrap().duration(), 2.5e-4);
        assert_eq!(Hertz::new(2.5e-4).unwrap().duration(), 2.5e-4);
        assert_eq!(Rectangle::new(2.5e-4).unwrap().duration(), 2.5e-4);
        assert_eq!(SinePower::new(2.5e-4, 1.5).unwrap().duration(), 2.5e-4);
        let t = Tabulated::new(&table, Some(2.5e-4), src).unwrap();
        assert_eq!(t.duration(), 2.5e-4);
        // The duration is checked before the file is read: no I/O error for a bad one.
        let missing = Path::new("/nonexistent/profile.csv");
        let e = Tabulated::from_csv_file(missing, Some(0.0)).unwrap_err();
        assert!(matches!(e, Error::InvalidParameter { .. }), "{e:?}");
        assert!(matches!(
            Tabulated::from_csv_file(missing, None),
            Err(Error::Io { .. })
        ));
    }

    /// A caller's own profile, which keeps the default inverse: phi(s) = 3 s^2, Phi(s) = s^3,
    /// so Phi^-1(q) = q^(1/3) exactly.
    struct Cubic;

    impl ForceProfile for Cubic {
        fn duration(&self) -> f64 {
            1.0
        }
        fn shape(&self, s: f64) -> f64 {
            if (0.0..=1.0).contains(&s) {
                3.0 * s * s
            } else {
                0.0
            }
        }
        fn cumulative(&self, s: f64) -> f64 {
            let s = s.clamp(0.0, 1.0);
            s * s * s
        }
    }

    /// The default inverse keeps full relative accuracy down to tiny impulse fractions (a
    /// stick after a tiny slip): s from 0.9 down to 1e-30, against q^(1/3). The bracket's
    /// stop is relative to its upper end; a stop of 4 eps / hi would end the search at
    /// s ~ 2e-8, far above a root at 1e-10.
    #[test]
    fn default_inverse_is_relatively_accurate_at_tiny_fractions() {
        for s in [0.9, 0.5, 1e-2, 1e-5, 1e-8, 1e-10, 1e-15, 1e-30] {
            let q: f64 = s * s * s;
            let want = q.cbrt();
            let got = invert_cumulative(&Cubic, q);
            assert!(
                (got - want).abs() <= 4.0 * f64::EPSILON * want,
                "q = {q:e}: s = {got:e}, q^(1/3) = {want:e}"
            );
            assert_eq!(Cubic.time_at_cumulative(q), got);
        }
    }

    /// The default inverse is Newton's method, safeguarded: from s = q it converges in a few
    /// steps where bisection alone (the fallback) would take about 50 to reach 4 eps.
    #[test]
    fn default_inverse_converges_like_newton() {
        struct Counted(std::cell::Cell<usize>);
        impl ForceProfile for Counted {
            fn duration(&self) -> f64 {
                1.0
            }
            fn shape(&self, s: f64) -> f64 {
                Cubic.shape(s)
            }
            fn cumulative(&self, s: f64) -> f64 {
                self.0.set(self.0.get() + 1);
                Cubic.cumulative(s)
            }
        }
        for q in [0.3, 0.05, 0.9] {
            let p = Counted(std::cell::Cell::new(0));
            let got = invert_cumulative(&p, q);
            assert!((got - q.cbrt()).abs() <= 4.0 * f64::EPSILON * got);
            assert!(p.0.get() <= 15, "q = {q}: {} evaluations", p.0.get());
        }
    }

    /// Composite Gauss-Legendre quadrature of phi over [a, b] (independent of `cumulative`),
    /// split at the profile's breakpoints and, for algebraic ends, at points graded toward
    /// them (2^-k and 1 - 2^-k, k = 2..20), with compensated summation.
    pub fn integrate_shape(p: &dyn ForceProfile, a: f64, b: f64, panels: usize) -> f64 {
        let graded: Vec<f64> = match p.end_power() {
            Some(_) => (2..=20)
                .map(|k| 0.5_f64.powi(k))
                .flat_map(|h| [h, 1.0 - h])
                .collect(),
            None => Vec::new(),
        };
        let mut cuts = vec![a];
        cuts.extend(
            p.breakpoints()
                .iter()
                .chain(&graded)
                .copied()
                .filter(|&x| x > a && x < b),
        );
        cuts.sort_by(f64::total_cmp);
        cuts.push(b);
        let nodes = [
            (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
            (-0.538_469_310_105_683, 0.478_628_670_499_366_5),
            (0.0, 0.568_888_888_888_888_9),
            (0.538_469_310_105_683, 0.478_628_670_499_366_5),
            (0.906_179_845_938_664, 0.236_926_885_056_189_1),
        ];
        let (mut sum, mut carry) = (0.0_f64, 0.0_f64);
        for w in cuts.windows(2) {
            let h = (w[1] - w[0]) / panels as f64;
            for i in 0..panels {
                let lo = w[0] + h * i as f64;
                for (z, wt) in nodes {
                    let term = 0.5 * h * wt * p.shape(lo + 0.5 * h * (1.0 + z));
                    let t = sum + term;
                    carry += if sum.abs() >= term.abs() {
                        (sum - t) + term
                    } else {
                        (term - t) + sum
                    };
                    sum = t;
                }
            }
        }
        sum + carry
    }

    /// Checks the contract of a profile: Phi(0) = 0, Phi(1) = 1, Phi(s) agrees with the
    /// quadrature of phi, the inverse round-trips.
    pub fn check_profile(p: &dyn ForceProfile, tol: f64) {
        assert_eq!(p.cumulative(0.0), 0.0);
        assert!((p.cumulative(1.0) - 1.0).abs() <= 1e-15);
        assert_eq!(p.shape(-0.1), 0.0);
        assert_eq!(p.shape(1.1), 0.0);
        let mut last = 0.0;
        let mut prev_phi = 0.0;
        for i in 1..=40 {
            let s = i as f64 / 40.0;
            let want = integrate_shape(p, 0.0, s, 2000);
            let got = p.cumulative(s);
            assert!(
                (got - want).abs() < tol,
                "Phi({s}) = {got}, quadrature {want}"
            );
            assert!(got >= last, "Phi not monotone at {s}");
            last = got;
            let q = prev_phi + 0.37 * (got - prev_phi);
            let back = p.time_at_cumulative(q);
            assert!(
                (p.cumulative(back) - q).abs() < 1e-14,
                "inverse at q = {q}: s = {back}, Phi = {}",
                p.cumulative(back)
            );
            prev_phi = got;
        }
    }
}
