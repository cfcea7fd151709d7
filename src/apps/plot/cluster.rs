//! The pictures of a cluster run (docs/cluster.md, docs/formats.md#the-cluster-trace):
//!
//! - `run SCENE --plot-trace FILE.svg|png`: the normal force of each contact against time,
//!   one line a pair of balls, labelled by the pair; below it the friction force of each
//!   contact (with friction) and the cumulative normal impulse of each pair. The rows drawn
//!   are those the trace CSV holds for the same run and sampling.
//! - `run SCENE --plot FILE.svg|png`: a top view (x right, y up, lab frame) of the balls
//!   where the last contact opened, circles to scale with their indices, each ball's
//!   outgoing velocity as an arrow (with a scale bar), and each pair that pressed as a grey
//!   bar between the centres, its width growing with the pair's normal impulse.

use super::style::{
    decimals_for, draw_legend, legend_row, short, write_drawn, Drawn, Figure, LegendEntry, Line,
    MeshAxes, Swatch,
};
use super::trace::{
    TimeAxis, DESC_FONT, LEGEND_FONT, PANEL_FONT, SUBTITLE_FONT, TICK_FONT, TITLE_FONT,
};
use super::FONT;
use crate::base::error::Error;
use crate::base::number::shortest;
use crate::cluster::resolve::{ClusterOutcome, ClusterSettings};
use crate::outputs::cluster_trace::{ClusterColumns, FRICTION_FORCE, NORMAL_FORCE, NORMAL_IMPULSE};
use crate::scene::cluster::ClusterScene;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Size (px) of the trace figure: the panels on the left, the legend of pairs on the right.
const TRACE_SIZE: (u32, u32) = (1400, 1200);
/// Width (px) of the legend column of the trace figure.
const LEGEND_W: u32 = 230;
/// Height (px) of the title strip.
const HEADER_PX: u32 = 92;
/// Text size (px) of the pairs' labels at their peaks and of the legend's note (the other
/// sizes: the trace figure's).
const LABEL_FONT: u32 = 15;
/// Two pairs' force curves closer than this fraction of the largest force everywhere are
/// one curve to the eye (mirror images in a symmetric rack).
const SAME_CURVE: f64 = 2e-3;
/// Force (relative to the largest) above which a pair counts as pressing, for the order of
/// the pairs: the balls of a rack at rest press on each other by the rounding of their
/// positions (1e-17 N against kN).
const PRESSING: f64 = 1e-9;
/// Peaks closer than this (px) share one label.
const SAME_PEAK_PX: i32 = 8;

/// Colours of the pairs (Tableau 10), cycled; each cycle a new line style.
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];
/// Line styles of the successive cycles through [`PALETTE`].
const LINES: [Line; 3] = [Line::Solid, Line::Dashed, Line::Dotted];

/// The look of the `k`-th pair's curves.
fn pair_swatch(k: usize) -> Swatch {
    Swatch::line(PALETTE[k % PALETTE.len()], 2).with_line(LINES[(k / PALETTE.len()) % 3])
}

/// The label of a pair: `i-j`.
fn pair_label((i, j): (usize, usize)) -> String {
    format!("{i}-{j}")
}

/// The trace's cells a figure keeps: per row its time and, per pair, the normal force, the
/// friction force and the cumulative normal impulse.
pub(crate) struct ClusterTraceData {
    pairs: Vec<(usize, usize)>,
    /// Time (s) of each row.
    t: Vec<f64>,
    /// Per pair, per row: normal force (N), friction force (N), normal impulse (N s).
    values: Vec<[Vec<f64>; 3]>,
}

impl ClusterTraceData {
    /// Empty, for the pairs of `columns`.
    pub(crate) fn new(columns: &ClusterColumns) -> Self {
        let pairs = columns.pairs().to_vec();
        ClusterTraceData {
            values: pairs.iter().map(|_| Default::default()).collect(),
            pairs,
            t: Vec::new(),
        }
    }

    /// Keeps a row of cells (in the order of [`ClusterColumns::header`]).
    pub(crate) fn push(&mut self, cells: &[Option<f64>]) {
        self.t.push(cells[0].unwrap_or(f64::NAN));
        for (p, v) in self.values.iter_mut().enumerate() {
            let o = ClusterColumns::pair_offset(p);
            for (k, col) in [NORMAL_FORCE, FRICTION_FORCE, NORMAL_IMPULSE]
                .iter()
                .enumerate()
            {
                v[k].push(cells[o + col].unwrap_or(0.0));
            }
        }
    }
}

