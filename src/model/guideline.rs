//! Load cases and the guideline their required factors of safety come from: US Army Corps of
//! Engineers, EM 1110-2-2100, Stability Analysis of Concrete Structures (2005), Tables 3-2
//! (critical structures) and 3-3 (normal structures) (`derivations/11-dam-loads.md` §5).

use super::names::named;

/// A load combination's category (EM 1110-2-2100, §3-4: usual, unusual, extreme).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Category {
    /// Loads of normal operation.
    Usual,
    /// Loads of rare floods and construction.
    Unusual,
    /// Loads of the maximum design earthquake.
    Extreme,
}

named!(Category, "category", [Usual => "usual", Unusual => "unusual", Extreme => "extreme"]);

/// The structure's class in EM 1110-2-2100 (§3-2): critical (its failure would cost lives)
/// or normal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Structure {
    /// A structure whose failure would not cost lives.
    Normal,
    /// A structure whose failure would cost lives.
    Critical,
}

named!(Structure, "structure", [Normal => "normal", Critical => "critical"]);

/// How well the site is known (EM 1110-2-2100, §3-3): well-defined, ordinary, limited.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum SiteInformation {
    /// Extensive investigation and testing.
    WellDefined,
    /// The usual investigation.
    Ordinary,
    /// Little investigation.
    Limited,
}

named!(
    SiteInformation,
    "site information",
    [WellDefined => "well-defined", Ordinary => "ordinary", Limited => "limited"]
);

/// The table the required sliding factors of safety come from. Default: a normal structure,
/// ordinary site information.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Guideline {
    /// The structure's class.
    pub structure: Structure,
    /// How well the site is known.
    pub site_information: SiteInformation,
    /// The foundation's allowable bearing stress (Pa), if the case's base pressures are to be
    /// checked against one (`[check] allowable_bearing_pa`).
    pub allowable_bearing_pa: Option<f64>,
}

impl Default for Guideline {
    fn default() -> Self {
        Guideline {
            structure: Structure::Normal,
            site_information: SiteInformation::Ordinary,
            allowable_bearing_pa: None,
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
        format!(
            "EM 1110-2-2100, {} structure, {} site information",
            self.structure, self.site_information
        )
    }
}

/// One load combination.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LoadCase {
    /// Its name, for people.
    pub name: String,
    /// Its category.
    pub category: Category,
    /// The factor of safety it requires: its own, or the guideline's for its category.
    pub required_fs: f64,
    /// The scene keys it sets (`water.headwater_m`, `water.tailwater_m`, `seismic.kh`,
    /// `seismic.kv`), in the file's units.
    pub keys: Vec<(String, f64)>,
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
            allowable_bearing_pa: None,
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
        for s in Structure::ALL {
            for i in SiteInformation::ALL {
                let r = Category::ALL.map(|c| g(s, i).required(c));
                assert!(r[0] > r[1] && r[1] >= r[2], "{s:?} {i:?} {r:?}");
                let normal = Category::ALL.map(|c| g(Structure::Normal, i).required(c));
                assert!((0..3).all(|k| r[k] >= normal[k]));
            }
        }
        assert_eq!(
            Guideline::default().describe(),
            "EM 1110-2-2100, normal structure, ordinary site information"
        );
    }
}
