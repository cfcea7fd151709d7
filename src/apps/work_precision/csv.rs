//! The study's CSV: written with the contract's columns first, read back with the rows
//! the peers' script appended.

use crate::apps::work_precision::plan::StudyRow;
use crate::base::error::Error;
use crate::base::method::Method;
use crate::base::number::shortest;
use crate::base::settings::Stats;
use std::io::{Read, Write};
use std::path::Path;

/// The columns every study CSV starts with, in this order (docs/formats.md#work-precision-csv).
pub const COLUMNS: [&str; 9] = [
    "profile",
    "method",
    "rtol",
    "steps",
    "error",
    "stick_time_error",
    "rhs_evaluations",
    "accepted_steps",
    "seconds_per_contact",
];

/// Columns after [`COLUMNS`]: whether the integrator stepped to the profile's breakpoints,
/// the scene, rejected steps, timed samples and solves per sample, a note (why a run
/// failed), whether the time transform was on, and for a contact law the realised
/// restitution and the damping coefficient.
pub(crate) const EXTRA_COLUMNS: [&str; 9] = [
    "breakpoints",
    "scene",
    "rejected_steps",
    "samples",
    "solves_per_sample",
    "note",
    "time_transform",
    "restitution",
    "coefficient",
];

fn opt<T: ToString>(v: Option<T>) -> String {
    v.map(|x| x.to_string()).unwrap_or_default()
}

/// Writes the rows as CSV: [`COLUMNS`], then the extra columns (docs/formats.md#work-precision-csv). Empty cells: `rtol` of
/// rk4 and the closed form, `steps` of the adaptive methods and the closed form,
/// `stick_time_error` when sliding does not stop, `error` when the run failed.
pub fn write_csv<W: Write>(out: W, rows: &[StudyRow]) -> Result<W, Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record(COLUMNS.iter().chain(EXTRA_COLUMNS.iter()))?;
    for r in rows {
        for (name, v) in [
            ("error", r.error),
            ("stick_time_error", r.stick_time_error),
            ("seconds_per_contact", Some(r.seconds_per_contact)),
            ("restitution", r.restitution),
            ("coefficient", r.coefficient),
        ] {
            if let Some(x) = v {
                if !x.is_finite() && r.note.is_empty() {
                    return Err(Error::NonFinite {
                        field: format!("{name} of {} {} {:?}", r.profile, r.method, r.rtol),
                        value: x,
                    });
                }
            }
        }
        let seconds = if r.seconds_per_contact.is_finite() {
            shortest(r.seconds_per_contact)
        } else {
            String::new()
        };
        w.write_record([
            r.profile.clone(),
            r.method.clone(),
            opt(r.rtol.map(shortest)),
            opt(r.steps),
            opt(r.error.map(shortest)),
            opt(r.stick_time_error.map(shortest)),
            r.stats.rhs_evaluations.to_string(),
            r.stats.accepted_steps.to_string(),
            seconds,
            r.breakpoints.to_string(),
            r.scene.clone(),
            r.stats.rejected_steps.to_string(),
            r.samples.to_string(),
            r.solves_per_sample.to_string(),
            r.note.clone(),
            r.time_transform.to_string(),
            opt(r.restitution.map(shortest)),
            opt(r.coefficient.map(shortest)),
        ])?;
    }
    w.into_inner()
        .map_err(|e| Error::io("work_precision.csv", e.into_error()))
}

/// Whether `method` is a peer's (e.g. `scipy-DOP853`, from `benches/peers/`), not one of
/// this crate's methods.
pub(crate) fn is_peer_method(method: &str) -> bool {
    !Method::ALL.iter().any(|m| m.name() == method)
}

