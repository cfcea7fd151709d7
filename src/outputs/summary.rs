//! The report of a run as text for people: [`Report::summary`].

use crate::base::number::{count, decimal, sci, si};
use crate::model::result::ContactResult;
use crate::outputs::report::{force_and_duration, HeldFrictionJson, Report};
use crate::scene::run::SceneOutcome;
use crate::scene::types::{Incoming, Scene};
use crate::solve::outcome::LawOutcome;
use crate::table_phase::outcome::TableOutcome;
use crate::table_phase::roll_out::RollOut;
use nalgebra::Vector3;

impl Report<'_> {
    /// The report as a human-readable summary: numbers for people (SI prefixes, plain
    /// decimals), a heat within the run's round-off of zero as 0 (the checks line gives the
    /// size of the round-off). The outcome's warnings are not part of it (the command line
    /// prints them on stderr; they are in [`SceneOutcome`] and the JSON report).
    pub fn summary(&self) -> String {
        summary(self.scene, self.run)
    }
}

/// A human-readable summary: numbers for people ([`crate::base::number::si`] prefixes,
/// plain decimals), a heat within the run's round-off of zero as 0 (the checks line gives
/// the size of the round-off). The outcome's warnings are not part of it (the command
/// line prints them on stderr; they are in [`SceneOutcome`] and the JSON report).
fn summary(scene: &Scene, so: &SceneOutcome) -> String {
    use std::fmt::Write;
    let o = &so.outcome;
    let r = &o.result;
    let mut s = String::new();
    let _ = writeln!(s, "{}", scene.name);
    let (force, duration) = force_and_duration(scene, so);
    let _ = writeln!(
        s,
        "  profile {} over {}, method {}, effects: {}",
        force,
        si(duration, "s", 5),
        so.settings.method(),
        scene.effects.simulated(&scene.contact.friction).join(", ")
    );
    if let Some(l) = &o.law {
        s.push_str(&law_summary(l));
    }
    if let Some(c) = &so.compliant {
        let xi = c.final_displacement;
        let _ = writeln!(
            s,
            "  tangential {}: Mindlin's spring under mu = {}; final displacement [{}, {}] m \
             (y, z), slip {}, tangential work {}",
            scene.tangential.name(),
            decimal(c.mu, 6),
            sci(xi.x, 6),
            sci(xi.y, 6),
            if c.slip_reversed() {
                "reversed"
            } else {
                "kept its sense"
            },
            si(c.outcome.tangential_work, "J", 5),
        );
    }
    if let Ok(Some(h)) = scene.hertz() {
        let _ = writeln!(
            s,
            "  Hertz contact of the material: compression {}, peak force {}, contact radius {}",
            si(h.max_compression, "m", 5),
            si(h.peak_force, "N", 5),
            si(h.contact_radius, "m", 5)
        );
    }
    if HeldFrictionJson::new(&scene.contact.friction, r.s0).is_some() {
        let _ = writeln!(
            s,
            "  friction          mu(S(0)) = {:.6} held through the contact (evaluate = initial)",
            scene.contact.friction.mu(r.s0)
        );
    }
    let plane = match (&so.plane_out, &scene.incoming) {
        (Some(out), Incoming::Plane(p)) => Some((p, out)),
        _ => None,
    };
    if !r.collided() {
        match plane {
            Some((p, _)) => writeln!(
                s,
                "  no collision: the ball does not move into the plane (v.n = {:.6} m/s); state \
                 unchanged",
                -p.approach_speed()
            ),
            None => writeln!(
                s,
                "  no collision: the balls do not approach (U(0) = {:.6} m/s); state unchanged",
                so.cm_in.u_cm.x
            ),
        }
        .ok();
        return s;
    }
    s.push_str(&contact_summary(
        r,
        o.stick_time,
        heat_round_off(scene, so),
        so.compliant.is_some(),
    ));
    let fmt = |v: &Vector3<f64>| vec3_text(v, 9);
    if let Some((p, out)) = plane {
        let _ = writeln!(
            s,
            "  ball against the plane of normal {}, out:",
            fmt(&p.normal)
        );
        let _ = writeln!(s, "    v        {} m/s", fmt(&out.velocity));
        let _ = writeln!(s, "    spin     {} rad/s", fmt(&out.spin));
    } else {
        let _ = writeln!(s, "  centre-of-mass frame, out:");
        let _ = writeln!(s, "    U        {} m/s", fmt(&r.out.u_cm));
        let _ = writeln!(s, "    omega_A  {} rad/s", fmt(&r.out.omega_a));
        let _ = writeln!(s, "    omega_B  {} rad/s", fmt(&r.out.omega_b));
    }
    if let Some((a, b)) = so.lab_out {
        let _ = writeln!(s, "  lab frame, out:");
        let _ = writeln!(s, "    v_A      {} m/s", fmt(&a.velocity));
        let _ = writeln!(s, "    spin_A   {} rad/s", fmt(&a.spin));
        let _ = writeln!(s, "    v_B      {} m/s", fmt(&b.velocity));
        let _ = writeln!(s, "    spin_B   {} rad/s", fmt(&b.spin));
    }
    if let Some(th) = so.throw_angle_deg {
        let _ = writeln!(s, "  throw angle       {th:.6} deg");
    }
    let c = &o.check;
    let _ = writeln!(
        s,
        "  checks (scaled): closed form {}, theta drift {}, momentum {}, angular momentum {}, \
         energy balance {}",
        sci(c.closed_form_error, 2),
        sci(c.theta_drift, 2),
        sci(c.momentum_error, 2),
        sci(c.angular_momentum_error, 2),
        sci(c.energy_balance_error, 2)
    );
    let _ = writeln!(
        s,
        "  solver: {}, {} accepted and {} rejected steps",
        count(o.stats.rhs_evaluations, "rhs evaluation", "rhs evaluations"),
        o.stats.accepted_steps,
        o.stats.rejected_steps
    );
    if let Some(t) = &so.table {
        s.push_str(&table_summary(t));
    }
    s
}

