//! Top view of both balls' paths on the table (`--plot FILE.svg`), lab frame.
//!
//! Axes: lab x and y when `up` is +z (otherwise the lab x axis projected on the cloth and
//! up x that). Drawn: the line of centres at contact (dashed, grey), both balls' outlines at
//! contact, each path (flight thin and light, sliding solid, rolling thick), the landing
//! points (crosses), where each ball starts to roll (filled dots) and, with rolling
//! resistance, where it rests (squares), and an arrow along each final rolling direction.
//! Both axes have the same scale, so angles on the figure are the true angles.

use super::FONT;
use crate::error::Error;
use crate::model::frame::horizontal;
use crate::table_phase::{BallMotion, RollOut, TableOutcome};
use nalgebra::Vector3;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;

/// Figure size in pixels.
pub const SIZE: (u32, u32) = (900, 820);

/// A point on the figure (m, m).
type Point = (f64, f64);
/// An arrow on the figure: from, to, colour.
type Arrow = (Point, Point, RGBColor);
/// A stretch of a path with one kind of motion, as points on the figure.
type Run = (BallMotion, Vec<Point>);
/// The chart: figure coordinates (m) on both axes.
type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;
/// What a drawing step returns.
type Drawn<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

const COLOR_A: RGBColor = RGBColor(31, 90, 180);
const COLOR_B: RGBColor = RGBColor(200, 60, 30);
/// The line of centres.
const COLOR_LINE: RGBColor = RGBColor(90, 90, 90);
/// Points per segment of a path (one for a ball at rest).
const POINTS_PER_SEGMENT: u32 = 120;
/// Points on a ball's outline.
const OUTLINE_POINTS: u32 = 72;
/// Heights (px) of the x label area and the caption, width (px) of the y label area.
const LABEL_X: u32 = 60;
const CAPTION: u32 = 40;
const LABEL_Y: u32 = 90;

/// The figure's horizontal axes: e1 (lab x on the cloth, or lab y when x is vertical) and
/// e2 = up x e1.
struct Projection {
    e1: Vector3<f64>,
    e2: Vector3<f64>,
    /// Whether `up` is +z, so that e1, e2 are the lab x and y axes.
    lab_xy: bool,
}

impl Projection {
    /// The axes for the unit vertical `up`.
    fn new(up: &Vector3<f64>) -> Self {
        let mut e1 = Vector3::x() - up * up.x;
        if e1.norm() < 1e-6 {
            e1 = Vector3::y() - up * up.y;
        }
        let e1 = e1.normalize();
        let e2 = up.cross(&e1);
        let lab_xy = (up - Vector3::z()).norm() < 1e-12;
        Projection { e1, e2, lab_xy }
    }

    /// The point (m) of a lab position (m) on the figure.
    fn xy(&self, p: &Vector3<f64>) -> Point {
        (p.dot(&self.e1), p.dot(&self.e2))
    }

    /// The axis descriptions, x then y.
    fn axis_names(&self) -> (&'static str, &'static str) {
        if self.lab_xy {
            ("x (m)", "y (m)")
        } else {
            ("horizontal e1 (m)", "horizontal e2 = up x e1 (m)")
        }
    }
}

/// The smallest box holding some points (m).
#[derive(Clone, Copy)]
struct Bounds {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
}

