//! Throw charts: one scene's balls, contact, profile, solver and effects run over a grid of
//! shots (spin kind, cue-ball speed, side spin, cut angle), one row per shot
//! (docs/formats.md#sweep-csv, docs/throw.md).
//!
//! Every shot is the same lab set-up: the cue ball A, centre at height r above the cloth
//! (`up` = +z), moves along +y at speed v toward the object ball B at rest; B touches A at
//! A + 2r (sin(cut), cos(cut), 0), so a positive cut sends B to the right of A's path
//! (the lab-frame scenes' geometry turned so that A travels along +y). A's spin is
//! k v / r of topspin about -x (k = 0 stun, 1 natural roll, -1 draw) plus
//! side · sign(cut) · v / r about +z (sign(0) = +1): positive side spin is inside English,
//! which adds to the throw of the cut. Balls of different radii both rest on the cloth:
//! B's centre is then A + 2 sqrt(r_A r_B) (sin(cut), cos(cut), 0) + (r_B - r_A) e_z, and
//! r is A's radius in the spins (docs/unequal-balls.md).

use crate::base::error::Error;
use crate::base::number::shortest;
use crate::base::settings::SolverSettings;
use crate::base::validate::finite_output;
use crate::model::frame::{horizontal, LabScene};
use crate::model::params::BallPair;
use crate::model::state::LabBall;
use crate::scene::run::run_scene;
use crate::scene::types::{Incoming, Scene};
use nalgebra::Vector3;
use rayon::prelude::*;
use std::io::Write;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The columns every sweep CSV starts with, in order; with the table effect the two cue
/// columns are `cue_speed_rolling` and `cue_deflection_rolling_deg` instead.
pub const COLUMNS: [&str; 13] = [
    "spin",
    "speed",
    "side",
    "cut_deg",
    "throw_deg",
    "object_speed",
    "object_spin_x",
    "object_spin_y",
    "object_spin_z",
    "cue_speed",
    "cue_deflection_deg",
    "sticks",
    "stick_time",
];

/// The names of the cue ball's two columns (indices 9 and 10) when the table effect is
/// on: its speed and deflection once it rolls on the cloth.
pub(crate) const ROLLING_CUE_COLUMNS: [&str; 2] =
    ["cue_speed_rolling", "cue_deflection_rolling_deg"];

/// The cue ball's vertical-plane spin, as a named shot or a multiple of natural roll.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spin {
    /// No spin at impact.
    Stun,
    /// Natural roll: topspin v / r.
    Roll,
    /// Backspin equal and opposite to natural roll: -v / r.
    Draw,
    /// Topspin k v / r (negative k: backspin).
    Topspin(f64),
}

impl Spin {
    /// The names accepted besides a number.
    pub const NAMES: [&str; 3] = ["stun", "roll", "draw"];

    /// `stun`, `roll`, `draw`, or a finite number k (topspin k v / r).
    ///
    /// ```
    /// use billiard_contact::sweep::Spin;
    /// assert_eq!(Spin::parse("draw").unwrap().factor(), -1.0);
    /// assert_eq!(Spin::parse("0.5").unwrap(), Spin::Topspin(0.5));
    /// assert!(Spin::parse("massé").is_err());
    /// ```
    pub fn parse(text: &str) -> Result<Self, Error> {
        match text.trim() {
            "stun" => Ok(Spin::Stun),
            "roll" => Ok(Spin::Roll),
            "draw" => Ok(Spin::Draw),
            t => match t.parse::<f64>() {
                Ok(k) if k.is_finite() => Ok(Spin::Topspin(k)),
                _ => Err(Error::invalid(
                    "--spin",
                    format!("\"{t}\""),
                    "stun, roll, draw, or a number k (topspin k v/r)",
                )),
            },
        }
    }

    /// The topspin as a fraction of natural roll: 0, 1, -1 or k.
    pub fn factor(&self) -> f64 {
        match *self {
            Spin::Stun => 0.0,
            Spin::Roll => 1.0,
            Spin::Draw => -1.0,
            Spin::Topspin(k) => k,
        }
    }

