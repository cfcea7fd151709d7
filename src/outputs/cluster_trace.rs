//! A cluster scene's trace CSV (docs/formats.md#the-cluster-trace): one row per
//! [`ClusterTraceRow`], streaming; `t (s)`, then a group of columns per pair of balls that
//! carried force in the run (the pairs of the report's contacts, in the order (i, j)), then
//! each ball's velocity and spin. On a cloth, each ball's contact with it has a group too,
//! after the pairs', prefixed `c{i}_cloth_` (docs/cluster.md#the-cloth).
//!
//! A pair's impulses and heat are cumulative over the run: a pair that closes again adds its
//! new contact's to those of its earlier ones, so that the last row holds, per pair, the sum
//! of the report's contacts of that pair.

use crate::base::error::Error;
use crate::base::number::shortest;
use crate::base::validate::finite_output;
use crate::cluster::params::Cluster;
use crate::cluster::resolve::{ClusterOutcome, ClusterTraceRow, ContactRecord, ContactTrace};
use crate::outputs::trace_csv::StreamingCsv;
use nalgebra::Vector3;
use std::io::Write;

/// The columns of a pair, after its prefix `c{i}_{j}_`: name and unit.
pub(crate) const PAIR_COLUMNS: [(&str, &str); 10] = [
    ("compression", "m"),
    ("normal_force", "N"),
    ("normal_impulse", "N s"),
    ("friction_force", "N"),
    ("friction_impulse_x", "N s"),
    ("friction_impulse_y", "N s"),
    ("friction_impulse_z", "N s"),
    ("slip_speed", "m/s"),
    ("stuck", "-"),
    ("heat", "J"),
];

/// Index in [`PAIR_COLUMNS`] of the normal force.
pub(crate) const NORMAL_FORCE: usize = 1;
/// Index in [`PAIR_COLUMNS`] of the cumulative normal impulse.
pub(crate) const NORMAL_IMPULSE: usize = 2;
/// Index in [`PAIR_COLUMNS`] of the friction force's magnitude.
pub(crate) const FRICTION_FORCE: usize = 3;

/// The columns of a ball, after its prefix `b{k}_`: name and unit.
pub(crate) const BALL_COLUMNS: [(&str, &str); 6] = [
    ("v_x", "m/s"),
    ("v_y", "m/s"),
    ("v_z", "m/s"),
    ("spin_x", "rad/s"),
    ("spin_y", "rad/s"),
    ("spin_z", "rad/s"),
];

/// What a pair's earlier contacts left, and the current contact's accumulators.
#[derive(Debug, Clone, Copy, Default)]
struct PairSum {
    /// Closing time (s) of the contact in the set; `None` while the pair has none.
    start: Option<f64>,
    /// Normal impulse (N s), friction impulse on ball i (N s), heat (J) of the closed
    /// contacts.
    done: (f64, Vector3<f64>, f64),
    /// The same of the contact in the set.
    now: (f64, Vector3<f64>, f64),
}

impl PairSum {
    /// Takes the pair's contacts that left the set since the last row (`opened`, their final
    /// values) and its contact in this row (`None`: not in the set); the cumulative normal
    /// impulse, friction impulse and heat.
    fn take<'r>(
        &mut self,
        opened: impl Iterator<Item = &'r ContactRecord>,
        c: Option<&ContactTrace>,
    ) -> (f64, Vector3<f64>, f64) {
        for r in opened {
            if self.start == Some(r.start) {
                // The contact of the last rows: its final values replace the last seen.
                self.start = None;
                self.now = (0.0, Vector3::zeros(), 0.0);
            }
            self.done.0 += r.normal_impulse;
            self.done.1 += r.friction_impulse;
            self.done.2 += r.heat;
        }
        let new = c.map(|c| c.start);
        if self.start.is_some() && self.start != new {
            // The contact of the last row opened: its accumulators are final.
            self.done.0 += self.now.0;
            self.done.1 += self.now.1;
            self.done.2 += self.now.2;
            self.now = (0.0, Vector3::zeros(), 0.0);
        }
        self.start = new;
        if let Some(c) = c {
            self.now = (c.normal_impulse, c.friction_impulse, c.heat);
        }
        (
            self.done.0 + self.now.0,
            self.done.1 + self.now.1,
            self.done.2 + self.now.2,
        )
    }
}

