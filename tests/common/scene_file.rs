//! A scene file of `data/scenes/` read with `toml` into the independent references' types
//! (`Balls`, `Law`, `Pair`, each profile's p(t) by its own formula, the cloth of
//! `table`), not through the crate's scene code, and the outcome expected of it: the
//! first-principles resolution, or for speed-dependent mu the closed form of
//! tests/common/hard.rs. Identical balls only (`[balls]`).
#![allow(dead_code)]

use super::table::Cloth;
use super::{resolve, Balls, Expected, Law, Pair, Rule, Table};
use crate::hard;
use billiard_contact::CmState;
use nalgebra::{Matrix3, Vector3};
use std::f64::consts::PI;
use std::path::Path;

/// A profile's reference p(t)/P inverse: scaled time at which p = q P.
pub enum ProfileRef {
    HalfSine,
    Hertz,
    SinePower(f64),
    Rectangle,
    Table(Table),
}

impl ProfileRef {
    /// p(t)/P at s = t / duration.
    pub fn fraction(&self, s: f64) -> f64 {
        match self {
            ProfileRef::HalfSine => super::half_sine_fraction(s),
            ProfileRef::Hertz => hard::hertz_phi(s),
            ProfileRef::SinePower(n) => super::sine_power_fraction(*n, s),
            ProfileRef::Rectangle => s.clamp(0.0, 1.0),
            ProfileRef::Table(t) => t.fraction(s),
        }
    }

    /// p(t)/P and the force in units of P / duration at s = t / duration, the force by each
    /// profile's formula:
    /// half-sine (pi/2) sin(pi s); sin^n(pi s) pi / B((n+1)/2, 1/2); rectangle 1; the table's
    /// interpolant over its area; Hertz from the energy integral of delta'' = -delta^(3/2)
    /// (tests/common/mod.rs, `hertz_f`): with q = p/P, delta' = 1 - 2q and
    /// delta^(5/2) = (5/4) (1 - delta'^2) = (5/4) 4 q (1 - q), the force delta^(3/2) over the
    /// impulse 2 in the scaled time T = 2 delta_max F(1) of the whole contact gives
    /// dq/ds = (T/2) delta^(3/2) = F(1) (5/4) (4 q (1 - q))^(3/5).
    pub fn fraction_and_shape(&self, s: f64) -> (f64, f64) {
        let q = self.fraction(s);
        let shape = match self {
            ProfileRef::HalfSine => PI / 2.0 * (PI * s).sin(),
            ProfileRef::Hertz => super::hertz_half() * 1.25 * (4.0 * q * (1.0 - q)).powf(0.6),
            ProfileRef::SinePower(n) => {
                PI * (PI * s).sin().max(0.0).powf(*n) / super::beta_fn(0.5 * (n + 1.0), 0.5)
            }
            ProfileRef::Rectangle => 1.0,
            ProfileRef::Table(t) => t.shape(s),
        };
        (q, shape)
    }

    pub fn time(&self, q: f64) -> f64 {
        match self {
            ProfileRef::HalfSine => 2.0 / PI * q.sqrt().asin(),
            ProfileRef::Hertz => super::hertz_time(q),
            ProfileRef::SinePower(n) => super::invert(|s| super::sine_power_fraction(*n, s), q),
            ProfileRef::Rectangle => q,
            ProfileRef::Table(t) => t.time(q),
        }
    }
}

/// A scene file as the references read it.
pub struct SceneRef {
    /// The file's name.
    pub name: String,
    pub balls: Balls,
    pub law: Law,
    /// (a, b, c) of mu(S) = a + b exp(-c S) (`law.mu` is then 0).
    pub speed_law: Option<(f64, f64, f64)>,
    /// The cloth, with the table effect.
    pub cloth: Option<Cloth>,
    pub pair: Pair,
    /// Lab positions of A and B (zero for centre-of-mass scenes).
    pub positions: [Vector3<f64>; 2],
    pub lab: bool,
    pub up: Vector3<f64>,
    pub duration: f64,
    pub profile: ProfileRef,
    /// Hertz's contact of the balls' material, when the scene gives it (the duration is then
    /// its contact time).
    pub hertz: Option<super::HertzRef>,
}

fn vec3(v: &toml::Value) -> Vector3<f64> {
    let a = v.as_array().expect("an array of 3 numbers");
    let num = |x: &toml::Value| x.as_float().or(x.as_integer().map(|i| i as f64)).unwrap();
    Vector3::new(num(&a[0]), num(&a[1]), num(&a[2]))
}

