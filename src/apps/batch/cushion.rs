//! A batch of cushion impacts (docs/formats.md#cushion-batch-csv): one ball meeting the
//! scene's cushion per row, streamed from CSV to CSV in chunks and resolved in parallel.
//!
//! Input columns (header names, any order, a trailing unit in parentheses ignored, empty
//! cells "not given"): `v_x, v_y` (m/s, required), `v_z` (m/s, default 0), `w_x, w_y, w_z`
//! (rad/s, default 0), in the cushion's frame (x along it, y towards it, z up); optional
//! `id` (copied) and per-row overrides of the scene's cushion: `height` (m), `mu_cushion`,
//! `mu_table`, `restitution`. Output: `line`, `id` (when given), the outgoing `v_x, v_y, v_z,
//! w_x, w_y, w_z`, `rebound_deg` (empty without horizontal velocity), `speed_out`,
//! `impulse_cushion`, `impulse_compression`, `impulse_table` (N s), `energy_lost` (J),
//! `lifts_off`, `events` (the slip events as `contact kind @ P_I`, `;`-separated) and
//! `rhs_evaluations`.

use crate::apps::batch::crlf::CrlfAsLf;
use crate::apps::batch::stream::{read_chunk, BatchSummary, DEFAULT_CHUNK_ROWS};
use crate::base::error::Error;
use crate::base::names::did_you_mean;
use crate::base::number::shortest;
use crate::base::settings::SolverSettings;
use crate::cushion::outcome::CushionOutcome;
use crate::cushion::params::Cushion;
use crate::outputs::cushion::{angle_from_normal, change_name, contact_name, horizontal_speed};
use crate::scene::cushion::CushionScene;
use nalgebra::Vector3;
use rayon::prelude::*;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// The accepted input columns.
pub(crate) const CUSHION_INPUT_COLUMNS: [&str; 11] = [
    "id",
    "v_x",
    "v_y",
    "v_z",
    "w_x",
    "w_y",
    "w_z",
    "height",
    "mu_cushion",
    "mu_table",
    "restitution",
];

/// The output columns after `line` (and `id` when the input has it).
pub(crate) const CUSHION_OUTPUT_COLUMNS: [&str; 15] = [
    "v_x",
    "v_y",
    "v_z",
    "w_x",
    "w_y",
    "w_z",
    "rebound_deg",
    "speed_out",
    "impulse_cushion",
    "impulse_compression",
    "impulse_table",
    "energy_lost",
    "lifts_off",
    "events",
    "rhs_evaluations",
];

/// Where each accepted column is in the input (index into [`CUSHION_INPUT_COLUMNS`]).
struct Layout {
    at: [Option<usize>; 11],
}

impl Layout {
    fn from_header(header: &csv::StringRecord) -> Result<Self, String> {
        let mut at = [None; 11];
        for (i, cell) in header.iter().enumerate() {
            let name = match cell.find('(') {
                Some(k) => cell[..k].trim(),
                None => cell.trim(),
            };
            let Some(k) = CUSHION_INPUT_COLUMNS.iter().position(|c| *c == name) else {
                return Err(format!(
                    "column {} {:?}: not a column of a cushion batch (accepted: {}){}",
                    i + 1,
                    name.escape_debug().to_string(),
                    CUSHION_INPUT_COLUMNS.join(", "),
                    did_you_mean(name, &CUSHION_INPUT_COLUMNS)
                ));
            };
            if at[k].is_some() {
                return Err(format!("column {name} appears twice"));
            }
            at[k] = Some(i);
        }
        for required in [1, 2] {
            if at[required].is_none() {
                return Err(format!(
                    "no column {}: a cushion batch needs v_x and v_y (m/s, the cushion's \
                     frame: x along it, y towards it)",
                    CUSHION_INPUT_COLUMNS[required]
                ));
            }
        }
        Ok(Layout { at })
    }

    /// The number in column `k` of `rec`, `None` when absent or empty.
    fn number(&self, rec: &csv::StringRecord, k: usize) -> Result<Option<f64>, String> {
        let Some(cell) = self.at[k]
            .and_then(|i| rec.get(i))
            .filter(|c| !c.is_empty())
        else {
            return Ok(None);
        };
        match cell.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(Some(x)),
            _ => Err(format!(
                "{} = {:?}: a finite number",
                CUSHION_INPUT_COLUMNS[k],
                cell.escape_debug().to_string()
            )),
        }
    }
}

/// One row resolved: its output line's text, and whether the ball left the cloth.
fn resolve_row(
    scene: &CushionScene,
    settings: &SolverSettings,
    layout: &Layout,
    rec: &csv::StringRecord,
    line: u64,
) -> Result<(String, bool), String> {
    let get = |k: usize| layout.number(rec, k);
    let v = Vector3::new(
        get(1)?.unwrap_or(0.0),
        get(2)?.unwrap_or(0.0),
        get(3)?.unwrap_or(0.0),
    );
    let w = Vector3::new(
        get(4)?.unwrap_or(0.0),
        get(5)?.unwrap_or(0.0),
        get(6)?.unwrap_or(0.0),
    );
    let c = &scene.cushion;
    let cushion = Cushion::new(
        get(7)?.unwrap_or(c.height()),
        get(8)?.unwrap_or(c.mu_cushion()),
        get(9)?.unwrap_or(c.mu_table()),
        get(10)?.unwrap_or(c.restitution()),
        c.rule(),
    )
    .map_err(|e| e.to_string())?;
    let out = crate::cushion::impact::resolve_cushion(&scene.ball, &cushion, v, w, settings, None)
        .map_err(|e| e.to_string())?;
    let id = layout.at[0].and_then(|i| rec.get(i));
    Ok((format_row(line, id, &out)?, out.lifts_off))
}

