//! A simulation: the bodies, the rock they stand on, the joints between them, what every pair
//! of surfaces carries, and how it is run — checked once when it is built.

use super::base::Base;
use super::body::Body;
use super::error::ModelError;
use super::foundation::Foundation;
use super::friction::Friction;
use super::joint::{Joint, check_joints};
use super::settings::{Contacts, DynamicsModel, RunSettings};
use super::strength::Strengths;
use crate::geometry::Site;
use std::sync::Arc;

/// What a route is computed from: the bodies (a one-body scene is a one-element list), the
/// foundation (the rock and its shaking), the joints between bodies, what every pair of
/// surfaces carries in shear, and the run settings — every part present and checked, and their
/// combination one the dynamics can run. Built by [`Simulation::builder`] from typed parts, or
/// from a scene file by the scene reader; its fields are private, so that running one checks
/// nothing again.
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    name: String,
    /// At least one.
    bodies: Vec<Body>,
    foundation: Foundation,
    joints: Vec<Joint>,
    strengths: Strengths,
    settings: RunSettings,
}

/// The parts of a [`Simulation`], set one by one and checked together by
/// [`SimulationBuilder::build`].
///
/// ```
/// use slideroute::{Block, Body, DynamicsModel, Foundation, Friction, Loads};
/// use slideroute::{RunSettings, Simulation};
/// # let site = slideroute::Scene::default_scene().site().clone();
/// let body = Body::builder(site.clone())
///     .block(Block::plate(1.0e6, 1.1e7))
///     .loads(Loads::plain(8.0e6, 1.0, 9.81))
///     .build()?;
/// let sim = Simulation::builder()
///     .name("my monolith")
///     .body(body)
///     .foundation(Foundation::under(&site))
///     .friction(Friction::coulomb(0.4))
///     .settings(RunSettings::new(DynamicsModel::RigidBody, 1e-3, 2.0))
///     .build()?;
/// let route = slideroute::simulate(&sim);
/// # assert!(route.travel_m > 0.0);
/// # Ok::<(), slideroute::ModelError>(())
/// ```
#[derive(Debug, Clone, Default)]
#[must_use]
pub struct SimulationBuilder {
    name: Option<String>,
    bodies: Vec<Body>,
    foundation: Option<Foundation>,
    joints: Vec<Joint>,
    strengths: Option<Strengths>,
    settings: Option<RunSettings>,
}

impl Simulation {
    /// A builder named "unnamed", with no body, no joint and no cohesion until told.
    pub fn builder() -> SimulationBuilder {
        SimulationBuilder::default()
    }

    /// Its name (the scene's), written into routes.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The bodies, in their order (at least one).
    pub fn bodies(&self) -> &[Body] {
        &self.bodies
    }

    /// The first body: the one the paper's dynamics and the three-point frame follow (they
    /// take a simulation of one body only).
    pub fn first_body(&self) -> &Body {
        // `build` refuses a simulation without a body, and nothing else makes one.
        &self.bodies[0]
    }

    /// The rock the bodies stand on, and its shaking.
    pub fn foundation(&self) -> &Foundation {
        &self.foundation
    }

    /// The joints between bodies.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// What every pair of surfaces carries: each rock face's criterion and cohesion, and each
    /// joint's.
    pub fn strengths(&self) -> &Strengths {
        &self.strengths
    }

    /// The run settings: mode, dynamics, integrator, dt, t_end, stride.
    pub fn settings(&self) -> &RunSettings {
        &self.settings
    }

    /// The same simulation under one polarity of its record: reversed (every acceleration
    /// negated) or as it is, run once.
    pub fn one_polarity(&self, reversed: bool) -> Result<Simulation, ModelError> {
        Ok(Simulation {
            foundation: self.foundation.one_polarity(reversed)?,
            ..self.clone()
        })
    }
}