/// One panel of the trace figure: a curve per pair (in the figure's order of pairs).
struct TracePanel {
    title: String,
    y_desc: String,
    /// (t in the axis' unit from the first touch, value).
    curves: Vec<Vec<(f64, f64)>>,
    /// Whether the pairs are labelled at their curves' peaks.
    labels: bool,
}

/// The trace figure of a cluster run.
pub(crate) struct ClusterTraceFigure {
    title: String,
    subtitle: String,
    time: TimeAxis,
    /// Span of the time axis (its unit).
    span: f64,
    /// The pairs in the order they first closed, with their looks.
    pairs: Vec<((usize, usize), Swatch)>,
    panels: Vec<TracePanel>,
}

impl ClusterTraceFigure {
    /// The figure of `out`, the run of `scene` with `settings`, from its trace `data`;
    /// `samples`: the rows were taken at that many intervals (else one per step).
    pub(crate) fn new(
        scene: &ClusterScene,
        settings: &ClusterSettings,
        out: &ClusterOutcome,
        data: &ClusterTraceData,
        samples: Option<u64>,
    ) -> Self {
        let t0 = out.first_touch;
        let time = TimeAxis::for_duration(out.time - t0);
        // The pairs in the order they first pressed (balls of a rack touch from the start,
        // and press only once the impulse reaches them).
        let mut order: Vec<usize> = (0..data.pairs.len()).collect();
        let peak = data
            .values
            .iter()
            .flat_map(|v| v[0].iter())
            .fold(0.0, |a: f64, b| a.max(*b));
        let first = |p: usize| {
            data.values[p][0]
                .iter()
                .position(|f| *f > PRESSING * peak)
                .unwrap_or(usize::MAX)
        };
        order.sort_by_key(|&p| (first(p), data.pairs[p]));
        // Rows before the first touch (a cue ball's flight) press nothing: left out.
        let x: Vec<f64> = data.t.iter().map(|t| (t - t0) * time.per_second).collect();
        let curves = |k: usize| -> Vec<Vec<(f64, f64)>> {
            order
                .iter()
                .map(|&p| {
                    x.iter()
                        .copied()
                        .zip(data.values[p][k].iter().copied())
                        .filter(|q| q.0 >= 0.0)
                        .collect()
                })
                .collect()
        };
        let friction =
            scene.cluster.mu() > 0.0 && data.values.iter().any(|v| v[1].iter().any(|f| *f > 0.0));
        let mut panels = vec![TracePanel {
            title: "normal force of each contact".into(),
            y_desc: "normal force (N)".into(),
            curves: curves(0),
            labels: true,
        }];
        if friction {
            panels.push(TracePanel {
                title: "friction force of each contact (size)".into(),
                y_desc: "friction force (N)".into(),
                curves: curves(1),
                labels: false,
            });
        }
        panels.push(TracePanel {
            title: "normal impulse of each pair so far".into(),
            y_desc: "normal impulse (N s)".into(),
            curves: curves(2),
            labels: false,
        });
        let rows = match samples {
            Some(n) => format!("{} rows at even times (--samples {n})", data.t.len()),
            None => format!("{} rows, one per accepted step", data.t.len()),
        };
        // A pair whose force follows an earlier pair's (mirror images in a symmetric rack) is
        // drawn over it: the earlier one is drawn wider, so that both are seen.
        let force = curves(0);
        let top = force.iter().flatten().map(|p| p.1).fold(0.0, f64::max);
        let same = |a: &[(f64, f64)], b: &[(f64, f64)]| {
            a.iter()
                .zip(b)
                .all(|(p, q)| (p.1 - q.1).abs() <= SAME_CURVE * top)
        };
        let swatches: Vec<Swatch> = (0..order.len())
            .map(|k| {
                let s = pair_swatch(k);
                let under = (k + 1..order.len()).any(|m| same(&force[k], &force[m]));
                if under {
                    Swatch { width: 6, ..s }
                } else {
                    s
                }
            })
            .collect();
        let t0_unit = TimeAxis::for_duration(t0);
        ClusterTraceFigure {
            title: format!("{}: the contacts' forces", scene.name),
            subtitle: format!(
                "{} balls, {} pairs pressed; t from the first touch ({}) to the last \
                 contact's opening; rtol {}; {rows}",
                out.balls.len(),
                data.pairs.len(),
                if t0 > 0.0 {
                    format!(
                        "{} {} after the start",
                        short(t0 * t0_unit.per_second),
                        t0_unit.unit
                    )
                } else {
                    "at the start".to_string()
                },
                shortest(settings.rtol),
            ),
            span: (out.time - t0) * time.per_second,
            time,
            pairs: order
                .iter()
                .enumerate()
                .map(|(k, &p)| (data.pairs[p], swatches[k]))
                .collect(),
            panels,
        }
    }

