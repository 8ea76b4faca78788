//! Load cases (issue #16): `[check]` names the guideline table, each `[[case]]` a load
//! combination — its category, its own levels and seismic coefficients, and the factor of
//! safety it requires (by default the table's). `crate::check` runs them.

use super::SceneError;
use super::checks::{check, positive};
use super::raw::{RawCase, RawCheck};

/// A load combination's category (EM 1110-2-2100, §3-4: usual, unusual, extreme).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Category {
    Usual,
    Unusual,
    Extreme,
}

impl Category {
    pub const ALL: [Category; 3] = [Category::Usual, Category::Unusual, Category::Extreme];

    pub fn as_str(self) -> &'static str {
        match self {
            Category::Usual => "usual",
            Category::Unusual => "unusual",
            Category::Extreme => "extreme",
        }
    }
}

/// The structure's class in EM 1110-2-2100 (§3-2): critical (its failure would cost lives)
/// or normal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Structure {
    Normal,
    Critical,
}

/// How well the site is known (EM 1110-2-2100, §3-3): well-defined, ordinary, limited.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SiteInformation {
    WellDefined,
    Ordinary,
    Limited,
}

/// The table the required sliding factors of safety come from: US Army Corps of Engineers,
/// EM 1110-2-2100, Stability Analysis of Concrete Structures (2005), Table 3-2 (critical
/// structures) and Table 3-3 (normal structures). Default: a normal structure, ordinary site
/// information.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Guideline {
    pub structure: Structure,
    pub site_information: SiteInformation,
}

impl Default for Guideline {
    fn default() -> Self {
        Guideline {
            structure: Structure::Normal,
            site_information: SiteInformation::Ordinary,
        }
    }
}

impl Guideline {
    /// The sliding factor of safety the table requires of a load combination of `category`.
    pub fn required(&self, category: Category) -> f64 {
        use SiteInformation::*;
        let row = match (self.structure, self.site_information) {
            (Structure::Critical, WellDefined) => [1.7, 1.3, 1.1],
            (Structure::Critical, Ordinary) => [2.0, 1.5, 1.1],
            (Structure::Critical, Limited) => [3.0, 2.0, 1.3],
            (Structure::Normal, WellDefined) => [1.4, 1.2, 1.1],
            (Structure::Normal, Ordinary) => [1.5, 1.3, 1.1],
            (Structure::Normal, Limited) => [2.0, 1.7, 1.3],
        };
        row[category as usize]
    }

    /// "EM 1110-2-2100, normal structure, ordinary site information".
    pub fn describe(&self) -> String {
        let structure = match self.structure {
            Structure::Normal => "normal",
            Structure::Critical => "critical",
        };
        let site = match self.site_information {
            SiteInformation::WellDefined => "well-defined",
            SiteInformation::Ordinary => "ordinary",
            SiteInformation::Limited => "limited",
        };
        format!("EM 1110-2-2100, {structure} structure, {site} site information")
    }
}

/// One load combination.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LoadCase {
    pub name: String,
    pub category: Category,
    /// The factor of safety it requires: `required_fs`, or the guideline's for its category.
    pub required_fs: f64,
    /// The scene keys it sets (`water.headwater_m`, `water.tailwater_m`, `seismic.kh`,
    /// `seismic.kv`), in the file's units.
    pub keys: Vec<(String, f64)>,
}

pub(super) fn guideline(o: &str, c: &RawCheck) -> Result<Guideline, SceneError> {
    let structure = match c.structure.as_deref() {
        None | Some("normal") => Structure::Normal,
        Some("critical") => Structure::Critical,
        Some(other) => {
            return Err(SceneError::new(
                o,
                "check.structure",
                format!("unknown structure \"{other}\"; expected one of \"normal\", \"critical\""),
            ));
        }
    };
    let site_information = match c.site_information.as_deref() {
        None | Some("ordinary") => SiteInformation::Ordinary,
        Some("well-defined") => SiteInformation::WellDefined,
        Some("limited") => SiteInformation::Limited,
        Some(other) => {
            return Err(SceneError::new(
                o,
                "check.site_information",
                format!(
                    "unknown site information \"{other}\"; expected one of \"well-defined\", \
                     \"ordinary\", \"limited\""
                ),
            ));
        }
    };
    Ok(Guideline {
        structure,
        site_information,
    })
}

pub(super) fn cases(o: &str, g: &Guideline, raw: &[RawCase]) -> Result<Vec<LoadCase>, SceneError> {
    raw.iter()
        .enumerate()
        .map(|(k, c)| {
            let key = |name: &str| format!("case[{k}].{name}");
            let category = match c.category.as_deref() {
                None | Some("usual") => Category::Usual,
                Some("unusual") => Category::Unusual,
                Some("extreme") => Category::Extreme,
                Some(other) => {
                    return Err(SceneError::new(
                        o,
                        key("category"),
                        format!(
                            "unknown category \"{other}\"; expected one of \"usual\", \
                             \"unusual\", \"extreme\""
                        ),
                    ));
                }
            };
            let required_fs = match c.required_fs {
                Some(v) => positive(o, &key("required_fs"), v)?,
                None => g.required(category),
            };
            let mut keys = Vec::new();
            for (name, scene_key, v) in [
                ("headwater_m", "water.headwater_m", c.headwater_m),
                ("tailwater_m", "water.tailwater_m", c.tailwater_m),
                ("kh", "seismic.kh", c.kh),
                ("kv", "seismic.kv", c.kv),
            ] {
                if let Some(v) = v {
                    check(o, &key(name), v, true, "finite")?;
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_guideline_tables_rise_with_the_stakes_and_fall_with_the_load_s_rarity() {
        // EM 1110-2-2100 Tables 3-2 and 3-3: a critical structure or less site information asks
        // more; an unusual or extreme combination less.
        let g = |structure, site_information| Guideline {
            structure,
            site_information,
        };
        assert_eq!(Guideline::default().required(Category::Usual), 1.5);
        assert_eq!(
            g(Structure::Critical, SiteInformation::Limited).required(Category::Usual),
            3.0
        );
        assert_eq!(
            g(Structure::Normal, SiteInformation::WellDefined).required(Category::Extreme),
            1.1
        );
        for s in [Structure::Normal, Structure::Critical] {
            for i in [
                SiteInformation::WellDefined,
                SiteInformation::Ordinary,
                SiteInformation::Limited,
            ] {
                let r = Category::ALL.map(|c| g(s, i).required(c));
                assert!(r[0] > r[1] && r[1] >= r[2], "{s:?} {i:?} {r:?}");
                let normal = Category::ALL.map(|c| g(Structure::Normal, i).required(c));
                assert!((0..3).all(|k| r[k] >= normal[k]));
            }
        }
    }
}