impl SimulationBuilder {
    /// Its name, written into routes.
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.name = Some(name.into());
        self
    }

    /// One more body (the first is body 0).
    pub fn body(mut self, body: Body) -> Self {
        self.bodies.push(body);
        self
    }

    /// The rock the bodies stand on, and its shaking.
    pub fn foundation(mut self, foundation: Foundation) -> Self {
        self.foundation = Some(foundation);
        self
    }

    /// One more joint between two bodies.
    pub fn joint(mut self, joint: Joint) -> Self {
        self.joints.push(joint);
        self
    }

    /// The friction criterion of every face without its own (the default of
    /// [`SimulationBuilder::strengths`], or of no cohesion and no face of its own).
    pub fn friction(mut self, friction: Friction) -> Self {
        self.strengths = Some(match self.strengths {
            Some(mut s) => {
                s.friction = friction;
                s
            }
            None => Strengths::new(friction),
        });
        self
    }

    /// What the rock's faces carry: the default criterion and cohesion, and faces with their
    /// own (replacing a criterion given before by [`SimulationBuilder::friction`]).
    pub fn strengths(mut self, strengths: Strengths) -> Self {
        self.strengths = Some(strengths);
        self
    }

    /// How the route is run.
    pub fn settings(mut self, settings: RunSettings) -> Self {
        self.settings = Some(settings);
        self
    }

    /// The simulation, or the first fault: a part missing, a value out of its range, or parts
    /// that do not go together.
    pub fn build(self) -> Result<Simulation, ModelError> {
        let missing = |part: &str, key: &str| {
            ModelError::new(
                key,
                format!("missing: a simulation needs {part} (SimulationBuilder::{key})"),
            )
        };
        if self.bodies.is_empty() {
            return Err(missing("a body", "body"));
        }
        let foundation = self
            .foundation
            .ok_or_else(|| missing("the rock its bodies stand on", "foundation"))?;
        let strengths = self
            .strengths
            .ok_or_else(|| missing("a friction criterion", "friction"))?;
        let settings = self
            .settings
            .ok_or_else(|| missing("run settings", "settings"))?;
        check_rock(&self.bodies, &foundation)?;
        strengths.check(foundation.face_count())?;
        settings.check()?;
        settings.check_runnable()?;
        let count = self.bodies.len();
        check_one_body(&settings, count)?;
        check_rigid_only(
            settings.dynamics,
            foundation.record().is_some(),
            strengths.has_cohesion(),
        )?;
        let anchored = self.bodies.iter().any(|b| !b.tendons().is_empty());
        check_anchored(&settings, anchored)?;
        let bodies = match settings.contacts {
            Contacts::Frame => self.bodies.into_iter().map(|b| b.with_base(None)).collect(),
            Contacts::Base => self
                .bodies
                .into_iter()
                .map(|b| {
                    let base = match b.base() {
                        Some(base) => base.clone(),
                        None => Base::around(b.site().contacts(), b.loads().cm_height)?,
                    };
                    Ok(b.with_base(Some(base)))
                })
                .collect::<Result<_, ModelError>>()?,
        };
        check_joints(&self.joints, count)?;
        let pairs = self
            .joints
            .iter()
            .map(|j| (j.bodies, j.strength()))
            .collect();
        Ok(Simulation {
            name: self.name.unwrap_or_else(|| "unnamed".to_string()),
            bodies,
            foundation,
            strengths: strengths.with_joints(pairs),
            joints: self.joints,
            settings,
        })
    }
}

/// The paper's dynamics and the three-point frame (`contacts = "frame"`, whatever the dynamics)
/// follow one body; several are taken only by the body model (`contacts = "base"`, which the
/// rigid body's dynamics alone runs).
fn check_one_body(settings: &RunSettings, bodies: usize) -> Result<(), ModelError> {
    if bodies > 1 && settings.contacts == Contacts::Frame {
        return Err(ModelError::new(
            "solver.contacts",
            format!(
                "{bodies} bodies: the paper's dynamics and the three-point frame follow one \
                 body; several bodies take contacts = \"base\""
            ),
        ));
    }
    Ok(())
}

/// Each body whose frame stands on a ground of faces or a surface stands on the foundation's:
/// the frame's faces are the rock's, numbered as the strengths name them.
fn check_rock(bodies: &[Body], foundation: &Foundation) -> Result<(), ModelError> {
    let rock = foundation.ground();
    let other = bodies.iter().position(|b| {
        b.site()
            .shared_ground()
            .is_some_and(|g| !(Arc::ptr_eq(g, rock) || **g == **rock))
    });
    match other {
        Some(k) => Err(ModelError::new(
            "foundation",
            format!(
                "body {k}'s three-point frame stands on another rock than the foundation's \
                 (Foundation::under its site gives the one it stands on)"
            ),
        )),
        None => Ok(()),
    }
}

/// Anchors are followed by the rigid body, on its three contacts or its base (the tendon's
/// pull is a load on the body at its pose, `derivations/11-dam-loads.md` §10); the paper's
/// dynamics takes none.
pub(crate) fn check_anchored(settings: &RunSettings, anchored: bool) -> Result<(), ModelError> {
    if anchored
        && settings.dynamics != DynamicsModel::RigidBody
        && settings.contacts == Contacts::Frame
    {
        return Err(ModelError::new(
            "anchor",
            "anchors are followed by the rigid body's dynamics: they need solver.dynamics = \
             \"rigid-body\"",
        ));
    }
    Ok(())
}