    /// Writes the figure to `path` ([`write_drawn`]).
    pub(crate) fn write(&self, option: &str, path: &Path) -> Result<(), Error> {
        write_drawn(option, path, self)
    }
}

impl Figure for ClusterTraceFigure {
    fn dims(&self) -> (u32, u32) {
        TRACE_SIZE
    }

    fn draw_all<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Drawn<DB> {
        root.fill(&WHITE)?;
        let (header, body) = root.split_vertically(HEADER_PX);
        draw_header(&header, &self.title, &self.subtitle)?;
        let (panels, legend) = body.split_horizontally(TRACE_SIZE.0 - LEGEND_W);
        let areas = panels.split_evenly((self.panels.len(), 1));
        for (panel, area) in self.panels.iter().zip(&areas) {
            self.draw_panel(area, panel)?;
        }
        let legend = legend.margin(8, 8, 0, 10);
        legend.draw(&Text::new(
            "pair i-j (balls)",
            (0, 0),
            (FONT, LEGEND_FONT).into_font().style(FontStyle::Bold),
        ))?;
        let entries: Vec<LegendEntry> = self
            .pairs
            .iter()
            .map(|(p, s)| LegendEntry::new(*s, pair_label(*p)))
            .collect();
        // One column while it fits, else two.
        let (_, h) = legend.dim_in_pixel();
        let fits = (h as i32 - 30) / legend_row(LEGEND_FONT);
        let columns = if entries.len() as i32 <= fits { 1 } else { 2 };
        draw_legend(
            &legend,
            &entries,
            (0, 28),
            (columns, (LEGEND_W as i32 - 18) / 2),
            LEGEND_FONT,
        )?;
        if self.pairs.iter().any(|(_, s)| s.width > 2) {
            // A wide line: a later pair's curve lies on it.
            let rows = entries.len().div_ceil(columns) as i32;
            let y = 28 + rows * legend_row(LEGEND_FONT) + 12;
            for (k, line) in [
                "wide line: a later pair",
                "has the same curve,",
                "drawn over it",
            ]
            .iter()
            .enumerate()
            {
                legend.draw(&Text::new(
                    line.to_string(),
                    (0, y + k as i32 * (LABEL_FONT as i32 + 4)),
                    (FONT, LABEL_FONT).into_font(),
                ))?;
            }
        }
        root.present()
    }
}

