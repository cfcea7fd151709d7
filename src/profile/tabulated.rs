//! A force profile read from a (time, force) table, linearly interpolated.

use crate::base::error::Error;
use crate::profile::force::valid_duration;
use crate::profile::force::ForceProfile;
use std::path::{Path, PathBuf};

/// Linear interpolation of (time, force) points, normalised to unit impulse.
///
/// The table's time axis is stretched to `duration` when given (else its own span) and its
/// force scaled so the impulse is P. The cumulative impulse is the exact integral of the
/// interpolant (trapezoids, and a quadratic inside a segment); the inverse solves that
/// quadratic. Interior knots are breakpoints (kinks of f).
#[derive(Debug, Clone, PartialEq)]
pub struct Tabulated {
    duration: f64,
    /// Knots s_i = t_i / t_last, s_0 = 0, s_last = 1.
    s: Vec<f64>,
    /// Normalised force at the knots.
    phi: Vec<f64>,
    /// Phi at the knots (exact trapezoid sums), last = 1.
    cum: Vec<f64>,
    /// Interior knots.
    breaks: Vec<f64>,
}

impl Tabulated {
    /// A profile from (time (s), force (N)) points: at least two, time finite and strictly
    /// increasing from 0 (consecutive times at least 1e-9 of the span apart),
    /// force finite and >= 0, positive area. `duration` (s), finite and > 0, stretches the
    /// time axis (default the table's span). `source` names the table in errors.
    ///
    /// Errors: [`Error::InvalidParameter`] naming `contact.profile.duration`;
    /// [`Error::ProfileTable`] at line 0 for the points, naming the point.
    ///
    /// ```
    /// use billiard_contact::profile::{ForceProfile, Tabulated};
    /// use std::path::Path;
    /// // a triangle: f = 0 -> 2 -> 0 N over 2 s, stretched to 1 ms
    /// let p = Tabulated::new(&[(0.0, 0.0), (1.0, 2.0), (2.0, 0.0)], Some(1e-3), Path::new("t"))?;
    /// assert_eq!(p.cumulative(0.5), 0.5);
    /// assert!(Tabulated::new(&[(0.0, 1.0), (1.0, -1.0)], None, Path::new("t")).is_err());
    /// # Ok::<(), billiard_contact::Error>(())
    /// ```
    pub fn new(points: &[(f64, f64)], duration: Option<f64>, source: &Path) -> Result<Self, Error> {
        let duration = duration.map(valid_duration).transpose()?;
        let whole = |message: String| Error::ProfileTable {
            path: source.to_path_buf(),
            line: 0,
            message,
        };
        for (k, &(t, f)) in points.iter().enumerate() {
            let prev = k.checked_sub(1).map(|j| points[j].0);
            if let Some(fault) = point_fault(prev, t, f) {
                return Err(whole(format!("point {k}: {fault}")));
            }
        }
        if points.len() < 2 {
            return Err(whole(format!(
                "{} data row(s): a tabulated profile needs at least two (time, force) points",
                points.len()
            )));
        }
        let span = points[points.len() - 1].0;
        if let Some(k) = unresolved_step(points) {
            return Err(whole(format!(
                "point {k} (time {} s) is within {MIN_TIME_STEP:e} of the span ({span} s) of the \
                 previous time: the time axis cannot resolve it",
                points[k].0
            )));
        }
        let area: f64 = points
            .windows(2)
            .map(|w| 0.5 * (w[1].0 - w[0].0) * (w[0].1 + w[1].1))
            .sum();
        if !(area > 0.0 && area.is_finite()) {
            return Err(whole(format!(
                "the force integrates to {area} N s: a profile needs a positive impulse"
            )));
        }
        let s: Vec<f64> = points.iter().map(|p| p.0 / span).collect();
        // phi = f * span / area, so that integral_0^1 phi ds = 1.
        // Divided first: f * span overflows for forces near f64::MAX (a force of 1.8e308 N
        // would give phi = inf, and NaN after normalisation).
        let phi: Vec<f64> = points.iter().map(|p| p.1 / area * span).collect();
        if let Some(k) = phi.iter().position(|x| !x.is_finite()) {
            return Err(whole(format!(
                "point {k} (force {} N) is too large against the table's impulse {area} N s",
                points[k].1
            )));
        }
        let mut cum = Vec::with_capacity(s.len());
        let mut acc = 0.0;
        cum.push(0.0);
        for i in 1..s.len() {
            acc += 0.5 * (s[i] - s[i - 1]) * (phi[i - 1] + phi[i]);
            cum.push(acc);
        }
        // Round-off: the exact total is 1; spread the residue proportionally.
        let total = acc;
        for c in cum.iter_mut() {
            *c /= total;
        }
        let phi: Vec<f64> = phi.iter().map(|p| p / total).collect();
        if let Some(last) = cum.last_mut() {
            *last = 1.0;
        }
        let breaks = s[1..s.len() - 1].to_vec();
        Ok(Tabulated {
            duration: duration.unwrap_or(span),
            s,
            phi,
            cum,
            breaks,
        })
    }

