//! The rebound sweep (`billiard-contact rebound`, docs/cushion.md#the-rebound-sweep): a
//! cushion scene's ball sent into its cushion over a grid of incidence angles, speeds, spins
//! and side spins, each impact resolved, the rebound angle and speed written as CSV.
//!
//! A shot rolls (or slides) on the cloth at speed V, at the incidence angle beta from the
//! cushion's normal: v = V (sin beta, cos beta, 0) in the cushion's frame (x along the
//! cushion, y towards it, z up). Its spin is k (z x v)/r, topspin k V / r about the horizontal
//! axis across its path (k = 1 natural roll, "follow"; 0 "stun"; -1 "draw"), plus side spin
//! s V / r about z (positive: counter-clockwise seen from above).

use crate::apps::sweep::{parse_list, Spin, MAX_SHOTS};
use crate::base::error::Error;
use crate::base::number::shortest;
use crate::base::settings::SolverSettings;
use crate::cushion::impact::resolve_cushion;
use crate::outputs::cushion::{angle_from_normal, horizontal_speed};
use crate::scene::cushion::CushionScene;
use nalgebra::Vector3;
use rayon::prelude::*;
use std::io::Write;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A spin kind of the rebound sweep: `stun`, `follow` (natural roll; `roll` too), `draw`, or
/// a number k (topspin k V / r).
pub(crate) fn parse_spin(text: &str) -> Result<Spin, Error> {
    match text.trim() {
        "follow" => Ok(Spin::Roll),
        other => Spin::parse(other).map_err(|_| {
            Error::invalid(
                "--spin",
                format!("\"{}\"", other.escape_debug()),
                "stun, follow (natural roll; also roll), draw, or a number k (topspin k v/r)",
            )
        }),
    }
}

/// The name of a spin kind in the rebound sweep (`follow` for natural roll).
pub(crate) fn spin_name(s: &Spin) -> String {
    match s {
        Spin::Roll => "follow".into(),
        other => other.name(),
    }
}

/// One shot of the sweep.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ReboundShot {
    /// Topspin kind.
    pub spin: Spin,
    /// Speed V (m/s).
    pub speed: f64,
    /// Side spin as a fraction of V / r.
    pub side: f64,
    /// Incidence angle from the cushion's normal (degrees, in [0, 90)).
    pub incidence_deg: f64,
}

impl ReboundShot {
    /// The ball's velocity and spin for a ball of radius `r`.
    pub(crate) fn state(&self, r: f64) -> (Vector3<f64>, Vector3<f64>) {
        let b = self.incidence_deg.to_radians();
        let v = Vector3::new(b.sin(), b.cos(), 0.0) * self.speed;
        let w = Vector3::z().cross(&v) * (self.spin.factor() / r)
            + Vector3::z() * (self.side * self.speed / r);
        (v, w)
    }
}

/// A shot and its impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ReboundRow {
    /// The shot.
    pub shot: ReboundShot,
    /// Outgoing velocity (m/s) and spin (rad/s).
    pub v: Vector3<f64>,
    /// Outgoing spin (rad/s).
    pub w: Vector3<f64>,
    /// Rebound angle from the normal (degrees; positive along +x), `None` without
    /// horizontal velocity.
    pub rebound_deg: Option<f64>,
    /// Outgoing horizontal speed (m/s).
    pub speed_out: f64,
    /// Whether the ball left the cloth.
    pub lifts_off: bool,
    /// Kinetic energy lost (J).
    pub energy_lost: f64,
}

/// The shots of a grid, spin by spin, side by side, speed by speed, incidence last (the
/// curves' order), validated: incidences in [0, 90), speeds finite and > 0, sides finite,
/// at most [`MAX_SHOTS`] in all.
pub(crate) fn grid(
    spins: &[Spin],
    speeds: &[f64],
    sides: &[f64],
    incidences: &[f64],
) -> Result<Vec<ReboundShot>, Error> {
    for (option, list) in [
        ("--speed", speeds),
        ("--side", sides),
        ("--incidence", incidences),
    ] {
        if list.is_empty() {
            return Err(Error::invalid(option, "(empty)", "at least one value"));
        }
    }
    if let Some(v) = speeds.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
        return Err(Error::invalid("--speed", v, "finite speeds > 0 (m/s)"));
    }
    if let Some(s) = sides.iter().find(|s| !s.is_finite()) {
        return Err(Error::invalid("--side", s, "finite fractions of v/r"));
    }
    if let Some(b) = incidences.iter().find(|b| !(**b >= 0.0 && **b < 90.0)) {
        return Err(Error::invalid(
            "--incidence",
            b,
            "angles in [0, 90) degrees from the cushion's normal (90: along the cushion, \
             never reaching it)",
        ));
    }
    let n = [spins.len(), speeds.len(), sides.len(), incidences.len()]
        .iter()
        .try_fold(1usize, |a, b| a.checked_mul(*b))
        .filter(|n| *n <= MAX_SHOTS);
    let Some(n) = n else {
        return Err(Error::invalid(
            "--spin x --speed x --side x --incidence",
            format!(
                "{} x {} x {} x {} shots",
                spins.len(),
                speeds.len(),
                sides.len(),
                incidences.len()
            ),
            format!("at most {MAX_SHOTS} shots in all"),
        ));
    };
    let mut shots = Vec::with_capacity(n);
    for spin in spins {
        for side in sides {
            for speed in speeds {
                for b in incidences {
                    shots.push(ReboundShot {
                        spin: *spin,
                        speed: *speed,
                        side: *side,
                        incidence_deg: *b,
                    });
                }
            }
        }
    }
    Ok(shots)
}

