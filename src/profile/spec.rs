//! The built-in profiles as one type ([`Profile`]), their kinds, and the profile as a scene
//! file writes it ([`ProfileSpec`]).

use crate::base::error::Error;
use crate::base::fields::DURATION_FIELD;
use crate::base::names::did_you_mean;
use crate::profile::force::ForceProfile;
use crate::profile::half_sine::HalfSine;
use crate::profile::hertz::Hertz;
use crate::profile::rectangle::Rectangle;
use crate::profile::sine_power::SinePower;
use crate::profile::tabulated::Tabulated;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

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

impl std::str::FromStr for ProfileKind {
    type Err = Error;
    /// The kind of its name in scene files; another name is refused naming the field
    /// `contact.profile.shape`, with the closest name when one is close.
    fn from_str(s: &str) -> Result<Self, Error> {
        let names = ProfileKind::ALL.map(|k| k.name());
        ProfileKind::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| {
                Error::invalid(
                    "contact.profile.shape",
                    format!("\"{s}\""),
                    format!("one of {}{}", names.join(", "), did_you_mean(s, &names)),
                )
            })
    }
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
}