fn num(v: Option<&toml::Value>) -> Option<f64> {
    v.and_then(|x| x.as_float().or(x.as_integer().map(|i| i as f64)))
}

pub fn read_scene(path: &Path) -> SceneRef {
    let text = std::fs::read_to_string(path).unwrap();
    let t: toml::Table = text.parse().unwrap();
    let balls = &t["balls"];
    let balls = Balls {
        m: num(balls.get("mass")).unwrap(),
        r: num(balls.get("radius")).unwrap(),
        alpha: num(balls.get("alpha")).unwrap_or(0.4),
    };
    let contact = &t["contact"];
    let mu = num(contact.get("mu"));
    let speed_law = contact.get("mu").and_then(|m| m.as_table()).map(|m| {
        assert_eq!(m["model"].as_str(), Some("speed-dependent"));
        assert!(m.get("evaluate").is_none(), "mu held at the initial slip");
        let k = |key: &str| num(m.get(key)).unwrap();
        (k("a"), k("b"), k("c"))
    });
    let rule = match (num(contact.get("restitution")), num(contact.get("impulse"))) {
        (Some(e), None) => Rule::Restitution(e),
        (None, Some(p)) => Rule::Explicit(p),
        (None, None) => Rule::Restitution(1.0),
        _ => panic!("both restitution and impulse"),
    };
    let effects = t.get("effects");
    let flag = |k: &str| effects.and_then(|e| e.get(k)).and_then(|v| v.as_bool());
    let mut law = Law::new(mu.unwrap_or(0.0), rule);
    law.friction = flag("friction").unwrap_or(true);
    law.stick = flag("stick").unwrap_or(true);
    let prof = &contact["profile"];
    let shape = prof["shape"].as_str().unwrap();
    let mut duration = num(prof.get("duration"));
    let profile = match shape {
        "half-sine" => ProfileRef::HalfSine,
        "hertz" => ProfileRef::Hertz,
        "sine-power" => ProfileRef::SinePower(num(prof.get("exponent")).unwrap_or(1.5)),
        "rectangle" => ProfileRef::Rectangle,
        "tabulated" => {
            let file = path.parent().unwrap().join(prof["file"].as_str().unwrap());
            if duration.is_none() {
                // The table's own span: its last time.
                let text = std::fs::read_to_string(&file).unwrap();
                let last = text.lines().rev().find(|l| !l.trim().is_empty()).unwrap();
                duration = Some(last.split(',').next().unwrap().trim().parse().unwrap());
            }
            ProfileRef::Table(Table::read(&file))
        }
        other => panic!("unknown shape {other}"),
    };
    let inc = &t["incoming"];
    let (pair, lab, up, positions) = if let Some(cm) = inc.get("cm") {
        let z = toml::Value::Array(vec![0.0.into(), 0.0.into(), 0.0.into()]);
        (
            Pair::cm(
                vec3(&cm["u"]),
                vec3(cm.get("omega_a").unwrap_or(&z)),
                vec3(cm.get("omega_b").unwrap_or(&z)),
            ),
            false,
            Vector3::z(),
            [Vector3::zeros(); 2],
        )
    } else {
        let lab = &inc["lab"];
        let ball = |k: &str| {
            let b = &lab[k];
            let spin = b.get("spin").map(vec3).unwrap_or_else(Vector3::zeros);
            (vec3(&b["position"]), vec3(&b["velocity"]), spin)
        };
        let (pa, va, wa) = ball("a");
        let (pb, vb, wb) = ball("b");
        let up = lab.get("up").map(vec3).unwrap_or_else(Vector3::z);
        (
            Pair {
                n: (pb - pa).normalize(),
                va,
                wa,
                vb,
                wb,
            },
            true,
            up.normalize(),
            [pa, pb],
        )
    };
    // The balls' material instead of a duration: Hertz's contact time at v = 2 U(0).
    let material = (
        num(t["balls"].get("youngs_modulus")),
        num(t["balls"].get("poisson_ratio")),
    );
    let hertz = match material {
        (Some(e), Some(nu)) => Some(super::hertz_identical(
            balls.m,
            balls.r,
            e,
            nu,
            2.0 * pair.u0(),
        )),
        _ => None,
    };
    // The cloth's parameters with the defaults of docs/formats.md#cloth-parameters.
    let cloth = flag("table").unwrap_or(false).then(|| {
        let c = t.get("table");
        let get = |k: &str, default: f64| num(c.and_then(|c| c.get(k))).unwrap_or(default);
        assert!(
            c.and_then(|c| c.get("height")).is_none(),
            "the cloth r below"
        );
        Cloth {
            mu: get("mu", 0.2),
            restitution: get("restitution", 0.0),
            g: get("g", 9.81),
            rolling_resistance: get("rolling_resistance", 0.0),
            spin_decay: get("spin_decay", 0.0),
            up,
        }
    });
    SceneRef {
        name: path.file_name().unwrap().to_string_lossy().into_owned(),
        balls,
        law,
        speed_law,
        cloth,
        pair,
        positions,
        lab,
        up,
        duration: duration.or(hertz.map(|h| h.duration)).unwrap(),
        profile,
        hertz,
    }
}

