//! The work-precision diagram: error of the outgoing state (log x) against wall time per
//! contact (log y), one line per method, one panel per profile (rows) and scene (columns).
//! One legend for the whole figure (colour: method; solid with circles: the default
//! settings; dashed with crosses: time transform or breakpoints off; triangles: the peers),
//! and beside each panel the observed order p of each of its lines
//! ([`crate::apps::work_precision::Series::order_fit`]), or why it has none. Errors of
//! exactly 0 (the closed form, and runs that are exact to round-off) are drawn at 1e-17 as
//! hollow markers (docs/formats.md#work-precision-csv).

use super::style::{draw_legend, legend_row, Drawn, LegendEntry, Line, Mark, Swatch};
use super::FONT;
use crate::apps::work_precision::order::{series, NoOrder, Series};
use crate::apps::work_precision::plan::StudyRow;
use crate::base::error::Error;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Where errors of exactly 0 are drawn (dimensionless, scaled error;
/// docs/formats.md#work-precision-csv).
pub(crate) const ZERO_ERROR_AT: f64 = 1e-17;

/// Width and height (px) of one panel: the chart and, at its right, the orders.
const PANEL: (u32, u32) = (700, 400);
/// Width (px) of the orders beside a chart.
const ORDERS: u32 = 210;
/// Smallest width (px): the title strip's text.
const MIN_WIDTH: u32 = 1400;
/// Height (px) of the title strip above the legend.
const TITLE: u32 = 122;
/// Height (px) of the scenes' names above the columns of panels.
const COLUMN_TITLES: u32 = 40;
/// Columns of the figure's legend.
const LEGEND_COLUMNS: usize = 4;
/// Text sizes (px): title, notes, panel titles, axis descriptions, ticks, legends.
const TITLE_FONT: u32 = 28;
const NOTE_FONT: u32 = 17;
const PANEL_FONT: u32 = 20;
const DESC_FONT: u32 = 17;
const TICK_FONT: u32 = 16;
const LEGEND_FONT: u32 = 17;

/// The panels: profiles (rows) and scenes (columns), in order of first appearance.
fn layout(rows: &[StudyRow]) -> (Vec<&str>, Vec<&str>) {
    let mut scenes: Vec<&str> = Vec::new();
    let mut profiles: Vec<&str> = Vec::new();
    for r in rows {
        if !scenes.contains(&r.scene.as_str()) {
            scenes.push(&r.scene);
        }
        if !profiles.contains(&r.profile.as_str()) {
            profiles.push(&r.profile);
        }
    }
    (scenes, profiles)
}

/// The figure's legend: one entry per kind of line present (method and settings), in
/// order of first appearance.
fn legend(lines: &[Series<'_>]) -> Vec<LegendEntry> {
    let mut out: Vec<LegendEntry> = Vec::new();
    for l in lines {
        let label = l.label();
        if !out.iter().any(|e| e.label == label) {
            out.push(LegendEntry::new(swatch(l), label));
        }
    }
    out
}

/// Height (px) of the header: the title strip and the legend.
fn header_height(entries: usize) -> u32 {
    TITLE
        + (legend_row(LEGEND_FONT) * entries.div_ceil(LEGEND_COLUMNS) as i32) as u32
        + 12
        + COLUMN_TITLES
}

/// The figure's size (px) for these rows.
pub(crate) fn size(rows: &[StudyRow]) -> (u32, u32) {
    let (scenes, profiles) = layout(rows);
    let entries = legend(&series(rows)).len();
    (
        (PANEL.0 * scenes.len().max(1) as u32).max(MIN_WIDTH),
        header_height(entries) + PANEL.1 * profiles.len().max(1) as u32,
    )
}

/// The time axis range (s): all finite times, padded by a factor 1.6.
fn time_range(rows: &[StudyRow]) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, 0.0_f64);
    for r in rows {
        let t = r.seconds_per_contact;
        if t.is_finite() && t > 0.0 && r.error.is_some() {
            lo = lo.min(t);
            hi = hi.max(t);
        }
    }
    if !(lo.is_finite() && hi > 0.0) {
        return (1e-9, 1.0);
    }
    (lo / 1.6, hi * 1.6)
}

/// The x position of an error: errors of exactly 0 at [`ZERO_ERROR_AT`]; errors above 1
/// clamped to 1.
fn x_of(error: f64) -> f64 {
    if error == 0.0 {
        ZERO_ERROR_AT
    } else {
        error.clamp(1e-18, 1.0)
    }
}

