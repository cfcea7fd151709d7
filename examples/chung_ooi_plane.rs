//! Chung and Ooi's Test 4 with the compliant sphere-plane kernel (docs/tangential.md): a
//! sphere at 3.9 m/s on a rigid plane at incidence 1 to 89 degrees, no spin, for the
//! aluminium oxide and aluminium alloy spheres of data/chung_ooi/README.md. Writes
//! docs/tangential/rebound.csv (every run), docs/tangential/trace_alumina_20deg.csv (one time
//! history) and the figure docs/tangential/rebound.svg and .png: Maw, Barber and Fawcett's
//! normalised rebound Psi_2 against the normalised incidence Psi_1, with the gross-sliding
//! line, and the trace's forces. The same sweep for two spheres of the material
//! (`resolve_sphere_sphere_compliant`, ball B at rest, relative speed 3.9 m/s): two
//! identical spheres, and ball B of twice A's radius, written to
//! docs/tangential/rebound_pair.csv and drawn as markers on the same panel.
//!
//! `cargo run --release --example chung_ooi_plane`

use billiard_contact::nalgebra::Vector3;
use billiard_contact::plot::{register_fonts, write_svg_and_png, FONT};
use billiard_contact::*;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;

/// The benchmark's speed (m/s).
const SPEED: f64 = 3.9;

struct Case {
    name: &'static str,
    density: f64,
    radius: f64,
    youngs: f64,
    poisson: f64,
    mu: f64,
    colour: RGBColor,
}

const CASES: [Case; 2] = [
    Case {
        name: "aluminium oxide",
        density: 4000.0,
        radius: 0.0025,
        youngs: 3.8e11,
        poisson: 0.23,
        mu: 0.092,
        colour: RGBColor(31, 119, 180),
    },
    Case {
        name: "aluminium alloy",
        density: 2700.0,
        radius: 0.0025,
        youngs: 7.0e10,
        poisson: 0.33,
        mu: 0.092,
        colour: RGBColor(214, 39, 40),
    },
];

fn settings() -> Result<SolverSettings, Error> {
    SolverSettings::default().with_rtol(1e-10)?.with_atol(1e-10)
}

fn impact(case: &Case, deg: f64) -> Result<(Ball, CompliantOutcome), Error> {
    let r = case.radius;
    let ball = Ball::new(case.density * 4.0 / 3.0 * PI * r.powi(3), r, ALPHA_SOLID)?;
    let mat = Material::new(case.youngs, case.poisson)?;
    let a = deg.to_radians();
    let v = SPEED * Vector3::new(a.sin(), -a.cos(), 0.0);
    let out = resolve_sphere_plane_compliant(
        &ball,
        mat,
        None,
        case.mu,
        v,
        Vector3::zeros(),
        Vector3::y(),
        &settings()?,
    )?;
    Ok((ball, out))
}

/// Two spheres of `case`'s material, A of the case's radius and B of `ratio` times it (B at
/// rest), meeting at the relative speed 3.9 m/s at incidence `deg`.
fn pair_impact(case: &Case, ratio: f64, deg: f64) -> Result<CompliantPairOutcome, Error> {
    let solid = |r: f64| Ball::new(case.density * 4.0 / 3.0 * PI * r.powi(3), r, ALPHA_SOLID);
    let material = Material::new(case.youngs, case.poisson)?;
    let a = deg.to_radians();
    let ball_a = CompliantSphere {
        ball: solid(case.radius)?,
        material,
        velocity: SPEED * Vector3::new(a.cos(), a.sin(), 0.0),
        spin: Vector3::zeros(),
    };
    let ball_b = CompliantSphere {
        ball: solid(ratio * case.radius)?,
        material,
        velocity: Vector3::zeros(),
        spin: Vector3::zeros(),
    };
    resolve_sphere_sphere_compliant(&ball_a, &ball_b, Vector3::x(), case.mu, 1.0, &settings()?)
}

/// The points (Psi_1, Psi_2) of one pair sweep, with its colour and radius ratio.
type PairSeries = (RGBColor, f64, Vec<(f64, f64)>);

/// The radius ratios r_B / r_A of the pairs drawn: identical spheres, and B twice A.
const RATIOS: [f64; 2] = [1.0, 2.0];

/// The gross-sliding line's offset 2 chi mu (1 + 1/alpha), chi = 2 (1 - nu) / (mu (2 - nu)).
fn offset(case: &Case) -> f64 {
    4.0 * (1.0 - case.poisson) / (2.0 - case.poisson) * (1.0 + 1.0 / ALPHA_SOLID)
}

