//! The picture of a cushion impact (`run --plot-trace` on a cushion scene): the trace's rows
//! against the cushion's normal impulse P_I in six panels: the ball's velocity and spin, the
//! slip at the cushion and at the cloth (components and size), the normal velocity at the
//! cushion with the work W, and the cloth's impulse P_C. Every slip event is a grey dashed
//! line; the figure draws the rows the trace CSV holds.

use super::style::{short, Line, Mark, Swatch};
use super::trace::{Curve, Panel, TimeAxis, TraceFigure, MARKED_ROWS, XYZ};
use crate::base::settings::SolverSettings;
use crate::cushion::outcome::{CushionOutcome, CushionTraceRow};
use crate::outputs::cushion::{change_name, contact_angle_deg, contact_name, CUSHION_HEADER};
use crate::scene::cushion::CushionScene;

/// The impulse axis: N s, mN s or µN s by the total impulse.
fn impulse_axis(total: f64) -> TimeAxis {
    let (unit, per_second) = if total >= 1.0 {
        ("N s", 1.0)
    } else if total >= 1e-3 {
        ("mN s", 1e3)
    } else {
        ("µN s", 1e6)
    };
    TimeAxis { unit, per_second }
}

/// The figure of the impact `out` of `scene` (run with `settings`) from its trace `rows`.
pub(crate) fn cushion_figure(
    scene: &CushionScene,
    settings: &SolverSettings,
    out: &CushionOutcome,
    rows: &[CushionTraceRow],
) -> TraceFigure {
    let axis = impulse_axis(out.impulse_cushion);
    let marked = rows.len() <= MARKED_ROWS;
    let swatch = |i: usize| {
        let s = Swatch::line(XYZ[i % 3], 2);
        if marked {
            s.with_mark(Mark::Circle, 3)
        } else {
            s
        }
    };
    let curve =
        |column: usize, label: &str, i: usize, value: &dyn Fn(&CushionTraceRow) -> f64| Curve {
            column: CUSHION_HEADER[column],
            label: label.into(),
            swatch: swatch(i),
            points: rows
                .iter()
                .map(|r| (r.p_i * axis.per_second, value(r)))
                .collect(),
            right_axis: false,
        };
    let size = |i: usize, label: &str, value: &dyn Fn(&CushionTraceRow) -> f64| Curve {
        swatch: swatch(i).with_line(Line::Dashed),
        ..curve(8, label, i, value)
    };
    let velocity = Panel::new(
        "ball velocity v (x along the cushion, y towards it, z up)",
        "velocity (m/s)",
        vec![
            curve(2, "v_x", 0, &|r| r.v.x),
            curve(3, "v_y", 1, &|r| r.v.y),
            curve(4, "v_z", 2, &|r| r.v.z),
        ],
    );
    let spin = Panel::new(
        "ball spin",
        "spin (rad/s)",
        vec![
            curve(5, "spin_x", 0, &|r| r.w.x),
            curve(6, "spin_y", 1, &|r| r.w.y),
            curve(7, "spin_z", 2, &|r| r.w.z),
        ],
    );
    let slip_cushion = Panel::new(
        "slip at the cushion: along x, up its face, size",
        "slip (m/s)",
        vec![
            curve(8, "along x", 0, &|r| r.slip_cushion[0]),
            curve(9, "up the face", 1, &|r| r.slip_cushion[1]),
            size(2, "size", &|r| r.slip_cushion[0].hypot(r.slip_cushion[1])),
        ],
    );
    let slip_table = Panel::new(
        "slip at the cloth: along x, y, size",
        "slip (m/s)",
        vec![
            curve(10, "along x", 0, &|r| r.slip_table[0]),
            curve(11, "along y", 1, &|r| r.slip_table[1]),
            size(2, "size", &|r| r.slip_table[0].hypot(r.slip_table[1])),
        ],
    );
    let work = Curve {
        right_axis: true,
        swatch: swatch(1).with_line(Line::Dashed),
        ..curve(13, "W (right axis)", 1, &|r| r.work)
    };
    let normal = Panel {
        y2_desc: Some("W (J)".into()),
        ..Panel::new(
            "normal velocity at the cushion v_n, work W",
            "v_n (m/s)",
            vec![curve(12, "v_n", 0, &|r| r.normal_velocity), work],
        )
    };
    let table = Panel {
        note: out
            .lifts_off
            .then(|| "the ball leaves the cloth where P_C stays flat".into()),
        ..Panel::new(
            "the cloth's normal impulse P_C",
            "P_C (N s)",
            vec![curve(1, "P_C", 0, &|r| r.p_c)],
        )
    };
    let events: Vec<String> = out
        .events
        .iter()
        .map(|e| format!("{} {}", contact_name(e.contact), change_name(e.kind)))
        .collect();
    let (b, c) = (&scene.ball, &scene.cushion);
    let how = match settings.method() {
        crate::base::method::Method::Rk4 => format!("rk4, {} steps", settings.steps()),
        m => format!("{}, rtol {:e}", m.name(), settings.rtol()),
    };
    TraceFigure {
        title: format!("{}: cushion impact, {how}", scene.name),
        subtitle: format!(
            "contact {} deg above the equator, mu_cushion {}, mu_table {}, e {} ({}); P_I from \
             first touch to the end ({} {}){}{}",
            short(contact_angle_deg(c.height(), b.radius())),
            short(c.mu_cushion()),
            short(c.mu_table()),
            short(c.restitution()),
            c.rule().name(),
            short(out.impulse_cushion * axis.per_second),
            axis.unit,
            if events.is_empty() {
                String::new()
            } else {
                format!("; grey dashed lines: {}", events.join(", "))
            },
            if marked {
                "; dots: the trace's rows"
            } else {
                ""
            },
        ),
        time: axis,
        duration: out.impulse_cushion * axis.per_second,
        stick_time: None,
        x_name: "P_I",
        marks: out
            .events
            .iter()
            .map(|e| e.impulse * axis.per_second)
            .collect(),
        panels: vec![velocity, spin, slip_cushion, slip_table, normal, table],
        marked,
    }
}