impl Bounds {
    /// The box of `points`.
    fn of(points: impl Iterator<Item = Point>) -> Self {
        let (x0, x1, y0, y1) = points.fold(
            (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ),
            |(a, b, c, d), (x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
        );
        Bounds { x0, x1, y0, y1 }
    }

    /// Grows the box to hold `p`.
    fn include(&mut self, p: Point) {
        self.x0 = self.x0.min(p.0);
        self.x1 = self.x1.max(p.0);
        self.y0 = self.y0.min(p.1);
        self.y1 = self.y1.max(p.1);
    }

    /// The larger side (m), at least 8 `radius` (m).
    fn span(&self, radius: f64) -> f64 {
        (self.x1 - self.x0).max(self.y1 - self.y0).max(8.0 * radius)
    }
}

/// Everything the figure shows, on the figure's axes.
struct Layout {
    /// Ball A's and ball B's paths, run by run.
    runs: [Vec<Run>; 2],
    /// Arrows along the final rolling directions (none for a ball at rest).
    arrows: Vec<Arrow>,
    /// Where the dotted line of ball A's incoming direction starts (it ends at A).
    incoming_from: Option<Point>,
    /// The box holding the paths, the outlines at contact and the arrows.
    bounds: Bounds,
}

impl Layout {
    /// The layout of `t`'s figure, balls A and B of radii `radii` (m).
    fn new(t: &TableOutcome, radii: [f64; 2], proj: &Projection) -> Self {
        let up = t.table.up;
        let end = t.end_time();
        let runs = [runs(&t.a, &up, end, proj), runs(&t.b, &up, end, proj)];
        let outlines = [&t.a, &t.b].into_iter().zip(radii).flat_map(|(r, radius)| {
            let (x, y) = proj.xy(&r.start.position);
            [(x - radius, y - radius), (x + radius, y + radius)]
        });
        let paths = runs.iter().flatten().flat_map(|(_, p)| p.iter().copied());
        let mut bounds = Bounds::of(paths.chain(outlines));
        let span = bounds.span(larger(radii));
        let arrows = final_arrows(t, proj, end, 0.2 * span);
        let vin = horizontal(&t.incoming[0], &up);
        let incoming_from = (vin.norm() > 0.0).then(|| {
            let (ax, ay) = proj.xy(&t.a.start.position);
            let back = proj.xy(&(vin.normalize() * (0.25 * span)));
            (ax - back.0, ay - back.1)
        });
        for to in arrows.iter().map(|a| a.1).chain(incoming_from) {
            bounds.include(to);
        }
        Layout {
            runs,
            arrows,
            incoming_from,
            bounds,
        }
    }
}

/// Points of a ball's path from separation to `end` (s), split into runs of one motion.
fn runs(r: &RollOut, up: &Vector3<f64>, end: f64, proj: &Projection) -> Vec<Run> {
    let mut out = Vec::new();
    for seg in &r.segments {
        if seg.t0 > end {
            break;
        }
        let t1 = seg.t1.min(end);
        let n = if seg.phase == BallMotion::Rest {
            1
        } else {
            POINTS_PER_SEGMENT
        };
        let pts = (0..=n)
            .map(|i| {
                let t = seg.t0 + (t1 - seg.t0) * f64::from(i) / f64::from(n);
                proj.xy(&seg.at(up, t).position)
            })
            .collect();
        out.push((seg.phase, pts));
    }
    out
}

/// Arrows of length `len` (m) from each ball's position at `end` (s) along its final
/// rolling direction.
fn final_arrows(t: &TableOutcome, proj: &Projection, end: f64, len: f64) -> Vec<Arrow> {
    let up = t.table.up;
    [(&t.a, COLOR_A), (&t.b, COLOR_B)]
        .into_iter()
        .filter_map(|(r, c)| {
            let (_, s) = r.at(&up, end, true);
            let vh = horizontal(&r.rolling.velocity, &up);
            (vh.norm() > 0.0).then(|| {
                let from = proj.xy(&s.position);
                let d = proj.xy(&(vh.normalize() * len));
                (from, (from.0 + d.0, from.1 + d.1), c)
            })
        })
        .collect()
}

/// The axis ranges (m): `b` padded by 6 % of its span and widened along the shorter side
/// so that both axes have the same scale on a figure of `dims` (px).
fn equal_scale(b: &Bounds, radius: f64, dims: (u32, u32)) -> (Range<f64>, Range<f64>) {
    let (w, h) = dims;
    let pw = f64::from(w.saturating_sub(LABEL_Y + 40));
    let ph = f64::from(h.saturating_sub(LABEL_X + CAPTION + 40));
    let pad = 0.06 * b.span(radius);
    let (cx0, cx1, cy0, cy1) = (b.x0 - pad, b.x1 + pad, b.y0 - pad, b.y1 + pad);
    let scale = ((cx1 - cx0) / pw).max((cy1 - cy0) / ph);
    let (mx, my) = (0.5 * (cx0 + cx1), 0.5 * (cy0 + cy1));
    (
        mx - 0.5 * scale * pw..mx + 0.5 * scale * pw,
        my - 0.5 * scale * ph..my + 0.5 * scale * ph,
    )
}

/// The larger of two radii (m): what the figure's margins are measured in.
fn larger(radii: [f64; 2]) -> f64 {
    radii[0].max(radii[1])
}

/// Draws the figure of the table phase `t` on `root` with title `title`, balls A and B of
/// radii `radii` (m); an error carries the backend's message.
pub fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    t: &TableOutcome,
    radii: [f64; 2],
    title: &str,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    super::register_fonts();
    draw_figure(root, t, radii, title).map_err(|e| e.to_string())
}

