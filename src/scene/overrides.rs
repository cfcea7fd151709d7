//! Solver settings as a scene's `[solver]` section or the command line gives them, and the
//! reading of names (methods, dampings) from a scene file.

use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::settings::SolverSettings;
use serde::de;
use serde::{Deserialize, Deserializer};

/// Solver settings as a scene's `[solver]` section or the command line gives them: each
/// one given replaces the base's (the defaults for a scene, the scene's on the command
/// line).
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolverOverrides {
    /// Method.
    #[serde(default, deserialize_with = "optional_name")]
    pub method: Option<Method>,
    /// Relative tolerance.
    pub rtol: Option<f64>,
    /// Absolute tolerance on the scaled variables; default: a new `rtol` when one is
    /// given, the base's otherwise.
    pub atol: Option<f64>,
    /// RK4 steps over the contact.
    pub steps: Option<u32>,
    /// The smoothing time transform of pulses with algebraic ends.
    pub time_transform: Option<bool>,
}

impl SolverOverrides {
    /// `base` with these overrides, validated by [`SolverSettings::new`]: a new rtol
    /// carries atol with it unless atol is given too; `breakpoints` stays the base's, and
    /// so does `time_transform` unless given.
    ///
    /// ```
    /// use billiard_contact::{Method, SolverOverrides, SolverSettings};
    /// let base = SolverSettings::new(Method::Dop853, 1e-10, 1e-12, 1000).unwrap();
    /// let tighter = SolverOverrides { rtol: Some(1e-12), ..Default::default() };
    /// let s = tighter.apply(&base).unwrap();
    /// assert_eq!((s.method(), s.rtol(), s.atol(), s.steps()), (Method::Dop853, 1e-12, 1e-12, 1000));
    /// let rk4 = SolverOverrides { method: Some(Method::Rk4), ..Default::default() };
    /// assert_eq!(rk4.apply(&base).unwrap().atol(), 1e-12);
    /// ```
    pub fn apply(&self, base: &SolverSettings) -> Result<SolverSettings, Error> {
        let rtol = self.rtol.unwrap_or(base.rtol());
        let atol = self.atol.unwrap_or(if self.rtol.is_some() {
            rtol
        } else {
            base.atol()
        });
        let settings = SolverSettings::new(
            self.method.unwrap_or(base.method()),
            rtol,
            atol,
            self.steps.unwrap_or(base.steps()),
        )?;
        Ok(settings
            .with_breakpoints(base.breakpoints())
            .with_time_transform(self.time_transform.unwrap_or(base.time_transform())))
    }

    /// The overrides given here that a run with `settings` does not use, each as its field
    /// (`rtol`, `atol`, `time_transform`) and what it has no effect with: tolerances with rk4
    /// and with the closed form of a profile (under a contact law, `law`, the closed form
    /// integrates the normal law with dop853 at them), the time transform with the closed
    /// form or under a contact law
    /// (`law`: a law finds the end of the contact as an event, so its runs step in their own
    /// time: docs/contact-law.md#time-stepping). `billiard-contact` warns on stderr, the
    /// Python package with a `UserWarning`.
    ///
    /// ```
    /// use billiard_contact::{Method, SolverOverrides, SolverSettings};
    /// let o = SolverOverrides { rtol: Some(1e-8), time_transform: Some(false), ..Default::default() };
    /// let dop853 = SolverSettings::default();
    /// assert!(o.unused(&dop853, false).is_empty());
    /// let unused = o.unused(&dop853, true);
    /// assert_eq!(unused.len(), 1);
    /// assert_eq!(unused[0].0, "time_transform");
    /// assert!(unused[0].1.starts_with("a contact law"));
    /// let cf = dop853.with_method(Method::ClosedForm);
    /// let names = |u: Vec<(&'static str, String)>| u.iter().map(|u| u.0).collect::<Vec<_>>();
    /// assert_eq!(names(o.unused(&cf, false)), ["rtol", "time_transform"]);
    /// assert_eq!(names(o.unused(&cf, true)), ["time_transform"]);
    /// ```
    pub fn unused(&self, settings: &SolverSettings, law: bool) -> Vec<(&'static str, String)> {
        let method = settings.method();
        let by_method = || {
            format!(
                "the method {method} (tolerances act on dopri5 and dop853; the time transform \
                 on the time-stepping methods)"
            )
        };
        let mut v = Vec::new();
        // Under a law the closed form integrates the normal law with dop853 at the run's
        // tolerances.
        let tolerances_unused = method == Method::Rk4 || (method == Method::ClosedForm && !law);
        for (field, given) in [("rtol", self.rtol.is_some()), ("atol", self.atol.is_some())] {
            if given && tolerances_unused {
                v.push((field, by_method()));
            }
        }
        if self.time_transform.is_some() {
            if method == Method::ClosedForm {
                v.push(("time_transform", by_method()));
            } else if law {
                v.push((
                    "time_transform",
                    "a contact law (a law finds the end of the contact as an event, so its \
                     runs step in their own time and need no transform: \
                     docs/contact-law.md#time-stepping)"
                        .to_string(),
                ));
            }
        }
        v
    }
}

/// A value of a unit-variant enum, given by its name: a string first, so that another
/// type is reported as "expected a string" (TOML's own enum reading says only "wanted
/// string or table"), then the variant of that name.
pub(crate) fn name<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    deserializer: D,
) -> Result<T, D::Error> {
    let name = String::deserialize(deserializer)?;
    T::deserialize(de::IntoDeserializer::<D::Error>::into_deserializer(name))
}

/// [`name`] of an optional key.
pub(crate) fn optional_name<'de, D: Deserializer<'de>, T: Deserialize<'de>>(
    deserializer: D,
) -> Result<Option<T>, D::Error> {
    name(deserializer).map(Some)
}
