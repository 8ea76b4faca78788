//! A simulation: the physical model and how it is run, checked once when it is built.

use super::anchor::{RockAnchor, Tendon};
use super::base::Base;
use super::block::Block;
use super::error::ModelError;
use super::friction::{Friction, Strength, Strengths};
use super::initial::Initial;
use super::loads::Loads;
use super::monolith::Monolith;
use super::record::Record;
use super::settings::{Contacts, DynamicsModel, RunSettings};
use crate::geometry::{LocalFrame, Site};
use nalgebra::Vector3;
use std::sync::Arc;

/// What a route is computed from: the site (the contacts and the ground under them), the
/// block, its loads, what the faces carry in shear, the motion at the start, the ground's
/// shaking, and the run settings — every part present and checked, and their combination one
/// the dynamics can run. Built by [`Simulation::builder`] from typed parts, or from a scene
/// file by the scene reader; its fields are private, so that running one checks nothing again.
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    name: String,
    site: Site,
    block: Block,
    loads: Loads,
    friction: Friction,
    strengths: Strengths,
    settings: RunSettings,
    initial: Initial,
    record: Option<Arc<Record>>,
    /// The record run as it is and reversed (`seismic.polarity = "both"`).
    both_polarities: bool,
    /// The base the block touches the ground with (`contacts = "base"`).
    base: Option<Base>,
    /// The upward unit normals of the planes under contacts 0, 1, 2, computed once.
    normals: [Vector3<f64>; 3],
    /// `[[anchor]]`: post-tensioned anchors through a monolith into the rock.
    tendons: Vec<Tendon>,
}

/// The parts of a [`Simulation`], set one by one and checked together by
/// [`SimulationBuilder::build`].
///
/// ```
/// use slideroute::{Block, DynamicsModel, Friction, Loads, RunSettings, Simulation, Site};
/// # let site = slideroute::Scene::default_scene().site().clone();
/// let sim = Simulation::builder(site)
///     .name("my monolith")
///     .block(Block::plate(1.0e6, 1.1e7))
///     .loads(Loads::plain(8.0e6, 1.0, 9.81))
///     .friction(Friction::coulomb(0.4))
///     .settings(RunSettings::new(DynamicsModel::RigidBody, 1e-3, 2.0))
///     .build()?;
/// let route = slideroute::simulate(&sim);
/// # assert!(route.travel_m > 0.0);
/// # Ok::<(), slideroute::ModelError>(())
/// ```
#[derive(Debug, Clone)]
#[must_use]
pub struct SimulationBuilder {
    name: String,
    site: Site,
    block: Option<Block>,
    loads: Option<Loads>,
    friction: Option<Friction>,
    strengths: Strengths,
    settings: Option<RunSettings>,
    initial: Initial,
    record: Option<Arc<Record>>,
    both_polarities: bool,
    base: Option<Base>,
    tendons: Vec<Tendon>,
    /// The first anchor that is not on the monolith, found when the anchors were given.
    anchor_fault: Option<ModelError>,
}

impl Simulation {
    /// A builder on `site`, named "unnamed", at rest, with no cohesion and no shaking until told.
    pub fn builder(site: Site) -> SimulationBuilder {
        SimulationBuilder {
            name: "unnamed".to_string(),
            site,
            block: None,
            loads: None,
            friction: None,
            strengths: Strengths::default(),
            settings: None,
            initial: Initial::default(),
            record: None,
            both_polarities: false,
            base: None,
            tendons: Vec::new(),
            anchor_fault: None,
        }
    }

    /// Its name (the scene's), written into routes.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The contacts and the ground under them.
    pub fn site(&self) -> &Site {
        &self.site
    }

    /// The block's mass properties.
    pub fn block(&self) -> &Block {
        &self.block
    }

    /// The loads.
    pub fn loads(&self) -> &Loads {
        &self.loads
    }

    /// The friction criterion of every face without its own.
    pub fn friction(&self) -> &Friction {
        &self.friction
    }