/// The output line of a row (with its newline).
fn format_row(line: u64, id: Option<&str>, out: &CushionOutcome) -> Result<String, String> {
    let mut cells: Vec<String> = vec![line.to_string()];
    if let Some(id) = id {
        cells.push(quote(id));
    }
    let numbers = [out.v.x, out.v.y, out.v.z, out.w.x, out.w.y, out.w.z];
    for (name, x) in CUSHION_OUTPUT_COLUMNS.iter().zip(numbers) {
        if !x.is_finite() {
            return Err(format!("{name} = {x}: the result is not finite"));
        }
        cells.push(shortest(x + 0.0));
    }
    cells.push(angle_from_normal(&out.v, false).map_or(String::new(), shortest));
    for x in [
        horizontal_speed(&out.v),
        out.impulse_cushion,
        out.impulse_compression,
        out.impulse_table,
        out.energy_lost,
    ] {
        if !x.is_finite() {
            return Err(format!("the result {x} is not finite"));
        }
        cells.push(shortest(x + 0.0));
    }
    cells.push(out.lifts_off.to_string());
    let events: Vec<String> = out
        .events
        .iter()
        .map(|e| {
            format!(
                "{} {} @ {}",
                contact_name(e.contact),
                change_name(e.kind),
                shortest(e.impulse)
            )
        })
        .collect();
    cells.push(quote(&events.join("; ")));
    cells.push(out.stats.rhs_evaluations.to_string());
    Ok(cells.join(",") + "\n")
}

/// A cell quoted for CSV when it needs it.
fn quote(cell: &str) -> String {
    if cell.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", cell.replace('"', "\"\""))
    } else {
        cell.to_string()
    }
}

/// Streams a cushion batch: reads rows from `input` (`input_name` in errors), resolves them
/// `chunk_rows` at a time in parallel against `scene`'s ball and cushion with `settings`,
/// writes the results to `output` in input order and calls `progress(rows, bytes_read)` after
/// each chunk. Errors name the input line. `BatchSummary::sticks` counts the rows where the
/// ball left the cloth; `collisions` every row (every row's ball meets the cushion).
pub(crate) fn run_cushion_csv<R: Read, W: Write>(
    scene: &CushionScene,
    settings: &SolverSettings,
    input: R,
    input_name: &Path,
    mut output: W,
    chunk_rows: usize,
    mut progress: impl FnMut(u64, u64),
) -> Result<(W, BatchSummary), Error> {
    let chunk_rows = chunk_rows.max(1);
    let path = PathBuf::from(input_name);
    let bad = |line: u64, message: String| Error::BatchInput {
        path: path.clone(),
        line,
        message,
    };
    let mut rd = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(CrlfAsLf::new(input));
    let header = rd.headers().map_err(|e| bad(1, e.to_string()))?.clone();
    let layout = Layout::from_header(&header).map_err(|m| bad(1, m))?;
    let io = |e: std::io::Error| Error::io("batch output", e);
    let mut head = vec!["line"];
    if layout.at[0].is_some() {
        head.push("id");
    }
    head.extend(CUSHION_OUTPUT_COLUMNS);
    output
        .write_all((head.join(",") + "\n").as_bytes())
        .map_err(io)?;
    let mut summary = BatchSummary::default();
    let first = chunk_rows.min(DEFAULT_CHUNK_ROWS);
    let mut records: Vec<csv::StringRecord> = Vec::with_capacity(first);
    let mut lines: Vec<u64> = Vec::with_capacity(first);
    let mut results: Vec<Result<(String, bool), String>> = Vec::with_capacity(first);
    loop {
        let n = read_chunk(&mut rd, &mut records, &mut lines, chunk_rows, &bad)?;
        if n == 0 {
            break;
        }
        summary.max_rows_in_memory = summary.max_rows_in_memory.max(records.len());
        records[..n]
            .par_iter()
            .zip(lines[..n].par_iter())
            .map(|(rec, &line)| resolve_row(scene, settings, &layout, rec, line))
            .collect_into_vec(&mut results);
        for (k, r) in results.iter().enumerate() {
            let (text, lifts) = r.as_ref().map_err(|m| bad(lines[k], m.clone()))?;
            output.write_all(text.as_bytes()).map_err(io)?;
            summary.rows += 1;
            summary.collisions += 1;
            summary.sticks += u64::from(*lifts);
        }
        progress(summary.rows, rd.position().byte());
        if n < chunk_rows {
            break;
        }
    }
    output.flush().map_err(io)?;
    Ok((output, summary))
}
