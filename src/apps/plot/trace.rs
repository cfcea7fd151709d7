//! The pictures of one run (`run --plot-trace FILE.svg|png`): the trace's rows against time
//! in six panels: the normal force f(t) with the impulse p(t), the slip speed S(t) with the
//! stop of sliding marked, the slip direction theta(t) (constant while the balls slide,
//! docs/model.md eq 23), the centre-of-mass velocity (U, V, W), both balls' spins, and the
//! sliding heat H_sfr(t).
//!
//! The figure draws the rows the trace CSV holds for the same run and sampling
//! (docs/formats.md#trace-csv): one per accepted step of an integrator, the closed form
//! sampled at `--samples` (default 100) times, plus the stop of sliding. Every curve is one
//! CSV column ([`Curve::column`]) in the figure's units: time in s, ms, µs or ns by the
//! contact's duration, theta in degrees, everything else in the CSV's SI units.

use super::style::{
    decimals_for, draw_legend, legend_row, light, short, tick_label, write_drawn, Drawn, Figure,
    LegendEntry, Line, Mark, MeshAxes, Swatch,
};
use super::FONT;
use crate::base::error::Error;
use crate::base::method::Method;
use crate::model::trace::TraceRow;
use crate::outputs::trace_csv::{HEADER, PLANE_HEADER, TANGENTIAL_HEADER};
use crate::profile::force::ForceProfile;
use crate::scene::compliant::CompliantRow;
use crate::scene::run::SceneOutcome;
use crate::scene::types::Scene;
use crate::solve::plane::PlaneCollision;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Figure size (px): two columns of three panels, readable at page width.
pub(crate) const SIZE: (u32, u32) = (1400, 1280);
/// Height (px) of the title strip.
const HEADER_PX: u32 = 96;
/// Text sizes (px): title, subtitle, panel titles, axis descriptions, tick labels, legends
/// (also those of the cluster's figures).
pub(crate) const TITLE_FONT: u32 = 26;
pub(crate) const SUBTITLE_FONT: u32 = 17;
pub(crate) const PANEL_FONT: u32 = 21;
pub(crate) const DESC_FONT: u32 = 18;
pub(crate) const TICK_FONT: u32 = 16;
pub(crate) const LEGEND_FONT: u32 = 16;
/// With at most this many rows the rows are marked with dots.
pub(crate) const MARKED_ROWS: usize = 80;

/// Colours of the x, y and z components (and of single curves: the first).
pub(crate) const XYZ: [RGBColor; 3] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
];
/// The stop of sliding.
const STOP: RGBColor = RGBColor(110, 110, 110);

/// The figure's time axis: its unit and how many of them make a second.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct TimeAxis {
    /// The unit's symbol (`s`, `ms`, `µs`, `ns`).
    pub unit: &'static str,
    /// Units per second.
    pub per_second: f64,
}

impl TimeAxis {
    /// The unit in which a contact of `duration` (s) reads between 1 and 1000.
    pub(crate) fn for_duration(duration: f64) -> Self {
        let (unit, per_second) = if duration >= 1.0 {
            ("s", 1.0)
        } else if duration >= 1e-3 {
            ("ms", 1e3)
        } else if duration >= 1e-6 {
            ("µs", 1e6)
        } else {
            ("ns", 1e9)
        };
        TimeAxis { unit, per_second }
    }
}

/// One curve: a column of the trace CSV against t, in the figure's units.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Curve {
    /// The trace CSV's header cell of the column drawn ([`HEADER`]).
    pub column: &'static str,
    /// The legend's text.
    pub label: String,
    /// How it is drawn.
    pub swatch: Swatch,
    /// (t in the time axis' unit, value in the panel's unit), one per trace row that has
    /// a value in this column.
    pub points: Vec<(f64, f64)>,
    /// Drawn against the panel's right-hand axis.
    pub right_axis: bool,
}