/// The trace's columns for one run: the pairs, their cumulative sums, the balls.
pub(crate) struct ClusterColumns {
    /// The pairs (i < j) with columns, in order, then the balls on the cloth (i, N).
    pairs: Vec<(usize, usize)>,
    /// How many of `pairs` are pairs of balls (the rest are the cloth's).
    ball_pairs: usize,
    /// Each ball's radius (m).
    radii: Vec<f64>,
    /// The cloth's height (m), if the balls rest on one.
    cloth_height: Option<f64>,
    sums: Vec<PairSum>,
}

impl ClusterColumns {
    /// The columns of a trace of `cluster` whose run (without trace) gave `out`: a group per
    /// pair among its contacts.
    pub(crate) fn new(cluster: &Cluster, out: &ClusterOutcome) -> Self {
        let mut pairs: Vec<(usize, usize)> = out.contacts.iter().map(|c| c.pair).collect();
        pairs.sort_unstable();
        pairs.dedup();
        let ball_pairs = pairs.len();
        let mut cloth: Vec<(usize, usize)> = out.cloth.iter().map(|c| c.pair).collect();
        cloth.sort_unstable();
        cloth.dedup();
        pairs.extend(cloth);
        ClusterColumns {
            sums: vec![PairSum::default(); pairs.len()],
            pairs,
            ball_pairs,
            radii: cluster.balls().iter().map(|b| b.ball.radius()).collect(),
            cloth_height: cluster.cloth().map(|c| c.height),
        }
    }

    /// The pairs of balls with columns, in order (the first groups).
    pub(crate) fn pairs(&self) -> &[(usize, usize)] {
        &self.pairs[..self.ball_pairs]
    }

    /// The header cell of column `k` of [`PAIR_COLUMNS`] for pair `(i, j)` (j = the number of
    /// balls: ball i on the cloth).
    fn pair_cell(&self, (i, j): (usize, usize), k: usize) -> String {
        let (name, unit) = PAIR_COLUMNS[k];
        if j == self.radii.len() {
            format!("c{i}_cloth_{name} ({unit})")
        } else {
            format!("c{i}_{j}_{name} ({unit})")
        }
    }

    /// The header cells, in order.
    pub(crate) fn header(&self) -> Vec<String> {
        let mut h = vec!["t (s)".to_string()];
        for &p in &self.pairs {
            h.extend((0..PAIR_COLUMNS.len()).map(|k| self.pair_cell(p, k)));
        }
        for b in 0..self.radii.len() {
            h.extend(
                BALL_COLUMNS
                    .iter()
                    .map(|(name, unit)| format!("b{b}_{name} ({unit})")),
            );
        }
        h
    }

    /// Index of the first cell of pair `p`'s group (its compression) in a row of cells.
    pub(crate) fn pair_offset(p: usize) -> usize {
        1 + p * PAIR_COLUMNS.len()
    }

    /// The cells of `row` in the header's order (`None`: an empty cell, the slip of a pair
    /// not in contact); the pairs' sums move on.
    pub(crate) fn cells(&mut self, row: &ClusterTraceRow<'_>) -> Vec<Option<f64>> {
        let mut out = Vec::with_capacity(
            1 + self.pairs.len() * PAIR_COLUMNS.len() + row.balls.len() * BALL_COLUMNS.len(),
        );
        out.push(Some(row.t));
        for (&(i, j), sum) in self.pairs.iter().zip(&mut self.sums) {
            let c = row.contacts.iter().find(|c| c.pair == (i, j));
            let opened = row.opened.iter().filter(|r| r.pair == (i, j));
            let (p, fi, heat) = sum.take(opened, c);
            let gap = || match self.cloth_height {
                // A ball off the cloth: its height above it, negated.
                Some(h) if j == self.radii.len() => self.radii[i] - (row.balls[i].position.z - h),
                _ => {
                    let d = (row.balls[j].position - row.balls[i].position).norm();
                    self.radii[i] + self.radii[j] - d
                }
            };
            let (delta, f, fr, slip, stuck) = match c {
                Some(c) => (
                    c.compression,
                    c.normal_force,
                    c.friction_force.norm(),
                    Some(c.slip.norm()),
                    if c.stuck { 1.0 } else { 0.0 },
                ),
                None => (gap(), 0.0, 0.0, None, 0.0),
            };
            out.extend([
                Some(delta),
                Some(f),
                Some(p),
                Some(fr),
                Some(fi.x),
                Some(fi.y),
                Some(fi.z),
                slip,
                Some(stuck),
                Some(heat),
            ]);
        }
        for b in row.balls {
            out.extend(b.velocity.iter().chain(b.spin.iter()).map(|x| Some(*x)));
        }
        out
    }
}

