//! Restitution and contact time against speed for pool balls under the two damped contact
//! laws (docs/contact-law.md#restitution-and-contact-time-of-pool-balls).
//!
//! Phenolic resin balls (E = 5.4 GPa, nu = 0.34, m = 0.17 kg, r = 28.575 mm): Hertz's
//! stiffness k = (4/3) E* sqrt(R), and both damping laws calibrated to e = 0.95 at a relative
//! approach speed of 1 m/s (a user's calibration, not a measured constant). Each law's
//! head-on impact is integrated at 60 speeds from 0.1 to 8 m/s; the figure (e(v) and tau(v),
//! with the elastic Hertz time) is written to `docs/contact_law.svg` and `.png`, the values
//! at 0.1, 1 and 8 m/s are printed, and the run fails unless both laws give 0.95 at 1 m/s
//! to 1e-10 and e falls with speed.
//!
//! ```sh
//! cargo run --release --example contact_law_restitution
//! ```

use billiard_contact::details::{elastic_impact, hertz_stiffness};
use billiard_contact::plot::{register_fonts, write_svg_and_png, FONT};
use billiard_contact::{Ball, ContactLaw, Damping, Error, Material};
use plotters::coord::combinators::{LogCoord, WithKeyPoints};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;
use std::process::ExitCode;

/// Tolerance of the head-on integrations (dop853).
const RTOL: f64 = 1e-12;
/// The speeds drawn (m/s), log-spaced.
const SPEEDS: (f64, f64, usize) = (0.1, 8.0, 60);

/// The speeds labelled on the axis (m/s).
const SPEED_LABELS: [f64; 7] = [0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 8.0];

/// One law's curve: (v, e, tau in us).
struct Curve {
    name: String,
    colour: RGBColor,
    points: Vec<(f64, f64, f64)>,
}

pub fn run() -> Result<(), Error> {
    let ball = Ball::new(0.17, 0.028575, 0.4)?;
    let resin = Material::new(5.4e9, 0.34)?;
    let (_, _, k) = hertz_stiffness((&ball, &resin), (&ball, &resin));
    let reduced = 0.5 * ball.mass();
    let (lo, hi, n) = SPEEDS;
    let speeds: Vec<f64> = (0..n)
        .map(|i| lo * (hi / lo).powf(i as f64 / (n - 1) as f64))
        .collect();
    let mut curves = Vec::new();
    for (damping, colour) in [(Damping::HuntCrossley, BLUE), (Damping::KuwabaraKono, RED)] {
        let law = ContactLaw::calibrated(k, damping, 0.95, 1.0, reduced)?;
        let mut points = Vec::new();
        for &v in &speeds {
            let h = law.head_on(reduced, v, RTOL)?;
            points.push((v, h.restitution, h.duration * 1e6));
        }
        println!(
            "{damping}: coefficient {:.6e} {}",
            law.coefficient(),
            damping.unit()
        );
        for v in [0.1, 1.0, 8.0] {
            let h = law.head_on(reduced, v, RTOL)?;
            println!(
                "  v = {v:>4} m/s: e = {:.6}, tau = {:.1} us",
                h.restitution,
                h.duration * 1e6
            );
        }
        check(&law, reduced, &points)?;
        curves.push(Curve {
            name: format!(
                "{damping} ({} = {:.3e} {})",
                symbol(damping),
                law.coefficient(),
                damping.unit()
            ),
            colour,
            points,
        });
    }
    let elastic: Vec<(f64, f64)> = speeds
        .iter()
        .map(|&v| (v, elastic_impact(k, reduced, v).1 * 1e6))
        .collect();
    register_fonts();
    let dims = (1100, 480);
    write_svg_and_png(
        dims,
        Path::new("docs/contact_law.svg"),
        Path::new("docs/contact_law.png"),
        |root| draw(root, &curves, &elastic),
        |root| draw(root, &curves, &elastic),
    )?;
    println!("wrote docs/contact_law.svg and docs/contact_law.png");
    Ok(())
}

/// The coefficient's symbol.
fn symbol(d: Damping) -> &'static str {
    match d {
        Damping::HuntCrossley => "beta",
        _ => "gamma",
    }
}

/// Both laws give 0.95 at 1 m/s to 1e-10, and e falls with speed.
fn check(law: &ContactLaw, reduced: f64, points: &[(f64, f64, f64)]) -> Result<(), Error> {
    let e1 = law.head_on(reduced, 1.0, RTOL)?.restitution;
    let falls = points.windows(2).all(|w| w[1].1 < w[0].1);
    if (e1 - 0.95).abs() > 1e-10 || !falls {
        return Err(Error::invalid(
            "contact_law_restitution",
            format!("e(1 m/s) = {e1}, falling with speed: {falls}"),
            "e = 0.95 at 1 m/s to 1e-10, falling with speed",
        ));
    }
    Ok(())
}

/// The axes of both panels: speed on a log axis (0.1 to 8 m/s), `y` linear.
type Axes = Cartesian2d<WithKeyPoints<LogCoord<f64>>, RangedCoordf64>;

/// A panel on `area`: its caption, the speed axis and `y` over `range`, with the mesh drawn.
fn panel<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    range: std::ops::Range<f64>,
    y: &str,
) -> Result<ChartContext<'a, DB, Axes>, String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(
            (SPEEDS.0..SPEEDS.1)
                .log_scale()
                .with_key_points(SPEED_LABELS.to_vec()),
            range,
        )
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("relative approach speed v (m/s)")
        .x_label_formatter(&|v| format!("{v}"))
        .y_desc(y)
        .label_style((FONT, 14))
        .draw()
        .map_err(e)?;
    Ok(chart)
}

/// The panel's legend at `position`, on a translucent white box.
fn legend<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Axes>,
    position: SeriesLabelPosition,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .position(position)
        .label_font((FONT, 13))
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|x| x.to_string())
}

/// The two panels: e(v) and tau(v), speed on a log axis.
fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    curves: &[Curve],
    elastic: &[(f64, f64)],
) -> Result<(), String> {
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let (left, right) = root.split_horizontally(550);
    let mut chart = panel(&left, "restitution e(v), pool balls", 0.68..1.0, "e")?;
    for c in curves {
        let colour = c.colour;
        chart
            .draw_series(LineSeries::new(
                c.points.iter().map(|p| (p.0, p.1)),
                colour.stroke_width(2),
            ))
            .map_err(e)?
            .label(c.name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
    }
    chart
        .draw_series(std::iter::once(Circle::new((1.0, 0.95), 5, BLACK.filled())))
        .map_err(e)?
        .label("calibration: e = 0.95 at 1 m/s")
        .legend(|(x, y)| Circle::new((x + 10, y), 4, BLACK.filled()));
    legend(&mut chart, SeriesLabelPosition::LowerLeft)?;
    let mut chart = panel(&right, "contact time tau(v)", 200.0..700.0, "tau (us)")?;
    for c in curves {
        chart
            .draw_series(LineSeries::new(
                c.points.iter().map(|p| (p.0, p.2)),
                c.colour.stroke_width(2),
            ))
            .map_err(e)?;
    }
    chart
        .draw_series(LineSeries::new(
            elastic.iter().copied(),
            ShapeStyle::from(&BLACK).stroke_width(1),
        ))
        .map_err(e)?
        .label("elastic Hertz, 2.9433 delta_max / v")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK));
    legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    root.present().map_err(e)
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
