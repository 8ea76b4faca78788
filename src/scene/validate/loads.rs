//! `[loads]`, `[water]` and `[seismic]`: the loads, from a force as given or from the water's
//! levels on a monolith, with the pseudo-static coefficients; and a ground-motion record.

use super::Reader;
use crate::model::{Levels, Loads, Monolith, Record};
use crate::scene::SceneError;
use crate::scene::raw::{RawLoads, RawScene, RawSeismic, RawWater};
use std::sync::Arc;

impl Reader<'_> {
    /// The loads (`None` without `[loads]`, which `[water]` and `[seismic]` then may not be
    /// without) and the ground-motion record.
    pub(super) fn loads(
        &self,
        raw: &RawScene,
        monolith: Option<&Monolith>,
    ) -> Result<(Option<Loads>, Option<Arc<Record>>), SceneError> {
        let (kh, kv, record) = match &raw.seismic {
            Some(s) => self.seismic(s)?,
            None => (0.0, 0.0, None),
        };
        let Some(l) = &raw.loads else {
            for (present, name) in [
                (raw.water.is_some(), "water"),
                (raw.seismic.is_some(), "seismic"),
            ] {
                if present {
                    return Err(self.invalid(
                        name,
                        format!("[{name}] needs [loads] (gravity_m_s2, eccentricity_m)"),
                    ));
                }
            }
            return Ok((None, record));
        };
        let loads = match &raw.water {
            Some(w) => self.water(w, l, monolith)?,
            None => self.plain(l, monolith)?,
        }
        .with_pseudo_static(kh, kv);
        loads.check().map_err(|e| self.model(e))?;
        Ok((Some(loads), record))
    }

    /// The eccentricity c and gravity g of `[loads]`.
    fn line_and_gravity(&self, l: &RawLoads) -> Result<(f64, f64), SceneError> {
        let eccentricity = self.need("loads.eccentricity_m", l.eccentricity_m)?;
        let eccentricity = self.finite("loads.eccentricity_m", eccentricity)?;
        let gravity = self.need("loads.gravity_m_s2", l.gravity_m_s2)?;
        let gravity = self.positive("loads.gravity_m_s2", gravity)?;
        Ok((eccentricity, gravity))
    }

    /// `[loads]` as given: a force in the base plane (at a monolith's centre of mass height, if
    /// the block is one).
    fn plain(&self, l: &RawLoads, monolith: Option<&Monolith>) -> Result<Loads, SceneError> {
        let (eccentricity, gravity) = self.line_and_gravity(l)?;
        let force = self.need("loads.hydraulic_force_n", l.hydraulic_force_n)?;
        let force = self.non_negative("loads.hydraulic_force_n", force)?;
        Ok(Loads::plain(force, eccentricity, gravity)
            .at_height(monolith.map_or(0.0, |m| m.props.cm_height)))
    }

    /// The water's loads of `[water]` on the monolith (`derivations/11-dam-loads.md` §2).
    fn water(
        &self,
        w: &RawWater,
        l: &RawLoads,
        monolith: Option<&Monolith>,
    ) -> Result<Loads, SceneError> {
        let (eccentricity, gravity) = self.line_and_gravity(l)?;
        if l.hydraulic_force_n.is_some() {
            return Err(self.invalid(
                "loads.hydraulic_force_n",
                "[water] gives the water's force from its levels: remove loads.hydraulic_force_n",
            ));
        }
        let m = monolith.ok_or_else(|| {
            self.invalid(
                "water",
                "[water] needs [monolith]: the faces and the base the water acts on",
            )
        })?;
        let headwater = self.need("water.headwater_m", w.headwater_m)?;
        let efficiency = w.drain_efficiency.unwrap_or(0.0);
        if w.drain_position_m.is_none() && efficiency > 0.0 {
            return Err(self.invalid(
                "water.drain_position_m",
                "drains of some efficiency need their position (m from the heel)",
            ));
        }
        let levels = Levels {
            headwater,
            tailwater: w.tailwater_m.unwrap_or(0.0),
            density: w.density_kg_m3.unwrap_or(1000.0),
            drain_efficiency: efficiency,
            drain_position: w.drain_position_m.unwrap_or(0.0),
        };
        levels.check(&m.section).map_err(|e| self.model(e))?;
        Ok(Loads::from_water(m, &levels, eccentricity, gravity))
    }

    /// (k_h, k_v), fractions of g (checked with the loads they belong to), and the
    /// ground-motion record, read from the scene's folder (or the one read before under that
    /// name).
    fn seismic(&self, s: &RawSeismic) -> Result<(f64, f64, Option<Arc<Record>>), SceneError> {
        let record = match &s.record {
            Some(name) => Some(
                self.files
                    .record(self.folder, name)
                    .map_err(|why| self.invalid("seismic.record", why))?,
            ),
            None => None,
        };
        Ok((s.kh.unwrap_or(0.0), s.kv.unwrap_or(0.0), record))
    }
}
