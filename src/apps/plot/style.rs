//! What the figures share: a series' look (colour, line, marker) drawn the same on the chart
//! and in its legend, legends drawn beside the charts (never over the data), and tick labels.

use super::FONT;
use crate::base::error::Error;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;

/// What a drawing step returns.
pub(crate) type Drawn<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// Dash and gap lengths (px) of a dashed line.
const DASH: (u32, u32) = (8, 5);
/// Dash and gap lengths (px) of a dotted line.
const DOT: (u32, u32) = (2, 4);
/// Length (px) of a legend swatch.
const SWATCH_LEN: i32 = 40;

/// How a series' line is stroked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Line {
    /// Markers only.
    None,
    /// A solid line.
    Solid,
    /// A dashed line.
    Dashed,
    /// A dotted line.
    Dotted,
}

/// The marker at a series' points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mark {
    /// No marker.
    None,
    /// A circle.
    Circle,
    /// A diagonal cross.
    Cross,
    /// A triangle.
    Triangle,
    /// A square.
    Square,
}

/// The look of one series: the same on the chart and in the legend.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Swatch {
    /// Colour of the line and the markers.
    pub color: RGBColor,
    /// Line width (px).
    pub width: u32,
    /// How the line is stroked.
    pub line: Line,
    /// The marker at each point.
    pub mark: Mark,
    /// Marker size (px, about its radius).
    pub mark_size: i32,
}

impl Swatch {
    /// A solid line of `width` px without markers.
    pub(crate) fn line(color: RGBColor, width: u32) -> Self {
        Swatch {
            color,
            width,
            line: Line::Solid,
            mark: Mark::None,
            mark_size: 4,
        }
    }

    /// This swatch with line `line`.
    pub(crate) fn with_line(self, line: Line) -> Self {
        Swatch { line, ..self }
    }

    /// This swatch with marker `mark` of `size` px.
    pub(crate) fn with_mark(self, mark: Mark, size: i32) -> Self {
        Swatch {
            mark,
            mark_size: size,
            ..self
        }
    }

    /// The line's stroke.
    pub(crate) fn stroke(&self) -> ShapeStyle {
        self.color.stroke_width(self.width)
    }

    /// The fill of a marker: filled, or its outline when `hollow`.
    fn mark_style(&self, hollow: bool) -> ShapeStyle {
        if hollow {
            self.color.stroke_width(2)
        } else {
            self.color.filled()
        }
    }

    /// The line through `pts` on `area` (a chart's plotting area, or pixels). Dashes run on
    /// along the whole line (not restarted at each point), and the line is drawn segment by
    /// segment in pixels: the bitmap backend joins wide polylines with unlimited miters,
    /// which spike where a line doubles back.
    pub(crate) fn draw_line<DB, CT>(
        &self,
        area: &DrawingArea<DB, CT>,
        pts: &[CT::From],
    ) -> Drawn<DB>
    where
        DB: DrawingBackend,
        CT: CoordTranslate,
    {
        let base = area.get_base_pixel();
        let px: Vec<(f64, f64)> = pts
            .iter()
            .map(|p| {
                let (x, y) = area.map_coordinate(p);
                (f64::from(x - base.0), f64::from(y - base.1))
            })
            .collect();
        let pieces = match self.line {
            Line::None => Vec::new(),
            Line::Solid => vec![px],
            Line::Dashed => dashes(&px, DASH),
            Line::Dotted => dashes(&px, DOT),
        };
        let pixels = area.strip_coord_spec();
        let round = |p: (f64, f64)| (p.0.round() as i32, p.1.round() as i32);
        for piece in pieces.iter().map(|p| thinned(p)) {
            for w in piece.windows(2) {
                let (p, q) = (round(w[0]), round(w[1]));
                if p != q {
                    pixels.draw(&PathElement::new(vec![p, q], self.stroke()))?;
                }
            }
            if let [only] = piece[..] {
                let p = round(only);
                pixels.draw(&PathElement::new(vec![p, (p.0 + 1, p.1)], self.stroke()))?;
            }
        }
        Ok(())
    }

    /// The markers at `pts` on `area` (a chart's plotting area, or pixels), hollow where
    /// the flag says so.
    pub(crate) fn draw_marks<DB, CT>(
        &self,
        area: &DrawingArea<DB, CT>,
        pts: impl IntoIterator<Item = (CT::From, bool)>,
    ) -> Drawn<DB>
    where
        DB: DrawingBackend,
        CT: CoordTranslate,
        CT::From: Clone,
    {
        let r = self.mark_size;
        let thin = self.color.stroke_width(2);
        for (p, hollow) in pts {
            let e = EmptyElement::at(p);
            let fill = self.mark_style(hollow);
            match self.mark {
                Mark::None => {}
                Mark::Circle => area.draw(&(e + Circle::new((0, 0), r, fill)))?,
                Mark::Cross => area.draw(&(e + Cross::new((0, 0), r + 1, thin)))?,
                Mark::Triangle => area.draw(&(e + TriangleMarker::new((0, 0), r + 1, fill)))?,
                Mark::Square => area.draw(&(e + Rectangle::new([(-r, -r), (r, r)], fill)))?,
            }
        }
        Ok(())
    }