impl ClusterTraceFigure {
    fn draw_panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        panel: &TracePanel,
    ) -> Drawn<DB> {
        let area = area.margin(6, 6, 14, 10);
        area.draw(&Text::new(
            panel.title.clone(),
            (0, 0),
            (FONT, PANEL_FONT).into_font().style(FontStyle::Bold),
        ))?;
        let (_, chart_area) = area.split_vertically(PANEL_FONT + 12);
        let top = panel
            .curves
            .iter()
            .flatten()
            .map(|p| p.1)
            .fold(0.0, f64::max);
        let top = if top > 0.0 { top * 1.08 } else { 1.0 };
        let span = if self.span > 0.0 { self.span } else { 1.0 };
        let mut chart = ChartBuilder::on(&chart_area)
            .margin_right(12)
            .x_label_area_size(50)
            .y_label_area_size(90)
            .build_cartesian_2d(0.0..span, 0.0..top)?;
        MeshAxes {
            desc: (
                format!("t from the first touch ({})", self.time.unit),
                panel.y_desc.clone(),
            ),
            labels: Some((10, 7)),
            decimals: (decimals_for(span / 8.0), decimals_for(top / 6.0)),
            fonts: (TICK_FONT, DESC_FONT),
        }
        .draw(&mut chart)?;
        for (curve, (_, swatch)) in panel.curves.iter().zip(&self.pairs) {
            swatch.draw_line(chart.plotting_area(), curve)?;
        }
        if panel.labels {
            self.draw_peak_labels(&chart, panel)?;
        }
        Ok(())
    }

    /// Each pair's label above its curve's peak, in its colour, where it overlaps no label
    /// placed before it (the larger peaks first).
    fn draw_peak_labels<'b, DB: DrawingBackend + 'b>(
        &self,
        chart: &ChartContext<'b, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        panel: &TracePanel,
    ) -> Drawn<DB> {
        let area = chart.plotting_area();
        let mut peaks: Vec<(usize, (f64, f64))> = panel
            .curves
            .iter()
            .enumerate()
            .filter_map(|(k, c)| {
                c.iter()
                    .copied()
                    .max_by(|a, b| a.1.total_cmp(&b.1))
                    .filter(|p| p.1 > 0.0)
                    .map(|p| (k, p))
            })
            .collect();
        peaks.sort_by(|a, b| b.1 .1.total_cmp(&a.1 .1));
        let (w, h) = area.dim_in_pixel();
        let base = area.get_base_pixel();
        let mut placed: Vec<(i32, i32, i32, i32)> = Vec::new();
        let pixels = area.strip_coord_spec();
        let px = |p: &(f64, f64)| {
            let q = area.map_coordinate(p);
            (q.0 - base.0, q.1 - base.1)
        };
        let mut done = vec![false; self.pairs.len()];
        for &(k, p) in &peaks {
            if done[k] {
                continue;
            }
            let (x, y) = px(&p);
            // The pairs whose peaks fall here share the label, in the colour drawn on top.
            let here: Vec<usize> = peaks
                .iter()
                .filter(|(m, q)| {
                    let (qx, qy) = px(q);
                    !done[*m] && (qx - x).abs() <= SAME_PEAK_PX && (qy - y).abs() <= SAME_PEAK_PX
                })
                .map(|(m, _)| *m)
                .collect();
            for &m in &here {
                done[m] = true;
            }
            let text = here
                .iter()
                .map(|&m| pair_label(self.pairs[m].0))
                .collect::<Vec<_>>()
                .join(", ");
            let swatch = &self.pairs[here.iter().copied().max().unwrap_or(k)].1;
            let tw = (text.len() as i32) * (LABEL_FONT as i32) * 6 / 10 + 4;
            let th = LABEL_FONT as i32 + 2;
            let bx = (x - tw / 2).clamp(0, (w as i32 - tw).max(0));
            let by = (y - th - 3).clamp(0, (h as i32 - th).max(0));
            let bbox = (bx, by, bx + tw, by + th);
            let hits = placed
                .iter()
                .any(|b| bbox.0 < b.2 && b.0 < bbox.2 && bbox.1 < b.3 && b.1 < bbox.3);
            if hits {
                continue;
            }
            placed.push(bbox);
            pixels.draw(&Rectangle::new(
                [(bbox.0, bbox.1), (bbox.2, bbox.3)],
                WHITE.mix(0.85).filled(),
            ))?;
            pixels.draw(&Text::new(
                text,
                (bx + 2, by),
                (FONT, LABEL_FONT)
                    .into_font()
                    .style(FontStyle::Bold)
                    .color(&swatch.color),
            ))?;
        }
        Ok(())
    }
}

/// The title and subtitle strip.
fn draw_header<DB: DrawingBackend>(
    header: &DrawingArea<DB, Shift>,
    title: &str,
    subtitle: &str,
) -> Drawn<DB> {
    header.draw(&Text::new(
        title.to_string(),
        (20, 14),
        (FONT, TITLE_FONT).into_font().style(FontStyle::Bold),
    ))?;
    header.draw(&Text::new(
        subtitle.to_string(),
        (20, 14 + TITLE_FONT as i32 + 14),
        (FONT, SUBTITLE_FONT).into_font(),
    ))
}