/// One panel: its curves against t.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Panel {
    /// Title above the panel.
    pub title: String,
    /// The left axis' description, with its unit.
    pub y_desc: String,
    /// The right axis' description (for the curves with `right_axis`).
    pub y2_desc: Option<String>,
    /// The curves.
    pub curves: Vec<Curve>,
    /// A note written in the panel (e.g. why it is empty).
    pub note: Option<String>,
    /// The smallest span (panel units) of the left axis, so that a constant reads as
    /// constant instead of magnified round-off.
    pub min_span: f64,
}

/// The figure of one run, built from its trace rows.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct TraceFigure {
    /// The title: the scene, the profile and the method.
    pub title: String,
    /// How to read the figure.
    pub subtitle: String,
    /// The time axis.
    pub time: TimeAxis,
    /// The contact's duration (time axis' unit).
    pub duration: f64,
    /// When sliding stops (time axis' unit); `None` when it does not.
    pub stick_time: Option<f64>,
    /// The name of the horizontal axis' variable (`t`; `P_I` for a cushion impact, whose
    /// [`TimeAxis`] then holds an impulse unit).
    pub x_name: &'static str,
    /// Other events marked like the stop of sliding (the slip events of a cushion impact),
    /// in the horizontal axis' unit.
    pub marks: Vec<f64>,
    /// The panels, row by row.
    pub panels: Vec<Panel>,
    /// Whether the rows are marked with dots (few rows).
    pub marked: bool,
}

impl Panel {
    /// A panel titled `title` with the left axis `y_desc` and `curves`: no right axis, no
    /// note, no least span.
    pub(crate) fn new(title: &str, y_desc: &str, curves: Vec<Curve>) -> Self {
        Panel {
            title: title.into(),
            y_desc: y_desc.into(),
            y2_desc: None,
            curves,
            note: None,
            min_span: 0.0,
        }
    }
}

/// The trace's rows as the figure's curves.
struct Columns<'a> {
    rows: &'a [TraceRow],
    /// A compliant run's rows (`contact.tangential = "mindlin"`): the tangential force with
    /// Coulomb's cap and the spring's displacement are drawn too.
    compliant: Option<&'a [CompliantRow]>,
    /// The ball meeting a plane (plane scenes): its velocity and spin are drawn.
    plane: Option<PlaneCollision>,
    time: TimeAxis,
    /// Few rows: each marked with a dot.
    marked: bool,
}

