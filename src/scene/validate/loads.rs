//! `[loads]`, `[water]` (with `[silt]` and `[ice]`) and `[seismic]`: the loads, from a force
//! as given or from the water's levels on a monolith, with the pseudo-static coefficients; and
//! a ground-motion record.

use super::Reader;
use crate::model::{Ice, Levels, Loads, Monolith, Record, RockAnchor, STRAND_MODULUS_PA, Silt};
use crate::scene::SceneError;
use crate::scene::raw::{RawAnchor, RawIce, RawLoads, RawScene, RawSeismic, RawSilt, RawWater};
use crate::scene::record_files::{Component, Units, combine, read_component};
use std::sync::Arc;

impl Reader<'_> {
    /// The loads (`None` without `[loads]`, which `[water]` and `[seismic]` then may not be
    /// without) and the ground-motion record.
    pub(super) fn loads(
        &self,
        raw: &RawScene,
        monolith: Option<&Monolith>,
    ) -> Result<(Option<Loads>, Option<Arc<Record>>), SceneError> {
        let gravity = raw.loads.as_ref().and_then(|l| l.gravity_m_s2);
        let (kh, kv, record) = match &raw.seismic {
            Some(s) => self.seismic(s, gravity)?,
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
        if raw.water.is_none() {
            for (present, name) in [(raw.silt.is_some(), "silt"), (raw.ice.is_some(), "ice")] {
                if present {
                    return Err(self.invalid(
                        name,
                        format!("[{name}] is a load of the reservoir: it needs [water]"),
                    ));
                }
            }
        }
        let loads = match &raw.water {
            Some(w) => self.water(w, (raw.silt.as_ref(), raw.ice.as_ref()), l, monolith)?,
            None => self.plain(l, monolith)?,
        }
        .with_pseudo_static(kh, kv);
        loads.check().map_err(|e| self.model(e))?;
        Ok((Some(loads), record))
    }

    /// `[[anchor]]` on the monolith (`derivations/11-dam-loads.md` §10): the head at `x_m`
    /// from the heel, `y_m` above the base (0) and `z_m` across (0), plunging `plunge_deg`
    /// (90, vertical) towards `trend_deg` (0, downstream), its prestress, capacity, free
    /// length, steel area and modulus (that of strand when not given).
    pub(super) fn anchors(
        &self,
        raw: &[RawAnchor],
        monolith: Option<&Monolith>,
    ) -> Result<Vec<RockAnchor>, SceneError> {
        if raw.is_empty() {
            return Ok(Vec::new());
        }
        let Some(m) = monolith else {
            return Err(self.invalid(
                "anchor",
                "[[anchor]] is placed on a monolith's section: it needs [monolith]",
            ));
        };
        raw.iter()
            .enumerate()
            .map(|(k, a)| {
                let key = |name: &str| format!("anchor[{k}].{name}");
                let anchor = RockAnchor {
                    head: [
                        self.need(&key("x_m"), a.x_m)?,
                        a.y_m.unwrap_or(0.0),
                        a.z_m.unwrap_or(0.0),
                    ],
                    plunge: a.plunge_deg.unwrap_or(90.0).to_radians(),
                    trend: a.trend_deg.unwrap_or(0.0).to_radians(),
                    prestress: self.need(&key("prestress_n"), a.prestress_n)?,
                    capacity: self.need(&key("capacity_n"), a.capacity_n)?,
                    free_length: self.need(&key("free_length_m"), a.free_length_m)?,
                    steel_area: self.need(&key("steel_area_m2"), a.steel_area_m2)?,
                    modulus: a.modulus_pa.unwrap_or(STRAND_MODULUS_PA),
                };
                anchor.check(k, &m.section).map_err(|e| self.model(e))?;
                Ok(anchor)
            })
            .collect()
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
        (silt, ice): (Option<&RawSilt>, Option<&RawIce>),
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
            crack: w.crack.unwrap_or(true),
            silt: silt
                .map(|s| {
                    Ok::<_, SceneError>(Silt {
                        depth: self.need("silt.depth_m", s.depth_m)?,
                        unit_weight: self.need("silt.unit_weight_n_m3", s.unit_weight_n_m3)?,
                        friction_angle: self
                            .need("silt.friction_angle_deg", s.friction_angle_deg)?
                            .to_radians(),
                    })
                })
                .transpose()?,
            ice: ice
                .map(|i| {
                    Ok::<_, SceneError>(Ice {
                        force_per_m: self.need("ice.force_n_m", i.force_n_m)?,
                        elevation: self.need("ice.elevation_m", i.elevation_m)?,
                    })
                })
                .transpose()?,
        };
        levels.check(&m.section).map_err(|e| self.model(e))?;
        Ok(Loads::from_water(m, &levels, eccentricity, gravity))
    }

    /// (k_h, k_v), fractions of g (checked with the loads they belong to), and the
    /// ground-motion record: three components in one file (`record`, read from the scene's
    /// folder, or the one read before under that name), or one file a component
    /// (`record_x`, `record_y`, `record_z`: `scene/record_files.rs`) in `units` with gravity
    /// `gravity` (m/s²); then scaled by `scale` or to `target_pga_g`, and reversed by
    /// `polarity`.
    fn seismic(
        &self,
        s: &RawSeismic,
        gravity: Option<f64>,
    ) -> Result<(f64, f64, Option<Arc<Record>>), SceneError> {
        let parts = [&s.record_x, &s.record_y, &s.record_z];
        let components = parts.iter().any(|p| p.is_some());
        let record = match (&s.record, components) {
            (Some(_), true) => {
                return Err(self.invalid(
                    "seismic.record",
                    "give the record as one file of three components (record) or one file a \
                     component (record_x, record_y, record_z), not both",
                ));
            }
            (Some(name), false) => {
                for (key, given) in [
                    ("seismic.units", s.units.is_some()),
                    ("seismic.dt_s", s.dt_s.is_some()),
                ] {
                    if given {
                        return Err(self.invalid(
                            key,
                            "is for one file a component (record_x, record_y, record_z); \
                             seismic.record is in g with its times (t_s,ax_g,ay_g,az_g)",
                        ));
                    }
                }
                Some(
                    self.files
                        .record(self.folder, name)
                        .map_err(|why| self.invalid("seismic.record", why))?,
                )
            }
            (None, true) => Some(Arc::new(self.components(s, gravity)?)),
            (None, false) => {
                for (key, given) in [
                    ("seismic.units", s.units.is_some()),
                    ("seismic.dt_s", s.dt_s.is_some()),
                    ("seismic.scale", s.scale.is_some()),
                    ("seismic.target_pga_g", s.target_pga_g.is_some()),
                    ("seismic.polarity", s.polarity.is_some()),
                ] {
                    if given {
                        return Err(self.invalid(key, "is for a record, and the scene has none"));
                    }
                }
                None
            }
        };
        let record = match record {
            Some(r) => Some(self.adjusted(s, r)?),
            None => None,
        };
        Ok((s.kh.unwrap_or(0.0), s.kv.unwrap_or(0.0), record))
    }

    /// The record of one file a component.
    fn components(&self, s: &RawSeismic, gravity: Option<f64>) -> Result<Record, SceneError> {
        let units = match &s.units {
            Some(u) => Some(Units::parse(u).map_err(|why| self.invalid("seismic.units", why))?),
            None => None,
        };
        let gravity = gravity
            .filter(|g| *g > 0.0 && g.is_finite())
            .unwrap_or(9.81);
        let mut parts: [Option<Component>; 3] = [None, None, None];
        for (part, (key, name)) in parts.iter_mut().zip([
            ("seismic.record_x", &s.record_x),
            ("seismic.record_y", &s.record_y),
            ("seismic.record_z", &s.record_z),
        ]) {
            if let Some(name) = name {
                let path = self.folder.join(name);
                let read = read_component(&path, s.dt_s)
                    .and_then(|c| c.in_g(units, gravity))
                    .map_err(|why| self.invalid(key, format!("{}: {why}", path.display())))?;
                if let Some(k) = read.a.iter().position(|a| a.abs() > 10.0) {
                    let hint = if units.is_none() {
                        " (is it in cm/s2 or m/s2? say so with seismic.units)"
                    } else {
                        ""
                    };
                    return Err(self.invalid(
                        key,
                        format!(
                            "{}: the sample at t = {} s is {} g, over 10 g{hint}",
                            path.display(),
                            read.t[k],
                            read.a[k]
                        ),
                    ));
                }
                *part = Some(read);
            }
        }
        Record::new(combine(&parts)).map_err(|e| self.invalid("seismic.record_x", e.reason))
    }

    /// `record` scaled by `scale` or to `target_pga_g`, and reversed by `polarity`.
    fn adjusted(&self, s: &RawSeismic, record: Arc<Record>) -> Result<Arc<Record>, SceneError> {
        let mut k = match (s.scale, s.target_pga_g) {
            (Some(_), Some(_)) => {
                return Err(self.invalid(
                    "seismic.scale",
                    "give a scale or a target PGA (seismic.target_pga_g), not both",
                ));
            }
            (Some(scale), None) => self.positive("seismic.scale", scale)?,
            (None, Some(target)) => {
                let target = self.positive("seismic.target_pga_g", target)?;
                let pga = record.pga();
                if pga <= 0.0 {
                    return Err(self.invalid(
                        "seismic.target_pga_g",
                        "the record has no horizontal acceleration to scale",
                    ));
                }
                target / pga
            }
            (None, None) => 1.0,
        };
        match s.polarity.as_deref() {
            None | Some("normal") => {}
            Some("reversed") => k = -k,
            // Run as it is and reversed (`Foundation::both_polarities`).
            Some("both") => {}
            Some(other) => {
                return Err(self.invalid(
                    "seismic.polarity",
                    format!("`{other}` is not a polarity: \"normal\", \"reversed\" or \"both\""),
                ));
            }
        }
        if k == 1.0 {
            return Ok(record);
        }
        record
            .scaled(k)
            .map(Arc::new)
            .map_err(|e| self.invalid("seismic.scale", e.reason))
    }
}
