//! Verification of a run: conservation laws, the energy balance of eq 50, and the distance
//! to the closed form, all scaled by the collision's reference scales
//! (docs/model.md#scales-and-scaled-errors).

use crate::closed_form::kernel::ClosedForm;
use crate::model::collision::Collision;
use crate::model::state::CmState;
use nalgebra::Vector3;
use serde::Serialize;

/// What every run reports about its own accuracy. All values are scaled and >= 0.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Checks {
    /// Largest |slip x e0| / v_ref over accepted steps while sliding (theta constant, eq 23).
    pub theta_drift: f64,
    /// Largest component difference of the outgoing state from the closed form: velocities
    /// over v_ref, spins over v_ref / r.
    pub closed_form_error: f64,
    /// Ball A's momentum change against the applied impulses -P e_x - J e, over m v_ref
    /// (M u for the pair mass M of unequal balls).
    pub momentum_error: f64,
    /// Change of the angular momentum of eq 36, over m v_ref r.
    pub angular_momentum_error: f64,
    /// |(H - H_sfr) - (2 U(0) P - P^2/m)| over m v_ref^2 (eq 50), H from the kinetic
    /// energies (eq 38); m the pair mass M for unequal balls.
    pub energy_balance_error: f64,
    /// The carried slip against (2V + r Omega_z, 2W - r Omega_y) recomputed, over v_ref
    /// (time stepping only).
    pub slip_consistency: f64,
}

/// Largest scaled component difference between two states.
pub fn state_error(c: &Collision, a: &CmState, b: &CmState) -> f64 {
    let sc = c.scales;
    let ratio = |d: f64, r: f64| if d == 0.0 { 0.0 } else { d / r };
    ratio((a.u_cm - b.u_cm).amax(), sc.speed)
        .max(ratio((a.omega_a - b.omega_a).amax(), sc.spin))
        .max(ratio((a.omega_b - b.omega_b).amax(), sc.spin))
}

/// The checks of an outgoing state `out` with tangential impulse `j` and integrated
/// sliding heat `heat_sliding` against the collision and its closed form.
pub fn checks(
    c: &Collision,
    exact: &ClosedForm,
    out: &CmState,
    j: f64,
    heat_sliding: f64,
) -> Checks {
    let sc = c.scales;
    let ratio = |d: f64, r: f64| if d == 0.0 { 0.0 } else { d / r };
    let m = c.balls.pair_mass();
    let e = c.direction.unwrap_or_default();
    let applied = -Vector3::new(c.impulse, j * e.x, j * e.y);
    let momentum = (m * (out.u_cm - c.incoming.u_cm) - applied).amax();
    let angular = (out.angular_momentum(&c.balls) - c.incoming.angular_momentum(&c.balls)).amax();
    let heat = c.incoming.kinetic_energy(&c.balls) - out.kinetic_energy(&c.balls);
    let u0 = c.incoming.u_cm.x;
    let p = c.impulse;
    let balance = (heat - heat_sliding) - p * (2.0 * u0 - p / m);
    Checks {
        theta_drift: 0.0,
        closed_form_error: state_error(c, out, &exact.result.out),
        momentum_error: ratio(momentum, sc.impulse),
        angular_momentum_error: ratio(angular, sc.angular_momentum),
        energy_balance_error: ratio(balance.abs(), sc.energy),
        slip_consistency: 0.0,
    }
}