impl Columns<'_> {
    /// The look of the `i`-th curve of a panel (x, y, z colours), dotted rows when marked.
    fn swatch(&self, i: usize) -> Swatch {
        let s = Swatch::line(XYZ[i % 3], 2);
        if self.marked {
            s.with_mark(Mark::Circle, 3)
        } else {
            s
        }
    }

    /// The trace CSV's column `i` (its cells times `factor`) against t.
    fn curve(&self, i: usize, label: &str, swatch: Swatch, factor: f64) -> Curve {
        Curve {
            column: HEADER[i],
            label: label.into(),
            swatch,
            points: self
                .rows
                .iter()
                .filter_map(|r| Some((r.t * self.time.per_second, r.values()[i]? * factor)))
                .collect(),
            right_axis: false,
        }
    }

    /// The ball's velocity (`spin` false) or spin component `i` of a plane scene, against t.
    fn ball_curve(&self, plane: &PlaneCollision, spin: bool, i: usize, swatch: Swatch) -> Curve {
        let k = if spin { 3 + i } else { i };
        Curve {
            column: PLANE_HEADER[k],
            label: format!("{} {}", if spin { "spin" } else { "v" }, ["x", "y", "z"][i]),
            swatch,
            points: self
                .rows
                .iter()
                .map(|r| {
                    let x = match spin {
                        true => plane.spin_of(&r.state)[i],
                        false => plane.velocity_of(&r.state)[i],
                    };
                    (r.t * self.time.per_second, x)
                })
                .collect(),
            right_axis: false,
        }
    }

    /// The compliant run's column `i` of [`TANGENTIAL_HEADER`] (its cells times `factor`)
    /// against t.
    fn tangential_curve(
        &self,
        rows: &[CompliantRow],
        i: usize,
        label: &str,
        swatch: Swatch,
        factor: f64,
    ) -> Curve {
        Curve {
            column: TANGENTIAL_HEADER[i],
            label: label.into(),
            swatch,
            points: rows
                .iter()
                .map(|r| {
                    let x = [
                        r.force.x,
                        r.force.y,
                        r.cap,
                        r.displacement.x,
                        r.displacement.y,
                    ][i];
                    (r.row.t * self.time.per_second, x * factor)
                })
                .collect(),
            right_axis: false,
        }
    }

    /// The compliant run's two panels: the tangential force against Coulomb's cap +-mu f(t),
    /// and the spring's displacement.
    fn tangential_panels(&self, rows: &[CompliantRow]) -> [Panel; 2] {
        let cap = Swatch::line(STOP, 2).with_line(Line::Dashed);
        let force = Panel::new(
            "tangential force F_t(t) on ball A (y, z of the trace), cap +-mu f(t) dashed",
            "force (N)",
            vec![
                self.tangential_curve(rows, 0, "F_t y", self.swatch(0), 1.0),
                self.tangential_curve(rows, 1, "F_t z", self.swatch(1), 1.0),
                self.tangential_curve(rows, 2, "mu f(t)", cap, 1.0),
                self.tangential_curve(rows, 2, "-mu f(t)", cap, -1.0),
            ],
        );
        let xi = Panel::new(
            "spring displacement xi(t) = -F_t / k_t",
            "xi (m)",
            vec![
                self.tangential_curve(rows, 3, "xi y", self.swatch(0), 1.0),
                self.tangential_curve(rows, 4, "xi z", self.swatch(1), 1.0),
            ],
        );
        [force, xi]
    }

    /// The six panels (eight for a compliant run); `slip_note` says whether and when
    /// sliding stops, `no_slip` that S(0) = 0.
    fn panels(&self, slip_note: String, no_slip: bool) -> Vec<Panel> {
        let mut panels = self.rigid_panels(slip_note, no_slip);
        if let Some(rows) = self.compliant {
            panels[5].title = "tangential work W_t(t) = -integral F_t.u dt (column H_sfr)".into();
            panels.extend(self.tangential_panels(rows));
        }
        panels
    }

    /// The six panels of every run.
    fn rigid_panels(&self, slip_note: String, no_slip: bool) -> Vec<Panel> {
        let p = Curve {
            right_axis: true,
            ..self.curve(
                2,
                "p(t) (right axis)",
                self.swatch(1).with_line(Line::Dashed),
                1.0,
            )
        };
        let force = Panel {
            y2_desc: Some("p (N s)".into()),
            ..Panel::new(
                "normal force f(t) and impulse p(t)",
                "f (N)",
                vec![self.curve(1, "f(t)", self.swatch(0), 1.0), p],
            )
        };
        let slip = Panel {
            note: Some(slip_note),
            ..Panel::new(
                "slip speed S(t)",
                "S (m/s)",
                vec![self.curve(12, "S(t)", self.swatch(0), 1.0)],
            )
        };
        let degrees = 180.0 / std::f64::consts::PI;
        let theta = Panel {
            note: no_slip.then(|| "theta undefined: S(0) = 0".into()),
            min_span: 2.0,
            ..Panel::new(
                "slip direction theta(t): constant while sliding",
                "theta (deg)",
                vec![self.curve(13, "theta(t)", self.swatch(0), degrees)],
            )
        };
        let heat = Panel::new(
            "sliding heat H_sfr(t)",
            "H_sfr (J)",
            vec![self.curve(14, "H_sfr(t)", self.swatch(0), 1.0)],
        );
        if let Some(plane) = &self.plane {
            let ball = |spin: bool| -> Vec<Curve> {
                (0..3)
                    .map(|i| self.ball_curve(plane, spin, i, self.swatch(i)))
                    .collect()
            };
            let velocity = Panel::new("ball velocity v (lab axes)", "velocity (m/s)", ball(false));
            let spin = Panel::new("ball spin (lab axes)", "spin (rad/s)", ball(true));
            return vec![force, slip, theta, velocity, spin, heat];
        }
        let velocity = Panel::new(
            "centre-of-mass velocity u = (U, V, W) of ball A",
            "velocity (m/s)",
            (0..3)
                .map(|i| self.curve(3 + i, ["U", "V", "W"][i], self.swatch(i), 1.0))
                .collect(),
        );
        let spins = (0..6)
            .map(|i| {
                let label = format!("omega_{} {}", ["A", "B"][i / 3], ["x", "y", "z"][i % 3]);
                let s = if i < 3 {
                    self.swatch(i)
                } else {
                    // Lighter and dashed, over A's (equal spins are then both seen).
                    Swatch {
                        color: light(XYZ[i % 3]),
                        ..self.swatch(i).with_line(Line::Dashed)
                    }
                };
                self.curve(6 + i, &label, s, 1.0)
            })
            .collect();
        let spin = Panel::new("spins: ball A solid, ball B dashed", "spin (rad/s)", spins);
        vec![force, slip, theta, velocity, spin, heat]
    }
}

