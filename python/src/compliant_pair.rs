//! `BallBall(..., tangential="mindlin")`: the compliant impact of two balls (Hertz's normal
//! force, elastic or damped, Mindlin's tangential spring under Coulomb's cap;
//! docs/tangential.md#two-spheres), the library's `resolve_sphere_sphere_compliant_damped`
//! (with `(Damping::None, 0.0)`: the elastic `resolve_sphere_sphere_compliant`, bit for
//! bit), row by row from `resolve_lab`'s arrays.

use crate::inputs::{with_argument_names, Inputs};
use crate::outputs::{float64, vector};
use crate::plane::{damping_law, renamed};
use billiard_contact::batch::LabRows;
use billiard_contact::details::hertz_stiffness;
use billiard_contact::nalgebra::Vector3;
use billiard_contact::{
    resolve_sphere_sphere_compliant_damped, BallPair, CompliantSphere, Damping, Error, Frame,
    Material, SolverSettings,
};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;

/// Rows from which the compliant rows spread over rayon's pool (each row steps a contact:
/// hundreds of steps, so a few rows already fill a thread).
const PARALLEL_ROWS: usize = 64;

/// The compliant contact of a pair: one material for both balls, Coulomb's mu, the factor
/// on Mindlin's tangential stiffness and the damping of Hertz's normal force.
#[derive(Clone, Copy, PartialEq)]
pub(crate) struct PairMindlin {
    pub(crate) material: Material,
    /// Coulomb friction between the balls.
    pub(crate) mu: f64,
    /// The factor on Mindlin's stiffness 8 G* a (1: Mindlin's spring).
    pub(crate) shear_stiffness_factor: f64,
    /// The damping law and its coefficient (beta in s/m or gamma in s), as run;
    /// `(Damping::None, 0.0)`: elastic Hertz.
    pub(crate) law: (Damping, f64),
    /// The keywords it came from: a coefficient given (s/m or s), or the relative approach
    /// speed of the calibration (m/s).
    pub(crate) coefficient: Option<f64>,
    pub(crate) at_speed: Option<f64>,
}

/// The keywords of the normal force's damping: `damping=`, `coefficient=`, `restitution=`
/// and `at_speed=`.
pub(crate) struct DampingKeywords<'a> {
    pub(crate) damping: Option<&'a str>,
    pub(crate) coefficient: Option<f64>,
    pub(crate) restitution: f64,
    pub(crate) at_speed: Option<f64>,
}

/// The numbers of one row: va, wa, vb, wb, the normal impulse (N s), the magnitude of the
/// tangential impulse (N s), the contact time (s) and A's rebound angle relative to B
/// (rad; NaN without contact).
type Row = [f64; 16];

/// The compliant rows as output columns.
pub(crate) struct PairRows {
    rows: Vec<Row>,
}

impl PairMindlin {
    /// The material from the keywords (both or neither), checked; the factor checked; the
    /// damping law as `BallPlane`'s (elastic, a coefficient, or calibrated to the restitution
    /// of a head-on impact at the relative approach speed `at_speed` on the pair's Hertz
    /// stiffness and reduced mass m* = m_A m_B / (m_A + m_B)).
    pub(crate) fn of(
        balls: &BallPair,
        youngs_modulus: Option<f64>,
        poisson_ratio: Option<f64>,
        mu: f64,
        shear_stiffness_factor: Option<f64>,
        keywords: DampingKeywords<'_>,
    ) -> Result<Self, Error> {
        let (Some(e), Some(nu)) = (youngs_modulus, poisson_ratio) else {
            return Err(Error::invalid(
                "youngs_modulus, poisson_ratio",
                "not both given with tangential=\"mindlin\"",
                "the balls' material (Mindlin's spring and Hertz's force need it)",
            ));
        };
        let material = Material::new(e, nu).map_err(|err| {
            renamed(
                renamed(err, "balls.youngs_modulus", "youngs_modulus"),
                "balls.poisson_ratio",
                "poisson_ratio",
            )
        })?;
        let factor = shear_stiffness_factor.unwrap_or(1.0);
        if !(factor > 0.0 && factor.is_finite()) {
            return Err(Error::invalid(
                "shear_stiffness_factor",
                factor,
                "> 0 and finite (1: Mindlin's stiffness; larger: stiffer, towards the rigid \
                 stick rule)",
            ));
        }
        let DampingKeywords {
            damping,
            coefficient,
            restitution,
            at_speed,
        } = keywords;
        let law = damping_law(
            crate::cluster::damping_of(damping)?,
            restitution,
            coefficient,
            at_speed,
            balls.reduced_mass(),
            // k = (4/3) E* sqrt(R*), which does not depend on the speed (the calibration
            // checks at_speed itself and names it).
            |_| Ok(hertz_stiffness((&balls.a, &material), (&balls.b, &material)).2),
        )?;
        Ok(PairMindlin {
            material,
            mu,
            shear_stiffness_factor: factor,
            law,
            coefficient,
            at_speed,
        })
    }

