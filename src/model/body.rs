//! One rigid body of a simulation and everything that is its own: its mass properties, its
//! loads, its motion at the start, its base, its anchors' tendons, and its three-point contact
//! frame on the rock (the frame contact model's; the body model, `contacts = "base"`, touches
//! the rock with its base and reports its tilts through the frame's three points all the same).

use super::anchor::{RockAnchor, Tendon};
use super::base::Base;
use super::block::Block;
use super::error::{ModelError, non_negative};
use super::initial::Initial;
use super::loads::Loads;
use super::monolith::Monolith;
use super::strength::{ContactStrength, Strengths};
use crate::geometry::{LocalFrame, Site};
use nalgebra::Vector3;

/// A rigid body: a block with its loads, the motion it starts with, the base it may touch the
/// rock with, the anchors through it into the rock, and its three-point contact frame (the
/// [`Site`]: the contacts' triangle and the planes under them at the start) with the upward
/// normals of those planes and the bonded area each contact stands for. Built by
/// [`Body::builder`] and checked once; its fields are private.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    name: String,
    site: Site,
    /// The upward unit normals of the planes under contacts 0, 1, 2, computed once.
    normals: [Vector3<f64>; 3],
    /// The bonded area (m²) each frame contact stands for: the area times the contact's
    /// barycentric weight of the area's centroid, so that a uniform cohesion's resultant acts
    /// there.
    shares_m2: [f64; 3],
    block: Block,
    loads: Loads,
    initial: Initial,
    /// The base the block touches the rock with (`contacts = "base"`).
    base: Option<Base>,
    /// `[[anchor]]`: post-tensioned anchors through the monolith into the rock.
    tendons: Vec<Tendon>,
}

/// The parts of a [`Body`], set one by one and checked together by [`BodyBuilder::build`].
#[derive(Debug, Clone)]
#[must_use]
pub struct BodyBuilder {
    name: String,
    site: Site,
    shares_m2: [f64; 3],
    block: Option<Block>,
    loads: Option<Loads>,
    initial: Initial,
    base: Option<Base>,
    tendons: Vec<Tendon>,
    /// The first anchor that is not on the monolith, found when the anchors were given.
    anchor_fault: Option<ModelError>,
}

impl Body {
    /// A builder of a body whose three-point frame is `site`, named "unnamed", at rest, with no
    /// bonded area, no base of its own and no anchors until told.
    pub fn builder(site: Site) -> BodyBuilder {
        BodyBuilder {
            name: "unnamed".to_string(),
            site,
            shares_m2: [0.0; 3],
            block: None,
            loads: None,
            initial: Initial::default(),
            base: None,
            tendons: Vec::new(),
            anchor_fault: None,
        }
    }

    /// Its name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Its three-point contact frame: the contacts and the ground under them.
    pub fn site(&self) -> &Site {
        &self.site
    }

    /// The upward unit normals of the planes under its frame's contacts 0, 1, 2 at the start.
    pub fn normals(&self) -> &[Vector3<f64>; 3] {
        &self.normals
    }

    /// The frame's length scale L (m).
    pub fn l(&self) -> f64 {
        self.site.l()
    }

    /// The bonded area (m²) each of the frame's contacts stands for.
    pub fn shares_m2(&self) -> &[f64; 3] {
        &self.shares_m2
    }

    /// The block's mass properties.
    pub fn block(&self) -> &Block {
        &self.block
    }

    /// The loads.
    pub fn loads(&self) -> &Loads {
        &self.loads
    }

    /// The motion at t = 0.
    pub fn initial(&self) -> &Initial {
        &self.initial
    }

    /// The base the block touches the rock with: set where the run settings say
    /// `contacts = "base"` (the one given, or the bounding rectangle of the frame's contacts).
    pub fn base(&self) -> Option<&Base> {
        self.base.as_ref()
    }

    /// The anchors' tendons, as the route has them (fixed in the rock, broken) or, before, as
    /// given.
    pub fn tendons(&self) -> &[Tendon] {
        &self.tendons
    }

    /// What the frame's contacts on the rock's faces `faces` carry under `strengths`: each
    /// face's criterion, and its cohesion over the contact's share of the bonded area when
    /// `bonded` (at rest, never yet slid).
    pub fn frame_strength(
        &self,
        strengths: &Strengths,
        faces: [u32; 3],
        bonded: bool,
    ) -> [ContactStrength; 3] {
        std::array::from_fn(|i| strengths.face(faces[i]).contact(self.shares_m2[i], bonded))
    }

    /// The same body with every tendon fixed in the rock where the block is at (`origin`,
    /// `frame`): the route's start.
    pub fn tendons_fixed_at(&self, origin: &Vector3<f64>, frame: &LocalFrame) -> Body {
        Body {
            tendons: self
                .tendons
                .iter()
                .map(|t| t.fixed_at(origin, frame))
                .collect(),
            ..self.clone()
        }
    }