/// The contact law's line of the summary: its damping, the restitution it gave, the
/// largest compression and force.
fn law_summary(l: &LawOutcome) -> String {
    format!(
        "  contact law hertz, damping {} (coefficient {} {}): restitution {:.9}, compression \
         {}, peak force {}\n",
        l.law.damping(),
        decimal(l.law.coefficient(), 7),
        l.law.damping().unit(),
        l.restitution,
        si(l.max_compression, "m", 5),
        si(l.peak_force, "N", 5)
    )
}

/// The least round-off of a heat, relative to the energy scale m v_ref^2: a few ulps of the
/// kinetic energies whose difference it is (eq 38).
const HEAT_ROUND_OFF: f64 = 16.0 * f64::EPSILON;

/// The size of the energy's round-off in a run (J): the energy balance check's, and at
/// least a few ulps of the energy scale m v_ref^2.
fn heat_round_off(scene: &Scene, so: &SceneOutcome) -> f64 {
    scene.collision().map_or(0.0, |(c, _)| {
        so.outcome.check.energy_balance_error.max(HEAT_ROUND_OFF) * c.scales.energy
    })
}

/// A heat (J) for people: 0 within `round_off` (J) of zero, where its sign and digits are
/// the round-off of the difference of two kinetic energies.
fn heat_text(heat: f64, round_off: f64) -> String {
    si(if heat.abs() <= round_off { 0.0 } else { heat }, "J", 10)
}

/// The contact of a collision, human-readable: impulse, sliding, heat (within
/// `heat_round_off` J of zero: 0).
/// Under Mindlin's spring (`compliant`) the stop of sliding is where the spring holds, and
/// the sliding heat is the tangential force's work (docs/formats.md#json-report).
fn contact_summary(
    r: &ContactResult,
    stick_time: Option<f64>,
    heat_round_off: f64,
    compliant: bool,
) -> String {
    use std::fmt::Write;
    let mut s = String::new();
    let _ = writeln!(s, "  impulse P         {} N s", decimal(r.impulse, 10));
    if r.s0 == 0.0 {
        // docs/model.md#no-initial-sliding: the surfaces never slide.
        let _ = writeln!(
            s,
            "  sliding           none: S(0) = 0, theta undefined; purely normal throughout"
        );
    } else {
        let theta = r
            .theta
            .map(|t| format!("{:.6} deg", t.to_degrees()))
            .unwrap_or_else(|| "undefined (no slip)".into());
        let _ = writeln!(s, "  sliding S(0)      {:.9} m/s, theta {theta}", r.s0);
        match (r.sticks, stick_time) {
            (true, Some(t)) if compliant => {
                let _ = writeln!(
                    s,
                    "  spring holds      from t = {}, p = {} N s; S_out = {:.9} m/s",
                    si(t, "s", 7),
                    decimal(r.stick_impulse.unwrap_or(0.0), 7),
                    r.s_out
                );
            }
            (true, Some(t)) => {
                let _ = writeln!(
                    s,
                    "  sliding stops     at t = {}, p = {} N s; then purely normal",
                    si(t, "s", 7),
                    decimal(r.stick_impulse.unwrap_or(0.0), 7)
                );
            }
            _ => {
                let _ = writeln!(
                    s,
                    "  sliding           throughout, S_out = {:.9} m/s",
                    r.s_out
                );
            }
        }
    }
    let _ = writeln!(
        s,
        "  tangential J      {} N s",
        decimal(r.tangential_impulse, 10)
    );
    let _ = writeln!(
        s,
        "  heat H            {} ({} {})",
        heat_text(r.heat, heat_round_off),
        if compliant { "tangential" } else { "sliding" },
        heat_text(r.heat_sliding, heat_round_off)
    );
    s
}