impl TraceFigure {
    /// The figure of `run` (a run of `scene`) from its trace `rows`.
    pub(crate) fn new(scene: &Scene, run: &SceneOutcome, rows: &[TraceRow]) -> Self {
        // A compliant run's contact lasts as long as its kernel says (damping changes it
        // from the elastic pulse's time unit).
        let duration = match (&run.compliant, &run.outcome.law) {
            (Some(_), Some(l)) => l.duration,
            _ => scene.profile.duration(),
        };
        let time = TimeAxis::for_duration(duration);
        let plane = scene.plane().ok().flatten();
        let frame = match plane {
            Some(_) => "a ball against a plane, lab axes",
            None => "centre-of-mass frame of the paper",
        };
        let columns = Columns {
            rows,
            compliant: run.compliant.as_ref().map(|c| c.rows.as_slice()),
            plane,
            time,
            marked: rows.len() <= MARKED_ROWS,
        };
        let no_slip = rows.first().is_some_and(|r| r.theta.is_none());
        // With S(0) = 0 there is no sliding to stop.
        let stick = run.outcome.stick_time.filter(|_| !no_slip);
        let compliant = run.compliant.is_some();
        let stops = if compliant {
            "the spring holds from"
        } else {
            "sliding stops at"
        };
        let slip_note = match (no_slip, stick) {
            (true, _) => "no sliding: S(0) = 0".into(),
            (false, Some(t)) => format!("{stops} t = {} {}", short(t * time.per_second), time.unit),
            (false, None) => "slides throughout the contact".into(),
        };
        TraceFigure {
            title: format!(
                "{}: {}",
                scene.name,
                method_text(scene, run, rows.len(), &time)
            ),
            subtitle: format!(
                "{frame}{}, t from first touch to separation ({} {}){}{}",
                if compliant {
                    ", Mindlin's tangential spring"
                } else {
                    ""
                },
                short(duration * time.per_second),
                time.unit,
                if columns.marked {
                    "; dots: the rows of the trace (as --trace writes them)"
                } else {
                    ""
                },
                match (stick.is_some(), compliant) {
                    (true, false) => "; grey dashed line: sliding stops",
                    (true, true) => "; grey dashed line: the spring holds",
                    (false, _) => "",
                }
            ),
            time,
            duration: duration * time.per_second,
            stick_time: stick.map(|t| t * time.per_second),
            x_name: "t",
            marks: Vec::new(),
            panels: columns.panels(slip_note, no_slip),
            marked: columns.marked,
        }
    }