    /// The same body with tendon `k` broken.
    pub fn tendon_broken(&self, k: usize) -> Body {
        let mut tendons = self.tendons.clone();
        if let Some(t) = tendons.get_mut(k) {
            t.broken = true;
        }
        Body {
            tendons,
            ..self.clone()
        }
    }

    /// The same body on `base` (the simulation's builder gives a body without one the bounding
    /// rectangle of its frame's contacts under `contacts = "base"`).
    pub(super) fn with_base(self, base: Option<Base>) -> Body {
        Body { base, ..self }
    }
}

impl BodyBuilder {
    /// Its name.
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

    /// The motion at t = 0 (at rest by default).
    pub fn initial(mut self, initial: Initial) -> Self {
        self.initial = initial;
        self
    }

    /// The bonded area (m²) each of the frame's contacts stands for, over which the joint's
    /// cohesion holds the block at rest (none by default).
    pub fn shares_m2(mut self, shares_m2: [f64; 3]) -> Self {
        self.shares_m2 = shares_m2;
        self
    }

    /// The base the block touches the rock with under `contacts = "base"` (without one, the
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

    /// The body, or the first fault: a part missing, a value out of its range, or parts that do
    /// not go together. Each names its scene key.
    pub fn build(self) -> Result<Body, ModelError> {
        let missing = |part: &str, key: &str| {
            ModelError::new(
                key,
                format!("missing: a body needs {part} (BodyBuilder::{key})"),
            )
        };
        let block = self.block.ok_or_else(|| missing("the block", "block"))?;
        let loads = self.loads.ok_or_else(|| missing("the loads", "loads"))?;
        block.check()?;
        loads.check()?;
        for (k, s) in self.shares_m2.iter().enumerate() {
            non_negative(
                &format!("friction.cohesion_area_m2 (contact {k}'s share)"),
                *s,
            )?;
        }
        self.initial.check()?;
        check_ratios(self.site.l(), &block, &loads)?;
        if let Some(e) = self.anchor_fault {
            return Err(e);
        }
        check_anchor_ratios(&block, &loads, &self.tendons)?;
        Ok(Body {
            name: self.name,
            normals: self.site.normals(),
            site: self.site,
            shares_m2: self.shares_m2,
            block,
            loads,
            initial: self.initial,
            base: self.base,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Friction;

    fn site() -> Site {
        crate::scene::Scene::default_scene().site().clone()
    }

    fn builder() -> BodyBuilder {
        Body::builder(site())
            .block(Block::plate(1e6, 1.1e7))
            .loads(Loads::plain(8e6, 1.0, 9.81))
    }

    #[test]
    fn a_missing_part_or_a_value_out_of_range_is_refused_naming_the_key() {
        assert_eq!(Body::builder(site()).build().unwrap_err().key, "block");
        let e = Body::builder(site())
            .block(Block::plate(1e6, 1.1e7))
            .build()
            .unwrap_err();
        assert_eq!(e.key, "loads");
        let e = builder().block(Block::plate(0.0, 1.0)).build().unwrap_err();
        assert_eq!(e.key, "block.mass_kg");
        let e = builder().shares_m2([1.0, -1.0, 0.0]).build().unwrap_err();
        assert!(e.key.starts_with("friction.cohesion_area_m2"), "{e}");
        let e = builder()
            .initial(Initial::new(f64::NAN, 0.0, 0.0))
            .build()
            .unwrap_err();
        assert_eq!(e.key, "initial.vx_m_s");
        let e = builder()
            .loads(Loads::plain(1e20, 1.0, 9.81))
            .build()
            .unwrap_err();
        assert_eq!(e.key, "loads.hydraulic_force_n");
    }

    #[test]
    fn the_frames_contacts_take_their_faces_criterion_and_their_share_of_the_cohesion() {
        let body = builder().shares_m2([1.0, 2.0, 3.0]).build().unwrap();
        let mut strengths = Strengths::new(Friction::coulomb(0.4));
        strengths.cohesion_pa = 10.0;
        strengths.faces.push(crate::model::FaceStrength {
            faces: vec![2],
            friction: Friction::coulomb(0.9),
            cohesion_pa: 0.0,
        });
        let s = body.frame_strength(&strengths, [0, 1, 2], true);
        assert_eq!(s.map(|c| c.cohesion_n), [10.0, 20.0, 0.0]);
        assert_eq!(s[2].criterion, Friction::coulomb(0.9));
        let slid = body.frame_strength(&strengths, [0, 1, 2], false);
        assert_eq!(slid.map(|c| c.cohesion_n), [0.0; 3]);
        assert_eq!(body.normals(), &site().normals());
    }
}
