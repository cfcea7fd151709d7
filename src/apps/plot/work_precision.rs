//! The work-precision diagram: error of the outgoing state (log x) against wall time per
//! contact (log y), one line per method, one panel per profile, one row of panels per
//! scene. Each panel's legend gives the observed order p (error ~ evaluations^-p,
//! [`crate::apps::work_precision::Series::observed_order`]). Errors of exactly 0 (the closed form, and
//! runs that are exact to round-off) are drawn at 1e-17 as hollow markers
//! (docs/formats.md#work-precision-csv).

use super::FONT;
use crate::apps::work_precision::{series, Series, StudyRow};
use crate::error::Error;
use plotters::coord::combinators::LogCoord;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Where errors of exactly 0 are drawn (dimensionless, scaled error;
/// docs/formats.md#work-precision-csv).
pub const ZERO_ERROR_AT: f64 = 1e-17;

/// Width and height (px) of one panel.
const PANEL: (u32, u32) = (470, 430);
/// Smallest width (px): the title strip's text.
const MIN_WIDTH: u32 = 1120;
/// Height (px) of the title strip.
const HEADER: u32 = 70;

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

/// The panels: scenes (rows) and profiles (columns), in order of first appearance.
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

/// The figure's size (px) for these rows.
pub fn size(rows: &[StudyRow]) -> (u32, u32) {
    let (scenes, profiles) = layout(rows);
    // At least wide enough for the title lines.
    (
        (PANEL.0 * profiles.len().max(1) as u32).max(MIN_WIDTH),
        HEADER + PANEL.1 * scenes.len().max(1) as u32,
    )
}

/// The time axis range (s): all finite times, padded by a factor 1.6 below and 40 above
/// (room for the legends above the lines).
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
    (lo / 1.6, hi * 40.0)
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

/// Draws the diagram on `root`: the title strip, then one panel per scene and profile.
pub fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    rows: &[StudyRow],
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    super::register_fonts();
    root.fill(&WHITE)?;
    let (header, body) = root.split_vertically(HEADER);
    draw_header(&header)?;
    let (scenes, profiles) = layout(rows);
    let times = time_range(rows);
    let lines = series(rows);
    let panels = body.split_evenly((scenes.len().max(1), profiles.len().max(1)));
    for (i, scene) in scenes.iter().enumerate() {
        for (j, profile) in profiles.iter().enumerate() {
            let title = if j == 0 {
                format!("{profile}  [{}]", shorten(scene, 34))
            } else {
                profile.to_string()
            };
            let panel_lines = lines
                .iter()
                .filter(|l| l.scene == *scene && l.profile == *profile);
            draw_panel(&panels[i * profiles.len() + j], &title, times, panel_lines)?;
        }
    }
    root.present()?;
    Ok(())
}

/// The chart of one panel: error (scaled, log) across, seconds per contact (log) up.
type Panel<'a, DB> = ChartContext<'a, DB, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>;
/// What a drawing step returns.
type Drawn<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// The title strip: what the figure shows and how to read its markers.
fn draw_header<DB: DrawingBackend>(header: &DrawingArea<DB, Shift>) -> Drawn<DB> {
    header.draw(&Text::new(
        "Work-precision: wall time per contact against the error of the outgoing state",
        (14, 10),
        (FONT, 22).into_font().style(FontStyle::Bold),
    ))?;
    header.draw(&Text::new(
        "error = largest scaled deviation from the closed form; p = observed order \
         (error ~ evaluations^-p); hollow markers at 1e-17: error exactly 0; \
         dashed: breakpoints off",
        (14, 42),
        (FONT, 15).into_font(),
    ))
}

/// One panel titled `title`, time axis `times` (s): axes, the column of zero errors, the
/// `lines` and their legend.
fn draw_panel<'r, DB: DrawingBackend + 'r>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    (t_lo, t_hi): (f64, f64),
    lines: impl Iterator<Item = &'r Series<'r>>,
) -> Drawn<DB> {
    let mut chart = ChartBuilder::on(area)
        .caption(title, (FONT, 17))
        .margin(10)
        .x_label_area_size(42)
        .y_label_area_size(62)
        .build_cartesian_2d((1e-18f64..1.0f64).log_scale(), (t_lo..t_hi).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("error (scaled)")
        .y_desc("seconds per contact")
        .x_labels(7)
        .y_labels(6)
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style((FONT, 12))
        .axis_desc_style((FONT, 13))
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(BLACK.mix(0.08))
        .draw()?;
    // The column where errors of exactly 0 are drawn.
    chart.draw_series(DashedLineSeries::new(
        [(ZERO_ERROR_AT, t_lo), (ZERO_ERROR_AT, t_hi)],
        4,
        4,
        BLACK.mix(0.35).stroke_width(1),
    ))?;
    for line in lines {
        let pts = points(line);
        if pts.is_empty() {
            continue;
        }
        draw_line(&mut chart, line, &pts)?;
        draw_markers(&mut chart, line, &pts)?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .margin(6)
        .legend_area_size(22)
        .label_font((FONT, 12))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.3))
        .draw()
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

/// The line through `pts` in its method's colour, solid with breakpoints and dashed
/// without, with its legend entry (the observed order when there is one).
fn draw_line<'a, DB: DrawingBackend + 'a>(
    chart: &mut Panel<'a, DB>,
    line: &Series,
    pts: &[(f64, f64, bool)],
) -> Drawn<DB> {
    let c = colour(line.method);
    let style = c.stroke_width(2);
    let xy = apart_by_pixels(chart, pts);
    let label = match line.observed_order() {
        Some(p) => format!("{}  p = {p:.1}", line.label()),
        None => line.label(),
    };
    // Segment by segment: the bitmap backend joins wide polylines with unlimited
    // miters, which spike across the figure where a ladder doubles back.
    let drawn = if line.breakpoints {
        chart.draw_series(
            xy.windows(2)
                .map(|w| PathElement::new(vec![w[0], w[1]], style)),
        )?
    } else {
        chart.draw_series(
            xy.windows(2)
                .flat_map(|w| DashedLineSeries::new(vec![w[0], w[1]], 7, 4, style)),
        )?
    };
    drawn
        .label(label)
        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2)));
    Ok(())
}

