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
use crate::table_phase::{Phase, RollOut, TableOutcome};
use nalgebra::Vector3;
use plotters::coord::Shift;
use plotters::prelude::*;

/// Figure size in pixels.
pub const SIZE: (u32, u32) = (900, 820);

/// An arrow on the figure: from, to, colour.
type Arrow = ((f64, f64), (f64, f64), RGBColor);

const COLOR_A: RGBColor = RGBColor(31, 90, 180);
const COLOR_B: RGBColor = RGBColor(200, 60, 30);

/// The horizontal basis (e1, e2) of the figure.
fn basis(up: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>, bool) {
    let mut e1 = Vector3::x() - up * up.x;
    if e1.norm() < 1e-6 {
        e1 = Vector3::y() - up * up.y;
    }
    let e1 = e1.normalize();
    let e2 = up.cross(&e1);
    let lab_xy = (up - Vector3::z()).norm() < 1e-12;
    (e1, e2, lab_xy)
}

/// Points of a ball's path from separation to `end` (s), split into runs of one phase.
fn runs(r: &RollOut, up: &Vector3<f64>, end: f64) -> Vec<(Phase, Vec<Vector3<f64>>)> {
    let mut out = Vec::new();
    for seg in &r.segments {
        if seg.t0 > end {
            break;
        }
        let t1 = seg.t1.min(end);
        let n = if seg.phase == Phase::Rest { 1 } else { 120 };
        let pts = (0..=n)
            .map(|i| {
                seg.at(up, seg.t0 + (t1 - seg.t0) * i as f64 / n as f64)
                    .position
            })
            .collect();
        out.push((seg.phase, pts));
    }
    out
}

