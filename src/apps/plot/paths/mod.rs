//! Top view of both balls' paths on the table (`run --plot FILE.svg|png`), lab frame.
//!
//! Axes: lab x and y when `up` is +z (otherwise the lab x axis projected on the cloth and
//! up x that). Drawn: the table's cushions when the scene gives its size, the line of
//! centres at contact (dashed, grey), both balls' outlines at contact, each path (flight
//! thin and light, sliding medium, rolling thick), the landing points (crosses), where each
//! ball starts to roll (dots, with the time) and, with rolling resistance, where it rests
//! (squares, with the time); an arrow along the rolling direction of a ball still rolling
//! when the path ends. Both axes have the same scale, so angles on the figure are the true
//! angles; the figure's height follows the paths' extent. Below the chart: the legend, the
//! throw, the deflection and the times, and, when the balls are small on the chart, an
//! inset of the neighbourhood of the contact.

use super::style::{
    decimals_for, draw_legend, legend_row, light, short, tick_label, write_drawn, Drawn, Figure,
    LegendEntry, Line, Mark, Swatch,
};
use super::FONT;
use crate::base::error::Error;
use crate::scene::run::SceneOutcome;
use crate::scene::types::Scene;
use crate::table_phase::outcome::TableOutcome;
use crate::table_phase::params::TableSize;
use crate::table_phase::roll_out::RollOut;
use crate::table_phase::segment::BallMotion;
use nalgebra::Vector3;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::ops::Range;

mod geometry;
pub(crate) use geometry::WIDTH;
use geometry::{
    clip, cushion_corners, equal_scale, larger, Arrow, Layout, Point, Projection, COLOR_A, COLOR_B,
    LABEL_Y, MARGIN,
};

/// The chart: figure coordinates (m) on both axes.
type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The line of centres.
const COLOR_LINE: RGBColor = RGBColor(90, 90, 90);
/// The kinds of motion in the legend.
const COLOR_KEY: RGBColor = RGBColor(70, 70, 70);
/// The cushions and the cloth.
const COLOR_CUSHION: RGBColor = RGBColor(20, 110, 60);
const COLOR_CLOTH: RGBColor = RGBColor(225, 242, 228);
/// Points on a ball's outline.
const OUTLINE_POINTS: u32 = 72;
/// Heights (px) of the title strip, the x label area and the strip below the chart (the y
/// label area's width and the margin are with the geometry).
const HEADER: u32 = 50;
const LABEL_X: u32 = 56;
const STRIP: u32 = 300;
/// Landing crosses of one ball closer than this (px) are drawn once.
const CROWDED_PX: f64 = 10.0;
/// Balls smaller than this radius (px) on the chart get the inset near the contact.
const SMALL_BALL_PX: f64 = 8.0;
/// Text sizes (px): title, tick labels, axis descriptions, legend and notes.
const TITLE_FONT: u32 = 22;
const TICK_FONT: u32 = 15;
const DESC_FONT: u32 = 17;
const LEGEND_FONT: u32 = 15;

/// How each kind of motion is drawn, in `color`: flight thin and light, sliding medium,
/// rolling thick.
fn motion_swatch(motion: BallMotion, color: RGBColor) -> Swatch {
    match motion {
        BallMotion::Flight => Swatch::line(light(color), 1),
        BallMotion::Sliding => Swatch::line(color, 2),
        BallMotion::Rolling | BallMotion::Rest => Swatch::line(color, 5),
    }
}

/// The top view of a run's table phase, laid out and ready to draw.
pub(crate) struct TopView<'a> {
    t: &'a TableOutcome,
    /// Radii of balls A and B (m).
    radii: [f64; 2],
    title: String,
    size: Option<TableSize>,
    /// Throw angle at separation (degrees), from the contact.
    throw_deg: Option<f64>,
    proj: Projection,
    layout: Layout,
    x: Range<f64>,
    y: Range<f64>,
    /// Height (px) of the main chart's plotting area.
    plot_height: u32,
    /// Centre and half side (m) of the inset near the contact, when the balls are small.
    inset: Option<(Point, f64)>,
}