/// The points of `pts` at least 3 px (in x or y) from the previously kept one.
/// Consecutive points on the same pixel make the bitmap backend's wide-line polygon
/// degenerate (stray strokes across the figure): keep one of them.
fn apart_by_pixels<'a, DB: DrawingBackend + 'a>(
    chart: &Panel<'a, DB>,
    pts: &[(f64, f64, bool)],
) -> Vec<(f64, f64)> {
    let mut xy: Vec<(f64, f64)> = Vec::with_capacity(pts.len());
    let mut last_px: Option<(i32, i32)> = None;
    for p in pts {
        let px = chart.backend_coord(&(p.0, p.1));
        let near = last_px.is_some_and(|q| (q.0 - px.0).abs() <= 2 && (q.1 - px.1).abs() <= 2);
        if !near {
            xy.push((p.0, p.1));
            last_px = Some(px);
        }
    }
    xy
}

/// The markers of a line's points: triangles for the peers (scipy), circles with
/// breakpoints, crosses without; hollow and larger for errors of exactly 0.
fn draw_markers<'a, DB: DrawingBackend + 'a>(
    chart: &mut Panel<'a, DB>,
    line: &Series,
    pts: &[(f64, f64, bool)],
) -> Drawn<DB> {
    let c = colour(line.method);
    let peer = line.method.starts_with("scipy");
    let marker = |&(x, y, zero): &(f64, f64, bool)| {
        let st = if zero { c.stroke_width(2) } else { c.filled() };
        (x, y, if zero { 6 } else { 3 }, st)
    };
    if peer {
        chart.draw_series(pts.iter().map(marker).map(|(x, y, r, st)| {
            EmptyElement::at((x, y)) + TriangleMarker::new((0, 0), r + 1, st)
        }))?;
    } else if line.breakpoints {
        chart.draw_series(
            pts.iter()
                .map(marker)
                .map(|(x, y, r, st)| EmptyElement::at((x, y)) + Circle::new((0, 0), r, st)),
        )?;
    } else {
        chart.draw_series(pts.iter().map(marker).map(|(x, y, r, _)| {
            EmptyElement::at((x, y)) + Cross::new((0, 0), r + 1, c.stroke_width(2))
        }))?;
    }
    Ok(())
}

fn shorten(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        let mut t: String = s.chars().take(n - 1).collect();
        t.push('…');
        t
    }
}

/// Writes the diagram as SVG to `svg` and as PNG to `png`, each replacing its file only
/// once it is complete.
pub fn write(rows: &[StudyRow], svg: &Path, png: &Path) -> Result<(), Error> {
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
    use crate::integrator::Stats;

    fn row(method: &str, error: f64, t: f64, bp: bool) -> StudyRow {
        StudyRow {
            profile: "half-sine".into(),
            method: method.into(),
            rtol: None,
            steps: None,
            error: Some(error),
            stick_time_error: None,
            stats: Stats {
                rhs_evaluations: (t * 1e9).round() as u64,
                accepted_steps: 1,
                rejected_steps: 0,
            },
            seconds_per_contact: t,
            breakpoints: bp,
            scene: "scene".into(),
            samples: 1,
            solves_per_sample: 1,
            note: String::new(),
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
        assert_eq!(
            size(&rows),
            ((2 * PANEL.0).max(MIN_WIDTH), HEADER + PANEL.1)
        );
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, size(&rows)).into_drawing_area();
            draw(&root, &rows).unwrap();
        }
        assert!(svg.contains("half-sine"));
        assert!(svg.contains("hertz"));
        assert!(svg.contains("p = 4.0"), "rk4's order in the legend");
        assert!(svg.contains("dop853 (no breakpoints)"));
        assert!(svg.contains("exactly 0"));
    }

    #[test]
    fn zero_errors_are_drawn_at_1e_17() {
        assert_eq!(x_of(0.0), 1e-17);
        assert_eq!(x_of(3e-9), 3e-9);
        assert_eq!(x_of(7.0), 1.0);
    }
}