    /// Reads a CSV with the header `time,force` (seconds, newtons). Errors name the line;
    /// `duration` is checked as in [`Tabulated::new`] before the file is read.
    pub fn from_csv_file(path: &Path, duration: Option<f64>) -> Result<Self, Error> {
        let duration = duration.map(valid_duration).transpose()?;
        let text = std::fs::read_to_string(path).map_err(|e| {
            Error::io_doing(
                path,
                "cannot read the profile table (contact.profile.file, relative to the scene)",
                e,
            )
        })?;
        let points = parse_table(&text, path)?;
        Tabulated::new(&points, duration, path)
    }

    /// Number of knots.
    pub fn len(&self) -> usize {
        self.s.len()
    }

    /// Always false: a table has at least two knots.
    pub fn is_empty(&self) -> bool {
        self.s.is_empty()
    }

    /// Index k of the segment [s_k, s_k+1] holding s (s in [0, 1]).
    fn segment(&self, s: f64) -> usize {
        let k = self.s.partition_point(|&x| x <= s);
        k.saturating_sub(1).min(self.s.len() - 2)
    }
}

/// Smallest step between consecutive times, relative to the table's span. Closer knots
/// (times 0, 2e-5, .., 1e300, say) put breakpoints below the integrators' resolution and
/// make the adaptive methods stop with a step-size underflow.
pub(crate) const MIN_TIME_STEP: f64 = 1e-9;

/// The index of the first point closer than [`MIN_TIME_STEP`] of the span to its
/// predecessor.
fn unresolved_step(points: &[(f64, f64)]) -> Option<usize> {
    let span = points.last()?.0;
    (1..points.len()).find(|&k| points[k].0 - points[k - 1].0 < MIN_TIME_STEP * span)
}

/// What is wrong with the point (time `t` (s), force `f` (N)) of a table, after a point at
/// time `prev` (None: it is the first), or None.
fn point_fault(prev: Option<f64>, t: f64, f: f64) -> Option<String> {
    if !t.is_finite() {
        return Some(format!("time {t} is not finite"));
    }
    if !f.is_finite() {
        return Some(format!("force {f} is not finite"));
    }
    if f < 0.0 {
        return Some(format!("force {f} N is negative: force must be >= 0"));
    }
    match prev {
        None if t != 0.0 => Some(format!("time {t} s: the table must start at time 0")),
        Some(t_prev) if t <= t_prev => Some(format!(
            "time {t} s after {t_prev} s: times must be strictly increasing"
        )),
        _ => None,
    }
}

