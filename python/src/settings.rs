//! Solver settings: how the bindings build them from Python keywords, and the one place
//! that reads their fields.

use billiard_contact::{Error, Method, Scene, SolverSettings};

/// Method, rtol, atol and rk4 steps of `s`. The only read of `SolverSettings`'s fields in the
/// bindings (they become accessors in the library).
pub fn fields(s: &SolverSettings) -> (Method, f64, f64, u32) {
    (s.method(), s.rtol(), s.atol(), s.steps())
}

/// A method name as the command line takes it (`closed-form`, `rk4`, `dopri5`, `dop853`).
pub fn method(name: &str) -> Result<Method, Error> {
    name.parse::<Method>()
}

/// The scene's settings with the overrides of `billiard-contact run`: `--method`, `--rtol`
/// (which carries atol with it unless atol is given), `--atol`, `--steps`.
pub fn for_run(
    scene: &Scene,
    method_name: Option<&str>,
    rtol: Option<f64>,
    atol: Option<f64>,
    steps: Option<u32>,
) -> Result<SolverSettings, Error> {
    let (base_method, base_rtol, base_atol, base_steps) = fields(&scene.solver);
    let m = match method_name {
        Some(name) => method(name)?,
        None => base_method,
    };
    let r = rtol.unwrap_or(base_rtol);
    let a = atol.unwrap_or(if rtol.is_some() { r } else { base_atol });
    SolverSettings::new(m, r, a, steps.unwrap_or(base_steps))
}

/// Settings for a batch: the closed form unless a method is named; `rtol` (default the
/// library's, 1e-10) sets atol too, as `billiard-contact batch --rtol` does.
pub fn for_batch(method_name: Option<&str>, rtol: Option<f64>) -> Result<SolverSettings, Error> {
    let (_, default_rtol, _, default_steps) = fields(&SolverSettings::default());
    let m = match method_name {
        Some(name) => method(name)?,
        None => Method::ClosedForm,
    };
    let r = rtol.unwrap_or(default_rtol);
    SolverSettings::new(m, r, r, default_steps)
}