    /// The name in the CSV and the figures: `stun`, `roll`, `draw` or the number.
    pub fn name(&self) -> String {
        match *self {
            Spin::Stun => "stun".into(),
            Spin::Roll => "roll".into(),
            Spin::Draw => "draw".into(),
            Spin::Topspin(k) => shortest(k),
        }
    }
}

/// The grid of shots: every combination, in the order spin, speed, side, cut.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Spin kinds.
    pub spins: Vec<Spin>,
    /// Cue-ball speeds v (m/s), > 0.
    pub speeds: Vec<f64>,
    /// Side spins as fractions of v / r (positive: inside English).
    pub sides: Vec<f64>,
    /// Cut angles (degrees), in (-90, 90).
    pub cuts_deg: Vec<f64>,
}

/// The most shots a sweep takes: every row stays in memory for the figure and the summary.
pub const MAX_SHOTS: usize = 1_000_000;

impl Grid {
    /// A validated grid: every list non-empty, speeds finite and > 0, sides finite, cuts in
    /// (-90, 90) degrees.
    pub fn new(
        spins: Vec<Spin>,
        speeds: Vec<f64>,
        sides: Vec<f64>,
        cuts_deg: Vec<f64>,
    ) -> Result<Self, Error> {
        for (option, empty) in [
            ("--spin", spins.is_empty()),
            ("--speed", speeds.is_empty()),
            ("--side", sides.is_empty()),
            ("--cut", cuts_deg.is_empty()),
        ] {
            if empty {
                return Err(Error::invalid(
                    option,
                    "an empty list",
                    "at least one value",
                ));
            }
        }
        let shots = [spins.len(), speeds.len(), sides.len(), cuts_deg.len()]
            .iter()
            .try_fold(1usize, |n, &k| n.checked_mul(k))
            .filter(|&n| n <= MAX_SHOTS);
        if shots.is_none() {
            return Err(Error::invalid(
                "--spin x --speed x --side x --cut",
                format!(
                    "{} x {} x {} x {} shots",
                    spins.len(),
                    speeds.len(),
                    sides.len(),
                    cuts_deg.len()
                ),
                "at most 1e6 shots (every row is kept for the figure, about 200 bytes a shot)",
            ));
        }
        if let Some(v) = speeds.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
            return Err(Error::invalid("--speed", v, "speeds > 0 m/s"));
        }
        if let Some(s) = sides.iter().find(|s| !s.is_finite()) {
            return Err(Error::invalid("--side", s, "finite fractions of v/r"));
        }
        if let Some(c) = cuts_deg.iter().find(|c| c.is_nan() || c.abs() >= 90.0) {
            return Err(Error::invalid(
                "--cut",
                c,
                "angles in (-90, 90) degrees (at 90 the balls do not meet)",
            ));
        }
        Ok(Grid {
            spins,
            speeds,
            sides,
            cuts_deg,
        })
    }

    /// Number of shots.
    pub fn len(&self) -> usize {
        self.spins.len() * self.speeds.len() * self.sides.len() * self.cuts_deg.len()
    }

    /// True when the grid has no shot (never, for a grid from [`Grid::new`]).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The shot at index `i` in grid order (spin, speed, side, cut; cut fastest).
    pub fn shot(&self, i: usize) -> Shot {
        let nc = self.cuts_deg.len();
        let ns = self.sides.len();
        let nv = self.speeds.len();
        Shot {
            spin: self.spins[i / (nc * ns * nv)],
            speed: self.speeds[(i / (nc * ns)) % nv],
            side: self.sides[(i / nc) % ns],
            cut_deg: self.cuts_deg[i % nc],
        }
    }
}