/// Writes a cluster trace's cells as CSV, streaming; the first error is kept and returned by
/// [`ClusterTraceCsv::finish`] (the kernel's trace callback cannot fail).
pub(crate) struct ClusterTraceCsv<W: Write> {
    out: StreamingCsv<W>,
    header: Vec<String>,
}

impl<W: Write> ClusterTraceCsv<W> {
    /// A writer that starts with the header line `header`.
    pub(crate) fn new(out: W, header: Vec<String>) -> Result<Self, Error> {
        Ok(ClusterTraceCsv {
            out: StreamingCsv::new(out, &header)?,
            header,
        })
    }

    /// Writes one row of cells (after an earlier error: nothing).
    pub(crate) fn row(&mut self, cells: &[Option<f64>]) {
        let header = &self.header;
        self.out.row(|out| {
            let t = cells.first().copied().flatten().unwrap_or(f64::NAN);
            for (name, v) in header.iter().zip(cells) {
                match v {
                    Some(v) => {
                        let v = finite_output(*v, || format!("trace column {name} at t = {t}"))?;
                        // + 0.0: a zero is written 0.0, never -0.0.
                        out.write_field(shortest(v + 0.0))?;
                    }
                    None => out.write_field("")?,
                }
            }
            Ok(())
        });
    }

    /// Flushes and returns the underlying writer, or the first error met.
    pub(crate) fn finish(self) -> Result<W, Error> {
        self.out.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn contact(start: f64, p: f64, heat: f64) -> ContactTrace {
        ContactTrace {
            pair: (0, 1),
            start,
            compression: 1e-5,
            normal_force: 10.0,
            normal_impulse: p,
            friction_force: Vector3::zeros(),
            friction_impulse: Vector3::new(p / 10.0, 0.0, 0.0),
            slip: Vector3::zeros(),
            stuck: false,
            heat,
        }
    }

    fn record(start: f64, p: f64, heat: f64) -> ContactRecord {
        ContactRecord {
            pair: (0, 1),
            normal: Vector3::x(),
            normal_impulse: p,
            friction_impulse: Vector3::new(p / 10.0, 0.0, 0.0),
            start,
            duration: 1.0,
            heat,
            stick_time: None,
        }
    }

    /// A pair that closes, opens and closes again: its impulse and heat add up over its
    /// contacts, each counted with its final values (0.6 N s, not the 0.5 of its last row:
    /// rows between samples end before the contact), 0.6 + 0.25 = 0.85; a contact that
    /// opened and closed between two rows (0.1 N s) counts too.
    #[test]
    fn a_pairs_sums_run_over_its_contacts() {
        let none = std::iter::empty;
        let mut s = PairSum::default();
        assert_eq!(s.take(none(), Some(&contact(1.0, 0.2, 0.01))).0, 0.2);
        assert_eq!(s.take(none(), Some(&contact(1.0, 0.5, 0.02))).0, 0.5);
        let (p, fi, h) = s.take([record(1.0, 0.6, 0.03)].iter(), None);
        assert_eq!((p, fi.x, h), (0.6, 0.06, 0.03));
        assert_eq!(s.take(none(), Some(&contact(3.0, 0.25, 0.01))).0, 0.85);
        // Opened and reclosed between two rows: the next row has a new start.
        let (p, fi, h) = s.take(
            [record(3.0, 0.3, 0.01), record(3.5, 0.1, 0.0)].iter(),
            Some(&contact(4.0, 0.05, 0.0)),
        );
        assert!(
            (p - 1.05).abs() < 1e-15 && (fi.x - 0.105).abs() < 1e-15,
            "{p} {fi}"
        );
        assert!((h - 0.04).abs() < 1e-15, "{h}");
    }
}
