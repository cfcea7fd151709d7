//! The throw chart of a sweep (docs/throw.md): one column of panels per spin kind; the top
//! row the throw (degrees) against the cut angle (degrees), the bottom row the spin given
//! to the object ball (rad/s), one line per speed and side spin.

use super::angle_panel::{self, Axes, Shot};
use super::FONT;
use crate::apps::sweep::{curves, SweepRow};
use crate::base::error::Error;
use crate::model::params::FrictionLaw;
use crate::scene::types::Scene;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Width and height (px) of one panel.
const PANEL: (u32, u32) = (440, 360);
/// Smallest width (px): the title strip's text.
const MIN_WIDTH: u32 = 900;
/// Height (px) of the title strip.
const HEADER: u32 = 64;

/// What a drawing step returns.
type Drawn<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// The figure's title for `scene`: its friction model with how it is evaluated, and its
/// restitution rule.
pub(crate) fn title(scene: &Scene) -> String {
    let friction = match scene.contact.friction.law() {
        FrictionLaw::Constant(mu) => format!("constant mu = {mu}"),
        FrictionLaw::SpeedDependent { a, b, c, evaluate } => format!(
            "mu(S) = {a} + {b} exp(-{c} S), evaluate = {}",
            evaluate.name()
        ),
    };
    let friction = if scene.effects.friction {
        friction
    } else {
        "friction off".into()
    };
    format!("Throw and spin transfer: {friction}")
}

/// The spin kinds in order of first appearance (one column each).
fn spin_kinds(rows: &[SweepRow]) -> Vec<String> {
    let mut kinds: Vec<String> = Vec::new();
    for r in rows {
        let name = r.shot.spin.name();
        if !kinds.contains(&name) {
            kinds.push(name);
        }
    }
    kinds
}

/// The figure's size (px).
pub(crate) fn size(rows: &[SweepRow]) -> (u32, u32) {
    let columns = spin_kinds(rows).len().max(1) as u32;
    ((PANEL.0 * columns).max(MIN_WIDTH), HEADER + 2 * PANEL.1)
}

/// One quantity drawn against the cut angle.
struct Quantity {
    /// The axis label, with its unit.
    label: &'static str,
    /// The value of a row; `None` not drawn.
    value: fn(&SweepRow) -> Option<f64>,
}

const THROW: Quantity = Quantity {
    label: "throw (deg)",
    value: |r| r.throw_deg,
};

const SPIN: Quantity = Quantity {
    label: "object-ball spin |w_B| (rad/s)",
    value: |r| Some(r.object_spin.norm()),
};

/// Draws the chart on `root`.
pub(crate) fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    rows: &[SweepRow],
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
        "cue ball along +y into the object ball at rest; top: throw of the object ball, \
         bottom: its spin just after contact",
        (14, 38),
        (FONT, 14).into_font(),
    ))?;
    let kinds = spin_kinds(rows);
    let panels = body.split_evenly((2, kinds.len().max(1)));
    let all = curves(rows);
    for (j, kind) in kinds.iter().enumerate() {
        let mine: Vec<&[SweepRow]> = all
            .iter()
            .copied()
            .filter(|c| c[0].shot.spin.name() == *kind)
            .collect();
        for (i, q) in [THROW, SPIN].iter().enumerate() {
            draw_panel(&panels[i * kinds.len() + j], kind, q, &mine)?;
        }
    }
    root.present()
}

/// The axis ranges of a panel: the cut angles across, the values up (padded, with room
/// above for the legend).
fn ranges(q: &Quantity, curves: &[&[SweepRow]]) -> ((f64, f64), (f64, f64)) {
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, -f64::INFINITY, 0.0f64, 0.0f64);
    for r in curves.iter().flat_map(|c| c.iter()) {
        x0 = x0.min(r.shot.cut_deg);
        x1 = x1.max(r.shot.cut_deg);
        if let Some(v) = (q.value)(r) {
            y0 = y0.min(v);
            y1 = y1.max(v);
        }
    }
    if x1 <= x0 {
        (x0, x1) = (x0 - 1.0, x0 + 1.0);
    }
    if y1 <= y0 {
        y1 = y0 + 1.0;
    }
    let pad = 0.05 * (y1 - y0);
    let legend = 0.1 * (y1 - y0) * curves.len() as f64;
    (
        (x0, x1),
        (y0 - if y0 < 0.0 { pad } else { 0.0 }, y1 + pad + legend),
    )
}

/// One panel: quantity `q` against the cut angle, one line per curve, legend upper left.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    kind: &str,
    q: &Quantity,
    curves: &[&[SweepRow]],
) -> Drawn<DB> {
    let (x, y) = ranges(q, curves);
    let axes = Axes {
        x_desc: "cut angle (deg)",
        y_desc: q.label,
        x,
        y,
        diagonal: false,
    };
    angle_panel::draw(area, kind, &axes, curves, q.value)
}

impl Shot for SweepRow {
    fn speed(&self) -> f64 {
        self.shot.speed
    }
    fn side(&self) -> f64 {
        self.shot.side
    }
    fn angle(&self) -> f64 {
        self.shot.cut_deg
    }
}

/// Writes the chart as SVG to `svg` and as PNG to `png`, each replacing its file only once
/// it is complete.
pub(crate) fn write(rows: &[SweepRow], title: &str, svg: &Path, png: &Path) -> Result<(), Error> {
    super::write_svg_and_png(
        size(rows),
        svg,
        png,
        |root| draw(root, rows, title).map_err(|e| e.to_string()),
        |root| draw(root, rows, title).map_err(|e| e.to_string()),
    )
}