fn io(path: &str) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |e| Error::io(path, e)
}

pub fn run() -> Result<(), Error> {
    std::fs::create_dir_all("docs/tangential").map_err(io("docs/tangential"))?;
    let mut csv = String::from(
        "material,incidence_deg,psi1,psi2,rebound_angle_deg,tangential_restitution,spin_out,\
         contact_time_s,energy_ratio\n",
    );
    let mut curves = Vec::new();
    for case in &CASES {
        let mut points = Vec::new();
        for i in 1..=89 {
            let deg = i as f64;
            let (_, out) = impact(case, deg)?;
            let e_t = out.velocity.x / (SPEED * deg.to_radians().sin());
            writeln!(
                csv,
                "{},{deg},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.12}",
                case.name,
                out.normalised_incidence,
                out.normalised_rebound,
                out.rebound_angle.to_degrees(),
                e_t,
                out.spin.z,
                out.contact_time,
                out.kinetic_energy_out / out.kinetic_energy_in
            )
            .expect("writing to a String");
            if out.kinetic_energy_out > out.kinetic_energy_in * (1.0 + 1e-9) {
                return Err(Error::invalid(
                    "chung_ooi_plane",
                    format!("{} at {deg} degrees", case.name),
                    "a kinetic energy that does not grow",
                ));
            }
            points.push((out.normalised_incidence, out.normalised_rebound));
        }
        let line = offset(case);
        let psi_cross = points
            .windows(2)
            .find(|p| p[0].1 < 0.0 && p[1].1 >= 0.0)
            .map(|p| p[1].0);
        let min = points
            .iter()
            .cloned()
            .fold((0.0, f64::INFINITY), |m, p| if p.1 < m.1 { p } else { m });
        println!(
            "{}: gross-sliding offset {line:.4}, lowest Psi_2 {:.4} at Psi_1 {:.3}, Psi_2 back \
             to >= 0 at Psi_1 {:?}",
            case.name, min.1, min.0, psi_cross
        );
        curves.push((case, points));
    }
    std::fs::write("docs/tangential/rebound.csv", csv)
        .map_err(io("docs/tangential/rebound.csv"))?;

    let mut pair_csv = String::from("material,radius_ratio,incidence_deg,psi1,psi2,energy_ratio\n");
    let mut pairs = Vec::new();
    for case in &CASES {
        for ratio in RATIOS {
            let mut points = Vec::new();
            for i in 1..=17 {
                let deg = 5.0 * i as f64;
                let o = pair_impact(case, ratio, deg)?.ball_a;
                writeln!(
                    pair_csv,
                    "{},{ratio},{deg},{:.9e},{:.9e},{:.12}",
                    case.name,
                    o.normalised_incidence,
                    o.normalised_rebound,
                    o.kinetic_energy_out / o.kinetic_energy_in
                )
                .expect("writing to a String");
                points.push((o.normalised_incidence, o.normalised_rebound));
            }
            pairs.push((case.colour, ratio, points));
        }
    }
    std::fs::write("docs/tangential/rebound_pair.csv", pair_csv)
        .map_err(io("docs/tangential/rebound_pair.csv"))?;

    let (_, out) = impact(&CASES[0], 20.0)?;
    let mut trace = String::from(
        "time_s,compression_m,normal_force_n,tangential_force_n,displacement_m,slip_m_s,sliding\n",
    );
    for r in &out.trace {
        writeln!(
            trace,
            "{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{:.9e},{}",
            r.time,
            r.compression,
            r.normal_force,
            r.tangential_force.x,
            r.displacement.x,
            r.slip.x,
            r.sliding
        )
        .expect("writing to a String");
    }
    std::fs::write("docs/tangential/trace_alumina_20deg.csv", trace)
        .map_err(io("docs/tangential/trace_alumina_20deg.csv"))?;

    register_fonts();
    write_svg_and_png(
        (1200, 500),
        Path::new("docs/tangential/rebound.svg"),
        Path::new("docs/tangential/rebound.png"),
        |root| draw(root, &curves, &pairs, &out),
        |root| draw(root, &curves, &pairs, &out),
    )?;
    println!(
        "wrote docs/tangential/rebound.csv, rebound_pair.csv, trace_alumina_20deg.csv, \
         rebound.svg and .png"
    );
    Ok(())
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    curves: &[(&Case, Vec<(f64, f64)>)],
    pairs: &[PairSeries],
    trace: &CompliantOutcome,
) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let (left, right) = root.split_horizontally(680);
    let mut chart = ChartBuilder::on(&left)
        .caption(
            "Normalised rebound against normalised incidence, 3.9 m/s",
            (FONT, 18),
        )
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(55)
        .build_cartesian_2d(0.0..14.0, -3.0..9.0)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("Psi_1 = chi u(0) / v_n   (chi = 4 G* / (mu E*))")
        .y_desc("Psi_2 = chi u' / v_n'")
        .label_style((FONT, 14))
        .draw()
        .map_err(e)?;
    chart
        .draw_series(LineSeries::new([(0.0, 0.0), (14.0, 0.0)], BLACK.mix(0.4)))
        .map_err(e)?;
    for (case, points) in curves {
        let line = offset(case);
        let c = case.colour;
        chart
            .draw_series(DashedLineSeries::new(
                [(line - 3.0, -3.0), (14.0, 14.0 - line)],
                6,
                4,
                c.mix(0.6).stroke_width(1),
            ))
            .map_err(e)?
            .label(format!("gross sliding: Psi_1 - {line:.3}"))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], c.mix(0.6)));
        chart
            .draw_series(LineSeries::new(
                points.iter().cloned().filter(|p| p.0 <= 14.0),
                c.stroke_width(2),
            ))
            .map_err(e)?
            .label(format!("{} (mu = {})", case.name, case.mu))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], c.stroke_width(2)));
        chart
            .draw_series(
                points
                    .iter()
                    .enumerate()
                    .filter(|(i, p)| (i + 1) % 5 == 0 && p.0 <= 14.0)
                    .map(|(_, &p)| Circle::new(p, 3, c.filled())),
            )
            .map_err(e)?;
    }
    for (c, ratio, points) in pairs {
        let c = *c;
        let shown = points.iter().cloned().filter(|p| p.0 <= 14.0);
        if *ratio == 1.0 {
            chart
                .draw_series(shown.map(|p| {
                    Rectangle::new(
                        [(p.0 - 0.1, p.1 - 0.1), (p.0 + 0.1, p.1 + 0.1)],
                        c.stroke_width(1),
                    )
                }))
                .map_err(e)?
                .label("two identical spheres")
                .legend(move |(x, y)| {
                    Rectangle::new([(x + 6, y - 4), (x + 14, y + 4)], c.stroke_width(1))
                });
        } else {
            chart
                .draw_series(shown.map(|p| TriangleMarker::new(p, 6, c.stroke_width(1))))
                .map_err(e)?
                .label(format!("spheres, r_B = {ratio} r_A"))
                .legend(move |(x, y)| TriangleMarker::new((x + 10, y), 6, c.stroke_width(1)));
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .label_font((FONT, 13))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;

    let t_c = trace.contact_time;
    let f_max = trace.max_normal_force;
    let mut chart = ChartBuilder::on(&right)
        .caption("Aluminium oxide at 20 degrees: the forces", (FONT, 18))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(55)
        .build_cartesian_2d(0.0..1.0, -0.12..1.05)
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("t / contact time")
        .y_desc("force / peak normal force")
        .label_style((FONT, 14))
        .draw()
        .map_err(e)?;
    let mu = CASES[0].mu;
    type Series<'a> = (
        &'a str,
        RGBColor,
        Box<dyn Fn(&CompliantTraceRow) -> f64 + 'a>,
    );
    let series: [Series; 3] = [
        ("F_n", BLACK, Box::new(|r| r.normal_force / f_max)),
        (
            "mu F_n (the cap)",
            RGBColor(150, 150, 150),
            Box::new(move |r| mu * r.normal_force / f_max),
        ),
        (
            "F_t (along the incoming slip, sign reversed)",
            RGBColor(31, 119, 180),
            Box::new(|r| -r.tangential_force.x / f_max),
        ),
    ];
    for (name, c, f) in series {
        chart
            .draw_series(LineSeries::new(
                trace.trace.iter().map(|r| (r.time / t_c, f(r))),
                c.stroke_width(2),
            ))
            .map_err(e)?
            .label(name)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], c.stroke_width(2)));
    }
    chart
        .draw_series(trace.trace.iter().filter(|r| r.sliding).map(|r| {
            Circle::new(
                (r.time / t_c, -r.tangential_force.x / f_max),
                2,
                RED.filled(),
            )
        }))
        .map_err(e)?
        .label("sliding (|F_t| = mu F_n)")
        .legend(|(x, y)| Circle::new((x + 10, y), 3, RED.filled()));
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::MiddleRight)
        .label_font((FONT, 13))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(e)?;
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
