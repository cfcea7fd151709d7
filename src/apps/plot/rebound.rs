//! The rebound chart of a cushion sweep (docs/cushion.md#the-rebound-sweep): one column of
//! panels per spin kind; the top row the rebound angle against the incidence angle (both
//! from the cushion's normal, degrees; the grey diagonal is the mirror, rebound =
//! incidence), the bottom row the rebound speed over the incoming speed; one line per speed
//! and side spin.

use super::angle_panel::{self, Axes, Shot};
use super::style::Drawn;
use super::FONT;
use crate::apps::rebound::{curves, spin_name, ReboundRow};
use crate::base::error::Error;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Width and height (px) of one panel.
const PANEL: (u32, u32) = (460, 400);
/// Smallest width (px): the title strip's text.
const MIN_WIDTH: u32 = 1000;
/// Height (px) of the title strip.
const HEADER: u32 = 64;

/// The spin kinds in order of first appearance (one column each).
fn spin_kinds(rows: &[ReboundRow]) -> Vec<String> {
    let mut kinds: Vec<String> = Vec::new();
    for r in rows {
        let name = spin_name(&r.shot.spin);
        if !kinds.contains(&name) {
            kinds.push(name);
        }
    }
    kinds
}

/// The figure's size (px).
pub(crate) fn size(rows: &[ReboundRow]) -> (u32, u32) {
    let columns = spin_kinds(rows).len().max(1) as u32;
    ((PANEL.0 * columns).max(MIN_WIDTH), HEADER + 2 * PANEL.1)
}

/// One quantity drawn against the incidence angle.
struct Quantity {
    label: &'static str,
    value: fn(&ReboundRow) -> Option<f64>,
    /// Draw the mirror line rebound = incidence.
    mirror: bool,
}

const ANGLE: Quantity = Quantity {
    label: "rebound angle (deg)",
    value: |r| r.rebound_deg,
    mirror: true,
};

const SPEED: Quantity = Quantity {
    label: "rebound speed / incoming speed",
    value: |r| Some(r.speed_out / r.shot.speed),
    mirror: false,
};

/// Draws the chart on `root` titled `title`.
pub(crate) fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    rows: &[ReboundRow],
    title: &str,
) -> Drawn<DB> {
    super::register_fonts();
    root.fill(&WHITE)?;
    let (header, body) = root.split_vertically(HEADER);
    header.draw(&Text::new(
        title,
        (14, 10),
        (FONT, 20).into_font().style(FontStyle::Bold),
    ))?;
    header.draw(&Text::new(
        "angles from the cushion's normal, positive along the cushion; top: rebound angle \
         (grey: the mirror, rebound = incidence), bottom: rebound speed over incoming speed",
        (14, 38),
        (FONT, 14).into_font(),
    ))?;
    let kinds = spin_kinds(rows);
    let panels = body.split_evenly((2, kinds.len().max(1)));
    let all = curves(rows);
    for (j, kind) in kinds.iter().enumerate() {
        let mine: Vec<&[ReboundRow]> = all
            .iter()
            .copied()
            .filter(|c| spin_name(&c[0].shot.spin) == *kind)
            .collect();
        for (i, q) in [ANGLE, SPEED].iter().enumerate() {
            draw_panel(&panels[i * kinds.len() + j], kind, q, &mine)?;
        }
    }
    root.present()
}

/// The axis ranges of a panel: incidences across, values up (padded, room for the legend).
fn ranges(q: &Quantity, curves: &[&[ReboundRow]]) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1) = (f64::INFINITY, -f64::INFINITY);
    let (mut y0, mut y1) = (f64::INFINITY, -f64::INFINITY);
    for r in curves.iter().flat_map(|c| c.iter()) {
        x0 = x0.min(r.shot.incidence_deg);
        x1 = x1.max(r.shot.incidence_deg);
        if let Some(v) = (q.value)(r) {
            y0 = y0.min(v);
            y1 = y1.max(v);
        }
        if q.mirror {
            y0 = y0.min(r.shot.incidence_deg);
            y1 = y1.max(r.shot.incidence_deg);
        }
    }
    if x1.partial_cmp(&x0) != Some(std::cmp::Ordering::Greater) {
        (x0, x1) = (x0.min(0.0) - 1.0, x0.max(0.0) + 1.0);
    }
    if !y0.is_finite() || !y1.is_finite() {
        (y0, y1) = (0.0, 1.0);
    }
    if !q.mirror {
        y0 = y0.min(0.0);
    }
    if y1 <= y0 {
        y1 = y0 + 1.0;
    }
    let pad = 0.05 * (y1 - y0);
    let legend = 0.09 * (y1 - y0) * curves.len() as f64;
    ((x0, x1), (y0 - pad, y1 + pad + legend))
}

/// One panel: quantity `q` against the incidence angle, one line per curve.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    kind: &str,
    q: &Quantity,
    curves: &[&[ReboundRow]],
) -> Drawn<DB> {
    let (x, y) = ranges(q, curves);
    let axes = Axes {
        x_desc: "incidence angle (deg)",
        y_desc: q.label,
        x,
        y,
        diagonal: q.mirror,
    };
    angle_panel::draw(area, kind, &axes, curves, q.value)
}

impl Shot for ReboundRow {
    fn speed(&self) -> f64 {
        self.shot.speed
    }
    fn side(&self) -> f64 {
        self.shot.side
    }
    fn angle(&self) -> f64 {
        self.shot.incidence_deg
    }
}

/// Writes the chart as SVG to `svg` and PNG to `png`, each replacing its file only once
/// complete.
pub(crate) fn write(rows: &[ReboundRow], title: &str, svg: &Path, png: &Path) -> Result<(), Error> {
    super::write_svg_and_png(
        size(rows),
        svg,
        png,
        |root| draw(root, rows, title).map_err(|e| e.to_string()),
        |root| draw(root, rows, title).map_err(|e| e.to_string()),
    )
}