/// A list of numbers as the options write them: comma-separated items, each a number or a
/// range `start:stop:step` (stop included when the steps reach it to 1e-9 of a step).
/// Public only for the fuzz targets and their replay (`fuzz/`), which feed it the option text.
#[doc(hidden)]
pub fn parse_list(option: &str, text: &str) -> Result<Vec<f64>, Error> {
    let number = |t: &str| {
        t.trim()
            .parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| {
                Error::invalid(
                    option,
                    format!("\"{}\"", t.trim()),
                    "numbers or ranges start:stop:step, comma-separated",
                )
            })
    };
    let mut out = Vec::new();
    for item in text.split(',') {
        let parts: Vec<&str> = item.split(':').collect();
        match parts[..] {
            [x] if out.len() < MAX_SHOTS => out.push(number(x)?),
            [_] => return Err(too_many(option, out.len() + 1)),
            [a, b, s] => {
                let (start, stop, step) = (number(a)?, number(b)?, number(s)?);
                let n = (stop - start) / step;
                if !(step > 0.0 && (-1e-9..1e6).contains(&n)) {
                    return Err(Error::invalid(
                        option,
                        format!("\"{}\"", item.trim()),
                        "a range start:stop:step with step > 0, start <= stop and at most \
                         1e6 values",
                    ));
                }
                let count = (n + 1e-9).floor() as usize + 1;
                if out.len() + count > MAX_SHOTS {
                    return Err(too_many(option, out.len() + count));
                }
                out.extend((0..count).map(|i| start + i as f64 * step));
            }
            _ => return Err(number(item).unwrap_err()),
        }
    }
    Ok(out)
}

/// The error for a list longer than a sweep can take.
fn too_many(option: &str, values: usize) -> Error {
    Error::invalid(
        option,
        format!("{values} values or more"),
        "at most 1e6 values in all",
    )
}

/// One shot of the grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shot {
    /// Spin kind.
    pub spin: Spin,
    /// Cue-ball speed v (m/s).
    pub speed: f64,
    /// Side spin, a fraction of v / r (positive: inside English).
    pub side: f64,
    /// Cut angle (degrees).
    pub cut_deg: f64,
}

impl Shot {
    /// The lab scene of this shot for the balls `balls` (module documentation; one
    /// [`crate::Ball`] for two identical balls).
    pub fn lab_scene(&self, balls: impl Into<BallPair>) -> LabScene {
        let balls = balls.into();
        let (r, rb) = (balls.a.radius(), balls.b.radius());
        // 2 sqrt(r r) is 2r exactly (a correctly rounded square root of a square).
        let reach = 2.0 * (r * rb).sqrt();
        let v = self.speed;
        let (sin, cos) = self.cut_deg.to_radians().sin_cos();
        let a = Vector3::new(0.0, 0.0, r);
        let side_sign = if self.cut_deg < 0.0 { -1.0 } else { 1.0 };
        let w = v / r;
        LabScene {
            a: LabBall {
                position: a,
                velocity: Vector3::new(0.0, v, 0.0),
                spin: Vector3::new(-self.spin.factor() * w, 0.0, self.side * side_sign * w),
            },
            b: LabBall {
                position: a + reach * Vector3::new(sin, cos, 0.0) + Vector3::new(0.0, 0.0, rb - r),
                velocity: Vector3::zeros(),
                spin: Vector3::zeros(),
            },
            up: Vector3::z(),
        }
    }
}

/// The outcome of one shot (docs/formats.md#sweep-csv).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepRow {
    /// The shot.
    pub shot: Shot,
    /// Throw (degrees, counter-clockwise about up), as `run` reports it; `None` when
    /// undefined.
    pub throw_deg: Option<f64>,
    /// B's speed just after contact (m/s).
    pub object_speed: f64,
    /// B's spin just after contact (rad/s, lab axes: x right, y along A's path, z up).
    pub object_spin: Vector3<f64>,
    /// A's horizontal speed just after contact, or once it rolls with the table effect (m/s).
    pub cue_speed: f64,
    /// Angle (degrees, counter-clockwise about up) from A's incoming direction to its
    /// horizontal velocity (just after contact, or rolling with the table effect); `None`
    /// when A stops.
    pub cue_deflection_deg: Option<f64>,
    /// Whether sliding between the balls stopped during the contact.
    pub sticks: bool,
    /// When it stopped (s from first contact).
    pub stick_time: Option<f64>,
}