    /// The swatch in a legend: a short line with a marker at its middle, left end at `at`
    /// (px) on `area`.
    fn draw_sample<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        (x, y): (i32, i32),
    ) -> Drawn<DB> {
        self.draw_line(area, &[(x, y), (x + SWATCH_LEN, y)])?;
        self.draw_marks(area, [((x + SWATCH_LEN / 2, y), false)])
    }
}

/// The points of a polyline (px) at least 3 px from the previous one kept, and its last:
/// segments of a pixel or less, once rounded, draw a staircase.
fn thinned(pts: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(pts.len());
    for (i, &p) in pts.iter().enumerate() {
        let far = out
            .last()
            .is_none_or(|q: &(f64, f64)| (p.0 - q.0).hypot(p.1 - q.1) >= 3.0);
        if far || i + 1 == pts.len() {
            out.push(p);
        }
    }
    out
}

/// The "on" pieces of the polyline `pts` (px) dashed with `(on, off)` px, the pattern
/// running on along the whole line.
fn dashes(pts: &[(f64, f64)], (on, off): (u32, u32)) -> Vec<Vec<(f64, f64)>> {
    let (on, off) = (f64::from(on), f64::from(off));
    let mut pieces = Vec::new();
    let mut piece: Vec<(f64, f64)> = Vec::new();
    // Position in the pattern (px from the start of the current dash).
    let mut phase = 0.0;
    for w in pts.windows(2) {
        let (p, q) = (w[0], w[1]);
        let len = (q.0 - p.0).hypot(q.1 - p.1);
        let at = |d: f64| (p.0 + (q.0 - p.0) * d / len, p.1 + (q.1 - p.1) * d / len);
        let mut done = 0.0;
        while done < len {
            let drawing = phase < on;
            let left = if drawing {
                on - phase
            } else {
                on + off - phase
            };
            let step = left.min(len - done);
            if drawing {
                if piece.is_empty() {
                    piece.push(at(done));
                }
                piece.push(at(done + step));
            }
            done += step;
            phase += step;
            if drawing && phase >= on {
                pieces.push(std::mem::take(&mut piece));
            }
            if phase >= on + off {
                phase = 0.0;
            }
        }
    }
    if !piece.is_empty() {
        pieces.push(piece);
    }
    pieces
}

/// `c` blended half-way to white.
pub(crate) fn light(c: RGBColor) -> RGBColor {
    let f = |v: u8| ((u16::from(v) + 255) / 2) as u8;
    RGBColor(f(c.0), f(c.1), f(c.2))
}

/// One legend line: a swatch and its text.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct LegendEntry {
    /// How the series is drawn.
    pub swatch: Swatch,
    /// What it is.
    pub label: String,
}

impl LegendEntry {
    /// The entry `label` for `swatch`.
    pub(crate) fn new(swatch: Swatch, label: impl Into<String>) -> Self {
        LegendEntry {
            swatch,
            label: label.into(),
        }
    }
}

/// Height (px) of one legend line in a font of `font` px.
pub(crate) fn legend_row(font: u32) -> i32 {
    (font as i32 * 3) / 2
}

/// Draws `entries` on `area` from its top left corner `at` (px), in `columns` columns
/// `column_width` px apart (filled row by row), text `font` px high.
pub(crate) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry],
    at: (i32, i32),
    (columns, column_width): (usize, i32),
    font: u32,
) -> Drawn<DB> {
    let row = legend_row(font);
    let style =
        TextStyle::from((FONT, font).into_font()).pos(plotters::style::text_anchor::Pos::new(
            plotters::style::text_anchor::HPos::Left,
            plotters::style::text_anchor::VPos::Center,
        ));
    for (i, e) in entries.iter().enumerate() {
        let (r, c) = (i / columns.max(1), i % columns.max(1));
        let x = at.0 + c as i32 * column_width;
        let y = at.1 + r as i32 * row + row / 2;
        e.swatch.draw_sample(area, (x, y))?;
        area.draw(&Text::new(
            e.label.clone(),
            (x + SWATCH_LEN + 8, y),
            style.clone(),
        ))?;
    }
    Ok(())
}

/// A figure drawn the same on either backend: its size and its drawing.
pub(crate) trait Figure {
    /// The figure's size (px).
    fn dims(&self) -> (u32, u32);

    /// Draws the figure on `root` (the fonts registered).
    fn draw_all<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Drawn<DB>;
}