/// The table phase, human-readable.
fn table_summary(t: &TableOutcome) -> String {
    use std::fmt::Write;
    let p = &t.table.params;
    let mut s = String::new();
    let fmt = |v: &Vector3<f64>| vec3_text(v, 6);
    let _ = writeln!(
        s,
        "  table (cloth mu {}, restitution {}, g {} m/s^2): until both roll, {}",
        p.mu(),
        p.restitution(),
        p.g(),
        si(t.end_time(), "s", 7)
    );
    for (i, (name, r)) in [("A", &t.a), ("B", &t.b)].into_iter().enumerate() {
        let imp = &r.impacts[0];
        let _ = writeln!(s, "    {name}: {}", leaves_the_cloth(r, &t.table.up, p.g()));
        let _ = writeln!(
            s,
            "       impact: normal {} N s, tangential {} N s ({}), {}",
            decimal(imp.normal_impulse, 7),
            decimal(imp.tangential_impulse, 7),
            if imp.sticks {
                "slip stopped"
            } else {
                "slips on"
            },
            count(u64::from(r.bounces), "bounce", "bounces")
        );
        let _ = writeln!(
            s,
            "       slides {} over {} m, rolls from t = {}",
            si(r.slide_time, "s", 7),
            fmt(&r.slide_displacement),
            si(r.roll_time, "s", 7)
        );
        let _ = writeln!(
            s,
            "       rolling: v {} m/s, spin {} rad/s",
            fmt(&r.rolling.velocity),
            fmt(&r.rolling.spin)
        );
        let dir = t
            .direction_deg(r)
            .map(|d| format!("{d:.4} deg from the line of centres"))
            .unwrap_or_else(|| "at rest".into());
        let defl = t
            .deflection_deg(i, r)
            .map(|d| format!(", deflected {d:.4} deg from its incoming line"))
            .unwrap_or_default();
        let _ = writeln!(s, "       direction: {dir}{defl}");
        if let Some((time, pos)) = r.rest {
            let _ = writeln!(
                s,
                "       rests at t = {} at {} m",
                si(time, "s", 7),
                fmt(&pos)
            );
        }
    }
    let _ = writeln!(
        s,
        "    checks (scaled): energy increase {}, momentum {}",
        sci(t.check.energy_increase, 2),
        sci(t.check.momentum_error, 2)
    );
    s
}

/// How a ball leaves the contact with respect to the cloth (unit vertical `up`, gravity `g`
/// m/s^2): a hop when it moves up at separation; a bounce off the cloth at t = 0 when it is
/// pressed into a cloth with restitution (the flight the ball path shows, up to (v.n)^2 /
/// (2 g) after that first impact, docs/model.md#the-table-phase); else it stays on the cloth.
fn leaves_the_cloth(r: &RollOut, up: &Vector3<f64>, g: f64) -> String {
    let first = &r.impacts[0];
    if r.hop_time > 0.0 {
        format!(
            "hops {}, {} high, lands at t = {}",
            si(r.hop_time, "s", 7),
            si(r.hop_height, "m", 7),
            si(first.time, "s", 7)
        )
    } else if r.bounces > 0 {
        let vn = first.velocity.dot(up);
        format!(
            "pressed into the cloth at separation, bounces off it at t = 0, up to {} high",
            si(vn * vn / (2.0 * g), "m", 7)
        )
    } else {
        "stays on the cloth (no hop)".into()
    }
}

/// `[+x, +y, +z]` with `prec` decimals; a component that rounds to zero prints as +0 (not
/// as -0.000000000 for a round-off remainder of -1e-17).
fn vec3_text(v: &Vector3<f64>, prec: usize) -> String {
    let one = |x: f64| {
        let s = format!("{x:+.prec$}");
        if s[1..].chars().all(|c| c == '0' || c == '.') {
            format!("{:+.prec$}", 0.0)
        } else {
            s
        }
    };
    format!("[{}, {}, {}]", one(v.x), one(v.y), one(v.z))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A component that rounds to zero at the printed precision prints as +0, whatever its
    /// sign; others keep theirs.
    #[test]
    fn vectors_print_round_off_as_plus_zero() {
        let v = Vector3::new(-1e-17, -4e-10, -0.0);
        assert_eq!(
            vec3_text(&v, 9),
            "[+0.000000000, +0.000000000, +0.000000000]"
        );
        let v = Vector3::new(-6e-10, 1.25, -2.5);
        assert_eq!(
            vec3_text(&v, 9),
            "[-0.000000001, +1.250000000, -2.500000000]"
        );
        assert_eq!(
            vec3_text(&Vector3::new(-4e-7, 0.0, 3e-7), 6),
            "[+0.000000, +0.000000, +0.000000]"
        );
    }
}
