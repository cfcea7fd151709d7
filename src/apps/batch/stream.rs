//! A batch streamed from CSV to CSV in chunks: read, resolve in parallel, write in order.

use crate::apps::batch::columns::{format_row, Columns};
use crate::apps::batch::crlf::CrlfAsLf;
use crate::apps::batch::engine::{resolve_with, shared_kernel, BatchSetup};
use crate::base::error::Error;
use rayon::prelude::*;
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// Rows read, resolved and written per chunk by default: the memory held at any time.
pub const DEFAULT_CHUNK_ROWS: usize = 16_384;

/// The largest chunk `batch --chunk` accepts: 2^20 rows, about 1 GB held at once (a row's
/// record, result and output text take up to about 1 kB). Larger chunks gain nothing: the
/// parallel work per chunk is already far longer than reading and writing it.
pub const MAX_CHUNK_ROWS: usize = 1 << 20;

/// What a streamed batch did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BatchSummary {
    /// Rows resolved.
    pub rows: u64,
    /// Rows where the balls collided.
    pub collisions: u64,
    /// Rows where sliding stopped during contact.
    pub sticks: u64,
    /// The most rows held in memory at once (at most the chunk size).
    pub max_rows_in_memory: usize,
}

/// Reads up to `chunk_rows` records into the reused buffers `records`, with their input
/// lines in `lines`; returns how many it read (fewer at the end of the input). `bad` makes
/// the error of a line.
pub(crate) fn read_chunk<R: Read>(
    rd: &mut csv::Reader<R>,
    records: &mut Vec<csv::StringRecord>,
    lines: &mut Vec<u64>,
    chunk_rows: usize,
    bad: &impl Fn(u64, String) -> Error,
) -> Result<usize, Error> {
    let mut n = 0;
    while n < chunk_rows {
        if records.len() <= n {
            records.push(csv::StringRecord::new());
            lines.push(0);
        }
        let more = rd
            .read_record(&mut records[n])
            .map_err(|e| bad(line_read(rd, None), csv_cause(&e)))?;
        if !more {
            break;
        }
        lines[n] = line_read(rd, Some(&records[n]));
        n += 1;
    }
    Ok(n)
}

/// The input line where the record just read (`record`; `None` for one that failed to
/// read, counted as one line) starts. The CSV reader's own record positions are counted
/// before the blank lines it skips; its position after a record is exact: the line after
/// the record's terminating LF (every record has one: [`CrlfAsLf`]).
fn line_read<R: Read>(rd: &csv::Reader<R>, record: Option<&csv::StringRecord>) -> u64 {
    let inside = record.map_or(0, |r| r.iter().map(|f| f.matches('\n').count()).sum());
    rd.position()
        .line()
        .saturating_sub(1 + inside as u64)
        .max(1)
}

/// A CSV reading error's cause in words, without the reader's own record position (whose
/// line can be off; the caller names the line).
fn csv_cause(e: &csv::Error) -> String {
    match e.kind() {
        csv::ErrorKind::UnequalLengths {
            expected_len, len, ..
        } => format!("{len} cells where the header has {expected_len}"),
        csv::ErrorKind::Utf8 { err, .. } => {
            format!("cell {} is not valid UTF-8", err.field() + 1)
        }
        _ => e.to_string(),
    }
}

/// Streams a batch: reads CSV rows from `input` (`input_name` in errors), resolves them
/// `chunk_rows` at a time in parallel (rayon's current pool), writes the results to `output`
/// in input order, and calls `progress(rows_done, bytes_read)` after each chunk. Memory holds
/// at most one chunk of rows. Errors name the input line; the output is then incomplete
/// and the caller discards it (the command writes through an atomic file).
pub fn run_csv<R: Read, W: Write>(
    setup: &BatchSetup,
    input: R,
    input_name: &Path,
    output: W,
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
    // CRLF read as LF: the CSV reader counts the line of a record that follows a CRLF one
    // too low.
    let mut rd = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(CrlfAsLf::new(input));
    let header = rd.headers().map_err(|e| bad(1, e.to_string()))?.clone();
    let cols = Columns::from_header(&header).map_err(|m| bad(1, m))?;
    let method = setup.settings.method();
    let kernel = shared_kernel(setup);
    let mut w = output;
    let io = |e: std::io::Error| Error::io("batch output", e);
    w.write_all(cols.output_header(method).join(",").as_bytes())
        .and_then(|_| w.write_all(b"\n"))
        .map_err(io)?;
    let mut summary = BatchSummary::default();
    // Reused buffers: their size is bounded by the chunk, not by the file.
    // They grow with the rows actually read: a short file with a large chunk holds only
    // its own rows.
    let first = chunk_rows.min(DEFAULT_CHUNK_ROWS);
    let mut records: Vec<csv::StringRecord> = Vec::with_capacity(first);
    let mut lines: Vec<u64> = Vec::with_capacity(first);
    let mut results: Vec<Result<(String, bool, bool), String>> = Vec::with_capacity(first);
    loop {
        let n = read_chunk(&mut rd, &mut records, &mut lines, chunk_rows, &bad)?;
        if n == 0 {
            break;
        }
        summary.max_rows_in_memory = summary.max_rows_in_memory.max(records.len());
        results.clear();
        records[..n]
            .par_iter()
            .zip(lines[..n].par_iter())
            .map(|(rec, &line)| {
                let input = cols.parse(rec)?;
                let out =
                    resolve_with(setup, kernel.as_ref(), &input).map_err(|e| e.to_string())?;
                let id = cols.id.and_then(|i| rec.get(i));
                let mut text = String::with_capacity(400);
                format_row(line, id, &out, method, &mut text)?;
                Ok((text, out.result.collided(), out.result.sticks))
            })
            .collect_into_vec(&mut results);
        for (k, r) in results.iter().enumerate() {
            let (text, collision, sticks) = r.as_ref().map_err(|m| bad(lines[k], m.clone()))?;
            w.write_all(text.as_bytes()).map_err(io)?;
            summary.rows += 1;
            summary.collisions += u64::from(*collision);
            summary.sticks += u64::from(*sticks);
        }
        progress(summary.rows, rd.position().byte());
        if n < chunk_rows {
            break;
        }
    }
    w.flush().map_err(io)?;
    Ok((w, summary))
}
