//! The top view's geometry, apart from the drawing: the figure's axes on the cloth, the
//! box that holds the paths, the layout of runs and arrows, the equal-scale axis ranges and
//! the clipping of segments to the chart.

use crate::model::frame::horizontal;
use crate::table_phase::outcome::TableOutcome;
use crate::table_phase::params::TableSize;
use crate::table_phase::roll_out::RollOut;
use crate::table_phase::segment::BallMotion;
use nalgebra::Vector3;
use plotters::style::RGBColor;
use std::ops::Range;

/// Figure width (px); the height follows the paths' extent.
pub(crate) const WIDTH: u32 = 1100;
/// A point on the figure (m, m).
pub(super) type Point = (f64, f64);
/// An arrow on the figure: from, to, colour.
pub(super) type Arrow = (Point, Point, RGBColor);
/// A stretch of a path with one kind of motion, as points on the figure.
pub(super) type Run = (BallMotion, Vec<Point>);
/// Balls A and B.
pub(super) const COLOR_A: RGBColor = RGBColor(31, 90, 180);
pub(super) const COLOR_B: RGBColor = RGBColor(200, 60, 30);
/// Points per segment of a path (one for a ball at rest).
pub(super) const POINTS_PER_SEGMENT: u32 = 120;
/// Width (px) of the y label area and the chart's margin.
pub(super) const LABEL_Y: u32 = 84;
pub(super) const MARGIN: u32 = 16;
/// The plotting area's height over its width, at least and at most.
pub(super) const ASPECT: (f64, f64) = (0.3, 1.0);

/// The figure's horizontal axes: e1 (lab x on the cloth, or lab y when x is vertical) and
/// e2 = up x e1.
pub(super) struct Projection {
    pub(super) e1: Vector3<f64>,
    pub(super) e2: Vector3<f64>,
    /// Whether `up` is +z, so that e1, e2 are the lab x and y axes.
    pub(super) lab_xy: bool,
}