/// The colour of a method's line.
fn colour(method: &str) -> RGBColor {
    match method {
        "closed-form" => RGBColor(0, 0, 0),
        "rk4" => RGBColor(31, 119, 180),
        "dopri5" => RGBColor(44, 160, 44),
        "dop853" => RGBColor(214, 39, 40),
        "scipy-RK45" => RGBColor(255, 127, 14),
        "scipy-DOP853" => RGBColor(148, 103, 189),
        "scipy-LSODA" => RGBColor(140, 86, 75),
        _ => RGBColor(127, 127, 127),
    }
}

/// How a line is drawn: its method's colour; solid with circles with the default
/// settings, dashed with crosses with the time transform or the breakpoints off,
/// triangles for the peers (scipy).
fn swatch(line: &Series<'_>) -> Swatch {
    let s = Swatch::line(colour(line.method), 2);
    if line.is_peer() {
        s.with_mark(Mark::Triangle, 5)
    } else if line.is_default() {
        s.with_mark(Mark::Circle, 4)
    } else {
        s.with_line(Line::Dashed).with_mark(Mark::Cross, 5)
    }
}

/// Draws the diagram on `root`: the title strip with the legend, then one panel per
/// profile and scene.
pub(crate) fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    rows: &[StudyRow],
) -> Drawn<DB> {
    super::register_fonts();
    root.fill(&WHITE)?;
    let lines = series(rows);
    let entries = legend(&lines);
    let (header, body) = root.split_vertically(header_height(entries.len()));
    draw_header(&header, &entries)?;
    let (scenes, profiles) = layout(rows);
    let (_, names) = header.split_vertically(header_height(entries.len()) - COLUMN_TITLES);
    let (w, _) = names.dim_in_pixel();
    for (j, scene) in scenes.iter().enumerate() {
        let x = (w / scenes.len().max(1) as u32 * j as u32) as i32 + 16;
        names.draw(&Text::new(
            format!("scene: {scene}"),
            (x, 6),
            (FONT, PANEL_FONT + 2).into_font().style(FontStyle::Bold),
        ))?;
    }
    let times = time_range(rows);
    let panels = body.split_evenly((profiles.len().max(1), scenes.len().max(1)));
    for (i, profile) in profiles.iter().enumerate() {
        for (j, scene) in scenes.iter().enumerate() {
            let title = profile.to_string();
            let mine: Vec<&Series<'_>> = lines
                .iter()
                .filter(|l| l.scene == *scene && l.profile == *profile)
                .collect();
            draw_panel(&panels[i * scenes.len() + j], &title, times, &mine)?;
        }
    }
    root.present()
}

/// The title strip: what the figure shows, how to read it, and the legend.
fn draw_header<DB: DrawingBackend>(
    header: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry],
) -> Drawn<DB> {
    header.draw(&Text::new(
        "Work-precision: wall time per contact against the error of the outgoing state",
        (16, 12),
        (FONT, TITLE_FONT).into_font().style(FontStyle::Bold),
    ))?;
    for (k, line) in [
        "error = largest scaled deviation from the closed form (a law's: at its reference \
         impulse); hollow markers at 1e-17: error exactly 0; dashed: time transform or \
         breakpoints off.",
        "Beside each panel: p, the observed order (error ~ evaluations^-p) on the straight part \
         of the line, or - and why not: (s) no straight part,",
        "(w) error not set by the work (equal work, different errors), (>12) steeper than any \
         method's order.",
    ]
    .iter()
    .enumerate()
    {
        header.draw(&Text::new(
            *line,
            (16, 50 + 23 * k as i32),
            (FONT, NOTE_FONT).into_font(),
        ))?;
    }
    let (w, _) = header.dim_in_pixel();
    let column = (w as i32 - 32) / LEGEND_COLUMNS as i32;
    draw_legend(
        header,
        entries,
        (16, TITLE as i32),
        (LEGEND_COLUMNS, column),
        LEGEND_FONT,
    )
}