/// Parses the incidence list (`--incidence`: numbers or ranges start:stop:step).
pub(crate) fn parse_incidences(text: &str) -> Result<Vec<f64>, Error> {
    parse_list("--incidence", text)
}

/// Resolves every shot of `shots` against `scene`'s cushion with `settings`, in parallel,
/// calling `progress(done)` as shots finish. An impact that fails names its shot.
pub(crate) fn run_rebound(
    scene: &CushionScene,
    settings: &SolverSettings,
    shots: &[ReboundShot],
    progress: impl Fn(usize) + Sync,
) -> Result<Vec<ReboundRow>, Error> {
    let done = AtomicUsize::new(0);
    shots
        .par_iter()
        .map(|shot| {
            let (v, w) = shot.state(scene.ball.radius());
            let out = resolve_cushion(&scene.ball, &scene.cushion, v, w, settings, None).map_err(
                |e| {
                    Error::invalid(
                        "shot",
                        format!(
                            "{} at {} m/s, side {}, incidence {} deg",
                            spin_name(&shot.spin),
                            shortest(shot.speed),
                            shortest(shot.side),
                            shortest(shot.incidence_deg)
                        ),
                        format!("an impact that resolves: {e}"),
                    )
                },
            )?;
            progress(done.fetch_add(1, Ordering::Relaxed) + 1);
            Ok(ReboundRow {
                shot: *shot,
                v: out.v,
                w: out.w,
                rebound_deg: angle_from_normal(&out.v, false),
                speed_out: horizontal_speed(&out.v),
                lifts_off: out.lifts_off,
                energy_lost: out.energy_lost,
            })
        })
        .collect()
}

/// The CSV header of the sweep.
pub(crate) const REBOUND_HEADER: [&str; 16] = [
    "spin",
    "k",
    "side",
    "speed (m/s)",
    "incidence (deg)",
    "rebound (deg)",
    "speed_out (m/s)",
    "speed_ratio",
    "v_x (m/s)",
    "v_y (m/s)",
    "v_z (m/s)",
    "w_x (rad/s)",
    "w_y (rad/s)",
    "w_z (rad/s)",
    "lifts_off",
    "energy_lost (J)",
];

/// Writes the rows as CSV (header [`REBOUND_HEADER`]).
pub(crate) fn write_csv<W: Write>(out: W, rows: &[ReboundRow]) -> Result<(), Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record(REBOUND_HEADER)?;
    for r in rows {
        let s = &r.shot;
        let mut cells = vec![
            spin_name(&s.spin),
            shortest(s.spin.factor()),
            shortest(s.side),
            shortest(s.speed),
            shortest(s.incidence_deg),
            r.rebound_deg.map_or(String::new(), shortest),
            shortest(r.speed_out),
            shortest(r.speed_out / s.speed),
        ];
        for x in [r.v.x, r.v.y, r.v.z, r.w.x, r.w.y, r.w.z] {
            cells.push(shortest(x + 0.0));
        }
        cells.push(r.lifts_off.to_string());
        cells.push(shortest(r.energy_lost));
        w.write_record(&cells)?;
    }
    w.flush().map_err(|e| Error::io("rebound CSV", e))
}

/// A few lines for stdout: per curve, the rebound angle at the smallest, middle and largest
/// incidence.
pub(crate) fn summary(rows: &[ReboundRow]) -> String {
    let mut s = String::new();
    for curve in curves(rows) {
        let first = &curve[0].shot;
        let at = |r: &ReboundRow| {
            format!(
                "{} -> {}",
                shortest(r.shot.incidence_deg),
                r.rebound_deg.map_or("-".into(), |a| format!(
                    "{:.2}",
                    if a.abs() < 0.005 { 0.0 } else { a }
                ))
            )
        };
        s += &format!(
            "{:>7} side {:<5} {:>6} m/s: rebound (deg) {}, {}, {}\n",
            spin_name(&first.spin),
            shortest(first.side),
            shortest(first.speed),
            at(&curve[0]),
            at(&curve[curve.len() / 2]),
            at(&curve[curve.len() - 1])
        );
    }
    s
}

/// The rows split into curves: runs of equal spin, side and speed (the grid's order).
pub(crate) fn curves(rows: &[ReboundRow]) -> Vec<&[ReboundRow]> {
    rows.chunk_by(|a, b| {
        a.shot.spin == b.shot.spin && a.shot.side == b.shot.side && a.shot.speed == b.shot.speed
    })
    .collect()
}