impl Projection {
    /// The axes for the unit vertical `up`.
    pub(super) fn new(up: &Vector3<f64>) -> Self {
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
    pub(super) fn xy(&self, p: &Vector3<f64>) -> Point {
        (p.dot(&self.e1), p.dot(&self.e2))
    }

    /// The axis descriptions, x then y.
    pub(super) fn axis_names(&self) -> (&'static str, &'static str) {
        if self.lab_xy {
            ("x (m)", "y (m)")
        } else {
            ("horizontal e1 (m)", "horizontal e2 = up x e1 (m)")
        }
    }
}

/// The smallest box holding some points (m).
#[derive(Clone, Copy)]
pub(super) struct Bounds {
    pub(super) x0: f64,
    pub(super) x1: f64,
    pub(super) y0: f64,
    pub(super) y1: f64,
}

impl Bounds {
    /// The box of `points`.
    pub(super) fn of(points: impl Iterator<Item = Point>) -> Self {
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
    pub(super) fn include(&mut self, p: Point) {
        self.x0 = self.x0.min(p.0);
        self.x1 = self.x1.max(p.0);
        self.y0 = self.y0.min(p.1);
        self.y1 = self.y1.max(p.1);
    }

    /// The larger side (m), at least 8 `radius` (m).
    pub(super) fn span(&self, radius: f64) -> f64 {
        (self.x1 - self.x0).max(self.y1 - self.y0).max(8.0 * radius)
    }
}

/// Everything the figure shows, on the figure's axes.
pub(super) struct Layout {
    /// Ball A's and ball B's paths, run by run.
    pub(super) runs: [Vec<Run>; 2],
    /// Arrows along the rolling directions of balls still rolling at the end.
    pub(super) arrows: Vec<Arrow>,
    /// Where the dotted line of ball A's incoming direction starts (it ends at A).
    pub(super) incoming_from: Option<Point>,
    /// The box holding the paths, the outlines at contact, the arrows and the table.
    pub(super) bounds: Bounds,
}

impl Layout {
    /// The layout of `t`'s figure, balls A and B of radii `radii` (m), the table `size`.
    pub(super) fn new(
        t: &TableOutcome,
        radii: [f64; 2],
        size: Option<TableSize>,
        proj: &Projection,
    ) -> Self {
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
        let arrows = final_arrows(t, proj, end, 0.15 * span);
        let vin = horizontal(&t.incoming[0], &up);
        let incoming_from = (vin.norm() > 0.0).then(|| {
            let (ax, ay) = proj.xy(&t.a.start.position);
            let back = proj.xy(&(vin.normalize() * (0.2 * span)));
            (ax - back.0, ay - back.1)
        });
        for to in arrows.iter().map(|a| a.1).chain(incoming_from) {
            bounds.include(to);
        }
        for corner in size.iter().flat_map(cushion_corners) {
            bounds.include(corner);
        }
        Layout {
            runs,
            arrows,
            incoming_from,
            bounds,
        }
    }
}

/// The corners of the playing area (m, figure axes), closed: centred on the origin,
/// length along the first axis.
pub(super) fn cushion_corners(size: &TableSize) -> [Point; 5] {
    let (l, w) = (0.5 * size.length(), 0.5 * size.width());
    [(-l, -w), (l, -w), (l, w), (-l, w), (-l, -w)]
}

/// Points of a ball's path from separation to `end` (s), split into runs of one motion.
pub(super) fn runs(r: &RollOut, up: &Vector3<f64>, end: f64, proj: &Projection) -> Vec<Run> {
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

/// Arrows of length `len` (m) from the position at `end` (s) along the rolling direction
/// of each ball still rolling then (none for a ball that rests: its path ends there).
pub(super) fn final_arrows(t: &TableOutcome, proj: &Projection, end: f64, len: f64) -> Vec<Arrow> {
    let up = t.table.up;
    [(&t.a, COLOR_A), (&t.b, COLOR_B)]
        .into_iter()
        .filter(|(r, _)| r.rest.is_none())
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

/// The main chart's axis ranges (m) and its plotting area's height (px): `b` padded by 5 %
/// of its span, the height following the box's shape within [`ASPECT`], the shorter side
/// widened so that both axes have the same scale.
pub(super) fn equal_scale(b: &Bounds, radius: f64) -> (Range<f64>, Range<f64>, u32) {
    let pw = f64::from(WIDTH - 2 * MARGIN - LABEL_Y);
    let pad = 0.05 * b.span(radius);
    let (cx0, cx1, cy0, cy1) = (b.x0 - pad, b.x1 + pad, b.y0 - pad, b.y1 + pad);
    let ph = (pw * (cy1 - cy0) / (cx1 - cx0))
        .clamp(ASPECT.0 * pw, ASPECT.1 * pw)
        .round();
    let scale = ((cx1 - cx0) / pw).max((cy1 - cy0) / ph);
    let (mx, my) = (0.5 * (cx0 + cx1), 0.5 * (cy0 + cy1));
    (
        mx - 0.5 * scale * pw..mx + 0.5 * scale * pw,
        my - 0.5 * scale * ph..my + 0.5 * scale * ph,
        ph as u32,
    )
}

/// The larger of two radii (m): what the figure's margins are measured in.
pub(super) fn larger(radii: [f64; 2]) -> f64 {
    radii[0].max(radii[1])
}

/// The part of the segment `p`-`q` inside the box (Liang-Barsky); `None` when none is.
pub(super) fn clip(
    p: Point,
    q: Point,
    (xr, yr): (&Range<f64>, &Range<f64>),
) -> Option<(Point, Point)> {
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (pk, qk) in [
        (-dx, p.0 - xr.start),
        (dx, xr.end - p.0),
        (-dy, p.1 - yr.start),
        (dy, yr.end - p.1),
    ] {
        if pk == 0.0 {
            if qk < 0.0 {
                return None;
            }
        } else {
            let r = qk / pk;
            if pk < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then_some((
        (p.0 + t0 * dx, p.1 + t0 * dy),
        (p.0 + t1 * dx, p.1 + t1 * dy),
    ))
}