/// One panel titled `title`, time axis `times` (s): the chart with the column of zero
/// errors and the `lines`, and at its right each line's observed order.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    (t_lo, t_hi): (f64, f64),
    lines: &[&Series<'_>],
) -> Drawn<DB> {
    let area = area.margin(6, 6, 10, 10);
    let (w, _) = area.dim_in_pixel();
    let (plot, orders) = area.split_horizontally(w.saturating_sub(ORDERS));
    let mut chart = ChartBuilder::on(&plot)
        .caption(title, (FONT, PANEL_FONT))
        .margin(6)
        .x_label_area_size(46)
        .y_label_area_size(76)
        .build_cartesian_2d((1e-18f64..1.0f64).log_scale(), (t_lo..t_hi).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("error (scaled)")
        .y_desc("seconds per contact")
        .x_labels(7)
        .y_labels(6)
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style((FONT, TICK_FONT))
        .axis_desc_style((FONT, DESC_FONT))
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(BLACK.mix(0.08))
        .draw()?;
    // The column where errors of exactly 0 are drawn.
    Swatch::line(RGBColor(150, 150, 150), 1)
        .with_line(Line::Dashed)
        .draw_line(
            chart.plotting_area(),
            &[(ZERO_ERROR_AT, t_lo), (ZERO_ERROR_AT, t_hi)],
        )?;
    for line in lines {
        let pts = points(line);
        let sw = swatch(line);
        let xy: Vec<(f64, f64)> = pts.iter().map(|p| (p.0, p.1)).collect();
        sw.draw_line(chart.plotting_area(), &xy)?;
        sw.draw_marks(chart.plotting_area(), pts.iter().map(|p| ((p.0, p.1), p.2)))?;
    }
    let entries: Vec<LegendEntry> = lines
        .iter()
        .filter(|l| l.method != "closed-form")
        .map(|l| LegendEntry::new(swatch(l), order_text(l)))
        .collect();
    orders.draw(&Text::new(
        "p",
        (8, 34),
        (FONT, LEGEND_FONT).into_font().style(FontStyle::Bold),
    ))?;
    draw_legend(
        &orders,
        &entries,
        (0, 58),
        (1, ORDERS as i32),
        LEGEND_FONT - 1,
    )
}

/// A line's observed order beside its panel: a short name and p, or "-" and the reason's
/// code (the title strip explains them).
fn order_text(line: &Series<'_>) -> String {
    let name = line
        .label()
        .replace("scipy-", "")
        .replace(" (no transform)", " no tr.")
        .replace(" (no breakpoints)", " no bp.");
    match line.order_fit() {
        Ok(p) => format!("{name} {p:.1}"),
        Err(NoOrder::TooFewRuns) => format!("{name} -"),
        Err(NoOrder::NoStraightPart) => format!("{name} - (s)"),
        Err(NoOrder::NotSetByWork) => format!("{name} - (w)"),
        Err(NoOrder::FasterThanAnyOrder) => format!("{name} - (>12)"),
    }
}

/// A line's drawable points: (x of the error, seconds per contact, whether the error is
/// exactly 0), for runs with an error and a finite positive time.
fn points(line: &Series) -> Vec<(f64, f64, bool)> {
    line.rows
        .iter()
        .filter_map(|r| {
            let e = r.error?;
            let t = r.seconds_per_contact;
            (t.is_finite() && t > 0.0).then(|| (x_of(e), t, e == 0.0))
        })
        .collect()
}

/// Writes the diagram as SVG to `svg` and as PNG to `png`, each replacing its file only
/// once it is complete.
pub(crate) fn write(rows: &[StudyRow], svg: &Path, png: &Path) -> Result<(), Error> {
    super::write_svg_and_png(
        size(rows),
        svg,
        png,
        |root| draw(root, rows).map_err(|e| e.to_string()),
        |root| draw(root, rows).map_err(|e| e.to_string()),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::apps::work_precision::tests::made_up_row;

    fn row(method: &str, error: f64, t: f64, bp: bool) -> StudyRow {
        let n = (t * 1e9).round() as u64;
        StudyRow {
            breakpoints: bp,
            scene: "scene".into(),
            ..made_up_row("half-sine", method, error, n, t)
        }
    }

    /// The SVG has one panel title per profile, the legend's orders, and the marked zero.
    #[test]
    fn svg_has_panels_legend_and_zero_marker() {
        let mut rows = vec![row("closed-form", 0.0, 5e-8, true)];
        for k in 1..=4 {
            let n = 2f64.powi(k);
            rows.push(row("rk4", 1e-3 / n.powi(4), 1e-6 * n, true));
            rows.push(row("dop853", 1e-6 / n.powi(8), 1e-6 * n, false));
        }
        let mut other = rows.clone();
        for r in &mut other {
            r.profile = "hertz".into();
        }
        rows.extend(other);
        // Two profiles (rows) of one scene; a legend of three kinds of line in one row.
        assert_eq!(size(&rows), (MIN_WIDTH, header_height(3) + 2 * PANEL.1));
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, size(&rows)).into_drawing_area();
            draw(&root, &rows).unwrap();
        }
        assert!(svg.contains("half-sine"));
        assert!(svg.contains("hertz"));
        assert!(svg.contains("rk4 4.0"), "rk4's order beside its panel");
        assert!(svg.contains("dop853 (no breakpoints)"), "in the legend");
        assert!(
            svg.contains("dop853 no bp. 8.0"),
            "its order beside its panel"
        );
        assert!(svg.contains("exactly 0"));
    }

    #[test]
    fn zero_errors_are_drawn_at_1e_17() {
        assert_eq!(x_of(0.0), 1e-17);
        assert_eq!(x_of(3e-9), 3e-9);
        assert_eq!(x_of(7.0), 1.0);
    }
}