impl<'a> TopView<'a> {
    /// The top view of `t`, the table phase of `run` (a run of `scene`).
    pub(crate) fn new(scene: &Scene, run: &SceneOutcome, t: &'a TableOutcome) -> Self {
        let radii = scene.balls.radii();
        let radius = larger(radii);
        let proj = Projection::new(&t.table.up);
        let layout = Layout::new(t, radii, scene.table_size, &proj);
        let (x, y, plot_height) = equal_scale(&layout.bounds, radius);
        let px_per_m = f64::from(WIDTH - 2 * MARGIN - LABEL_Y) / (x.end - x.start);
        let inset = (radius * px_per_m < SMALL_BALL_PX)
            .then(|| inset_box(t, &proj, radius, x.end - x.start));
        TopView {
            t,
            radii,
            title: format!("{}: top view", scene.name),
            size: scene.table_size,
            throw_deg: run.throw_angle_deg,
            proj,
            layout,
            x,
            y,
            plot_height,
            inset,
        }
    }

    /// Writes the figure to `path` ([`write_drawn`]).
    pub(crate) fn write(&self, option: &str, path: &std::path::Path) -> Result<(), Error> {
        write_drawn(option, path, self)
    }
}

impl Figure for TopView<'_> {
    fn dims(&self) -> (u32, u32) {
        (
            WIDTH,
            HEADER + self.plot_height + 2 * MARGIN + LABEL_X + STRIP,
        )
    }

    /// The title, the main chart, then the strip: legend, notes and the inset.
    fn draw_all<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Drawn<DB> {
        root.fill(&WHITE)?;
        let (header, rest) = root.split_vertically(HEADER);
        header.draw(&Text::new(
            self.title.clone(),
            (MARGIN as i32, 14),
            (FONT, TITLE_FONT).into_font().style(FontStyle::Bold),
        ))?;
        let (main, strip) = rest.split_vertically(self.plot_height + 2 * MARGIN + LABEL_X);
        let mut chart = ChartBuilder::on(&main)
            .margin(MARGIN)
            .x_label_area_size(LABEL_X)
            .y_label_area_size(LABEL_Y)
            .build_cartesian_2d(self.x.clone(), self.y.clone())?;
        self.draw_axes(&mut chart)?;
        self.draw_scene(&mut chart, true)?;
        if let Some((c, h)) = self.inset {
            let frame = [
                (c.0 - h, c.1 - h),
                (c.0 + h, c.1 - h),
                (c.0 + h, c.1 + h),
                (c.0 - h, c.1 + h),
                (c.0 - h, c.1 - h),
            ];
            chart.draw_series(std::iter::once(PathElement::new(
                frame.to_vec(),
                BLACK.stroke_width(1),
            )))?;
        }
        let (notes, inset_area) =
            strip.split_horizontally(WIDTH - if self.inset.is_some() { STRIP } else { 0 });
        self.draw_notes(&notes)?;
        if let Some(b) = self.inset {
            self.draw_inset(&inset_area, b)?;
        }
        root.present()
    }
}