    /// Row i: the balls must touch (as for the closed form); a pair that does not approach
    /// passes unchanged with no impulse.
    fn row(
        &self,
        balls: &BallPair,
        inputs: &Inputs,
        i: usize,
        settings: &SolverSettings,
    ) -> Result<Row, Error> {
        let scene = inputs.row(i)?;
        Frame::of_pair(&scene, balls).map_err(with_argument_names)?;
        let (a, b) = (scene.a, scene.b);
        let normal = (b.position - a.position).normalize();
        if (a.velocity - b.velocity).dot(&normal) <= 0.0 {
            let (va, wa, vb, wb) = (a.velocity, a.spin, b.velocity, b.spin);
            return Ok(out_row([va, wa, vb, wb], [0.0, 0.0, 0.0, f64::NAN]));
        }
        let sphere = |ball, velocity, spin| CompliantSphere {
            ball,
            material: self.material,
            velocity,
            spin,
        };
        let o = resolve_sphere_sphere_compliant_damped(
            &sphere(balls.a, a.velocity, a.spin),
            &sphere(balls.b, b.velocity, b.spin),
            self.law,
            normal,
            self.mu,
            self.shear_stiffness_factor,
            settings,
        )
        .map_err(|e| {
            [
                ("incoming.velocity_a", "va"),
                ("incoming.velocity_b", "vb"),
                ("incoming.spin_a", "wa"),
                ("incoming.spin_b", "wb"),
                ("friction.mu", "mu"),
                // A ball's alpha below the compliant contact's bound: ball A's or B's
                // (the shared `alpha` when they are one ball).
                ("balls.a.alpha", "a.alpha"),
                ("balls.b.alpha", "b.alpha"),
                // Hertz's contact time out of the doubles' range: the material.
                ("contact.profile.duration", "youngs_modulus, poisson_ratio"),
            ]
            .iter()
            .fold(e, |e, (from, to)| renamed(e, from, to))
        })?;
        let (va, wa, vb, wb) = (o.ball_a.velocity, o.ball_a.spin, o.velocity_b, o.spin_b);
        Ok(out_row(
            [va, wa, vb, wb],
            [
                o.ball_a.normal_impulse,
                o.ball_a.tangential_impulse.norm(),
                o.ball_a.contact_time,
                o.ball_a.rebound_angle,
            ],
        ))
    }

    /// Every row (on rayon's pool from `PARALLEL_ROWS` rows); the first failure and its row.
    pub(crate) fn rows(
        &self,
        balls: &BallPair,
        inputs: &Inputs,
        n: usize,
        settings: &SolverSettings,
    ) -> Result<PairRows, (usize, Error)> {
        let one = |i: usize| self.row(balls, inputs, i, settings).map_err(|e| (i, e));
        let rows: Result<Vec<Row>, _> = if n >= PARALLEL_ROWS {
            (0..n).into_par_iter().map(one).collect()
        } else {
            (0..n).map(one).collect()
        };
        Ok(PairRows { rows: rows? })
    }
}

impl PairRows {
    /// The result dict: "va", "wa", "vb", "wb" ((N, 3), or (3,) for one collision),
    /// "impulse", "tangential_impulse", "contact_time", "rebound_angle" ((N,), or numpy
    /// scalars).
    pub(crate) fn into_dict(self, py: Python<'_>, single: bool) -> PyResult<Bound<'_, PyDict>> {
        use numpy::{PyArray1, PyArrayMethods};
        let d = PyDict::new(py);
        let n = self.rows.len();
        let vectors = [
            intern!(py, "va"),
            intern!(py, "wa"),
            intern!(py, "vb"),
            intern!(py, "wb"),
        ];
        let scalars = [
            intern!(py, "impulse"),
            intern!(py, "tangential_impulse"),
            intern!(py, "contact_time"),
            intern!(py, "rebound_angle"),
        ];
        for (k, key) in vectors.into_iter().enumerate() {
            if single {
                let r = &self.rows[0];
                d.set_item(key, vector(py, [r[3 * k], r[3 * k + 1], r[3 * k + 2]])?)?;
            } else {
                let flat: Vec<f64> = self
                    .rows
                    .iter()
                    .flat_map(|r| r[3 * k..3 * k + 3].iter().copied())
                    .collect();
                d.set_item(key, PyArray1::from_vec(py, flat).reshape([n, 3])?)?;
            }
        }
        for (k, key) in scalars.into_iter().enumerate() {
            if single {
                d.set_item(key, float64(py, self.rows[0][12 + k])?)?;
            } else {
                let column: Vec<f64> = self.rows.iter().map(|r| r[12 + k]).collect();
                d.set_item(key, PyArray1::from_vec(py, column))?;
            }
        }
        Ok(d)
    }
}

/// One output row: va, wa, vb, wb (12 components) and the four scalars.
fn out_row(vectors: [Vector3<f64>; 4], scalars: [f64; 4]) -> [f64; 16] {
    let mut row = [0.0; 16];
    for (k, v) in vectors.iter().enumerate() {
        row[3 * k..3 * k + 3].copy_from_slice(v.as_slice());
    }
    row[12..].copy_from_slice(&scalars);
    row
}