    /// One panel: title, legend above the chart, the chart with its curves and the stop.
    fn draw_panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        panel: &Panel,
    ) -> Drawn<DB> {
        let area = area.margin(8, 8, 14, 14);
        let (w, _) = area.dim_in_pixel();
        let columns = panel.curves.len().min(3);
        let rows = panel.curves.len().div_ceil(columns.max(1));
        let legend_h = legend_row(LEGEND_FONT) * rows as i32 + 6;
        let title_h = PANEL_FONT as i32 + 10;
        area.draw(&Text::new(
            panel.title.clone(),
            (0, 0),
            (FONT, PANEL_FONT).into_font().style(FontStyle::Bold),
        ))?;
        let entries: Vec<LegendEntry> = panel
            .curves
            .iter()
            .map(|c| LegendEntry::new(c.swatch, c.label.clone()))
            .collect();
        let column_w = (w as i32 - 90) / 3;
        draw_legend(
            &area,
            &entries,
            (90, title_h),
            (columns, column_w),
            LEGEND_FONT,
        )?;
        let (_, chart_area) = area.split_vertically((title_h + legend_h) as u32);
        self.draw_chart(&chart_area, panel)
    }

    /// The chart of a panel: axes, the curves, the stop of sliding and the note.
    fn draw_chart<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        panel: &Panel,
    ) -> Drawn<DB> {
        let left = value_range(
            panel.curves.iter().filter(|c| !c.right_axis),
            panel.min_span,
        );
        let right = value_range(panel.curves.iter().filter(|c| c.right_axis), 0.0);
        let x = 0.0..self.duration;
        let chart = ChartBuilder::on(area)
            .margin_right(10)
            .x_label_area_size(52)
            .y_label_area_size(96)
            .right_y_label_area_size(if panel.y2_desc.is_some() { 96 } else { 0 })
            .build_cartesian_2d(x.clone(), left.clone())?;
        // The right axis takes the right label area: set it before the left axis' mesh.
        let mut chart = chart.set_secondary_coord(x, right.clone());
        MeshAxes {
            desc: (
                format!("{} ({})", self.x_name, self.time.unit),
                panel.y_desc.clone(),
            ),
            labels: Some((9, 7)),
            decimals: (
                decimals_for(self.duration / 8.0),
                decimals_for((left.end - left.start) / 6.0),
            ),
            fonts: (TICK_FONT, DESC_FONT),
        }
        .draw(&mut chart)?;
        if let Some(y2) = &panel.y2_desc {
            let d2 = decimals_for((right.end - right.start) / 6.0);
            chart
                .configure_secondary_axes()
                .y_desc(y2.clone())
                .y_labels(7)
                .y_label_formatter(&|v| tick_label(*v, d2))
                .label_style((FONT, TICK_FONT))
                .axis_desc_style((FONT, DESC_FONT))
                .draw()?;
        }
        for t in self.stick_time.iter().chain(&self.marks) {
            let stop = Swatch::line(STOP, 2).with_line(Line::Dashed);
            stop.draw_line(chart.plotting_area(), &[(*t, left.start), (*t, left.end)])?;
        }
        for c in &panel.curves {
            let pts = c.points.iter().map(|p| (*p, false));
            if c.right_axis {
                c.swatch
                    .draw_line(chart.secondary_plotting_area(), &c.points)?;
                c.swatch.draw_marks(chart.secondary_plotting_area(), pts)?;
            } else {
                c.swatch.draw_line(chart.plotting_area(), &c.points)?;
                c.swatch.draw_marks(chart.plotting_area(), pts)?;
            }
        }
        if let Some(note) = &panel.note {
            let (w, _) = area.dim_in_pixel();
            area.draw(&Text::new(
                note.clone(),
                (w as i32 / 2 - 40, 10),
                (FONT, LEGEND_FONT).into_font().color(&STOP),
            ))?;
        }
        Ok(())
    }

    /// Writes the figure to `path` ([`write_drawn`]).
    pub(crate) fn write(&self, option: &str, path: &Path) -> Result<(), Error> {
        write_drawn(option, path, self)
    }
}

impl Figure for TraceFigure {
    fn dims(&self) -> (u32, u32) {
        // Three rows of panels in SIZE; a compliant run's fourth row adds a third of it.
        let rows = self.panels.len().div_ceil(2).max(3) as u32;
        (SIZE.0, HEADER_PX + (SIZE.1 - HEADER_PX) * rows / 3)
    }