impl TopView<'_> {
    /// The mesh and the axis descriptions, tick labels without "-0".
    fn draw_axes<'b, DB: DrawingBackend + 'b>(&self, chart: &mut Chart<'b, DB>) -> Drawn<DB> {
        let (xl, yl) = self.proj.axis_names();
        let d = decimals_for((self.x.end - self.x.start).min(self.y.end - self.y.start) / 8.0);
        chart
            .configure_mesh()
            .x_desc(xl)
            .y_desc(yl)
            .x_label_formatter(&|v| tick_label(*v, d))
            .y_label_formatter(&|v| tick_label(*v, d))
            .label_style((FONT, TICK_FONT))
            .axis_desc_style((FONT, DESC_FONT))
            .light_line_style(RGBColor(238, 238, 238))
            .draw()
    }

    /// Everything on the cloth, in this order (later on top): the table, the line of
    /// centres, A's incoming line, the paths, the arrows, the markers, the outlines at
    /// contact. `main`: the main chart (landings thinned out, times written).
    fn draw_scene<'b, DB: DrawingBackend + 'b>(
        &self,
        chart: &mut Chart<'b, DB>,
        main: bool,
    ) -> Drawn<DB> {
        let t = self.t;
        if let Some(size) = &self.size {
            let c = cushion_corners(size);
            chart.draw_series(std::iter::once(Polygon::new(
                c.to_vec(),
                COLOR_CLOTH.mix(0.6).filled(),
            )))?;
            draw_clipped(chart, Swatch::line(COLOR_CUSHION, 3), &c)?;
        }
        let reach = 4.0 * ((self.x.end - self.x.start) + (self.y.end - self.y.start));
        draw_line_of_centres(chart, t, &self.proj, reach)?;
        if let Some(from) = self.layout.incoming_from {
            let a = self.proj.xy(&t.a.start.position);
            draw_clipped(chart, incoming_swatch(), &[from, a])?;
        }
        let balls = [(&t.a, COLOR_A), (&t.b, COLOR_B)];
        for ((_, color), runs) in balls.iter().zip(&self.layout.runs) {
            for (motion, pts) in runs {
                draw_clipped(chart, motion_swatch(*motion, *color), pts)?;
            }
        }
        for arrow in &self.layout.arrows {
            draw_arrow(chart, arrow)?;
        }
        for (r, color) in balls {
            self.draw_markers(chart, r, color, main)?;
        }
        for ((r, color), radius) in balls.into_iter().zip(self.radii) {
            draw_outline(chart, self.proj.xy(&r.start.position), radius, color)?;
        }
        Ok(())
    }

    /// A ball's landings (crosses; those closer than [`CROWDED_PX`] to one drawn before
    /// are left out), where it starts to roll (dot) and where it rests
    /// (square); on the main chart with their times.
    fn draw_markers<'b, DB: DrawingBackend + 'b>(
        &self,
        chart: &mut Chart<'b, DB>,
        r: &RollOut,
        color: RGBColor,
        main: bool,
    ) -> Drawn<DB> {
        let up = &self.t.table.up;
        let (xr, yr) = (chart.x_range(), chart.y_range());
        let inside = |p: &Point| xr.contains(&p.0) && yr.contains(&p.1);
        let mut drawn: Vec<(i32, i32)> = Vec::new();
        let mut landings = Vec::new();
        for p in landings_of(r, up, &self.proj).filter(inside) {
            let px = chart.backend_coord(&p);
            let near =
                |q: &(i32, i32)| f64::from(q.0 - px.0).hypot(f64::from(q.1 - px.1)) < CROWDED_PX;
            if !drawn.iter().any(near) {
                drawn.push(px);
                landings.push((p, false));
            }
        }
        landing_swatch(color).draw_marks(chart.plotting_area(), landings)?;
        let roll = self.proj.xy(&r.rolling.position);
        let heading = self.proj.xy(&r.rolling.velocity);
        if inside(&roll) {
            roll_swatch(color).draw_marks(chart.plotting_area(), [(roll, false)])?;
            if main {
                let text = format!("rolls {} s", short(r.roll_time));
                time_label(chart, roll, heading, text, color)?;
            }
        }
        if let Some((time, p)) = r.rest.map(|(t, p)| (t, self.proj.xy(&p))) {
            if inside(&p) {
                rest_swatch(color).draw_marks(chart.plotting_area(), [(p, false)])?;
                if main {
                    time_label(chart, p, heading, format!("rests {} s", short(time)), color)?;
                }
            }
        }
        Ok(())
    }

    /// The strip below the chart: the legend in two columns, then the throw, the
    /// deflection and the times.
    fn draw_notes<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> Drawn<DB> {
        let entries = self.legend();
        let (w, _) = area.dim_in_pixel();
        let x0 = MARGIN as i32 + 8;
        let column = (w as i32 - x0) / 2;
        draw_legend(area, &entries, (x0, 6), (2, column), LEGEND_FONT)?;
        let rows = entries.len().div_ceil(2) as i32;
        let mut y = 6 + rows * legend_row(LEGEND_FONT) + 10;
        for line in self.annotations() {
            area.draw(&Text::new(line, (x0, y), (FONT, LEGEND_FONT).into_font()))?;
            y += legend_row(LEGEND_FONT);
        }
        Ok(())
    }

    /// The legend's entries: what each line and marker means (only the markers drawn).
    fn legend(&self) -> Vec<LegendEntry> {
        let t = self.t;
        let mut e = vec![
            LegendEntry::new(motion_swatch(BallMotion::Sliding, COLOR_A), "A (cue ball)"),
            LegendEntry::new(
                motion_swatch(BallMotion::Sliding, COLOR_B),
                "B (object ball)",
            ),
            LegendEntry::new(line_of_centres_swatch(), "line of centres at contact"),
            LegendEntry::new(incoming_swatch(), "A incoming"),
            LegendEntry::new(
                motion_swatch(BallMotion::Flight, COLOR_KEY),
                "in flight (thin)",
            ),
            LegendEntry::new(motion_swatch(BallMotion::Sliding, COLOR_KEY), "sliding"),
            LegendEntry::new(
                motion_swatch(BallMotion::Rolling, COLOR_KEY),
                "rolling (thick)",
            ),
        ];
        let up = &t.table.up;
        let landings = |r: &RollOut| landings_of(r, up, &self.proj).count();
        let (la, lb) = (landings(&t.a), landings(&t.b));
        if la + lb > 0 {
            e.push(LegendEntry::new(
                landing_swatch(COLOR_KEY),
                format!("landing (A {la}, B {lb}; those within {CROWDED_PX} px drawn once)"),
            ));
        }
        e.push(LegendEntry::new(
            roll_swatch(COLOR_KEY),
            "starts rolling (time)",
        ));
        if t.a.rest.is_some() || t.b.rest.is_some() {
            e.push(LegendEntry::new(
                rest_swatch(COLOR_KEY),
                "comes to rest (time)",
            ));
        }
        if !self.layout.arrows.is_empty() {
            e.push(LegendEntry::new(
                Swatch::line(COLOR_KEY, 2).with_line(Line::Dashed),
                "arrow: rolls on this way",
            ));
        }
        if self.size.is_some() {
            e.push(LegendEntry::new(
                Swatch::line(COLOR_CUSHION, 3),
                "cushions (not modelled)",
            ));
        }
        if self.inset.is_some() {
            e.push(LegendEntry::new(
                Swatch::line(BLACK, 1),
                "box: the inset, near the contact",
            ));
        }
        e
    }

    /// The throw, the deflection and the times, one line each.
    fn annotations(&self) -> Vec<String> {
        let t = self.t;
        let deg =
            |d: Option<f64>| d.map_or_else(|| "none (at rest)".into(), |d| format!("{d:.2} deg"));
        let mut lines = vec![
            format!(
                "throw of B: {} from the line of centres once rolling ({} at separation)",
                deg(t.direction_deg(&t.b)),
                deg(self.throw_deg)
            ),
            format!(
                "deflection of A: {} from its incoming line",
                deg(t.deflection_deg(0, &t.a))
            ),
        ];
        for (name, r) in [("A", &t.a), ("B", &t.b)] {
            lines.push(ball_times(name, r));
        }
        if let Some(s) = &self.size {
            lines.push(format!(
                "table {} m x {} m centred on the lab origin; paths run on through the cushions",
                short(s.length()),
                short(s.width())
            ));
        }
        lines
    }

    /// The inset on `area`: the square of half side `h` (m) about `c`, where the balls
    /// touch, with everything the main chart draws there.
    fn draw_inset<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        (c, h): (Point, f64),
    ) -> Drawn<DB> {
        let area = area.margin(4, 12, 4, 12);
        area.draw(&Text::new(
            format!("near the contact ({} m across)", short(2.0 * h)),
            (50, 0),
            (FONT, LEGEND_FONT).into_font(),
        ))?;
        let (_, body) = area.split_vertically(legend_row(LEGEND_FONT) as u32);
        let mut chart = ChartBuilder::on(&body)
            .x_label_area_size(22)
            .y_label_area_size(50)
            .build_cartesian_2d(c.0 - h..c.0 + h, c.1 - h..c.1 + h)?;
        let d = decimals_for(h / 2.0);
        chart
            .configure_mesh()
            .x_labels(4)
            .y_labels(4)
            .x_label_formatter(&|v| tick_label(*v, d))
            .y_label_formatter(&|v| tick_label(*v, d))
            .label_style((FONT, 12))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.08))
            .draw()?;
        self.draw_scene(&mut chart, false)
    }
}