/// Width (px) of the top view.
const TOP_WIDTH: u32 = 1100;
/// Margin (px) round the top view's chart, and its label areas.
const TOP_MARGIN: u32 = 20;
const TOP_LABEL_X: u32 = 50;
const TOP_LABEL_Y: u32 = 70;
/// Height (px) of the strip below the chart (the legend).
const TOP_STRIP: u32 = 70;
/// The longest velocity arrow, in ball diameters.
const ARROW_DIAMETERS: f64 = 2.5;
/// Points of a ball's outline.
const OUTLINE_POINTS: u32 = 96;
/// Widths (px) of the contact bars: the smallest and the largest normal impulse's.
const BAR_WIDTH: (f64, f64) = (1.0, 9.0);
/// An arrow shorter than this (px) is not drawn (a ball at rest, or nearly).
const MIN_ARROW_PX: f64 = 3.0;
/// The ball's fill and outline, the arrows, the contact bars.
const BALL_FILL: RGBColor = RGBColor(236, 236, 228);
const BALL_EDGE: RGBColor = RGBColor(60, 60, 60);
const ARROW: RGBColor = RGBColor(200, 30, 30);
const BAR: RGBColor = RGBColor(120, 120, 120);

/// A point of the top view (mm).
type Point = (f64, f64);

/// The top view of a cluster run.
pub(crate) struct ClusterTopView {
    title: String,
    subtitle: String,
    /// Per ball: centre (mm), radius (mm), velocity (m/s) in x and y.
    balls: Vec<(Point, f64, Point)>,
    /// Per pair that pressed: the balls and its normal impulse (N s, summed over its
    /// contacts).
    bars: Vec<(usize, usize, f64)>,
    /// Arrow length per speed (mm per m/s).
    scale: f64,
    /// The speed of the scale bar (m/s).
    bar_speed: f64,
    x: std::ops::Range<f64>,
    y: std::ops::Range<f64>,
    /// Height (px) of the chart's plotting area, both axes at the same scale.
    plot_height: u32,
}

/// A round speed (1, 2 or 5 times a power of ten, m/s) at most `v`.
fn round_speed(v: f64) -> f64 {
    let p = 10f64.powf(v.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|s| *s <= v)
        .unwrap_or(p)
}

impl ClusterTopView {
    /// The top view of `out`, the run of `scene`.
    pub(crate) fn new(scene: &ClusterScene, out: &ClusterOutcome) -> Self {
        let mm = 1e3;
        let balls: Vec<(Point, f64, Point)> = scene
            .cluster
            .balls()
            .iter()
            .zip(&out.balls)
            .map(|(b, o)| {
                (
                    (o.position.x * mm, o.position.y * mm),
                    b.ball.radius() * mm,
                    (o.velocity.x, o.velocity.y),
                )
            })
            .collect();
        let mut bars: Vec<(usize, usize, f64)> = Vec::new();
        for c in &out.contacts {
            match bars.iter_mut().find(|b| (b.0, b.1) == c.pair) {
                Some(b) => b.2 += c.normal_impulse,
                None => bars.push((c.pair.0, c.pair.1, c.normal_impulse)),
            }
        }
        let r_max = balls.iter().map(|b| b.1).fold(0.0, f64::max);
        let v_max = balls
            .iter()
            .map(|b| b.2 .0.hypot(b.2 .1))
            .fold(0.0, f64::max);
        let scale = if v_max > 0.0 {
            ARROW_DIAMETERS * 2.0 * r_max / v_max
        } else {
            1.0
        };
        let bar_speed = if v_max > 0.0 { round_speed(v_max) } else { 1.0 };
        // The extent of the balls and the arrows' tips, padded by half a ball.
        let (mut lo, mut hi) = (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for &((cx, cy), r, (vx, vy)) in &balls {
            for (x, y, rr) in [(cx, cy, r), (cx + scale * vx, cy + scale * vy, 0.0)] {
                lo = (lo.0.min(x - rr), lo.1.min(y - rr));
                hi = (hi.0.max(x + rr), hi.1.max(y + rr));
            }
        }
        let pad = r_max;
        let (mut x, mut y) = ((lo.0 - pad)..(hi.0 + pad), (lo.1 - pad)..(hi.1 + pad));
        // Both axes at one scale: the chart's width is fixed, its height follows, at least
        // 0.35 and at most 1.2 times the width (a wider extent is padded in y).
        let plot_w = f64::from(TOP_WIDTH - 2 * TOP_MARGIN - TOP_LABEL_Y);
        let aspect = ((y.end - y.start) / (x.end - x.start)).clamp(0.35, 1.2);
        let want_h = aspect * (x.end - x.start);
        if want_h > y.end - y.start {
            let mid = 0.5 * (y.start + y.end);
            y = (mid - want_h / 2.0)..(mid + want_h / 2.0);
        } else {
            let want_w = (y.end - y.start) / aspect;
            let mid = 0.5 * (x.start + x.end);
            x = (mid - want_w / 2.0)..(mid + want_w / 2.0);
        }
        let plot_height = (plot_w * aspect).round() as u32;
        let moving: Vec<String> = scene
            .cluster
            .balls()
            .iter()
            .enumerate()
            .filter(|(_, b)| b.velocity.norm() > 0.0)
            .map(|(i, b)| format!("ball {i} at {} m/s", short(b.velocity.norm())))
            .collect();
        ClusterTopView {
            title: format!("{}: top view, velocities after the contacts", scene.name),
            subtitle: format!(
                "balls where the last contact opened (lab x-y, mm); before: {}",
                if moving.is_empty() {
                    "all at rest".to_string()
                } else {
                    moving.join(", ")
                }
            ),
            balls,
            bars,
            scale,
            bar_speed,
            x,
            y,
            plot_height,
        }
    }

    /// Writes the figure to `path` ([`write_drawn`]).
    pub(crate) fn write(&self, option: &str, path: &Path) -> Result<(), Error> {
        write_drawn(option, path, self)
    }
}

impl Figure for ClusterTopView {
    fn dims(&self) -> (u32, u32) {
        (
            TOP_WIDTH,
            HEADER_PX + self.plot_height + 2 * TOP_MARGIN + TOP_LABEL_X + TOP_STRIP,
        )
    }