impl SceneRef {
    /// The centre-of-mass basis (docs/model.md#the-lab-frame): e_x the line of centres, e_z = `up` without its
    /// e_x part, e_y = e_z x e_x (columns, lab coordinates).
    pub fn basis(&self) -> Matrix3<f64> {
        let ex = self.pair.n;
        let ez = (self.up - ex * self.up.dot(&ex)).normalize();
        Matrix3::from_columns(&[ex, ez.cross(&ex), ez])
    }

    /// Ball A's velocity and both spins in the centre-of-mass frame.
    pub fn to_cm(&self, p: &Pair) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let rt = self.basis().transpose();
        (rt * (0.5 * (p.va - p.vb)), rt * p.wa, rt * p.wb)
    }

    /// The closed form of speed-dependent friction (tests/common/hard.rs: eqs 24-35 with
    /// dS/dp = -k mu(S)) for this scene's incoming state, when it has such friction.
    pub fn speed_dependent(&self) -> Option<hard::Exact> {
        let abc = self.speed_law?;
        let b = &self.balls;
        let (u, wa, wb) = self.to_cm(&self.pair);
        let (e, impulse) = match self.law.rule {
            Rule::Restitution(e) => (e, None),
            Rule::Explicit(p) => (0.0, Some(p)),
        };
        assert!(self.law.friction && self.law.stick);
        let incoming = CmState::new(u, wa, wb);
        Some(hard::Exact::speed_dependent(
            b.m, b.r, b.alpha, abc, e, impulse, incoming,
        ))
    }

    /// The expected outcome: the first-principles resolution, or for speed-dependent mu the
    /// closed form taken back to the scene's frame (A moves with V + u, B with V - u, V the
    /// centre of mass's velocity; spins rotate as vectors).
    pub fn expected(&self) -> Expected {
        let Some(x) = self.speed_dependent() else {
            return resolve(&self.balls, &self.law, &self.pair);
        };
        let out = x.out();
        let basis = self.basis();
        let centre = 0.5 * (self.pair.va + self.pair.vb);
        let s = out.state;
        Expected {
            collision: x.p > 0.0,
            impulse: x.p,
            s0: x.s0,
            tangential: out.j,
            s_out: out.slip,
            sticks: x.sticks(),
            p_stick: (x.p > 0.0 && x.s0 > 0.0).then_some(x.p_stick),
            heat: out.heat,
            heat_sliding: out.heat_sliding,
            out: Pair {
                n: self.pair.n,
                va: centre + basis * s.u_cm,
                vb: centre - basis * s.u_cm,
                wa: basis * s.omega_a,
                wb: basis * s.omega_b,
            },
        }
    }

    /// The slip S(p) after a normal impulse p: S(0) - k mu p for constant mu (k =
    /// 2 (1 + 1/alpha) / m, eqs 25-33 along the slip), stopped at 0 by the stick rule; the
    /// closed form's S(p) for mu(S).
    pub fn slip_at(&self, want: &Expected, p: f64) -> f64 {
        if let Some(x) = self.speed_dependent() {
            return x.at(p).slip;
        }
        if !self.law.friction {
            return want.s0;
        }
        let b = &self.balls;
        let k = 2.0 * (1.0 + 1.0 / b.alpha) / b.m;
        let s = want.s0 - k * self.law.mu * p;
        if self.law.stick {
            s.max(0.0)
        } else {
            s
        }
    }
}