/// Parses `time,force` CSV text into points, validating every line.
pub fn parse_table(text: &str, path: &Path) -> Result<Vec<(f64, f64)>, Error> {
    let err = |line: u64, message: String| Error::ProfileTable {
        path: PathBuf::from(path),
        line,
        message,
    };
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    match lines.next() {
        Some((i, header)) => {
            let cells: Vec<String> = header
                .split(',')
                .map(|c| c.trim().trim_start_matches('\u{feff}').to_ascii_lowercase())
                .collect();
            if cells != ["time", "force"] {
                return Err(err(
                    i as u64 + 1,
                    format!(
                        "header `{}`: expected `time,force` (seconds, newtons)",
                        header.trim()
                    ),
                ));
            }
        }
        None => {
            return Err(err(
                0,
                "empty file: expected the header `time,force`".into(),
            ))
        }
    }
    let mut points: Vec<(f64, f64)> = Vec::new();
    let mut line_of: Vec<u64> = Vec::new();
    for (i, line) in lines {
        let n = i as u64 + 1;
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        if cells.len() != 2 {
            return Err(err(
                n,
                format!("`{}`: expected two cells, time and force", line.trim()),
            ));
        }
        let num = |cell: &str, what: &str| -> Result<f64, Error> {
            let v: f64 = cell
                .parse()
                .map_err(|_| err(n, format!("{what} `{cell}` is not a number")))?;
            if !v.is_finite() {
                return Err(err(n, format!("{what} {v} is not finite")));
            }
            Ok(v)
        };
        let t = num(cells[0], "time")?;
        let f = num(cells[1], "force")?;
        if let Some(fault) = point_fault(points.last().map(|p| p.0), t, f) {
            return Err(err(n, fault));
        }
        points.push((t, f));
        line_of.push(n);
    }
    if let Some(k) = unresolved_step(&points) {
        let span = points[points.len() - 1].0;
        return Err(err(
            line_of[k],
            format!(
                "time {} s is within {MIN_TIME_STEP:e} of the table's span ({span} s) of the \
                 previous time {} s: the time axis cannot resolve it",
                points[k].0,
                points[k - 1].0
            ),
        ));
    }
    Ok(points)
}

impl ForceProfile for Tabulated {
    fn duration(&self) -> f64 {
        self.duration
    }

    fn shape(&self, s: f64) -> f64 {
        if !(0.0..=1.0).contains(&s) {
            return 0.0;
        }
        let k = self.segment(s);
        let (s0, s1) = (self.s[k], self.s[k + 1]);
        let x = (s - s0) / (s1 - s0);
        self.phi[k] + x * (self.phi[k + 1] - self.phi[k])
    }

    fn cumulative(&self, s: f64) -> f64 {
        if s <= 0.0 {
            return 0.0;
        }
        if s >= 1.0 {
            return 1.0;
        }
        let k = self.segment(s);
        let h = s - self.s[k];
        let slope = (self.phi[k + 1] - self.phi[k]) / (self.s[k + 1] - self.s[k]);
        (self.cum[k] + h * (self.phi[k] + 0.5 * slope * h)).min(1.0)
    }

    fn time_at_cumulative(&self, q: f64) -> f64 {
        if q <= 0.0 {
            return 0.0;
        }
        if q >= 1.0 {
            return 1.0;
        }
        // First segment whose end reaches q.
        let k = self
            .cum
            .partition_point(|&c| c < q)
            .clamp(1, self.s.len() - 1)
            - 1;
        let r = q - self.cum[k];
        let width = self.s[k + 1] - self.s[k];
        let slope = (self.phi[k + 1] - self.phi[k]) / width;
        // (slope/2) h^2 + phi_k h - r = 0, in the form without cancellation.
        let disc = (self.phi[k] * self.phi[k] + 2.0 * slope * r).max(0.0);
        let den = self.phi[k] + disc.sqrt();
        let h = if den > 0.0 { 2.0 * r / den } else { 0.0 };
        (self.s[k] + h.clamp(0.0, width)).min(1.0)
    }