/// How many faces the ground under `site` has: the paper's three planes, or a ground's faces.
pub(crate) fn face_count(site: &Site) -> usize {
    site.ground().map_or(3, |(g, _)| g.faces().len())
}

/// What only the rigid body's dynamics follows: a ground-motion record (it moves the foundation
/// under a rigid body) and cohesion (it holds a block at rest and breaks when it slides, which
/// the rigid body's static check follows).
pub(crate) fn check_rigid_only(
    dynamics: DynamicsModel,
    shaken: bool,
    cohesion: bool,
) -> Result<(), ModelError> {
    let rigid_only = [
        (
            shaken,
            "seismic.record",
            "a ground-motion record moves the foundation under a rigid body",
        ),
        (
            cohesion,
            "friction.cohesion_pa",
            "cohesion holds a block at rest and breaks when it slides, which the rigid body's \
             static check follows",
        ),
    ];
    match rigid_only.iter().find(|(given, _, _)| *given) {
        Some((_, key, what)) if dynamics != DynamicsModel::RigidBody => Err(ModelError::new(
            *key,
            format!("{what}: it needs solver.dynamics = \"rigid-body\""),
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Block, BodyBuilder, Integrator, Joint, Loads, Mode, Record};

    fn site() -> Site {
        crate::scene::Scene::default_scene().site().clone()
    }

    fn body() -> BodyBuilder {
        Body::builder(site())
            .block(Block::plate(1e6, 1.1e7))
            .loads(Loads::plain(8e6, 1.0, 9.81))
    }

    fn builder() -> SimulationBuilder {
        Simulation::builder()
            .body(body().build().unwrap())
            .foundation(Foundation::under(&site()))
            .friction(Friction::coulomb(0.4))
            .settings(RunSettings::new(DynamicsModel::RigidBody, 1e-3, 1.0))
    }

    fn on_base() -> RunSettings {
        RunSettings::new(DynamicsModel::RigidBody, 1e-3, 1.0).with_contacts(Contacts::Base)
    }

    #[test]
    fn a_simulation_built_from_parts_is_the_one_its_scene_file_gives() {
        let scene = crate::scene::Scene::default_scene();
        let from_file = scene.simulation().unwrap();
        let settings = RunSettings::new(DynamicsModel::RigidBody, 1e-3, 20.0);
        let block = Block::plate(1e6, 11e6).with_axes(5.5e6, 5.5e6, 0.0);
        let built = Simulation::builder()
            .name("paper-like")
            .body(body().name("block").block(block).build().unwrap())
            .foundation(Foundation::under(&site()))
            .friction(Friction::coulomb(0.4))
            .settings(settings)
            .build()
            .unwrap();
        assert_eq!(built, from_file);
        assert_eq!(built.bodies().len(), 1);
    }

    #[test]
    fn a_missing_part_or_parts_that_do_not_go_together_are_refused_naming_the_key() {
        assert_eq!(Simulation::builder().build().unwrap_err().key, "body");
        let e = Simulation::builder()
            .body(body().build().unwrap())
            .build()
            .unwrap_err();
        assert_eq!(e.key, "foundation");
        let e = Simulation::builder()
            .body(body().build().unwrap())
            .foundation(Foundation::under(&site()))
            .build()
            .unwrap_err();
        assert_eq!(e.key, "friction");
        let small =
            RunSettings::new(DynamicsModel::RigidBody, 1e-3, 1.0).with_mode(Mode::SmallAngle);
        assert_eq!(
            builder().settings(small).build().unwrap_err().key,
            "solver.mode"
        );
        let paper = RunSettings::new(DynamicsModel::Paper, 1e-3, 1.0);
        assert_eq!(paper.integrator, Integrator::Paper);
        let record = Record::new(vec![(0.0, [0.0; 3]), (1.0, [0.1, 0.0, 0.0])]).unwrap();
        let e = builder()
            .settings(paper)
            .foundation(Foundation::under(&site()).shaken(record))
            .build()
            .unwrap_err();
        assert_eq!(e.key, "seismic.record");
        let e = builder()
            .friction(Friction::coulomb(f64::NAN))
            .build()
            .unwrap_err();
        assert_eq!(e.key, "friction.mu_k");
        // A base takes every criterion, and cohesion (held until the block first slides).
        let barton = Friction::barton_choubey(10.0, 50e6, 0.5, 2.0);
        assert!(
            builder()
                .friction(barton)
                .settings(on_base())
                .build()
                .is_ok()
        );
        let mut bonded = Strengths::new(barton);
        bonded.cohesion_pa = 2e5;
        let sim = builder()
            .strengths(bonded.clone())
            .settings(on_base())
            .build()
            .unwrap();
        assert_eq!(sim.strengths().cohesion_pa, 2e5);
        // Cohesion is still refused under the paper's dynamics on the frame, whose start test
        // knows none.
        let e = builder()
            .strengths(bonded)
            .settings(RunSettings::new(DynamicsModel::Paper, 1e-3, 1.0))
            .build()
            .unwrap_err();
        assert_eq!(e.key, "friction.cohesion_pa");
    }

    #[test]
    fn a_waters_moment_a_million_times_the_weights_is_refused_naming_the_eccentricity() {
        // Before, c = 1e12 m was taken, and its route of 0.2 s took a minute of sweeps.
        for c in [1e12, -9.2e18, f64::MAX] {
            let e = body()
                .loads(Loads::plain(8e6, c, 9.81))
                .build()
                .unwrap_err();
            assert_eq!(e.key, "loads.eccentricity_m");
            assert!(e.reason.contains("moment"), "{}", e.reason);
            assert!(!e.reason.contains("inf"), "{}", e.reason);
        }
        // F c = 8e12 N·m against 1e6 m g L ≈ 1e14 N·m: taken. No water, any c.
        assert!(body().loads(Loads::plain(8e6, 1e6, 9.81)).build().is_ok());
        assert!(body().loads(Loads::plain(0.0, 1e300, 9.81)).build().is_ok());
    }

    #[test]
    fn two_bodies_on_their_bases_make_a_simulation_with_a_joint_between_them() {
        let sim = builder()
            .body(body().name("right").build().unwrap())
            .joint(Joint::new([0, 1], Friction::coulomb(0.7)).with_cohesion(2e5))
            .settings(on_base())
            .build()
            .unwrap();
        assert_eq!(sim.bodies().len(), 2);
        assert_eq!(sim.bodies()[1].name(), "right");
        // Each body without a base of its own stands on its frame's bounding rectangle.
        for b in sim.bodies() {
            let base = b.base().unwrap();
            assert_eq!(base.depth(), b.loads().cm_height);
        }
        // The joint's strength is the pair's; a rock face against a body, the rock's.
        use crate::model::Surface::{Body as B, Rock};
        let joint = sim.strengths().between(B(1), B(0));
        assert_eq!(joint.criterion, Friction::coulomb(0.7));
        assert_eq!(joint.cohesion_pa, 2e5);
        assert_eq!(
            sim.strengths().between(Rock(1), B(1)).criterion,
            Friction::coulomb(0.4)
        );
        // A joint naming a body the simulation does not have is refused by its key.
        let e = builder()
            .body(body().build().unwrap())
            .joint(Joint::new([0, 2], Friction::coulomb(0.7)))
            .settings(on_base())
            .build()
            .unwrap_err();
        assert_eq!(e.key, "joint[0].bodies");
    }

    #[test]
    fn a_frame_on_another_rock_than_the_foundations_is_refused() {
        use crate::geometry::{Ground, Plane};
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-like-faces.toml");
        let scene = crate::scene::Scene::from_file(&path).unwrap();
        let site = scene.site().clone();
        let on = |foundation: Foundation| {
            Simulation::builder()
                .body(
                    Body::builder(site.clone())
                        .block(Block::plate(1e6, 1.1e7))
                        .loads(Loads::plain(8e6, 1.0, 9.81))
                        .build()
                        .unwrap(),
                )
                .foundation(foundation)
                .friction(Friction::coulomb(0.4))
                .settings(RunSettings::new(DynamicsModel::RigidBody, 1e-3, 1.0))
                .build()
        };
        let level = Plane::through(nalgebra::Vector3::y(), nalgebra::Vector3::zeros());
        let elsewhere = Foundation::new(Arc::new(Ground::planes(vec![level])));
        assert_eq!(on(elsewhere).unwrap_err().key, "foundation");
        assert!(on(Foundation::under(&site)).is_ok());
    }

    #[test]
    fn several_bodies_are_refused_by_the_dynamics_that_follow_one() {
        let two = || builder().body(body().build().unwrap());
        for settings in [
            RunSettings::new(DynamicsModel::RigidBody, 1e-3, 1.0),
            RunSettings::new(DynamicsModel::Paper, 1e-3, 1.0),
        ] {
            let e = two().settings(settings).build().unwrap_err();
            assert_eq!(e.key, "solver.contacts");
            assert!(e.reason.contains("follow one body"), "{e}");
        }
        assert!(two().settings(on_base()).build().is_ok());
    }
}