    /// Every face's criterion and cohesion.
    pub fn strengths(&self) -> &Strengths {
        &self.strengths
    }

    /// What the contacts on `faces` carry (each face's criterion; the cohesion when `bonded`:
    /// at rest, never yet slid).
    pub fn strength(&self, faces: [u32; 3], bonded: bool) -> Strength {
        self.strengths.at(&self.friction, faces, bonded)
    }

    /// The run settings: mode, dynamics, integrator, dt, t_end, stride.
    pub fn settings(&self) -> &RunSettings {
        &self.settings
    }

    /// The motion at t = 0.
    pub fn initial(&self) -> &Initial {
        &self.initial
    }

    /// The ground-motion record, when the foundation is shaken.
    pub fn record(&self) -> Option<&Record> {
        self.record.as_deref()
    }

    /// Whether the record is to be run as it is and reversed, the larger permanent
    /// displacement reported (`seismic.polarity = "both"`).
    pub fn both_polarities(&self) -> bool {
        self.both_polarities
    }

    /// The same simulation under one polarity of its record: reversed (every acceleration
    /// negated) or as it is, run once.
    pub fn one_polarity(&self, reversed: bool) -> Result<Simulation, ModelError> {
        let record = match (&self.record, reversed) {
            (Some(r), true) => Some(Arc::new(r.scaled(-1.0)?)),
            (r, _) => r.clone(),
        };
        Ok(Simulation {
            record,
            both_polarities: false,
            ..self.clone()
        })
    }

    /// The foundation's acceleration (g, along X, Y, Z) at time t: the record's, or none.
    pub fn ground(&self, t: f64) -> [f64; 3] {
        self.record.as_ref().map_or([0.0; 3], |r| r.at(t))
    }

    /// The base the block touches the ground with: set where the run settings say
    /// `contacts = "base"` (the one given, or the bounding rectangle of the frame's contacts).
    pub fn base(&self) -> Option<&Base> {
        self.base.as_ref()
    }

    /// The friction criterion of face `face` (its own, or the default).
    pub fn face_friction(&self, face: u32) -> Friction {
        self.strengths
            .faces
            .iter()
            .find(|f| f.faces.contains(&face))
            .map_or(self.friction, |f| f.friction)
    }

    /// The upward unit normals of the planes under contacts 0, 1, 2 at the start.
    pub fn normals(&self) -> &[Vector3<f64>; 3] {
        &self.normals
    }

    /// The frame's length scale L (m).
    pub fn l(&self) -> f64 {
        self.site.l()
    }

    /// The anchors' tendons, as the route has them (fixed in the rock, broken) or, before, as
    /// given.
    pub fn tendons(&self) -> &[Tendon] {
        &self.tendons
    }

    /// The same simulation with every tendon fixed in the rock where the block is at
    /// (`origin`, `frame`): the route's start.
    pub fn tendons_fixed_at(&self, origin: &Vector3<f64>, frame: &LocalFrame) -> Simulation {
        Simulation {
            tendons: self
                .tendons
                .iter()
                .map(|t| t.fixed_at(origin, frame))
                .collect(),
            ..self.clone()
        }
    }

    /// The same simulation with tendon `k` broken.
    pub fn tendon_broken(&self, k: usize) -> Simulation {
        let mut tendons = self.tendons.clone();
        if let Some(t) = tendons.get_mut(k) {
            t.broken = true;
        }
        Simulation {
            tendons,
            ..self.clone()
        }
    }
}

impl SimulationBuilder {
    /// Its name, written into routes.
    pub fn name(mut self, name: impl Into<String>) -> Self {
        self.name = name.into();
        self
    }

    /// The block's mass properties.
    pub fn block(mut self, block: Block) -> Self {
        self.block = Some(block);
        self
    }

    /// The loads.
    pub fn loads(mut self, loads: Loads) -> Self {
        self.loads = Some(loads);
        self
    }

    /// The friction criterion of every face without its own.
    pub fn friction(mut self, friction: Friction) -> Self {
        self.friction = Some(friction);
        self
    }

