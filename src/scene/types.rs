//! A validated scene and its incoming state: what the scene file, the builder and the
//! command line's options make, and what a run reads.

use crate::base::error::Error;
use crate::base::settings::SolverSettings;
use crate::model::collision::Collision;
use crate::model::contact_law::ContactLaw;
use crate::model::effects::Effects;
use crate::model::frame::{Frame, LabScene};
use crate::model::material::{HertzContact, Material};
use crate::model::params::{BallPair, Contact};
use crate::model::state::CmState;
use crate::profile::spec::Profile;
use crate::scene::overrides::SolverOverrides;
use crate::solve::plane::{equivalent_state, PlaneCollision};
use crate::table_phase::cloth::Table;
use crate::table_phase::params::{TableParams, TableSize};
use nalgebra::Vector3;
use serde::Deserialize;
use std::path::PathBuf;

/// The incoming state as a scene gives it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Incoming {
    /// Directly in the paper's centre-of-mass frame.
    Cm(CmState),
    /// Both balls in the lab frame.
    Lab(LabScene),
    /// One ball meeting a plane (`[plane]` and `[incoming.plane]`, docs/plane.md): the ball
    /// is `[balls]`, the run is that of its equivalent pair.
    Plane(PlaneIncoming),
}

/// A ball meeting a plane, as a scene gives it (lab axes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneIncoming {
    /// Unit normal of the plane, out of it towards the ball (`plane.normal`).
    pub normal: Vector3<f64>,
    /// The plane's material (`plane.youngs_modulus`, `plane.poisson_ratio`); `None`: rigid.
    pub material: Option<Material>,
    /// Velocity of the ball's centre (m/s).
    pub velocity: Vector3<f64>,
    /// Spin of the ball (rad/s).
    pub spin: Vector3<f64>,
}

impl PlaneIncoming {
    /// The normal approach speed -v.n (m/s): positive when the ball approaches.
    pub fn approach_speed(&self) -> f64 {
        -self.velocity.dot(&self.normal)
    }
}

/// A lab scene with the frame between it and the paper's centre-of-mass frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LabFrame<'a> {
    /// The change of frame.
    pub frame: Frame,
    /// The lab scene.
    pub lab: &'a LabScene,
}

impl Incoming {
    /// The paper's centre-of-mass state of the balls `balls`; for lab input also the lab
    /// scene with its frame (the balls must touch, see [`Frame::of_pair`]).
    pub fn to_cm(&self, balls: &BallPair) -> Result<(CmState, Option<LabFrame<'_>>), Error> {
        Ok(match self {
            Incoming::Cm(cm) => (*cm, None),
            Incoming::Lab(lab) => {
                let frame = Frame::of_pair(lab, balls)?;
                (frame.to_cm(lab), Some(LabFrame { frame, lab }))
            }
            Incoming::Plane(p) => (equivalent_state(&p.normal, &p.velocity, &p.spin), None),
        })
    }
}

/// The tangential law of a scene's contact (`[contact] tangential`, docs/tangential.md#scenes).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TangentialLaw {
    /// The paper's rigid contact: the stick rule (eqs 14-35).
    #[default]
    Rigid,
    /// Mindlin's elastic tangential spring under Coulomb's cap, with Hertz's normal force of
    /// the materials (the compliant kernel, docs/tangential.md).
    Mindlin,
}

impl TangentialLaw {
    /// The name a scene file and the report give it.
    pub fn name(&self) -> &'static str {
        match self {
            TangentialLaw::Rigid => "rigid",
            TangentialLaw::Mindlin => "mindlin",
        }
    }
}

