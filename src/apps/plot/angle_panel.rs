//! One panel of the sweep charts (the throw chart, the rebound chart): a quantity against an
//! angle, one line per curve of one speed and side spin, their colours by index, the legend
//! upper left.

use super::style::Drawn;
use super::FONT;
use plotters::coord::Shift;
use plotters::prelude::*;

/// A curve's colour: by its index among the curves of one panel.
pub(crate) fn colour(i: usize) -> RGBColor {
    const PALETTE: [RGBColor; 8] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(148, 103, 189),
        RGBColor(255, 127, 14),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(23, 190, 207),
    ];
    PALETTE[i % PALETTE.len()]
}

/// A row of a sweep as a panel reads it: its speed (m/s) and side spin, which pick its
/// curve, and its angle (degrees), the panel's x.
pub(crate) trait Shot {
    fn speed(&self) -> f64;
    fn side(&self) -> f64;
    fn angle(&self) -> f64;
}

/// The axes of a panel: the descriptions and ranges of x and y, and whether the grey
/// diagonal y = x is drawn (the mirror of the rebound chart).
pub(crate) struct Axes<'a> {
    pub(crate) x_desc: &'a str,
    pub(crate) y_desc: &'a str,
    pub(crate) x: (f64, f64),
    pub(crate) y: (f64, f64),
    pub(crate) diagonal: bool,
}

/// Draws the panel `caption` on `area`: the axes, the diagonal if asked, one line a curve
/// (rows of one speed and side spin) of `value` against the rows' angle, labelled by its
/// speed (and its side spin when the curves' sides differ); rows without a value are left
/// out.
pub(crate) fn draw<DB: DrawingBackend, R: Shot>(
    area: &DrawingArea<DB, Shift>,
    caption: &str,
    axes: &Axes<'_>,
    curves: &[&[R]],
    value: impl Fn(&R) -> Option<f64>,
) -> Drawn<DB> {
    let ((x0, x1), (y0, y1)) = (axes.x, axes.y);
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 17))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(56)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(axes.x_desc)
        .y_desc(axes.y_desc)
        .label_style((FONT, 12))
        .axis_desc_style((FONT, 13))
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(BLACK.mix(0.08))
        .draw()?;
    if axes.diagonal {
        let grey = RGBColor(150, 150, 150);
        chart.draw_series(LineSeries::new([(x0, x0), (x1, x1)], grey.stroke_width(1)))?;
    }
    let with_side = curves.iter().any(|c| c[0].side() != curves[0][0].side());
    for (i, c) in curves.iter().enumerate() {
        let colour = colour(i);
        let label = if with_side {
            format!("{} m/s, side {}", c[0].speed(), c[0].side())
        } else {
            format!("{} m/s", c[0].speed())
        };
        let points: Vec<(f64, f64)> = c
            .iter()
            .filter_map(|r| value(r).map(|v| (r.angle(), v)))
            .collect();
        chart
            .draw_series(LineSeries::new(points, colour.stroke_width(2)))?
            .label(label)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], colour.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .margin(6)
        .legend_area_size(22)
        .label_font((FONT, 12))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK.mix(0.3))
        .draw()
}