/// The figure, element by element (in this order, so later ones are on top).
fn draw_figure<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    t: &TableOutcome,
    radii: [f64; 2],
    title: &str,
) -> Drawn<DB> {
    let proj = Projection::new(&t.table.up);
    let layout = Layout::new(t, radii, &proj);
    let (x, y) = equal_scale(&layout.bounds, larger(radii), root.dim_in_pixel());
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(root)
        .caption(title, (FONT, 22))
        .margin(20)
        .x_label_area_size(LABEL_X)
        .y_label_area_size(LABEL_Y)
        .build_cartesian_2d(x.clone(), y.clone())?;
    draw_axes(&mut chart, &proj)?;
    draw_line_of_centres(&mut chart, t, &proj, (&x, &y))?;
    if let Some(from) = layout.incoming_from {
        draw_incoming(&mut chart, from, proj.xy(&t.a.start.position))?;
    }
    let balls = [
        ("A (cue ball)", &t.a, COLOR_A),
        ("B (object ball)", &t.b, COLOR_B),
    ];
    for (((name, r, color), runs), radius) in balls.into_iter().zip(&layout.runs).zip(radii) {
        draw_outline(&mut chart, proj.xy(&r.start.position), radius, color)?;
        draw_path(&mut chart, name, runs, color)?;
        draw_markers(&mut chart, r, &t.table.up, &proj, color, x.end - x.start)?;
    }
    for arrow in &layout.arrows {
        draw_arrow(&mut chart, arrow)?;
    }
    draw_legend(&mut chart)?;
    root.present()
}

/// The mesh and the axis descriptions.
fn draw_axes<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    proj: &Projection,
) -> Drawn<DB> {
    let (xl, yl) = proj.axis_names();
    chart
        .configure_mesh()
        .x_desc(xl)
        .y_desc(yl)
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 17))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
}

/// The line of centres at contact (dashed, grey) across the figure, whose axes span
/// `ranges` (m).
fn draw_line_of_centres<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    t: &TableOutcome,
    proj: &Projection,
    ranges: (&Range<f64>, &Range<f64>),
) -> Drawn<DB> {
    let ca = proj.xy(&t.a.start.position);
    let l = proj.xy(&t.line);
    // The backend moves a point outside the axes onto the border coordinate by coordinate,
    // which turns a slanted line towards a corner: draw only the part inside the axes.
    let Some((from, to)) = clip_line(ca, l, ranges) else {
        return Ok(());
    };
    let line = [from, to];
    chart
        .draw_series(DashedLineSeries::new(
            line,
            10,
            6,
            ShapeStyle::from(COLOR_LINE).stroke_width(2),
        ))?
        .label("line of centres at contact")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], COLOR_LINE.stroke_width(2)));
    Ok(())
}

