//! Throw and spin transfer with and without tangential compliance (docs/throw.md#tangential-compliance):
//! two phenolic-resin pool balls (0.17 kg, r = 28.575 mm, E = 5.4 GPa, nu = 0.34, as
//! docs/model.md), constant mu = 0.06, e = 1, a stun or rolling cue ball at 0.447, 1.341 and
//! 3.129 m/s, cuts 0.5 to 20 degrees. Rigid: the closed form with the stick rule (eqs 24-35);
//! compliant: `resolve_sphere_sphere_compliant` (Hertz and Mindlin's spring). Writes
//! docs/throw/compliant/throw.csv and throw.svg/.png.
//!
//! `cargo run --release --features plots --example throw_compliant`

use billiard_contact::nalgebra::Vector3;
use billiard_contact::plot::{register_fonts, write_svg_and_png, FONT};
use billiard_contact::*;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;

const MU: f64 = 0.06;
const SPEEDS: [f64; 3] = [0.447, 1.341, 3.129];
const OUT: &str = "docs/throw/compliant";

/// One shot: the object ball's throw (degrees) and outgoing spin magnitude over the
/// cue ball's v / r, rigid and compliant.
struct Shot {
    roll: bool,
    speed: f64,
    cut: f64,
    throw: [f64; 2],
    spin_b: [f64; 2],
}

fn shot(roll: bool, speed: f64, cut: f64) -> Result<Shot, Error> {
    let ball = Ball::new(0.17, 0.028575, ALPHA_SOLID)?;
    let resin = Material::new(5.4e9, 0.34)?;
    let c = cut.to_radians();
    // The cue ball A along +y, the object ball B at the cut angle to the right: n from A to B.
    let n = Vector3::new(c.sin(), c.cos(), 0.0);
    let z = Vector3::z();
    let t = z.cross(&n);
    let v_a = Vector3::new(0.0, speed, 0.0);
    // Rolling on the cloth: the contact with the table at rest, w = -(v / r) x.
    let w_a = if roll {
        Vector3::new(-speed / ball.radius(), 0.0, 0.0)
    } else {
        Vector3::zeros()
    };
    let throw = |v: Vector3<f64>| v.dot(&t).atan2(v.dot(&n)).to_degrees();
    // Rigid: the closed form in the frame (n, t, z); u = (v_A - v_B) / 2, B's lab velocity
    // is the centre of mass's minus u.
    let in_frame = |v: Vector3<f64>| Vector3::new(v.dot(&n), v.dot(&t), v.dot(&z));
    let contact = Contact {
        friction: Friction::constant(MU)?,
        impulse: ImpulseRule::restitution(1.0)?,
    };
    let s = CmState::new(in_frame(v_a / 2.0), in_frame(w_a), Vector3::zeros());
    let rigid = ClosedForm::new(&Collision::new(ball, contact, Effects::default(), s)?).result;
    let u = rigid.out.u_cm;
    let v_b_rigid = v_a / 2.0 - (u.x * n + u.y * t + u.z * z);
    let sphere = |v, w| CompliantSphere {
        ball,
        material: resin,
        velocity: v,
        spin: w,
    };
    let compliant = resolve_sphere_sphere_compliant(
        &sphere(v_a, w_a),
        &sphere(Vector3::zeros(), Vector3::zeros()),
        n,
        MU,
        1.0,
        &SolverSettings::default()
            .with_rtol(1e-10)?
            .with_atol(1e-10)?,
    )?;
    Ok(Shot {
        roll,
        speed,
        cut,
        throw: [throw(v_b_rigid), throw(compliant.velocity_b)],
        spin_b: [
            rigid.out.omega_b.norm() * ball.radius() / speed,
            compliant.spin_b.norm() * ball.radius() / speed,
        ],
    })
}

fn io(path: &str) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |e| Error::io(path, e)
}