/// A validated scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    /// Name shown in reports.
    pub name: String,
    /// The balls: `[balls]` (identical; `Ball::into()` makes the pair) or `[balls.a]` and
    /// `[balls.b]`.
    pub balls: BallPair,
    /// The balls' material (`balls.youngs_modulus`, `balls.poisson_ratio`, the same for
    /// both balls), when given: the profile's duration then follows from it
    /// ([`Scene::hertz`]).
    pub material: Option<Material>,
    /// Friction and impulse rule.
    pub contact: Contact,
    /// Normal-force profile. With a contact law, the elastic Hertz pulse of the law's
    /// stiffness at the approach speed (the law's time unit; the law decides the force).
    pub profile: Profile,
    /// The contact law (`[contact.law]`), when the force comes from the compression.
    pub law: Option<ContactLaw>,
    /// The tangential law (`contact.tangential`, default rigid). `Mindlin` comes with a
    /// contact law, the balls' material and a constant mu (checked when built).
    pub tangential: TangentialLaw,
    /// Incoming state.
    pub incoming: Incoming,
    /// Solver settings (`[solver]`, defaults when absent).
    pub solver: SolverSettings,
    /// The `[solver]` section as written (what it overrides; empty when absent), for the
    /// warnings about keys the scene does not use.
    pub solver_given: SolverOverrides,
    /// Effects (`[effects]`).
    pub effects: Effects,
    /// The file it was read from (`None` for the built-in scene).
    pub source: Option<PathBuf>,
    /// The cloth (`[table]`) as given; `None` when the section is absent (defaults apply
    /// when the effect `table` is on).
    pub table: Option<TableParams>,
    /// The playing area between the cushions (`[table] length, width`), drawn on the top
    /// view; `None` when not given.
    pub table_size: Option<TableSize>,
}

impl Scene {
    /// The cloth under the balls when the effect `table` is on (`None` when off): needs a
    /// lab scene whose line of centres is horizontal, both centres r above the cloth.
    pub fn cloth(&self) -> Result<Option<Table>, Error> {
        match &self.incoming {
            Incoming::Lab(lab) => self.cloth_under(lab),
            Incoming::Cm(_) | Incoming::Plane(_) if self.effects.table => {
                Err(table_needs_lab_scene())
            }
            Incoming::Cm(_) | Incoming::Plane(_) => Ok(None),
        }
    }

    /// The cloth under the balls of the lab scene `lab` when the effect `table` is on
    /// (`None` when off).
    pub fn cloth_under(&self, lab: &LabScene) -> Result<Option<Table>, Error> {
        if !self.effects.table {
            return Ok(None);
        }
        Table::new(
            self.table.unwrap_or_default(),
            lab.up,
            [lab.a.position, lab.b.position],
            [self.balls.a.radius(), self.balls.b.radius()],
        )
        .map(Some)
    }

    /// The collision in the centre-of-mass frame; for lab scenes also the frame and the
    /// lab scene.
    pub fn collision(&self) -> Result<(Collision, Option<LabFrame<'_>>), Error> {
        if let Some(plane) = self.plane()? {
            return Ok((*plane.equivalent(), None));
        }
        let (cm, lab) = self.incoming.to_cm(&self.balls)?;
        Ok((
            Collision::new(self.balls, self.contact, self.effects, cm)?,
            lab,
        ))
    }

    /// Hertz's contact of the balls' material at the scene's approach speed, when the scene
    /// gives the material for a profile (`None` otherwise, and with a contact law): the profile's duration is its contact time.
    pub fn hertz(&self) -> Result<Option<HertzContact>, Error> {
        let (Some(material), None) = (&self.material, &self.law) else {
            return Ok(None);
        };
        if let Incoming::Plane(p) = &self.incoming {
            let ball = &self.balls.a;
            return HertzContact::sphere_plane(
                ball,
                material,
                p.material.as_ref(),
                p.approach_speed(),
            )
            .map(Some);
        }
        let (c, _) = self.collision()?;
        HertzContact::of_pair(&self.balls, material, c.incoming.u_cm.x).map(Some)
    }

    /// The ball meeting the plane, for a plane scene (`None` for two balls).
    pub fn plane(&self) -> Result<Option<PlaneCollision>, Error> {
        let Incoming::Plane(p) = &self.incoming else {
            return Ok(None);
        };
        PlaneCollision::with_effects(
            self.balls.a,
            self.contact,
            self.effects,
            p.normal,
            p.velocity,
            p.spin,
        )
        .map(Some)
    }
}

/// The effect `table` in a centre-of-mass scene.
pub(crate) fn table_needs_lab_scene() -> Error {
    Error::invalid(
        "effects.table",
        true,
        "a scene with [incoming.lab]: the table needs the balls' positions and `up` \
         (the centre-of-mass frame has no cloth)",
    )
}