/// Where the cue ball came from: its incoming direction of travel, dotted, `from` to its
/// centre at contact `to`.
fn draw_incoming<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    from: Point,
    to: Point,
) -> Drawn<DB> {
    chart
        .draw_series(DashedLineSeries::new(
            [from, to],
            3,
            5,
            COLOR_A.mix(0.6).stroke_width(2),
        ))?
        .label("A incoming")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 20, y)], COLOR_A.mix(0.6).stroke_width(2)));
    Ok(())
}

/// The part inside the box `ranges` of the line through `p` along `d`: its two ends, or
/// `None` when the line misses the box (or `d` is zero). Each axis bounds the line
/// parameter s of p + s d; the part inside is the intersection of the two intervals.
fn clip_line(p: Point, d: Point, ranges: (&Range<f64>, &Range<f64>)) -> Option<(Point, Point)> {
    let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for (start, dir, range) in [(p.0, d.0, ranges.0), (p.1, d.1, ranges.1)] {
        if dir == 0.0 {
            if start < range.start || start > range.end {
                return None;
            }
        } else {
            let (a, b) = ((range.start - start) / dir, (range.end - start) / dir);
            lo = lo.max(a.min(b));
            hi = hi.min(a.max(b));
        }
    }
    (lo < hi && lo.is_finite() && hi.is_finite()).then_some((
        (p.0 + lo * d.0, p.1 + lo * d.1),
        (p.0 + hi * d.0, p.1 + hi * d.1),
    ))
}

/// A ball's outline at contact: the circle of `radius` (m) about `centre`.
fn draw_outline<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    centre: Point,
    radius: f64,
    color: RGBColor,
) -> Drawn<DB> {
    let (cx, cy) = centre;
    let outline: Vec<Point> = (0..=OUTLINE_POINTS)
        .map(|i| {
            let a = std::f64::consts::TAU * f64::from(i) / f64::from(OUTLINE_POINTS);
            (cx + radius * a.cos(), cy + radius * a.sin())
        })
        .collect();
    chart.draw_series(LineSeries::new(outline, color.stroke_width(1)))?;
    Ok(())
}

/// A ball's path, run by run: flight thin and light, sliding solid, rolling thick; one
/// legend entry `name`.
fn draw_path<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    name: &str,
    runs: &[Run],
    color: RGBColor,
) -> Drawn<DB> {
    for (i, (motion, pts)) in runs.iter().enumerate() {
        let style = match motion {
            BallMotion::Flight => color.mix(0.45).stroke_width(1),
            BallMotion::Sliding => color.stroke_width(2),
            BallMotion::Rolling | BallMotion::Rest => color.stroke_width(4),
        };
        let s = chart.draw_series(LineSeries::new(pts.iter().copied(), style))?;
        if i == 0 {
            s.label(format!("{name}: flight thin, sliding, rolling thick"))
                .legend(move |(x, y)| {
                    PathElement::new([(x, y), (x + 20, y)], color.stroke_width(3))
                });
        }
    }
    Ok(())
}

/// A ball's landing points (crosses), where it starts to roll (filled dot) and, with
/// rolling resistance, where it rests (a square of 1.2 % of the x range `x_span` (m)).
fn draw_markers<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    r: &RollOut,
    up: &Vector3<f64>,
    proj: &Projection,
    color: RGBColor,
    x_span: f64,
) -> Drawn<DB> {
    let landings: Vec<Point> = r
        .impacts
        .iter()
        .filter(|i| i.time > 0.0)
        .map(|i| proj.xy(&r.at(up, i.time, true).1.position))
        .collect();
    chart.draw_series(
        landings
            .into_iter()
            .map(|p| Cross::new(p, 7, color.stroke_width(2))),
    )?;
    chart.draw_series(std::iter::once(Circle::new(
        proj.xy(&r.rolling.position),
        5,
        color.filled(),
    )))?;
    if let Some((_, p)) = r.rest {
        let (px, py) = proj.xy(&p);
        let d = 0.006 * x_span;
        chart.draw_series(std::iter::once(Rectangle::new(
            [(px - d, py - d), (px + d, py + d)],
            color.filled(),
        )))?;
    }
    Ok(())
}