fn run() -> Result<(), Error> {
    std::fs::create_dir_all(OUT).map_err(io(OUT))?;
    let mut shots = Vec::new();
    let mut csv = String::from(
        "shot,speed_m_s,cut_deg,throw_rigid_deg,throw_compliant_deg,spin_b_rigid_r_over_v,\
         spin_b_compliant_r_over_v\n",
    );
    for roll in [false, true] {
        for speed in SPEEDS {
            for i in 1..=40 {
                let s = shot(roll, speed, 0.5 * i as f64)?;
                writeln!(
                    csv,
                    "{},{speed},{},{:.6},{:.6},{:.6},{:.6}",
                    if roll { "roll" } else { "stun" },
                    s.cut,
                    s.throw[0],
                    s.throw[1],
                    s.spin_b[0],
                    s.spin_b[1]
                )
                .expect("writing to a String");
                shots.push(s);
            }
        }
    }
    for roll in [false, true] {
        for speed in SPEEDS {
            let d = shots
                .iter()
                .filter(|s| s.roll == roll && s.speed == speed)
                .map(|s| (s.throw[1] - s.throw[0], s.cut))
                .fold(
                    (0.0f64, 0.0),
                    |m, x| if x.0.abs() > m.0.abs() { x } else { m },
                );
            println!(
                "{} {speed}: largest throw difference {:.3} deg at cut {}",
                if roll { "roll" } else { "stun" },
                d.0,
                d.1
            );
        }
    }
    let path = format!("{OUT}/throw.csv");
    std::fs::write(&path, csv).map_err(io(&path))?;
    register_fonts();
    write_svg_and_png(
        (1200, 500),
        Path::new(&format!("{OUT}/throw.svg")),
        Path::new(&format!("{OUT}/throw.png")),
        |root| draw(root, &shots),
        |root| draw(root, &shots),
    )?;
    println!("wrote {OUT}/throw.csv, throw.svg and .png");
    Ok(())
}

const COLOURS: [RGBColor; 3] = [
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
];

fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, shots: &[Shot]) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let (left, right) = root.split_horizontally(600);
    type Pick = fn(&Shot) -> [f64; 2];
    /// A panel: its area, title, y label, what it draws and its y range's top.
    type Panel<'a, DB> = (&'a DrawingArea<DB, Shift>, &'a str, &'a str, Pick, f64);
    let panels: [Panel<DB>; 2] = [
        (
            &left,
            "Throw, mu = 0.06, e = 1 (any speed: 0.447-3.129 m/s)",
            "throw (degrees)",
            |s| s.throw,
            4.0,
        ),
        (
            &right,
            "Object ball's spin after the contact",
            "r |Omega_B| / v",
            |s| s.spin_b,
            0.3,
        ),
    ];
    for (area, title, y_desc, pick, y_max) in panels {
        let mut chart = ChartBuilder::on(area)
            .caption(title, (FONT, 18))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(55)
            .build_cartesian_2d(0.0..20.0, 0.0..y_max)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc("cut angle (degrees)")
            .y_desc(y_desc)
            .label_style((FONT, 14))
            .draw()
            .map_err(e)?;
        // With a constant mu the three speeds give the same curves (the CSV has all three;
        // they agree to rounding): one speed is drawn, a colour a shot.
        let speed = SPEEDS[1];
        for (k, roll) in [false, true].into_iter().enumerate() {
            let c = COLOURS[2 * k];
            let pts: Vec<&Shot> = shots
                .iter()
                .filter(|s| s.roll == roll && s.speed == speed)
                .collect();
            let name = if roll { "rolling cue ball" } else { "stun" };
            chart
                .draw_series(LineSeries::new(
                    pts.iter().map(|s| (s.cut, pick(s)[0])),
                    c.stroke_width(2),
                ))
                .map_err(e)?
                .label(format!("{name}, rigid stick"))
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], c.stroke_width(2)));
            chart
                .draw_series(
                    pts.iter()
                        .map(|s| Circle::new((s.cut, pick(s)[1]), 3, c.filled())),
                )
                .map_err(e)?
                .label(format!("{name}, compliant (Mindlin)"))
                .legend(move |(x, y)| Circle::new((x + 10, y), 3, c.filled()));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperLeft)
            .label_font((FONT, 13))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(e)?;
    }
    root.present().map_err(e)?;
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