/// The square about the contact (centre, half side, m) holding both balls and the
/// landings near them: at least 4 radii, at most a fifth of the main chart's width `span`.
fn inset_box(t: &TableOutcome, proj: &Projection, radius: f64, span: f64) -> (Point, f64) {
    let (a, b) = (proj.xy(&t.a.start.position), proj.xy(&t.b.start.position));
    let c = (0.5 * (a.0 + b.0), 0.5 * (a.1 + b.1));
    let up = &t.table.up;
    let far = [&t.a, &t.b]
        .into_iter()
        .flat_map(|r| landings_of(r, up, proj))
        .map(|p| (p.0 - c.0).abs().max((p.1 - c.1).abs()))
        .filter(|d| *d < 0.1 * span)
        .fold(4.0 * radius, f64::max);
    (c, 1.2 * far + radius)
}

/// The points (m, figure axes) where a ball lands on the cloth after a flight.
fn landings_of<'r>(
    r: &'r RollOut,
    up: &'r Vector3<f64>,
    proj: &'r Projection,
) -> impl Iterator<Item = Point> + 'r {
    r.impacts
        .iter()
        .filter(|i| i.time > 0.0)
        .map(move |i| proj.xy(&r.at(up, i.time, true).1.position))
}

/// A ball's times from separation: flight, landings, rolling and rest.
fn ball_times(name: &str, r: &RollOut) -> String {
    let mut s = format!("{name}: ");
    if r.hop_time > 0.0 {
        s += &format!("hops {} s, ", short(r.hop_time));
    }
    if r.bounces > 0 {
        s += &format!(
            "bounces {} times until {} s, ",
            r.bounces,
            short(r.settle_time)
        );
    }
    s += &format!(
        "slides {} s, rolls from {} s",
        short(r.slide_time),
        short(r.roll_time)
    );
    if let Some((time, _)) = r.rest {
        s += &format!(", rests at {} s", short(time));
    }
    s + " (times from separation)"
}