    fn draw_all<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Drawn<DB> {
        root.fill(&WHITE)?;
        let (header, rest) = root.split_vertically(HEADER_PX);
        draw_header(&header, &self.title, &self.subtitle)?;
        let (main, strip) = rest.split_vertically(self.plot_height + 2 * TOP_MARGIN + TOP_LABEL_X);
        let mut chart = ChartBuilder::on(&main)
            .margin(TOP_MARGIN)
            .x_label_area_size(TOP_LABEL_X)
            .y_label_area_size(TOP_LABEL_Y)
            .build_cartesian_2d(self.x.clone(), self.y.clone())?;
        let d = decimals_for((self.x.end - self.x.start) / 10.0);
        MeshAxes {
            desc: ("x (mm)".into(), "y (mm)".into()),
            labels: None,
            decimals: (d, d),
            fonts: (TICK_FONT, DESC_FONT),
        }
        .draw(&mut chart)?;
        let area = chart.plotting_area();
        let outline = |(cx, cy): Point, r: f64| -> Vec<Point> {
            (0..=OUTLINE_POINTS)
                .map(|k| {
                    let a = std::f64::consts::TAU * f64::from(k) / f64::from(OUTLINE_POINTS);
                    (cx + r * a.cos(), cy + r * a.sin())
                })
                .collect()
        };
        for &(c, r, _) in &self.balls {
            area.draw(&Polygon::new(outline(c, r), BALL_FILL.filled()))?;
        }
        // The pairs that pressed, over the fills: the chains the impulse went along.
        let p_max = self.bars.iter().map(|b| b.2).fold(0.0, f64::max);
        for &(i, j, p) in &self.bars {
            let w = BAR_WIDTH.0 + (BAR_WIDTH.1 - BAR_WIDTH.0) * (p / p_max).clamp(0.0, 1.0);
            let s = Swatch::line(BAR, w.round() as u32);
            s.draw_line(area, &[self.balls[i].0, self.balls[j].0])?;
        }
        for &(c, r, _) in &self.balls {
            Swatch::line(BALL_EDGE, 2).draw_line(area, &outline(c, r))?;
        }
        for &((cx, cy), _, (vx, vy)) in &self.balls {
            self.draw_arrow(area, (cx, cy), (cx + self.scale * vx, cy + self.scale * vy))?;
        }
        let label = TextStyle::from((FONT, 18).into_font().style(FontStyle::Bold)).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Center,
                plotters::style::text_anchor::VPos::Center,
            ),
        );
        for (k, &(c, _, _)) in self.balls.iter().enumerate() {
            // The index on a white disc, readable over the bars and the arrow's tail.
            area.draw(&(EmptyElement::at(c) + Circle::new((0, 0), 12, WHITE.filled())))?;
            area.draw(&(EmptyElement::at(c) + Circle::new((0, 0), 12, BALL_EDGE.stroke_width(1))))?;
            area.draw(&Text::new(k.to_string(), c, label.clone()))?;
        }
        self.draw_strip(&strip)?;
        root.present()
    }
}

