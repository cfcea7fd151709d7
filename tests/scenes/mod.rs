//! Scene builders (lab scenes on a level table) shared by the integration tests. They build
//! inputs through the library's `Scene::parse`, so they live apart from the independent
//! references in tests/common.
#![allow(dead_code)]

use billiard_contact::Scene;
use std::path::Path;

/// Pool ball: mass (kg), radius (m).
pub const M: f64 = 0.17;
pub const R: f64 = 0.028575;

/// A lab scene on a level table (up = +z, cloth at z = 0): ball A at (-r, 0, r) with
/// `va`, `wa`, ball B at (r, 0, r) at rest; `mu` is the TOML of contact.mu; `extra` is
/// appended (e.g. `[effects]`, `[table]`, `[solver]`).
pub fn lab_scene(va: [f64; 3], wa: [f64; 3], mu: &str, restitution: f64, extra: &str) -> Scene {
    let text = format!(
        r#"
name = "test"
[balls]
mass = {M}
radius = {R}
alpha = 0.4
[contact]
mu = {mu}
restitution = {restitution}
[contact.profile]
shape = "half-sine"
duration = 2.5e-4
[incoming.lab]
a = {{ position = [{a:?}, 0.0, {R:?}], velocity = [{:?}, {:?}, {:?}], spin = [{:?}, {:?}, {:?}] }}
b = {{ position = [{R:?}, 0.0, {R:?}], velocity = [0.0, 0.0, 0.0] }}
up = [0.0, 0.0, 1.0]
{extra}
"#,
        va[0],
        va[1],
        va[2],
        wa[0],
        wa[1],
        wa[2],
        a = -R,
    );
    Scene::parse(&text, Path::new("."), None).unwrap_or_else(|e| panic!("{e}\n{text}"))
}

/// Velocity and rolling spin (w = z x v / r, eq 59) of a cue ball at speed `s` making the
/// cut angle `cut` (radians) with the line of centres +x; `spin_factor` scales the rolling
/// spin (1 rolling, 0 stun, < 0 draw).
pub fn cue(s: f64, cut: f64, spin_factor: f64) -> ([f64; 3], [f64; 3]) {
    let (u, v) = (s * cut.cos(), s * cut.sin());
    (
        [u, v, 0.0],
        [-v / R * spin_factor, u / R * spin_factor, 0.0],
    )
}
