//! `[check]`, `[[case]]` and `[uncertain]`: the guideline and the load combinations a check
//! runs, and the distributions of a probabilistic analysis.

use super::Reader;
use crate::model::{Category, Guideline, LoadCase, SiteInformation, Structure};
use crate::numeric::{Distribution, Uncertain};
use crate::scene::SceneError;
use crate::scene::raw::{RawCase, RawCheck};
use std::collections::BTreeMap;

impl Reader<'_> {
    /// `[check]`: the structure's class and the site information (a normal structure, ordinary
    /// site information, when not given).
    pub(super) fn guideline(&self, c: &RawCheck) -> Result<Guideline, SceneError> {
        let structure = match c.structure.as_deref() {
            None => Structure::Normal,
            Some(w) => self.named("check.structure", w)?,
        };
        let site_information = match c.site_information.as_deref() {
            None => SiteInformation::Ordinary,
            Some(w) => self.named("check.site_information", w)?,
        };
        let allowable_bearing_pa = c
            .allowable_bearing_pa
            .map(|v| {
                crate::model::check(
                    "check.allowable_bearing_pa",
                    v,
                    v.is_finite() && v > 0.0,
                    "a positive stress (Pa)",
                )
                .map_err(|e| self.model(e))
            })
            .transpose()?;
        Ok(Guideline {
            structure,
            site_information,
            allowable_bearing_pa,
        })
    }

    /// `[[case]]`: each combination's category (usual by default), the factor of safety it
    /// requires (the guideline's for its category by default) and the keys it sets.
    pub(super) fn cases(
        &self,
        g: &Guideline,
        raw: &[RawCase],
    ) -> Result<Vec<LoadCase>, SceneError> {
        raw.iter()
            .enumerate()
            .map(|(k, c)| {
                let key = |name: &str| format!("case[{k}].{name}");
                let category = match c.category.as_deref() {
                    None => Category::Usual,
                    Some(w) => self.named(&key("category"), w)?,
                };
                let required_fs = match c.required_fs {
                    Some(v) => self.positive(&key("required_fs"), v)?,
                    None => g.required(category),
                };
                let mut keys = Vec::new();
                for (name, scene_key, v) in [
                    ("headwater_m", "water.headwater_m", c.headwater_m),
                    ("tailwater_m", "water.tailwater_m", c.tailwater_m),
                    ("kh", "seismic.kh", c.kh),
                    ("kv", "seismic.kv", c.kv),
                    (
                        "drain_efficiency",
                        "water.drain_efficiency",
                        c.drain_efficiency,
                    ),
                    ("silt_depth_m", "silt.depth_m", c.silt_depth_m),
                    ("ice_force_n_m", "ice.force_n_m", c.ice_force_n_m),
                ] {
                    if let Some(v) = v {
                        self.finite(&key(name), v)?;
                        keys.push((scene_key.to_string(), v));
                    }
                }
                Ok(LoadCase {
                    name: c.name.clone().unwrap_or_else(|| format!("case {k}")),
                    category,
                    required_fs,
                    keys,
                })
            })
            .collect()
    }

    /// `[uncertain]`: each `"section.key" = "name:p1:p2…"` read as a distribution, in the order
    /// of the keys' names (so that a design's columns do not depend on how the file was
    /// written). Whether each key is a number of the scene is asked where the samples are run.
    pub(super) fn uncertain(
        &self,
        table: Option<&BTreeMap<String, String>>,
    ) -> Result<Vec<Uncertain>, SceneError> {
        let Some(table) = table else {
            return Ok(vec![]);
        };
        table
            .iter()
            .map(|(key, spec)| {
                let at = format!("uncertain.\"{key}\"");
                if !key.contains('.') || key.starts_with("uncertain.") {
                    return Err(self.invalid(
                        at,
                        "name a number of the scene as \"section.key\", e.g. \"friction.mu_k\"",
                    ));
                }
                Distribution::parse(spec)
                    .map(|distribution| Uncertain {
                        key: key.clone(),
                        distribution,
                    })
                    .map_err(|e| self.invalid(at, e))
            })
            .collect()
    }
}