/// Writes `figure` to `path` (SVG or PNG by its extension; `option` names the command-line
/// option in the error for another extension).
pub(crate) fn write_drawn(
    option: &str,
    path: &std::path::Path,
    figure: &impl Figure,
) -> Result<(), Error> {
    super::write_figure(
        option,
        path,
        figure.dims(),
        |r| draw_figure(figure, r),
        |r| draw_figure(figure, r),
    )
}

/// Draws `figure` on `root` with the fonts registered; an error carries the backend's
/// message.
fn draw_figure<DB: DrawingBackend>(
    figure: &impl Figure,
    root: &DrawingArea<DB, Shift>,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    super::register_fonts();
    figure.draw_all(root).map_err(|e| e.to_string())
}

/// The axes of a chart of numbers: the descriptions, the tick labels (their count and
/// decimals, without "-0") and a faint grid at the labelled ticks only.
pub(crate) struct MeshAxes {
    /// Descriptions of the x and the y axis.
    pub desc: (String, String),
    /// How many tick labels on x and on y (`None`: plotters' default).
    pub labels: Option<(usize, usize)>,
    /// Decimals of the x and the y tick labels.
    pub decimals: (usize, usize),
    /// Text sizes (px) of the tick labels and of the descriptions.
    pub fonts: (u32, u32),
}

impl MeshAxes {
    /// Draws the mesh of `chart`.
    pub(crate) fn draw<DB: DrawingBackend>(
        &self,
        chart: &mut ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    ) -> Drawn<DB> {
        let (dx, dy) = self.decimals;
        let x_label = |v: &f64| tick_label(*v, dx);
        let y_label = |v: &f64| tick_label(*v, dy);
        let mut mesh = chart.configure_mesh();
        mesh.x_desc(self.desc.0.clone()).y_desc(self.desc.1.clone());
        if let Some((nx, ny)) = self.labels {
            mesh.x_labels(nx).y_labels(ny);
        }
        mesh.x_label_formatter(&x_label)
            .y_label_formatter(&y_label)
            .label_style((FONT, self.fonts.0))
            .axis_desc_style((FONT, self.fonts.1))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.08))
            .draw()
    }
}

/// A tick label with `decimals` decimals, without the sign of a value that rounds to zero
/// ("0.0", never "-0.0").
pub(crate) fn tick_label(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
        s[1..].to_string()
    } else {
        s
    }
}

/// The decimals that tell apart ticks about `step` apart (0 for steps of 1 and more).
pub(crate) fn decimals_for(step: f64) -> usize {
    if !(step.is_finite() && step > 0.0) || step >= 1.0 {
        0
    } else {
        (-step.log10()).ceil().clamp(0.0, 12.0) as usize
    }
}

/// A number in 4 significant digits without trailing zeros (plain between 1e-3 and 1e4,
/// in exponent form otherwise).
pub(crate) fn short(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    if !(1e-3..1e4).contains(&v.abs()) {
        return format!("{v:.3e}");
    }
    let decimals = (3.0 - v.abs().log10().floor()).max(0.0) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tick_labels_have_no_negative_zero() {
        assert_eq!(tick_label(-0.0, 1), "0.0");
        assert_eq!(tick_label(-1e-17, 1), "0.0");
        assert_eq!(tick_label(-0.04, 1), "0.0");
        assert_eq!(tick_label(-0.06, 1), "-0.1");
        assert_eq!(tick_label(2.0, 0), "2");
    }

    #[test]
    fn dashes_run_on_across_points() {
        // 30 px in steps of 1 px, dashes 8 on 5 off: on at 0-8, 13-21, 26-30.
        let pts: Vec<(f64, f64)> = (0..=30).map(|i| (f64::from(i), 0.0)).collect();
        let d = dashes(&pts, (8, 5));
        let ends: Vec<(f64, f64)> = d.iter().map(|p| (p[0].0, p[p.len() - 1].0)).collect();
        assert_eq!(ends, vec![(0.0, 8.0), (13.0, 21.0), (26.0, 30.0)]);
    }

    #[test]
    fn short_numbers() {
        assert_eq!(short(200.0), "200");
        assert_eq!(short(0.5), "0.5");
        assert_eq!(short(123.456), "123.5");
        assert_eq!(short(10.551665), "10.55");
        assert_eq!(short(1.5e-5), "1.500e-5");
        assert_eq!(short(0.0), "0");
    }

    #[test]
    fn decimals_follow_the_step() {
        assert_eq!(decimals_for(2.0), 0);
        assert_eq!(decimals_for(0.5), 1);
        assert_eq!(decimals_for(0.2), 1);
        assert_eq!(decimals_for(0.05), 2);
        assert_eq!(decimals_for(0.0), 0);
    }
}