    fn draw_all<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Drawn<DB> {
        root.fill(&WHITE)?;
        let (header, body) = root.split_vertically(HEADER_PX);
        header.draw(&Text::new(
            self.title.clone(),
            (20, 14),
            (FONT, TITLE_FONT).into_font().style(FontStyle::Bold),
        ))?;
        header.draw(&Text::new(
            self.subtitle.clone(),
            (20, 14 + TITLE_FONT as i32 + 16),
            (FONT, SUBTITLE_FONT).into_font(),
        ))?;
        let areas = body.split_evenly((self.panels.len().div_ceil(2), 2));
        for (panel, area) in self.panels.iter().zip(&areas) {
            self.draw_panel(area, panel)?;
        }
        root.present()
    }
}

/// The range of the curves' values padded by 6 %, at least `min_span` wide (and never
/// empty: a constant 0 gets -1 .. 1).
fn value_range<'a>(curves: impl Iterator<Item = &'a Curve>, min_span: f64) -> std::ops::Range<f64> {
    let (lo, hi) = curves
        .flat_map(|c| c.points.iter().map(|p| p.1))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !(lo.is_finite() && hi.is_finite()) {
        return -1.0..1.0;
    }
    let span = (hi - lo).max(min_span).max(1e-6 * lo.abs().max(hi.abs()));
    let span = if span > 0.0 { span } else { 2.0 };
    let mid = 0.5 * (lo + hi);
    let half = 0.5 * span * 1.12;
    mid - half..mid + half
}