/// Runs every shot of `grid` with `scene`'s balls, contact, profile and effects under
/// `settings`, in parallel (rayon's current pool); the rows come back in grid order.
/// `progress` is called with the number of shots done after each one.
pub fn run_sweep(
    scene: &Scene,
    settings: &SolverSettings,
    grid: &Grid,
    progress: impl Fn(usize) + Sync,
) -> Result<Vec<SweepRow>, Error> {
    let done = AtomicUsize::new(0);
    (0..grid.len())
        .into_par_iter()
        .map(|i| {
            let row = run_shot(scene, settings, grid.shot(i));
            progress(done.fetch_add(1, Ordering::Relaxed) + 1);
            row
        })
        .collect()
}

/// One shot: the scene with the shot's lab set-up, run, and its row.
pub fn run_shot(scene: &Scene, settings: &SolverSettings, shot: Shot) -> Result<SweepRow, Error> {
    let lab = shot.lab_scene(scene.balls);
    let mut s = scene.clone();
    s.incoming = Incoming::Lab(lab);
    let run = run_scene(&s, settings, None)?;
    let (a, b) = run
        .lab_out
        .ok_or_else(|| Error::invalid("sweep", "a shot without lab output", "a lab-frame shot"))?;
    let cue = match &run.table {
        Some(t) => t.a.rolling.velocity,
        None => a.velocity,
    };
    let cue_h = horizontal(&cue, &lab.up);
    let incoming = lab.a.velocity;
    let cue_deflection_deg = (cue_h.norm() > 1e-12 * shot.speed).then(|| {
        incoming
            .cross(&cue_h)
            .dot(&lab.up)
            .atan2(incoming.dot(&cue_h))
            .to_degrees()
    });
    Ok(SweepRow {
        shot,
        throw_deg: run.throw_angle_deg,
        object_speed: b.velocity.norm(),
        object_spin: b.spin,
        cue_speed: cue_h.norm(),
        cue_deflection_deg,
        sticks: run.outcome.result.sticks,
        stick_time: run.outcome.stick_time,
    })
}

/// The header of a sweep CSV: [`COLUMNS`], with [`ROLLING_CUE_COLUMNS`] for the cue ball
/// when `rolling` (the table effect is on).
pub(crate) fn header(rolling: bool) -> Vec<&'static str> {
    let mut h = COLUMNS.to_vec();
    if rolling {
        h[9..11].copy_from_slice(&ROLLING_CUE_COLUMNS);
    }
    h
}

/// Writes the sweep CSV (docs/formats.md#sweep-csv): numbers as the shortest text that
/// reads back to the same value, empty cells for undefined values; a non-finite number
/// fails naming the column and the shot.
pub fn write_csv<W: Write>(out: W, rows: &[SweepRow], rolling: bool) -> Result<W, Error> {
    let names = header(rolling);
    let mut w = csv::Writer::from_writer(out);
    w.write_record(&names)?;
    for r in rows {
        let s = &r.shot;
        let values = [
            Some(s.speed),
            Some(s.side),
            Some(s.cut_deg),
            r.throw_deg,
            Some(r.object_speed),
            Some(r.object_spin.x),
            Some(r.object_spin.y),
            Some(r.object_spin.z),
            Some(r.cue_speed),
            r.cue_deflection_deg,
        ];
        let mut record = vec![s.spin.name()];
        for (name, v) in names[1..11].iter().zip(values) {
            record.push(match v {
                Some(x) => shortest(finite_output(x, || {
                    format!(
                        "{name} of {} {} {} {}",
                        s.spin.name(),
                        s.speed,
                        s.side,
                        s.cut_deg
                    )
                })?),
                None => String::new(),
            });
        }
        record.push(r.sticks.to_string());
        record.push(r.stick_time.map(shortest).unwrap_or_default());
        w.write_record(&record)?;
    }
    w.into_inner()
        .map_err(|e| Error::io("sweep.csv", e.into_error()))
}

/// The rows of one curve: consecutive rows sharing spin, speed and side (grid order).
pub(crate) fn curves(rows: &[SweepRow]) -> Vec<&[SweepRow]> {
    rows.chunk_by(|x, y| {
        let (p, q) = (&x.shot, &y.shot);
        p.spin == q.spin && p.speed == q.speed && p.side == q.side
    })
    .collect()
}