/// The study's own `rows` followed by the peers' rows of `existing` (an earlier CSV of the
/// same directory) for the scenes and profiles `rows` has, so that a new run of the study
/// keeps the rows a peer's script appended; also how many peer rows were dropped (their
/// scene or profile is not in this run).
pub(crate) fn with_peers_of(
    rows: Vec<StudyRow>,
    existing: Vec<StudyRow>,
) -> (Vec<StudyRow>, usize) {
    let ours = |r: &StudyRow| {
        rows.iter()
            .any(|o| o.scene == r.scene && o.profile == r.profile)
    };
    let (kept, dropped): (Vec<StudyRow>, Vec<StudyRow>) = existing
        .into_iter()
        .filter(|r| is_peer_method(&r.method))
        .partition(ours);
    let mut out = rows;
    out.extend(kept);
    (out, dropped.len())
}

/// Reads a study CSV (ours, possibly with rows appended by a peer's script). The columns of
/// [`COLUMNS`] are required (by name); of the extra columns, missing ones or empty cells
/// read as breakpoints = true, scene = "", zero counts, no note, time transform = true, no
/// restitution or coefficient (the defaults: a peer's rows, and files written before the
/// column existed). Errors name the line.
pub fn read_csv<R: Read>(input: R, path: &Path) -> Result<Vec<StudyRow>, Error> {
    let err = |line: u64, message: String| Error::BatchInput {
        path: path.to_path_buf(),
        line,
        message,
    };
    let mut rd = csv::ReaderBuilder::new().flexible(true).from_reader(input);
    let header = rd.headers().map_err(|e| err(1, e.to_string()))?.clone();
    let index = |name: &str| header.iter().position(|h| h.trim() == name);
    let mut required = [0usize; 9];
    for (slot, name) in required.iter_mut().zip(COLUMNS) {
        *slot = index(name).ok_or_else(|| err(1, format!("missing column `{name}`")))?;
    }
    let extra: Vec<Option<usize>> = EXTRA_COLUMNS.iter().map(|n| index(n)).collect();
    let mut rows = Vec::new();
    for rec in rd.records() {
        let rec = rec.map_err(|e| {
            let line = e.position().map(|p| p.line()).unwrap_or(0);
            err(line, e.to_string())
        })?;
        let line = rec.position().map(|p| p.line()).unwrap_or(0);
        let cell = |i: usize| rec.get(i).unwrap_or("").trim();
        let ext = |k: usize| extra[k].map(&cell).unwrap_or("");
        let number = |c: &str, name: &str| -> Result<Option<f64>, Error> {
            if c.is_empty() {
                return Ok(None);
            }
            c.parse::<f64>()
                .map(Some)
                .map_err(|_| err(line, format!("{name} `{c}` is not a number")))
        };
        let float = |i: usize, name: &str| number(cell(i), name);
        let int = |c: &str, name: &str| -> Result<u64, Error> {
            if c.is_empty() {
                return Ok(0);
            }
            c.parse::<u64>()
                .map_err(|_| err(line, format!("{name} `{c}` is not a whole number")))
        };
        let steps = match cell(required[3]) {
            "" => None,
            c => Some(
                c.parse::<u32>()
                    .map_err(|_| err(line, format!("steps `{c}` is not a whole number")))?,
            ),
        };
        rows.push(StudyRow {
            profile: cell(required[0]).to_string(),
            method: cell(required[1]).to_string(),
            rtol: float(required[2], "rtol")?,
            steps,
            error: float(required[4], "error")?,
            stick_time_error: float(required[5], "stick_time_error")?,
            stats: Stats {
                rhs_evaluations: int(cell(required[6]), "rhs_evaluations")?,
                accepted_steps: int(cell(required[7]), "accepted_steps")?,
                rejected_steps: int(ext(2), "rejected_steps")?,
            },
            seconds_per_contact: float(required[8], "seconds_per_contact")?.unwrap_or(f64::NAN),
            breakpoints: !matches!(ext(0), "false" | "False" | "0"),
            time_transform: !matches!(ext(6), "false" | "False" | "0"),
            scene: ext(1).to_string(),
            samples: int(ext(3), "samples")? as u32,
            solves_per_sample: int(ext(4), "solves_per_sample")? as u32,
            note: ext(5).to_string(),
            restitution: number(ext(7), "restitution")?,
            coefficient: number(ext(8), "coefficient")?,
        });
    }
    Ok(rows)
}