/// A dashed arrow with an open head a quarter of its length.
fn draw_arrow<'a, DB: DrawingBackend + 'a>(chart: &mut Chart<'a, DB>, arrow: &Arrow) -> Drawn<DB> {
    let &(from, to, color) = arrow;
    let (dx, dy) = (to.0 - from.0, to.1 - from.1);
    let len = dx.hypot(dy);
    let (ux, uy) = (dx / len, dy / len);
    let head = 0.25 * len;
    let wing = |s: f64| {
        (
            to.0 - head * (ux * 0.94 - s * uy * 0.34),
            to.1 - head * (uy * 0.94 + s * ux * 0.34),
        )
    };
    chart.draw_series(DashedLineSeries::new(
        [from, to],
        6,
        4,
        color.stroke_width(2),
    ))?;
    chart.draw_series(LineSeries::new(
        [wing(1.0), to, wing(-1.0)],
        color.stroke_width(2),
    ))?;
    Ok(())
}

/// The legend: the series' entries and one for the markers, upper left.
fn draw_legend<'a, DB: DrawingBackend + 'a>(chart: &mut Chart<'a, DB>) -> Drawn<DB> {
    let gray = RGBColor(60, 60, 60);
    chart
        .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
        .label("x landing on the cloth, dot: starts rolling, dashed arrow: rolling direction")
        .legend(move |(x, y)| Cross::new((x + 10, y), 5, gray.stroke_width(2)));
    chart
        .configure_series_labels()
        .label_font((FONT, 14))
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(160, 160, 160))
        .position(SeriesLabelPosition::UpperLeft)
        .draw()
}

/// The figure of `t` (balls A and B of radii `radii`, m) as SVG text.
pub fn svg(t: &TableOutcome, radii: [f64; 2], title: &str) -> Result<String, Error> {
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, SIZE).into_drawing_area();
        draw(&root, t, radii, title).map_err(plot_error)?;
    }
    Ok(out)
}

/// Renders the figure of `t` (balls A and B of radii `radii`, m) as PNG at `path` (written
/// directly; the CLI renames it into place).
pub fn png(
    t: &TableOutcome,
    radii: [f64; 2],
    title: &str,
    path: &std::path::Path,
) -> Result<(), Error> {
    let root = BitMapBackend::new(path, SIZE).into_drawing_area();
    draw(&root, t, radii, title).map_err(plot_error)
}

fn plot_error(message: String) -> Error {
    Error::Plot {
        path: "plot".into(),
        message: format!("drawing the path figure: {message}"),
    }
}

#[cfg(test)]
mod tests {
    use super::clip_line;

    #[test]
    fn the_line_of_centres_is_clipped_to_the_axes_along_itself() {
        let (x, y) = (-1.0..3.0, -1.0..1.0);
        // Horizontal through (0.5, 0.25): from x = -1 to x = 3 at y = 0.25.
        let h = clip_line((0.5, 0.25), (2.0, 0.0), (&x, &y)).unwrap();
        assert_eq!(h, ((-1.0, 0.25), (3.0, 0.25)));
        // Slope 1/2 through the origin: y reaches -1 and 1 at x = -2 and 2, outside x's
        // -1 on the left, so the part inside runs from (-1, -0.5) to (2, 1).
        let (a, b) = clip_line((0.0, 0.0), (0.8, 0.4), (&x, &y)).unwrap();
        let close = |p: (f64, f64), q: (f64, f64)| (p.0 - q.0).abs().max((p.1 - q.1).abs()) < 1e-15;
        assert!(
            close(a, (-1.0, -0.5)) && close(b, (2.0, 1.0)),
            "{a:?} {b:?}"
        );
        // A line that passes above the box, and a vertical one beside it.
        assert!(clip_line((0.0, 2.0), (1.0, 0.0), (&x, &y)).is_none());
        assert!(clip_line((4.0, 0.0), (0.0, 1.0), (&x, &y)).is_none());
        assert!(clip_line((0.0, 0.0), (0.0, 0.0), (&x, &y)).is_none());
    }
}