/// The largest |throw| of each curve, one line per curve: spin, speed, side, the throw and
/// its cut angle.
pub(crate) fn summary(rows: &[SweepRow]) -> String {
    use std::fmt::Write as _;
    let mut s = String::from("largest throw of each curve:\n");
    for curve in curves(rows) {
        let c = &curve[0].shot;
        let best = curve
            .iter()
            .filter_map(|r| r.throw_deg.map(|t| (t, r.shot.cut_deg)))
            .max_by(|x, y| x.0.abs().total_cmp(&y.0.abs()));
        let _ = match best {
            Some((t, cut)) => writeln!(
                s,
                "  {:>5} {:>6} m/s side {:>5}: {t:8.4} deg at cut {cut} deg",
                c.spin.name(),
                c.speed,
                c.side
            ),
            None => writeln!(
                s,
                "  {:>5} {:>6} m/s side {:>5}: no throw",
                c.spin.name(),
                c.speed,
                c.side
            ),
        };
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::params::Ball;

    #[test]
    fn grid_order_is_spin_speed_side_cut() {
        let g = Grid::new(
            vec![Spin::Stun, Spin::Draw],
            vec![1.0, 2.0],
            vec![0.0],
            vec![0.0, 10.0, 20.0],
        )
        .unwrap();
        assert_eq!(g.len(), 12);
        let s = g.shot(7); // draw (6..12), speed 1 (6..9), cut index 1
        assert_eq!((s.spin, s.speed, s.cut_deg), (Spin::Draw, 1.0, 10.0));
        assert_eq!(g.shot(11).speed, 2.0);
        assert!(Grid::new(vec![Spin::Stun], vec![0.0], vec![0.0], vec![0.0]).is_err());
        assert!(Grid::new(vec![Spin::Stun], vec![1.0], vec![0.0], vec![90.0]).is_err());
    }

    /// The shot's balls touch, A moves along +y with the asked spin, and B lies at the cut
    /// angle to the right of A's path.
    #[test]
    fn lab_scene_geometry() {
        let ball = Ball::new(0.17, 0.028575, 0.4).unwrap();
        let shot = Shot {
            spin: Spin::Roll,
            speed: 2.0,
            side: 0.5,
            cut_deg: -30.0,
        };
        let lab = shot.lab_scene(ball);
        let d = lab.b.position - lab.a.position;
        assert!((d.norm() - 2.0 * ball.radius()).abs() < 1e-15);
        assert!((d.x / d.norm() + 0.5).abs() < 1e-15);
        // Rolling: v = omega x (r up) at the contact with the cloth is matched, v = -omega_x r.
        assert!((lab.a.spin.x * ball.radius() + 2.0).abs() < 1e-13);
        // Negative cut: inside English is clockwise seen from above.
        assert!((lab.a.spin.z * ball.radius() + 1.0).abs() < 1e-13);
    }

    #[test]
    fn ranges_and_lists() {
        assert_eq!(parse_list("--cut", "0:1:0.25").unwrap().len(), 5);
        assert_eq!(parse_list("--cut", "0:60:1").unwrap().len(), 61);
        assert_eq!(parse_list("--cut", "5").unwrap(), vec![5.0]);
        let e = parse_list("--cut", "0:x:1").unwrap_err().to_string();
        assert!(e.contains("--cut") && e.contains("\"x\""), "{e}");
        assert!(parse_list("--cut", "60:0:1").is_err());
        assert!(parse_list("--speed", "1:2").is_err());
    }

    /// The examples of the documentation of `parse_list`.
    #[test]
    fn parse_list_examples() {
        assert_eq!(
            parse_list("--cut", "0:60:30").unwrap(),
            vec![0.0, 30.0, 60.0]
        );
        assert_eq!(
            parse_list("--speed", "0.447, 1.341").unwrap(),
            vec![0.447, 1.341]
        );
        assert!(parse_list("--cut", "0:60:0").is_err());
    }
}