/// The look of the line of centres.
fn line_of_centres_swatch() -> Swatch {
    Swatch::line(COLOR_LINE, 2).with_line(Line::Dashed)
}

/// The look of A's incoming line.
fn incoming_swatch() -> Swatch {
    Swatch::line(light(COLOR_A), 2).with_line(Line::Dotted)
}

/// The markers: landings (crosses), the start of rolling (dots), rest (squares).
fn landing_swatch(color: RGBColor) -> Swatch {
    Swatch::line(color, 2)
        .with_line(Line::None)
        .with_mark(Mark::Cross, 6)
}
fn roll_swatch(color: RGBColor) -> Swatch {
    Swatch::line(color, 2)
        .with_line(Line::None)
        .with_mark(Mark::Circle, 6)
}
fn rest_swatch(color: RGBColor) -> Swatch {
    Swatch::line(color, 2)
        .with_line(Line::None)
        .with_mark(Mark::Square, 6)
}

/// `text` beside the marker at `at`, in `color`: on the right-hand side of the ball's
/// direction of travel `heading` (figure axes), kept inside the chart.
fn time_label<'b, DB: DrawingBackend + 'b>(
    chart: &mut Chart<'b, DB>,
    at: Point,
    heading: Point,
    text: String,
    color: RGBColor,
) -> Drawn<DB> {
    let n = heading.0.hypot(heading.1);
    // Right-hand normal (figure axes), then in pixels (y down).
    let (rx, ry) = if n > 0.0 {
        (heading.1 / n, -heading.0 / n)
    } else {
        (0.0, 1.0)
    };
    let width = (text.chars().count() as f64 * 0.56 * f64::from(LEGEND_FONT)) as i32;
    let height = LEGEND_FONT as i32;
    let (px, py) = (rx * 16.0, -ry * 16.0);
    let mut dx = px as i32
        - if px < -4.0 {
            width
        } else if px.abs() <= 4.0 {
            width / 2
        } else {
            0
        };
    let mut dy = py as i32
        - if py < -4.0 {
            height
        } else if py.abs() <= 4.0 {
            height / 2
        } else {
            0
        };
    // Inside the plotting area.
    let (w, h) = chart.plotting_area().dim_in_pixel();
    let (ox, oy) = chart.plotting_area().get_base_pixel();
    let (ax, ay) = chart.backend_coord(&at);
    let (ax, ay) = (ax - ox, ay - oy);
    dx = dx.clamp(-ax + 2, w as i32 - ax - width - 2);
    dy = dy.clamp(-ay + 2, h as i32 - ay - height - 2);
    let style = TextStyle::from((FONT, LEGEND_FONT).into_font()).color(&color);
    chart.draw_series(std::iter::once(
        EmptyElement::at(at) + Text::new(text, (dx, dy), style),
    ))?;
    Ok(())
}