    fn breakpoints(&self) -> &[f64] {
        &self.breaks
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(points: &[(f64, f64)]) -> Tabulated {
        Tabulated::new(points, None, Path::new("test.csv")).unwrap()
    }

    #[test]
    fn contract_with_kinks_plateau_and_spike() {
        let p = table(&[
            (0.0, 0.0),
            (1.0, 2.0),
            (2.0, 2.0),
            (2.5, 0.0),
            (3.0, 0.0),
            (3.1, 9.0),
            (3.2, 0.0),
            (4.0, 1.0),
        ]);
        crate::profile::force::tests::check_profile(&p, 1e-14);
        assert_eq!(p.breakpoints().len(), 6);
        // Eight knots as given: the accessors count them.
        assert_eq!((p.len(), p.is_empty()), (8, false));
        // On the zero-force plateau (2.5 .. 3.0) the inverse gives the plateau's start.
        let q = p.cumulative(2.75 / 4.0);
        assert!((p.time_at_cumulative(q) - 2.5 / 4.0).abs() < 1e-12);
    }

    #[test]
    fn triangle_by_hand() {
        // f: 0 -> 2 -> 0 over [0, 2]: area 2, phi peaks at 2 at s = 1/2; Phi(1/4) = 1/8.
        let p = table(&[(0.0, 0.0), (1.0, 2.0), (2.0, 0.0)]);
        assert!((p.shape(0.5) - 2.0).abs() < 1e-15);
        assert!((p.cumulative(0.25) - 0.125).abs() < 1e-15);
        assert!((p.time_at_cumulative(0.125) - 0.25).abs() < 1e-15);
        assert_eq!(p.duration(), 2.0);
    }

    /// The inversion near q = 0 of a table that starts at zero force and rises slowly:
    /// f = 0.001 t on [0, 1] of a 3-unit pulse of area 1.001, so phi(s) = f(3 s) 3 / 1.001 =
    /// 0.009 s / 1.001 and Phi(s) = 0.0045 s^2 / 1.001 there, inverted by hand:
    /// s = sqrt(1.001 q / 0.0045). At q = 1e-300 that is 1.49e-149 (to 1e-14 relative); at
    /// the smallest positive q (4.9e-324), where the quadratic's discriminant 2 phi' q
    /// underflows to zero, it is 3.3e-161: the answer must stay near 0, not jump to the
    /// segment's end (1/3).
    #[test]
    fn inverts_near_zero_where_the_force_starts_at_zero() {
        let p = table(&[(0.0, 0.0), (1.0, 0.001), (2.0, 1.0), (3.0, 0.0)]);
        let exact = |q: f64| (1.001 * q / 0.0045).sqrt();
        let got = p.time_at_cumulative(1e-300);
        assert!((got / exact(1e-300) - 1.0).abs() < 1e-14, "{got}");
        let tiny = f64::from_bits(1);
        let got = p.time_at_cumulative(tiny);
        assert!(
            got <= 1e-150,
            "{got} at q = {tiny:e}, exact {:e}",
            exact(tiny)
        );
    }

    /// Points given directly get the checks `parse_table` makes, naming the point.
    #[test]
    fn new_checks_the_points() {
        let path = Path::new("p.csv");
        let cases: [(&[(f64, f64)], &str); 6] = [
            (
                &[(0.0, 1.0), (0.0, 2.0)],
                "point 1: time 0 s after 0 s: times must be strictly increasing",
            ),
            (
                &[(0.0, 1.0), (1.0, -2.0)],
                "point 1: force -2 N is negative",
            ),
            (
                &[(0.0, 1.0), (1.0, f64::NAN)],
                "point 1: force NaN is not finite",
            ),
            (
                &[(0.0, 1.0), (f64::INFINITY, 1.0)],
                "point 1: time inf is not finite",
            ),
            (
                &[(0.5, 1.0), (1.0, 1.0)],
                "point 0: time 0.5 s: the table must start at time 0",
            ),
            (
                &[(0.0, 1.0), (2.0, 1.0), (1.0, 1.0)],
                "point 2: time 1 s after 2 s",
            ),
        ];
        for (points, what) in cases {
            match Tabulated::new(points, None, path) {
                Err(Error::ProfileTable {
                    line: 0, message, ..
                }) => {
                    assert!(message.starts_with(what), "{points:?}: {message}");
                }
                other => panic!("{points:?}: {other:?}"),
            }
        }
    }
}
