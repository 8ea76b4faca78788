//! `[block]` or `[monolith]`: the block's mass properties, given or from a section.

use super::Reader;
use crate::geometry::Site;
use crate::model::{Base, Block, Monolith, Section};
use crate::scene::SceneError;
use crate::scene::raw::{RawBase, RawBlock, RawMonolith, RawScene};

impl Reader<'_> {
    /// The block: `[block]` as given, or `[monolith]`'s from its section (with the monolith, whose
    /// base the contacts must be on); not both.
    pub(super) fn body(
        &self,
        raw: &RawScene,
        site: &Site,
    ) -> Result<(Option<Block>, Option<Monolith>), SceneError> {
        match (&raw.block, &raw.monolith) {
            (Some(_), Some(_)) => Err(self.invalid(
                "monolith",
                "give the block's mass and inertia ([block]) or its section ([monolith]), not \
                 both",
            )),
            (Some(b), None) => Ok((Some(self.block(b)?), None)),
            (None, Some(m)) => {
                let monolith = self.monolith(m)?;
                monolith
                    .check_contacts(site.contacts(), 1e-9 * site.l())
                    .map_err(|e| self.model(e))?;
                // The section's mass properties are a rigid body's by construction; a fault of
                // them is the section's.
                let block = monolith.block();
                block
                    .check()
                    .map_err(|e| self.invalid("monolith", e.reason))?;
                Ok((Some(block), Some(monolith)))
            }
            (None, None) => Ok((None, None)),
        }
    }

    /// `[base] outline_m` (from the heel and the width's middle for a monolith, about the
    /// centre of mass for a block), or a monolith's base rectangle, cast onto its rock where
    /// `[base] cast` says so; `None` for a flat block's base without an outline (its frame's
    /// bounding rectangle is taken when the base is needed). A cast block's base without an
    /// outline is that rectangle, `cm_height` (m) below its centre of mass.
    pub(super) fn base(
        &self,
        raw: Option<&RawBase>,
        monolith: Option<&Monolith>,
        site: &Site,
        cm_height: f64,
    ) -> Result<Option<Base>, SceneError> {
        let cast = raw.and_then(|b| b.cast).unwrap_or(false);
        Ok(match self.flat_base(raw, monolith)? {
            Some(b) => Some(b.with_cast(cast)),
            None if cast => Some(
                Base::around(site.contacts(), cm_height)
                    .map_err(|e| self.model(e))?
                    .with_cast(true),
            ),
            None => None,
        })
    }

    /// The base's footprint as given, or a monolith's base rectangle.
    fn flat_base(
        &self,
        raw: Option<&RawBase>,
        monolith: Option<&Monolith>,
    ) -> Result<Option<Base>, SceneError> {
        let (shift, depth) = match monolith {
            Some(m) => (m.props.cm_from_heel, m.props.cm_height),
            None => (0.0, 0.0),
        };
        let outline = match raw.and_then(|b| b.outline_m.as_ref()) {
            Some(corners) => {
                let mut out = Vec::with_capacity(corners.len());
                for (k, c) in corners.iter().enumerate() {
                    let [x, z] = c[..] else {
                        return Err(self.invalid(
                            "base.outline_m",
                            format!("corner {k} must be a pair [x, z] in metres, got {c:?}"),
                        ));
                    };
                    out.push([x - shift, z]);
                }
                out
            }
            None => match monolith {
                Some(m) => {
                    let (b, w) = (m.section.base_length, m.section.width);
                    vec![
                        [-shift, -w / 2.0],
                        [b - shift, -w / 2.0],
                        [b - shift, w / 2.0],
                        [-shift, w / 2.0],
                    ]
                }
                None => return Ok(None),
            },
        };
        Base::polygon(outline, depth)
            .map(Some)
            .map_err(|e| self.model(e))
    }

    /// `[block]`, with the rigid-body inertia defaults (a thin plate in the x'z' plane).
    fn block(&self, b: &RawBlock) -> Result<Block, SceneError> {
        let mass = self.need("block.mass_kg", b.mass_kg)?;
        let inertia = self.need("block.inertia_kg_m2", b.inertia_kg_m2)?;
        let plate = Block::plate(mass, inertia);
        let block = plate.with_axes(
            b.inertia_x_kg_m2.unwrap_or(plate.inertia_x),
            b.inertia_z_kg_m2.unwrap_or(plate.inertia_z),
            b.inertia_xz_kg_m2.unwrap_or(0.0),
        );
        block.check().map_err(|e| self.model(e))?;
        Ok(block)
    }

    /// `[monolith]`: its section.
    fn monolith(&self, m: &RawMonolith) -> Result<Monolith, SceneError> {
        let get = |name: &str, v: Option<f64>| self.need(&format!("monolith.{name}"), v);
        let section = Section {
            base_length: get("base_length_m", m.base_length_m)?,
            width: get("width_m", m.width_m)?,
            height: get("height_m", m.height_m)?,
            crest_length: get("crest_length_m", m.crest_length_m)?,
            density: get("density_kg_m3", m.density_kg_m3)?,
        };
        Monolith::new(section).map_err(|e| self.model(e))
    }
}