    /// Faces with their own criterion, and the joint's cohesion (none by default).
    pub fn strengths(mut self, strengths: Strengths) -> Self {
        self.strengths = strengths;
        self
    }

    /// How the route is run.
    pub fn settings(mut self, settings: RunSettings) -> Self {
        self.settings = Some(settings);
        self
    }

    /// The motion at t = 0 (at rest by default).
    pub fn initial(mut self, initial: Initial) -> Self {
        self.initial = initial;
        self
    }

    /// The foundation's shaking (none by default).
    pub fn record(mut self, record: impl Into<Arc<Record>>) -> Self {
        self.record = Some(record.into());
        self
    }

    /// The record run as it is and reversed, the larger permanent displacement reported
    /// (`seismic.polarity = "both"`; `route::Runner::run`).
    pub fn both_polarities(mut self) -> Self {
        self.both_polarities = true;
        self
    }

    /// The base the block touches the ground with under `contacts = "base"` (without one, the
    /// bounding rectangle of the frame's contacts at the centre of mass's height).
    pub fn base(mut self, base: Base) -> Self {
        self.base = Some(base);
        self
    }

    /// Post-tensioned anchors through `monolith` into the rock (`[[anchor]]`; the rigid body
    /// follows them, on its three contacts or its base, the paper's dynamics not), each checked
    /// against its section when built.
    pub fn anchors(mut self, monolith: &Monolith, anchors: &[RockAnchor]) -> Self {
        self.anchor_fault = anchors
            .iter()
            .enumerate()
            .find_map(|(k, a)| a.check(k, &monolith.section).err());
        self.tendons = anchors.iter().map(|a| Tendon::on(monolith, *a)).collect();
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
        let block = self.block.ok_or_else(|| missing("the block", "block"))?;
        let loads = self.loads.ok_or_else(|| missing("the loads", "loads"))?;
        let friction = self
            .friction
            .ok_or_else(|| missing("a friction criterion", "friction"))?;
        let settings = self
            .settings
            .ok_or_else(|| missing("run settings", "settings"))?;
        block.check()?;
        loads.check()?;
        friction.check("friction")?;
        self.strengths.check(face_count(&self.site))?;
        settings.check()?;
        settings.check_runnable()?;
        self.initial.check()?;
        check_ratios(self.site.l(), &block, &loads)?;
        check_rigid_only(
            settings.dynamics,
            self.record.is_some(),
            self.strengths.has_cohesion(),
        )?;
        if let Some(e) = self.anchor_fault {
            return Err(e);
        }
        check_anchor_ratios(&block, &loads, &self.tendons)?;
        check_anchored(&settings, !self.tendons.is_empty())?;
        let base = match settings.contacts {
            Contacts::Frame => None,
            Contacts::Base => {
                check_base_friction(&friction, &self.strengths)?;
                match self.base {
                    Some(b) => Some(b),
                    None => Some(Base::around(self.site.contacts(), loads.cm_height)?),
                }
            }
        };
        Ok(Simulation {
            name: self.name,
            base,
            normals: self.site.normals(),
            site: self.site,
            block,
            loads,
            friction,
            strengths: self.strengths,
            settings,
            initial: self.initial,
            both_polarities: self.both_polarities && self.record.is_some(),
            record: self.record,
            tendons: self.tendons,
        })
    }
}