/// The method and its settings, and how the rows were taken, for the title.
fn method_text(scene: &Scene, run: &SceneOutcome, rows: usize, time: &TimeAxis) -> String {
    let s = &run.settings;
    let how = match s.method() {
        Method::ClosedForm => format!("closed form, {rows} samples"),
        Method::Rk4 => format!("rk4, {} steps", s.steps()),
        m => format!("{}, rtol {:e}", m.name(), s.rtol()),
    };
    format!(
        "{} pulse of {} {}, {how}",
        scene.profile.name(),
        short(scene.profile.duration() * time.per_second),
        time.unit
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::apps::work_precision::plan::study_profile;
    use crate::base::method::Method;
    use crate::base::settings::Sampling;
    use crate::model::trace::Tee;
    use crate::outputs::trace_csv::{CsvTrace, HEADER};
    use crate::profile::spec::ProfileKind;
    use crate::scene::overrides::SolverOverrides;
    use crate::scene::run::run_scene;
    use std::path::PathBuf;

    fn scene_path(name: &str) -> PathBuf {
        PathBuf::from(env!("CARGO_MANIFEST_DIR"))
            .join("data/scenes")
            .join(name)
    }

    /// The CSV's header and its columns, an empty cell as `None` (read with the csv crate,
    /// independently of the figure).
    fn parse(bytes: &[u8]) -> (Vec<String>, Vec<Vec<Option<f64>>>) {
        let mut r = csv::Reader::from_reader(bytes);
        let header: Vec<String> = r.headers().unwrap().iter().map(String::from).collect();
        let mut cols = vec![Vec::new(); header.len()];
        for rec in r.records() {
            for (j, cell) in rec.unwrap().iter().enumerate() {
                cols[j].push((!cell.is_empty()).then(|| cell.parse::<f64>().unwrap()));
            }
        }
        (header, cols)
    }

    /// Every curve of the figure is its CSV column against t: t in µs (these contacts last
    /// 200-250 µs), theta in degrees, the rest in the CSV's units; every column but t is drawn;
    /// the stop of sliding is where the CSV's S reaches 0.
    #[test]
    fn the_figure_draws_the_trace_csv_columns() {
        for name in [
            "stun_cut_slides.toml",
            "stun_cut_sticks.toml",
            "head_on_stun.toml",
        ] {
            for kind in ProfileKind::ALL {
                for method in Method::ALL {
                    let mut scene = Scene::load(&scene_path(name)).unwrap();
                    scene.profile = study_profile(kind, &scene).unwrap();
                    let over = SolverOverrides {
                        method: Some(method),
                        ..Default::default()
                    };
                    let settings = over.apply(&scene.solver).unwrap();
                    let mut csv = CsvTrace::new(Vec::new()).unwrap();
                    let mut rows = Vec::new();
                    let run = {
                        let mut both = Tee(&mut csv, &mut rows);
                        run_scene(&scene, &settings, Some((&mut both, Sampling::Steps))).unwrap()
                    };
                    let (header, cols) = parse(&csv.finish().unwrap());
                    let fig = TraceFigure::new(&scene, &run, &rows);
                    let case = format!("{name} {} {}", kind.name(), method.name());
                    check_curves(&fig, &header, &cols, &case);
                    check_stop(&fig, &header, &cols, name, &case);
                }
            }
        }
    }

    fn check_curves(fig: &TraceFigure, header: &[String], cols: &[Vec<Option<f64>>], case: &str) {
        assert_eq!(fig.time.unit, "µs", "{case}");
        let t = &cols[0];
        let mut drawn: Vec<&str> = Vec::new();
        for c in fig.panels.iter().flat_map(|p| &p.curves) {
            let j = header.iter().position(|h| h == c.column).unwrap();
            let factor = if c.column == "theta (rad)" {
                180.0 / std::f64::consts::PI
            } else {
                1.0
            };
            let expected: Vec<(f64, f64)> = t
                .iter()
                .zip(&cols[j])
                .filter_map(|(t, v)| Some((t.unwrap() * 1e6, (*v)? * factor)))
                .collect();
            assert_eq!(c.points, expected, "{case}: {}", c.column);
            drawn.push(c.column);
        }
        drawn.sort_unstable();
        let mut columns: Vec<&str> = HEADER[1..].to_vec();
        columns.sort_unstable();
        assert_eq!(drawn, columns, "{case}: every column but t, once");
    }

    fn check_stop(
        fig: &TraceFigure,
        header: &[String],
        cols: &[Vec<Option<f64>>],
        name: &str,
        case: &str,
    ) {
        let s = header.iter().position(|h| h == "S (m/s)").unwrap();
        let slip = &fig.panels[1];
        let note = slip.note.as_deref().unwrap_or_default();
        match name {
            "stun_cut_sticks.toml" => {
                let stop = fig.stick_time.unwrap_or_else(|| panic!("{case}: no stop"));
                let at = cols[0]
                    .iter()
                    .position(|t| t.unwrap() * 1e6 == stop)
                    .unwrap_or_else(|| panic!("{case}: a row at the stop"));
                assert_eq!(cols[s][at], Some(0.0), "{case}");
                assert!(cols[s][..at].iter().all(|v| v.unwrap() > 0.0), "{case}");
                assert!(note.starts_with("sliding stops at t = "), "{case}: {note}");
            }
            "stun_cut_slides.toml" => {
                assert_eq!(fig.stick_time, None, "{case}");
                assert!(cols[s].iter().all(|v| v.unwrap() > 0.0), "{case}");
                assert_eq!(note, "slides throughout the contact", "{case}");
            }
            _ => {
                assert_eq!(fig.stick_time, None, "{case}: nothing to stop");
                assert_eq!(note, "no sliding: S(0) = 0", "{case}");
                assert!(
                    fig.panels[2].curves[0].points.is_empty(),
                    "{case}: no theta"
                );
            }
        }
    }

    #[test]
    fn time_axis_reads_the_duration_between_1_and_1000() {
        assert_eq!(TimeAxis::for_duration(2e-4).unit, "µs");
        assert_eq!(TimeAxis::for_duration(2e-4).per_second, 1e6);
        assert_eq!(TimeAxis::for_duration(0.5e-3).unit, "µs");
        assert_eq!(TimeAxis::for_duration(3e-3).unit, "ms");
        assert_eq!(TimeAxis::for_duration(2.0).unit, "s");
        assert_eq!(TimeAxis::for_duration(5e-8).unit, "ns");
    }
}
