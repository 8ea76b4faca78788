//! The loads on the block (`derivations/11-dam-loads.md`): the water's push and its couples,
//! the weight, the uplift and the tailwater's weight, the pseudo-static forces of an earthquake.

use super::error::{ModelError, check, finite, non_negative, positive};
use super::monolith::Monolith;
use super::water::{Levels, WaterLoads, water_loads};

/// The loads. The driving ones — the water's push and its couples, the horizontal
/// pseudo-static force — are those the factor of safety scales; the weight, the uplift, the
/// tailwater's weight and the vertical pseudo-static force stay.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Loads {
    /// |F| (N), acting along x': `loads.hydraulic_force_n`, or from `[water]` the reservoir's
    /// push less the tailwater's.
    pub hydraulic_force: f64,
    /// c (m): F's line misses the CM by c; c > 0 turns the block so that θ grows.
    pub eccentricity: f64,
    /// g (m/s²).
    pub gravity: f64,
    /// The moment of the water's pushes about the base point under the CM, along k' (N·m):
    /// −Σ H y over the pushes at heights y above the base. 0 for a force in the base plane
    /// (the paper's).
    pub hydraulic_pitch: f64,
    /// The loads that stay, other than the weight, in the block's axes: the uplift less the
    /// tailwater's weight on the downstream face, along y' (N).
    pub held_normal: f64,
    /// Their moment along k' about the base point under the CM (N·m).
    pub held_pitch: f64,
    /// Horizontal pseudo-static coefficient (a fraction of g) along +X (downstream).
    pub kh: f64,
    /// Vertical pseudo-static coefficient (a fraction of g), up.
    pub kv: f64,
    /// The CM's height above the base plane (m), where the weight and the pseudo-static forces
    /// act: a monolith's; 0 for the paper's block (CM in the base plane).
    pub cm_height: f64,
    /// The water's loads from levels, where they come from levels.
    pub water: Option<WaterLoads>,
}

impl Loads {
    /// A force F (N) in the base plane along x′ whose line misses the CM by c (m), and gravity
    /// g (m/s²): the paper's loads.
    pub fn plain(hydraulic_force: f64, eccentricity: f64, gravity: f64) -> Loads {
        Loads {
            hydraulic_force,
            eccentricity,
            gravity,
            hydraulic_pitch: 0.0,
            held_normal: 0.0,
            held_pitch: 0.0,
            kh: 0.0,
            kv: 0.0,
            cm_height: 0.0,
            water: None,
        }
    }

    /// The water's loads on `monolith` from `levels`: the net push along x′ with its line `c`
    /// (m) off the CM, the pitch of the pushes about the base point under the centre of mass,
    /// and the uplift less the tailwater's weight with its pitch (`derivations/11-dam-loads.md`
    /// §2); the CM at the monolith's height. g in m/s².
    pub fn from_water(
        monolith: &Monolith,
        levels: &Levels,
        eccentricity: f64,
        gravity: f64,
    ) -> Loads {
        let l = water_loads(&monolith.section, levels, gravity);
        let x_cm = monolith.props.cm_from_heel;
        Loads {
            hydraulic_pitch: -(l.headwater.force_n * l.headwater.at_m
                - l.tailwater.force_n * l.tailwater.at_m
                + l.silt.force_n * l.silt.at_m
                + l.ice.force_n * l.ice.at_m),
            held_normal: l.uplift.force_n - l.tailwater_weight.force_n,
            held_pitch: l.uplift.force_n * (l.uplift.at_m - x_cm)
                - l.tailwater_weight.force_n * (l.tailwater_weight.at_m - x_cm),
            water: Some(l),
            ..Loads::plain(
                l.headwater.force_n - l.tailwater.force_n + l.silt.force_n + l.ice.force_n,
                eccentricity,
                gravity,
            )
        }
        .at_height(monolith.props.cm_height)
    }

    /// The same loads with pseudo-static coefficients k_h (downstream) and k_v (up), fractions
    /// of g.
    #[must_use]
    pub fn with_pseudo_static(self, kh: f64, kv: f64) -> Loads {
        Loads { kh, kv, ..self }
    }

    /// The same loads on a block whose CM stands `cm_height` (m) above its base.
    #[must_use]
    pub fn at_height(self, cm_height: f64) -> Loads {
        Loads { cm_height, ..self }
    }

    /// Each load finite and in its range: F zero or more, g positive, the pseudo-static
    /// coefficients below 1 in size, the CM's height zero or more.
    pub fn check(&self) -> Result<(), ModelError> {
        finite("loads.eccentricity_m", self.eccentricity)?;
        positive("loads.gravity_m_s2", self.gravity)?;
        non_negative("loads.hydraulic_force_n", self.hydraulic_force)?;
        for (key, v) in [("seismic.kh", self.kh), ("seismic.kv", self.kv)] {
            check(key, v, v.abs() < 1.0, "a fraction of g between −1 and 1")?;
        }
        non_negative(
            "monolith.height_m (the centre of mass's height)",
            self.cm_height,
        )?;
        finite("water (the pushes' pitch)", self.hydraulic_pitch)?;
        finite("water (the uplift)", self.held_normal)?;
        finite("water (the uplift's pitch)", self.held_pitch)?;
        Ok(())
    }
}
