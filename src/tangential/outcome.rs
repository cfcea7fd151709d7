//! What a compliant sphere-plane or sphere-sphere impact returns: the outgoing motion, the impulses, the
//! normalised incidence and rebound of Maw, Barber and Fawcett, and the time history.

use nalgebra::Vector3;
use serde::Serialize;

/// One accepted step of a compliant impact (lab-frame vectors, in the tangent plane).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CompliantTraceRow {
    /// Time since first touch (s).
    pub time: f64,
    /// Normal compression delta (m).
    pub compression: f64,
    /// Hertz's normal force F_n = (4/3) E* sqrt(R) delta^1.5 (N).
    pub normal_force: f64,
    /// Tangential force on the ball at the contact F_t (N): |F_t| <= mu F_n.
    pub tangential_force: Vector3<f64>,
    /// The tangential spring's elastic displacement xi = -F_t / k_t (m), k_t = 8 G* a.
    pub displacement: Vector3<f64>,
    /// Slip velocity of the contact point, u = v_t - R (w x n) (m/s).
    pub slip: Vector3<f64>,
    /// True while the spring slides (|F_t| = mu F_n).
    pub sliding: bool,
    /// Ball 1's centre's velocity relative to the partner's, g = v_1 - v_2 (m/s; on a plane,
    /// the ball's velocity).
    pub relative_velocity: Vector3<f64>,
    /// Ball 1's spin (rad/s).
    pub spin: Vector3<f64>,
    /// The partner's spin (rad/s; 0 for a plane).
    pub partner_spin: Vector3<f64>,
    /// The work the tangential force has taken from the balls so far, -integral of F_t.u dt
    /// (J): the energy stored in the spring plus what sliding and the spring's unloading
    /// rule have dissipated (docs/tangential.md#energy).
    pub tangential_work: f64,
}

/// The result of [`crate::resolve_sphere_plane_compliant`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CompliantOutcome {
    /// The ball's velocity after the contact (m/s).
    pub velocity: Vector3<f64>,
    /// The ball's spin after the contact (rad/s).
    pub spin: Vector3<f64>,
    /// Time from first touch until F_n returns to 0 (s).
    pub contact_time: f64,
    /// Normal impulse of the partner (the plane, or ball B) on the ball (N s).
    pub normal_impulse: f64,
    /// Tangential impulse of the partner on the ball (N s, in the tangent plane).
    pub tangential_impulse: Vector3<f64>,
    /// Largest normal force among the steps (N): at the largest compression when undamped;
    /// under damping the force peaks earlier, between steps, and this samples it from below.
    pub max_normal_force: f64,
    /// Largest compression (m).
    pub max_compression: f64,
    /// Angle of incidence of the contact point: atan(|u(0)| / |v.n(0)|) (rad), u the slip.
    pub incidence_angle: f64,
    /// Rebound angle of the contact point: atan2(u'.s, v'.n) (rad), s = u(0)/|u(0)| the
    /// incoming slip's direction: negative when the contact point's tangential velocity has
    /// reversed. 0 when the ball arrives without slip.
    pub rebound_angle: f64,
    /// Maw, Barber and Fawcett's normalised incidence Psi_1 = chi |u(0)| / |v.n(0)|, with
    /// chi = 4 G* / (mu E*) (= 2 (1 - nu) / (mu (2 - nu)) on a rigid plane); NaN when mu = 0.
    pub normalised_incidence: f64,
    /// The normalised rebound Psi_2 = chi (u'.s) / v'.n; NaN when mu = 0.
    pub normalised_rebound: f64,
    /// Kinetic energy before the contact (J).
    pub kinetic_energy_in: f64,
    /// Kinetic energy after the contact (J).
    pub kinetic_energy_out: f64,
    /// The work the tangential force took from the balls over the contact, -integral of
    /// F_t.u dt (J): the spring ends unloaded (its force falls with the contact), so all of
    /// it is dissipated, by sliding and by the spring's unloading rule. The rest of the
    /// kinetic energy lost is the normal force's (its damping).
    pub tangential_work: f64,
    /// Accepted steps.
    pub steps: u64,
    /// Rejected steps (error too large, or shortened to land on an event).
    pub rejected: u64,
    /// Every accepted step, from first touch to the end of the contact.
    pub trace: Vec<CompliantTraceRow>,
}

/// The result of [`crate::resolve_sphere_sphere_compliant`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CompliantPairOutcome {
    /// The contact as ball A sees it: A's outgoing velocity and spin, the impulses of B on A
    /// (the normal one along the normal from B towards A), the incidence and rebound of A's
    /// contact point relative to B's, the kinetic energies of both balls, and the trace
    /// (the force on A, the slip of A over B).
    pub ball_a: CompliantOutcome,
    /// Ball B's velocity after the contact (m/s).
    pub velocity_b: Vector3<f64>,
    /// Ball B's spin after the contact (rad/s).
    pub spin_b: Vector3<f64>,
}