/// Draws the figure on `root` with title `title`.
pub fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    t: &TableOutcome,
    radius: f64,
    title: &str,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    super::register_fonts();
    let up = t.table.up;
    let (e1, e2, lab_xy) = basis(&up);
    let xy = |p: &Vector3<f64>| (p.dot(&e1), p.dot(&e2));
    let end = t.end_time();
    let ra = runs(&t.a, &up, end);
    let rb = runs(&t.b, &up, end);
    // Bounds: paths, outlines and arrows.
    let mut pts: Vec<(f64, f64)> = ra
        .iter()
        .chain(rb.iter())
        .flat_map(|(_, p)| p.iter().map(xy))
        .collect();
    for r in [&t.a, &t.b] {
        let (x, y) = xy(&r.start.position);
        pts.extend([(x - radius, y - radius), (x + radius, y + radius)]);
    }
    let (mut x0, mut x1, mut y0, mut y1) = pts.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    let span0 = (x1 - x0).max(y1 - y0).max(8.0 * radius);
    // Arrows along the final rolling directions: a fifth of the span.
    let arrow_len = 0.2 * span0;
    let arrows: Vec<Arrow> = [(&t.a, COLOR_A), (&t.b, COLOR_B)]
        .into_iter()
        .filter_map(|(r, c)| {
            let (_, s) = r.at(&up, end, true);
            let v = r.rolling.velocity;
            let vh = crate::model::frame::horizontal(&v, &up);
            (vh.norm() > 0.0).then(|| {
                let from = xy(&s.position);
                let d = xy(&(vh.normalize() * arrow_len));
                (from, (from.0 + d.0, from.1 + d.1), c)
            })
        })
        .collect();
    let vin = crate::model::frame::horizontal(&t.incoming[0], &up);
    let incoming_from = (vin.norm() > 0.0).then(|| {
        let (ax, ay) = xy(&t.a.start.position);
        let back = xy(&(vin.normalize() * (0.25 * span0)));
        (ax - back.0, ay - back.1)
    });
    for to in arrows.iter().map(|a| &a.1).chain(incoming_from.iter()) {
        x0 = x0.min(to.0);
        x1 = x1.max(to.0);
        y0 = y0.min(to.1);
        y1 = y1.max(to.1);
    }
    // Equal scales: widen the shorter range to the plotting area's aspect.
    let (w, h) = root.dim_in_pixel();
    let (label_x, label_y, caption) = (60u32, 90u32, 40u32);
    let pw = f64::from(w.saturating_sub(label_y + 40));
    let ph = f64::from(h.saturating_sub(label_x + caption + 40));
    let pad = 0.06 * (x1 - x0).max(y1 - y0).max(8.0 * radius);
    let (mut cx0, mut cx1, mut cy0, mut cy1) = (x0 - pad, x1 + pad, y0 - pad, y1 + pad);
    let scale = ((cx1 - cx0) / pw).max((cy1 - cy0) / ph);
    let (mx, my) = (0.5 * (cx0 + cx1), 0.5 * (cy0 + cy1));
    cx0 = mx - 0.5 * scale * pw;
    cx1 = mx + 0.5 * scale * pw;
    cy0 = my - 0.5 * scale * ph;
    cy1 = my + 0.5 * scale * ph;

    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let mut chart = ChartBuilder::on(root)
        .caption(title, (FONT, 22))
        .margin(20)
        .x_label_area_size(label_x)
        .y_label_area_size(label_y)
        .build_cartesian_2d(cx0..cx1, cy0..cy1)
        .map_err(err)?;
    let (xl, yl) = if lab_xy {
        ("x (m)", "y (m)")
    } else {
        ("horizontal e1 (m)", "horizontal e2 = up x e1 (m)")
    };
    chart
        .configure_mesh()
        .x_desc(xl)
        .y_desc(yl)
        .label_style((FONT, 15))
        .axis_desc_style((FONT, 17))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(err)?;

    // Line of centres at contact, across the figure.
    let ca = xy(&t.a.start.position);
    let cb = xy(&t.b.start.position);
    let l = xy(&t.line);
    let reach = 2.0 * ((cx1 - cx0) + (cy1 - cy0));
    let line = [
        (ca.0 - reach * l.0, ca.1 - reach * l.1),
        (cb.0 + reach * l.0, cb.1 + reach * l.1),
    ];
    chart
        .draw_series(DashedLineSeries::new(
            line,
            10,
            6,
            ShapeStyle::from(RGBColor(90, 90, 90)).stroke_width(2),
        ))
        .map_err(err)?
        .label("line of centres at contact")
        .legend(|(x, y)| {
            PathElement::new([(x, y), (x + 20, y)], RGBColor(90, 90, 90).stroke_width(2))
        });
    // Where the cue ball came from: its incoming direction of travel, dotted.
    if let Some(from) = incoming_from {
        chart
            .draw_series(DashedLineSeries::new(
                [from, ca],
                3,
                5,
                COLOR_A.mix(0.6).stroke_width(2),
            ))
            .map_err(err)?
            .label("A incoming")
            .legend(|(x, y)| {
                PathElement::new([(x, y), (x + 20, y)], COLOR_A.mix(0.6).stroke_width(2))
            });
    }

    for (name, r, runs, color) in [
        ("A (cue ball)", &t.a, &ra, COLOR_A),
        ("B (object ball)", &t.b, &rb, COLOR_B),
    ] {
        // Outline at contact.
        let (cx, cy) = xy(&r.start.position);
        let outline: Vec<(f64, f64)> = (0..=72)
            .map(|i| {
                let a = std::f64::consts::TAU * f64::from(i) / 72.0;
                (cx + radius * a.cos(), cy + radius * a.sin())
            })
            .collect();
        chart
            .draw_series(LineSeries::new(outline, color.stroke_width(1)))
            .map_err(err)?;
        let mut labelled = false;
        for (phase, pts) in runs.iter() {
            let p: Vec<(f64, f64)> = pts.iter().map(xy).collect();
            let style = match phase {
                Phase::Flight => color.mix(0.45).stroke_width(1),
                Phase::Sliding => color.stroke_width(2),
                Phase::Rolling | Phase::Rest => color.stroke_width(4),
            };
            let s = chart.draw_series(LineSeries::new(p, style)).map_err(err)?;
            if !labelled {
                labelled = true;
                s.label(format!("{name}: flight thin, sliding, rolling thick"))
                    .legend(move |(x, y)| {
                        PathElement::new([(x, y), (x + 20, y)], color.stroke_width(3))
                    });
            }
        }
        // Landing points, start of rolling, rest.
        let landings: Vec<(f64, f64)> = r
            .impacts
            .iter()
            .filter(|i| i.time > 0.0)
            .map(|i| xy(&r.at(&up, i.time, true).1.position))
            .collect();
        chart
            .draw_series(
                landings
                    .into_iter()
                    .map(|p| Cross::new(p, 7, color.stroke_width(2))),
            )
            .map_err(err)?;
        chart
            .draw_series(std::iter::once(Circle::new(
                xy(&r.rolling.position),
                5,
                color.filled(),
            )))
            .map_err(err)?;
        if let Some((_, p)) = r.rest {
            let (px, py) = xy(&p);
            let d = 0.006 * (cx1 - cx0);
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(px - d, py - d), (px + d, py + d)],
                    color.filled(),
                )))
                .map_err(err)?;
        }
    }
    for (from, to, color) in arrows {
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
        chart
            .draw_series(DashedLineSeries::new(
                [from, to],
                6,
                4,
                color.stroke_width(2),
            ))
            .map_err(err)?;
        chart
            .draw_series(LineSeries::new(
                [wing(1.0), to, wing(-1.0)],
                color.stroke_width(2),
            ))
            .map_err(err)?;
    }
    // Legend entries for the markers.
    let gray = RGBColor(60, 60, 60);
    chart
        .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
        .map_err(err)?
        .label("x landing on the cloth, dot: starts rolling, dashed arrow: rolling direction")
        .legend(move |(x, y)| Cross::new((x + 10, y), 5, gray.stroke_width(2)));
    chart
        .configure_series_labels()
        .label_font((FONT, 14))
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(160, 160, 160))
        .position(SeriesLabelPosition::UpperLeft)
        .draw()
        .map_err(err)?;
    root.present().map_err(err)?;
    Ok(())
}

/// The figure as SVG text.
pub fn svg(t: &TableOutcome, radius: f64, title: &str) -> Result<String, Error> {
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, SIZE).into_drawing_area();
        draw(&root, t, radius, title).map_err(plot_error)?;
    }
    Ok(out)
}

/// Renders the figure as PNG at `path` (written directly; the CLI renames it into place).
pub fn png(
    t: &TableOutcome,
    radius: f64,
    title: &str,
    path: &std::path::Path,
) -> Result<(), Error> {
    let root = BitMapBackend::new(path, SIZE).into_drawing_area();
    draw(&root, t, radius, title).map_err(plot_error)
}

fn plot_error(message: String) -> Error {
    Error::io(
        "plot",
        std::io::Error::other(format!("drawing the path figure: {message}")),
    )
}