impl ClusterTopView {
    /// An arrow from `from` to `to` (mm) with a filled head; nothing when shorter than
    /// [`MIN_ARROW_PX`].
    fn draw_arrow<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        from: Point,
        to: Point,
    ) -> Drawn<DB> {
        let base = area.get_base_pixel();
        let px = |p: &Point| {
            let q = area.map_coordinate(p);
            (q.0 - base.0, q.1 - base.1)
        };
        let (a, b) = (px(&from), px(&to));
        let len = f64::from(b.0 - a.0).hypot(f64::from(b.1 - a.1));
        if len < MIN_ARROW_PX {
            return Ok(());
        }
        arrow_px(&area.strip_coord_spec(), a, b, ARROW, 3)
    }

    /// The legend below the chart: the scale bar, the bars, the circles.
    fn draw_strip<DB: DrawingBackend>(&self, strip: &DrawingArea<DB, Shift>) -> Drawn<DB> {
        let px_per_mm =
            f64::from(TOP_WIDTH - 2 * TOP_MARGIN - TOP_LABEL_Y) / (self.x.end - self.x.start);
        let len = self.bar_speed * self.scale * px_per_mm;
        let x0 = (TOP_MARGIN + TOP_LABEL_Y) as i32;
        let y = 22;
        arrow_px(strip, (x0, y), (x0 + len.round() as i32, y), ARROW, 3)?;
        let style = TextStyle::from((FONT, LEGEND_FONT).into_font()).pos(
            plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Left,
                plotters::style::text_anchor::VPos::Center,
            ),
        );
        strip.draw(&Text::new(
            format!(
                "{} m/s: each ball's velocity after the contacts (x-y part); circles: the \
                 balls to scale, numbered as in the scene",
                short(self.bar_speed)
            ),
            (x0 + len.round() as i32 + 12, y),
            style.clone(),
        ))?;
        let y2 = y + 28;
        Swatch::line(BAR, 6).draw_line(strip, &[(x0, y2), (x0 + 40, y2)])?;
        let p_max = self.bars.iter().map(|b| b.2).fold(0.0, f64::max);
        strip.draw(&Text::new(
            format!(
                "a pair that pressed, wider for a larger normal impulse ({} to {} N s)",
                short(self.bars.iter().map(|b| b.2).fold(f64::INFINITY, f64::min)),
                short(p_max)
            ),
            (x0 + 52, y2),
            style,
        ))
    }
}

/// A solid arrow from `a` to `b` (px) of `width`, with a filled head.
fn arrow_px<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    a: (i32, i32),
    b: (i32, i32),
    color: RGBColor,
    width: u32,
) -> Drawn<DB> {
    let (dx, dy) = (f64::from(b.0 - a.0), f64::from(b.1 - a.1));
    let len = dx.hypot(dy);
    if len <= 0.0 {
        return Ok(());
    }
    let (ux, uy) = (dx / len, dy / len);
    let head = (4.0 * f64::from(width) + 4.0).min(0.5 * len);
    let base = (f64::from(b.0) - head * ux, f64::from(b.1) - head * uy);
    let half = 0.45 * head;
    let p = |x: f64, y: f64| (x.round() as i32, y.round() as i32);
    area.draw(&PathElement::new(
        vec![a, p(base.0, base.1)],
        color.stroke_width(width),
    ))?;
    area.draw(&Polygon::new(
        vec![
            b,
            p(base.0 - half * uy, base.1 + half * ux),
            p(base.0 + half * uy, base.1 - half * ux),
        ],
        color.filled(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_speeds_are_1_2_5_times_a_power_of_ten() {
        assert_eq!(round_speed(7.3), 5.0);
        assert_eq!(round_speed(3.0), 2.0);
        assert_eq!(round_speed(1.4), 1.0);
        assert_eq!(round_speed(0.93), 0.5);
        assert!((round_speed(0.03) - 0.02).abs() < 1e-15);
    }
}