/// Each anchor's prestress within [`MAX_RATIO`] of the weight, and its E A within
/// [`MAX_RATIO`]² of it (a strain of 10⁻⁶ then pulls at most [`MAX_RATIO`] weights): a
/// tendon's pull is a number the contact problem can take.
fn check_anchor_ratios(b: &Block, l: &Loads, tendons: &[Tendon]) -> Result<(), ModelError> {
    let weight = b.mass * l.gravity;
    for (k, t) in tendons.iter().enumerate() {
        let a = &t.anchor;
        if a.prestress > MAX_RATIO * weight {
            return Err(ModelError::new(
                format!("anchor[{k}].prestress_n"),
                format!(
                    "{:e} N is more than {MAX_RATIO:e} times the weight ({weight:e} N)",
                    a.prestress
                ),
            ));
        }
        let ea = a.modulus * a.steel_area;
        if ea > MAX_RATIO * MAX_RATIO * weight {
            return Err(ModelError::new(
                format!("anchor[{k}].steel_area_m2"),
                format!(
                    "E A = {ea:e} N is more than {:e} times the weight ({weight:e} N)",
                    MAX_RATIO * MAX_RATIO
                ),
            ));
        }
    }
    Ok(())
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

/// What a base's contacts take for now: Coulomb friction on every face, no cohesion (a
/// stress-dependent criterion needs each contact's normal force, which a base's many contacts
/// share by impulses; cohesion needs a bonded area).
fn check_base_friction(friction: &Friction, strengths: &Strengths) -> Result<(), ModelError> {
    let criteria = std::iter::once(friction).chain(strengths.faces.iter().map(|f| &f.friction));
    if criteria.clone().any(Friction::is_stress_dependent) {
        return Err(ModelError::new(
            "solver.contacts",
            "a base touching the ground (contacts = \"base\") takes Coulomb friction only; \
             use contacts = \"frame\" for a stress-dependent criterion",
        ));
    }
    if strengths.has_cohesion() {
        return Err(ModelError::new(
            "friction.cohesion_pa",
            "a base touching the ground (contacts = \"base\") takes no cohesion yet; use \
             contacts = \"frame\"",
        ));
    }
    Ok(())
}

/// How many faces the ground under `site` has: the paper's three planes, or a ground's faces.
pub(crate) fn face_count(site: &Site) -> usize {
    site.ground().map_or(3, |(g, _)| g.faces().len())
}

/// The most a derived ratio may be, either way: the water load against the weight, and a
/// moment of inertia against m L². Each input is finite and positive on its own, but together
/// they can leave the mechanics nothing to compute with (a mass of 1e308 kg makes the weight
/// infinite and the contact problem singular; a water load of 1e308 N makes the cone program
/// fail). A dam monolith's ratios are of order one.
const MAX_RATIO: f64 = 1e6;

/// What follows from the inputs: the weight m g is a finite, normal number, the water load is
/// within [`MAX_RATIO`] of it, and each moment of inertia within [`MAX_RATIO`] of m L² either
/// way (`scale` is L, m). The error names the key to change.
pub(crate) fn check_ratios(scale: f64, b: &Block, l: &Loads) -> Result<(), ModelError> {
    let weight = b.mass * l.gravity;
    if !weight.is_normal() {
        let key = if b.mass > l.gravity {
            "block.mass_kg"
        } else {
            "loads.gravity_m_s2"
        };
        return Err(ModelError::new(
            key,
            // Said in words: an infinite weight printed would be `inf` in a sweep's table.
            format!(
                "the weight m g is {} (mass {:e} kg, gravity {:e} m/s²)",
                if weight.is_infinite() {
                    "beyond the largest number"
                } else {
                    "too small to compute with"
                },
                b.mass,
                l.gravity
            ),
        ));
    }
    if l.hydraulic_force > MAX_RATIO * weight {
        return Err(ModelError::new(
            "loads.hydraulic_force_n",
            format!(
                "{:e} N is more than {MAX_RATIO:e} times the weight ({weight:e} N, from a mass of \
                 {:e} kg)",
                l.hydraulic_force, b.mass
            ),
        ));
    }
    // The water's moment about the CM against the weight's over the block: c = 1e12 m (a
    // moment 1e11 times the weight's) spun the block so that a 0.2 s route took a minute.
    let moment = l.hydraulic_force * l.eccentricity.abs();
    if moment > MAX_RATIO * weight * scale {
        return Err(ModelError::new(
            "loads.eccentricity_m",
            // F and c given, not their product, which may be past the largest number.
            format!(
                "the water's moment F c (F = {:e} N, c = {:e} m) is more than {MAX_RATIO:e} \
                 times the weight's over the block, m g L = {:e} N·m",
                l.hydraulic_force,
                l.eccentricity,
                weight * scale
            ),
        ));
    }
    let ml2 = b.mass * scale * scale;
    for (key, i) in [
        ("block.inertia_kg_m2", b.inertia),
        ("block.inertia_x_kg_m2", b.inertia_x),
        ("block.inertia_z_kg_m2", b.inertia_z),
    ] {
        let ratio = i / ml2;
        if !(ratio.is_finite() && (1.0 / MAX_RATIO..=MAX_RATIO).contains(&ratio)) {
            // A ratio or m L² past the largest number said in words, not `inf`.
            let shown = |v: f64| {
                if v.is_finite() {
                    format!("{v:e}")
                } else {
                    "past the largest number".to_string()
                }
            };
            return Err(ModelError::new(
                key,
                format!(
                    "{i:e} kg·m² against m L² = {} kg·m²: a ratio of {}, outside 1e-6 … 1e6 (a \
                     monolith's is of order 0.1)",
                    shown(ml2),
                    shown(ratio)
                ),
            ));
        }
    }
    Ok(())
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
    use crate::model::{Integrator, Mode};

    fn builder() -> SimulationBuilder {
        let site = crate::scene::Scene::default_scene().site().clone();
        Simulation::builder(site)
            .block(Block::plate(1e6, 1.1e7))
            .loads(Loads::plain(8e6, 1.0, 9.81))
            .friction(Friction::coulomb(0.4))
            .settings(RunSettings::new(DynamicsModel::RigidBody, 1e-3, 1.0))
    }

    #[test]
    fn a_simulation_built_from_parts_is_the_one_its_scene_file_gives() {
        let scene = crate::scene::Scene::default_scene();
        let from_file = scene.simulation().unwrap();
        let settings = RunSettings::new(DynamicsModel::RigidBody, 1e-3, 20.0);
        let built = builder()
            .name("paper-like")
            .block(Block::plate(1e6, 11e6).with_axes(5.5e6, 5.5e6, 0.0))
            .settings(settings)
            .build()
            .unwrap();
        assert_eq!(built, from_file);
    }

    #[test]
    fn a_missing_part_or_parts_that_do_not_go_together_are_refused_naming_the_key() {
        let site = crate::scene::Scene::default_scene().site().clone();
        let e = Simulation::builder(site).build().unwrap_err();
        assert_eq!(e.key, "block");
        let e = builder().block(Block::plate(0.0, 1.0)).build().unwrap_err();
        assert_eq!(e.key, "block.mass_kg");
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
            .record(record)
            .build()
            .unwrap_err();
        assert_eq!(e.key, "seismic.record");
        let e = builder()
            .loads(Loads::plain(1e20, 1.0, 9.81))
            .build()
            .unwrap_err();
        assert_eq!(e.key, "loads.hydraulic_force_n");
        let e = builder()
            .friction(Friction::coulomb(f64::NAN))
            .build()
            .unwrap_err();
        assert_eq!(e.key, "friction.mu_k");
    }

    #[test]
    fn a_waters_moment_a_million_times_the_weights_is_refused_naming_the_eccentricity() {
        // Before, c = 1e12 m was taken, and its route of 0.2 s took a minute of sweeps.
        for c in [1e12, -9.2e18, f64::MAX] {
            let e = builder()
                .loads(Loads::plain(8e6, c, 9.81))
                .build()
                .unwrap_err();
            assert_eq!(e.key, "loads.eccentricity_m");
            assert!(e.reason.contains("moment"), "{}", e.reason);
            assert!(!e.reason.contains("inf"), "{}", e.reason);
        }
        // F c = 8e12 N·m against 1e6 m g L ≈ 1e14 N·m: taken. No water, any c.
        assert!(
            builder()
                .loads(Loads::plain(8e6, 1e6, 9.81))
                .build()
                .is_ok()
        );
        assert!(
            builder()
                .loads(Loads::plain(0.0, 1e300, 9.81))
                .build()
                .is_ok()
        );
    }
}