/// The polyline `pts` drawn with `swatch`, clipped to the chart's ranges.
fn draw_clipped<'b, DB: DrawingBackend + 'b>(
    chart: &mut Chart<'b, DB>,
    swatch: Swatch,
    pts: &[Point],
) -> Drawn<DB> {
    let (xr, yr) = (chart.x_range(), chart.y_range());
    let mut piece: Vec<Point> = Vec::new();
    for w in pts.windows(2) {
        match clip(w[0], w[1], (&xr, &yr)) {
            Some((p, q)) => {
                if piece.last() != Some(&p) {
                    swatch.draw_line(chart.plotting_area(), &piece)?;
                    piece = vec![p];
                }
                piece.push(q);
            }
            None => {
                swatch.draw_line(chart.plotting_area(), &piece)?;
                piece.clear();
            }
        }
    }
    swatch.draw_line(chart.plotting_area(), &piece)
}

/// The line of centres at contact, `reach` (m) beyond both balls: across the chart.
fn draw_line_of_centres<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    t: &TableOutcome,
    proj: &Projection,
    reach: f64,
) -> Drawn<DB> {
    let ca = proj.xy(&t.a.start.position);
    let cb = proj.xy(&t.b.start.position);
    let l = proj.xy(&t.line);
    let line = [
        (ca.0 - reach * l.0, ca.1 - reach * l.1),
        (cb.0 + reach * l.0, cb.1 + reach * l.1),
    ];
    draw_clipped(chart, line_of_centres_swatch(), &line)?;
    Ok(())
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
    draw_clipped(chart, Swatch::line(color, 2), &outline)
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
    let swatch = Swatch::line(color, 2);
    draw_clipped(chart, swatch.with_line(Line::Dashed), &[from, to])?;
    draw_clipped(chart, swatch, &[wing(1.0), to, wing(-1.0)])?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::geometry::ASPECT;
    use super::*;
    use crate::scene::run::run_scene;
    use std::path::Path;

    /// The draw shot of data/scenes, with `extra` added under its `[table]`.
    fn draw_shot(extra: &str) -> Scene {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenes");
        let text = std::fs::read_to_string(dir.join("draw_table.toml")).unwrap();
        let text = text.replace(
            "spin_decay = 0.044",
            &format!("spin_decay = 0.044\n{extra}"),
        );
        Scene::parse(&text, &dir, None).unwrap()
    }

    fn view_of<T>(scene: &Scene, f: impl FnOnce(&TopView<'_>) -> T) -> T {
        let run = run_scene(scene, &scene.solver, None).unwrap();
        let t = run.table.as_ref().unwrap();
        f(&TopView::new(scene, &run, t))
    }

    /// With rolling resistance both balls rest about 15 m apart along x and 0.3 m across:
    /// the chart's height shrinks to its least (the paths fill its width), no arrow runs
    /// past a rest point, and the balls at contact are small enough for the inset.
    #[test]
    fn the_frame_fits_paths_that_end_at_rest() {
        let scene = draw_shot("rolling_resistance = 0.01");
        view_of(&scene, |v| {
            let b = &v.layout.bounds;
            let width = v.x.end - v.x.start;
            assert!((b.x1 - b.x0) / width > 0.85, "paths fill the width");
            let pw = f64::from(WIDTH - 2 * MARGIN - LABEL_Y);
            assert_eq!(f64::from(v.plot_height), (ASPECT.0 * pw).round());
            // Equal scales: metres per pixel the same across and up.
            let (sx, sy) = (width / pw, (v.y.end - v.y.start) / f64::from(v.plot_height));
            assert!((sx / sy - 1.0).abs() < 1e-12);
            assert!(v.layout.arrows.is_empty(), "both balls rest: no arrows");
            assert!(v.inset.is_some());
        });
    }

    /// Without rolling resistance the balls roll on: one arrow each, starting where the
    /// path ends; the balls are large enough on the chart to need no inset.
    #[test]
    fn rolling_balls_get_arrows_from_the_end_of_their_paths() {
        let scene = draw_shot("");
        view_of(&scene, |v| {
            assert_eq!(v.layout.arrows.len(), 2);
            for (arrow, runs) in v.layout.arrows.iter().zip(&v.layout.runs) {
                let end = *runs.last().unwrap().1.last().unwrap();
                assert!((arrow.0 .0 - end.0).hypot(arrow.0 .1 - end.1) < 1e-9);
            }
            assert!(v.inset.is_none());
        });
    }

    /// `[table] length, width`: the cushions' rectangle, centred on the origin, inside the
    /// frame; one without the other, or a size <= 0, is refused naming the key.
    #[test]
    fn the_table_size_is_drawn_and_validated() {
        let scene = draw_shot("length = 2.54\nwidth = 1.27");
        let size = scene.table_size.unwrap();
        assert_eq!((size.length(), size.width()), (2.54, 1.27));
        assert_eq!(
            cushion_corners(&size),
            [
                (-1.27, -0.635),
                (1.27, -0.635),
                (1.27, 0.635),
                (-1.27, 0.635),
                (-1.27, -0.635)
            ]
        );
        view_of(&scene, |v| {
            assert!(v.x.start < -1.27 && v.x.end > 1.27);
            assert!(v.y.start < -0.635 && v.y.end > 0.635);
        });
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenes");
        let text = std::fs::read_to_string(dir.join("draw_table.toml")).unwrap();
        for (extra, message) in [
            (
                "length = 2.54",
                "table.length = 2.54: given together with table.width",
            ),
            (
                "width = 1.27",
                "table.width = 1.27: given together with table.length",
            ),
            ("length = 2.54\nwidth = 0", "table.width = 0: > 0 m"),
            ("length = -1\nwidth = 1", "table.length = -1: > 0 m"),
        ] {
            let t = text.replace(
                "spin_decay = 0.044",
                &format!("spin_decay = 0.044\n{extra}"),
            );
            let e = Scene::parse(&t, &dir, None).unwrap_err().to_string();
            assert!(e.contains(message), "{e}");
        }
    }

    /// Clipping keeps the part of a segment inside the box and drops one outside it.
    #[test]
    fn segments_are_clipped_to_the_chart() {
        let (x, y) = (0.0..1.0, 0.0..1.0);
        assert_eq!(
            clip((-1.0, 0.5), (2.0, 0.5), (&x, &y)),
            Some(((0.0, 0.5), (1.0, 0.5)))
        );
        assert_eq!(
            clip((-1.0, -1.0), (1.0, 1.0), (&x, &y)),
            Some(((0.0, 0.0), (1.0, 1.0)))
        );
        assert_eq!(clip((2.0, 2.0), (3.0, 2.5), (&x, &y)), None);
        assert_eq!(
            clip((0.2, 0.2), (0.4, 0.6), (&x, &y)),
            Some(((0.2, 0.2), (0.4, 0.6)))
        );
    }
}
