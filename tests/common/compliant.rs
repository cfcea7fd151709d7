//! Shared by the compliant-contact tests (tests/tangential.rs, tests/tangential_pair.rs,
//! tests/chung_ooi.rs): a solid sphere from its density, the tight solver settings, and
//! Hertz's impact written from its formula.

use billiard_contact::{Ball, SolverSettings, ALPHA_SOLID};
use std::f64::consts::PI;

/// A solid sphere of density `rho` (kg/m3) and radius `r` (m).
pub fn sphere(rho: f64, r: f64) -> Ball {
    Ball::new(rho * 4.0 / 3.0 * PI * r.powi(3), r, ALPHA_SOLID).unwrap()
}

/// rtol = atol = 1e-11.
pub fn tight() -> SolverSettings {
    SolverSettings::default()
        .with_rtol(1e-11)
        .unwrap()
        .with_atol(1e-11)
        .unwrap()
}

/// Hertz's impact of the mass `m` (kg; the reduced mass of a pair) of effective radius `r`
/// (m) and modulus `es` (Pa) at the approach speed `v` (m/s) (Johnson, Contact Mechanics,
/// 11.1): the largest compression delta_max = (15 m v^2 / (16 E* sqrt(R)))^(2/5), the peak
/// force F_max = (4/3) E* sqrt(R) delta_max^1.5 and the contact time 2.868265699 (m^2 /
/// (E*^2 R v))^(1/5) (the constant is (4/5) B(2/5, 1/2) (15/16)^(2/5), to ten digits).
pub fn hertz(m: f64, r: f64, es: f64, v: f64) -> (f64, f64, f64) {
    let d = (15.0 * m * v * v / (16.0 * es * r.sqrt())).powf(0.4);
    let f = 4.0 / 3.0 * es * r.sqrt() * d.powf(1.5);
    let t = 2.868_265_699 * (m * m / (es * es * r * v)).powf(0.2);
    (d, f, t)
}
