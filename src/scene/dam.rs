//! `[monolith]`, `[water]` and `[seismic]` (issue #16, `derivations/11-dam-loads.md`): the
//! block from its section, the water's loads from levels, pseudo-static coefficients.

use super::checks::{check, need, non_negative, positive};
use super::raw::{RawMonolith, RawSeismic, RawWater};
use super::record::Record;
use super::water::{Levels, MassProperties, Section, water_loads};
use super::{Block, Loads, SceneError, Site};
use std::sync::Arc;

/// A monolith from its section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Monolith {
    pub section: Section,
    pub props: MassProperties,
}

impl Monolith {
    /// Its mass properties as a block (the moment about y', the others, and ∫x'y' dm).
    pub fn block(&self) -> Block {
        let p = &self.props;
        Block {
            mass: p.mass,
            inertia: p.inertia_y,
            inertia_x: p.inertia_x,
            inertia_z: p.inertia_z,
            inertia_xz: 0.0,
            inertia_xy: p.product_xy,
        }
    }
}

pub(super) fn monolith(o: &str, m: &RawMonolith) -> Result<Monolith, SceneError> {
    let key = |k: &str| format!("monolith.{k}");
    let get = |k: &str, v: Option<f64>| -> Result<f64, SceneError> {
        positive(o, &key(k), need(o, &key(k), v)?)
    };
    let section = Section {
        base_length: get("base_length_m", m.base_length_m)?,
        width: get("width_m", m.width_m)?,
        height: get("height_m", m.height_m)?,
        crest_length: get("crest_length_m", m.crest_length_m)?,
        density: get("density_kg_m3", m.density_kg_m3)?,
    };
    if section.crest_length > section.base_length {
        return Err(SceneError::new(
            o,
            "monolith.crest_length_m",
            format!(
                "must be at most the base length ({} m), got {} m (the downstream face runs from \
                 the crest down to the toe)",
                section.base_length, section.crest_length
            ),
        ));
    }
    Ok(Monolith {
        section,
        props: section.mass_properties(),
    })
}

/// The centre of the monolith's base (x′, z′) about the centre of mass.
pub(super) fn base_centre(m: &Monolith) -> [f64; 2] {
    [0.5 * m.section.base_length - m.props.cm_from_heel, 0.0]
}

/// Each contact must be on the monolith's base: x' from the heel (−x̄) to the toe (b − x̄) and
/// z' across the width, about the centre of mass.
pub(super) fn contacts_on_base(o: &str, site: &Site, m: &Monolith) -> Result<(), SceneError> {
    let (b, w) = (m.section.base_length, m.section.width);
    let heel = -m.props.cm_from_heel;
    let tol = 1e-9 * site.l();
    for (k, [x, z]) in site.contacts().iter().enumerate() {
        let inside = (heel - tol..=heel + b + tol).contains(x) && z.abs() <= w / 2.0 + tol;
        if !inside {
            return Err(SceneError::new(
                o,
                "frame",
                format!(
                    "contact {k} at (x', z') = ({x}, {z}) m is off the monolith's base: x' from \
                     {heel:.6} to {:.6} m (heel to toe about the centre of mass, {:.6} m from the \
                     heel) and z' from {:.6} to {:.6} m",
                    heel + b,
                    m.props.cm_from_heel,
                    -w / 2.0,
                    w / 2.0
                ),
            ));
        }
    }
    Ok(())
}

/// (k_h, k_v): fractions of g, each below 1 in size; and the ground-motion record, read from
/// `folder` (or the one `read` already holds under that name).
pub(super) fn seismic(
    o: &str,
    s: &RawSeismic,
    (folder, read): (&std::path::Path, &Option<(String, Arc<Record>)>),
) -> Result<(f64, f64, Option<Arc<Record>>), SceneError> {
    let record = match &s.record {
        Some(name) if read.as_ref().is_some_and(|(n, _)| n == name) => {
            read.as_ref().map(|(_, r)| r.clone())
        }
        Some(name) => {
            let path = folder.join(name);
            let r = Record::read(&path).map_err(|why| {
                SceneError::new(o, "seismic.record", format!("{}: {why}", path.display()))
            })?;
            Some(Arc::new(r))
        }
        None => None,
    };
    let coefficient = |key: &str, v: Option<f64>| -> Result<f64, SceneError> {
        let v = v.unwrap_or(0.0);
        check(o, key, v, v.abs() < 1.0, "a fraction of g between −1 and 1")
    };
    Ok((
        coefficient("seismic.kh", s.kh)?,
        coefficient("seismic.kv", s.kv)?,
        record,
    ))
}

/// The loads of `[water]` on monolith `m`: the net push along x', the pitch of the pushes
/// about the base point under the centre of mass, and the uplift less the tailwater's weight
/// with its pitch (`derivations/11-dam-loads.md` §2).
pub(super) fn water(
    o: &str,
    w: &RawWater,
    m: &Monolith,
    eccentricity: f64,
    gravity: f64,
) -> Result<Loads, SceneError> {
    let b = m.section.base_length;
    let headwater = non_negative(
        o,
        "water.headwater_m",
        need(o, "water.headwater_m", w.headwater_m)?,
    )?;
    let tailwater = non_negative(o, "water.tailwater_m", w.tailwater_m.unwrap_or(0.0))?;
    if tailwater > headwater {
        return Err(SceneError::new(
            o,
            "water.tailwater_m",
            format!(
                "must be at most the headwater ({headwater} m), got {tailwater} m (the water \
                 pushes the monolith downstream)"
            ),
        ));
    }
    if tailwater > m.section.height {
        return Err(SceneError::new(
            o,
            "water.tailwater_m",
            format!(
                "must be at most the monolith's height ({} m), got {tailwater} m",
                m.section.height
            ),
        ));
    }
    let density = positive(o, "water.density_kg_m3", w.density_kg_m3.unwrap_or(1000.0))?;
    let efficiency = w.drain_efficiency.unwrap_or(0.0);
    let efficiency = check(
        o,
        "water.drain_efficiency",
        efficiency,
        (0.0..=1.0).contains(&efficiency),
        "between 0 and 1",
    )?;
    let position = match w.drain_position_m {
        Some(x) => check(
            o,
            "water.drain_position_m",
            x,
            x > 0.0 && x < b,
            &format!("within the base, between 0 and {b} m from the heel"),
        )?,
        None if efficiency > 0.0 => {
            return Err(SceneError::new(
                o,
                "water.drain_position_m",
                "drains of some efficiency need their position (m from the heel)".to_string(),
            ));
        }
        None => 0.0,
    };
    let levels = Levels {
        headwater,
        tailwater,
        density,
        drain_efficiency: efficiency,
        drain_position: position,
    };
    let l = water_loads(&m.section, &levels, gravity);
    let x_cm = m.props.cm_from_heel;
    let mut loads = Loads::plain(
        l.headwater.force_n - l.tailwater.force_n,
        eccentricity,
        gravity,
    );
    loads.hydraulic_pitch =
        -(l.headwater.force_n * l.headwater.at_m - l.tailwater.force_n * l.tailwater.at_m);
    loads.held_normal = l.uplift.force_n - l.tailwater_weight.force_n;
    loads.held_pitch = l.uplift.force_n * (l.uplift.at_m - x_cm)
        - l.tailwater_weight.force_n * (l.tailwater_weight.at_m - x_cm);
    loads.water = Some(l);
    Ok(loads)
}
