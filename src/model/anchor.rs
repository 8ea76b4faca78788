//! Post-tensioned rock anchors through a monolith into its foundation (`[[anchor]]`;
//! `derivations/11-dam-loads.md` §10): where each is, which way it runs into the rock, and the
//! tendon's prestress, capacity and stiffness. The gravity method takes each at its prestress;
//! the route lets it stretch with the block's motion and break at its capacity.

use super::error::{ModelError, check, non_negative, positive};
use super::monolith::{Monolith, Section};
use crate::geometry::LocalFrame;
use nalgebra::Vector3;

/// The modulus of prestressing steel when `[[anchor]]` gives none (Pa): seven-wire strand,
/// 195 GPa (ASTM A416's typical value; bars are about 200 GPa).
pub const STRAND_MODULUS_PA: f64 = 195.0e9;

/// The longest free length taken (m): a rock anchor's is tens of metres; beyond this the
/// tendon's geometry is lost in round-off against its length.
pub const MAX_FREE_LENGTH_M: f64 = 1.0e4;

/// One post-tensioned anchor (SI units, radians).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct RockAnchor {
    /// The head, where the tendon bears on the monolith: x′ from the heel, y′ above the base,
    /// z′ across from the middle of the width (m).
    pub head: [f64; 3],
    /// The plunge: the tendon's angle below the base's plane (x′z′), from the head into the
    /// rock (rad; π/2 along −y′, vertical on a level base; the section stands on its base).
    pub plunge: f64,
    /// The trend of its horizontal part, from the head into the rock: from x′ (downstream)
    /// towards z′ (rad; π points upstream).
    pub trend: f64,
    /// The prestress locked off in the tendon (N).
    pub prestress: f64,
    /// The force at which the tendon breaks (N), more than the prestress.
    pub capacity: f64,
    /// The free (unbonded) length from the head to the bond in the rock (m): the length that
    /// stretches.
    pub free_length: f64,
    /// The steel's cross-section (m²).
    pub steel_area: f64,
    /// The steel's modulus (Pa).
    pub modulus: f64,
}

impl RockAnchor {
    /// The unit vector from the head into the rock in the block's axes (x′, y′, z′).
    pub fn direction(&self) -> Vector3<f64> {
        let (sp, cp) = self.plunge.sin_cos();
        let (st, ct) = self.trend.sin_cos();
        Vector3::new(cp * ct, -sp, cp * st)
    }

    /// The tendon's axial stiffness E A / L (N/m).
    pub fn stiffness(&self) -> f64 {
        self.modulus * self.steel_area / self.free_length
    }

    /// The tendon's force (N) where its free length is `length` (m): the prestress and the
    /// stiffness times the stretch, none where it would be slack.
    pub fn force_at_length(&self, length: f64) -> f64 {
        (self.prestress + self.stiffness() * (length - self.free_length)).max(0.0)
    }

    /// The anchor on `section`, the `k`th of `[[anchor]]`: its head in the section (on or
    /// inside its outline, across the width), pointing down into the rock, its free length
    /// reaching at least the base, a prestress under its capacity. The errors name the key.
    pub fn check(&self, k: usize, section: &Section) -> Result<(), ModelError> {
        let key = |name: &str| format!("anchor[{k}].{name}");
        let [x, y, z] = self.head;
        let (b, h, c, w) = (
            section.base_length,
            section.height,
            section.crest_length,
            section.width,
        );
        check(
            &key("y_m"),
            y,
            (0.0..=h).contains(&y),
            &format!("in the section, from 0 (the base) to {h} m (the crest)"),
        )?;
        // The downstream face at height y: from the toe (b, 0) to the crest's edge (c, h).
        let face = b + (c - b) * y / h;
        check(
            &key("x_m"),
            x,
            (0.0..=face * (1.0 + 1e-12)).contains(&x),
            &format!(
                "in the section, from the heel (0) to the downstream face ({face} m at \
                 y = {y} m)"
            ),
        )?;
        check(
            &key("z_m"),
            z,
            z.abs() <= w / 2.0,
            &format!("across the width, from {} to {} m", -w / 2.0, w / 2.0),
        )?;
        let plunge = self.plunge.to_degrees();
        check(
            &key("plunge_deg"),
            plunge,
            plunge > 0.0 && plunge <= 90.0,
            "above 0 and at most 90° (the tendon runs down into the rock)",
        )?;
        check(&key("trend_deg"), self.trend.to_degrees(), true, "finite")?;
        let p = non_negative(&key("prestress_n"), self.prestress)?;
        check(
            &key("capacity_n"),
            self.capacity,
            self.capacity > p,
            &format!("more than the prestress ({p} N)"),
        )?;
        let reach = y / self.plunge.sin();
        check(
            &key("free_length_m"),
            self.free_length,
            self.free_length >= reach * (1.0 - 1e-12)
                && self.free_length > 0.0
                && self.free_length <= MAX_FREE_LENGTH_M,
            &format!(
                "positive, at least the tendon's length through the monolith ({reach} m from the \
                 head down to the base) and at most {MAX_FREE_LENGTH_M} m"
            ),
        )?;
        positive(&key("steel_area_m2"), self.steel_area)?;
        positive(&key("modulus_pa"), self.modulus)?;
        let k = self.stiffness();
        check(
            &key("steel_area_m2"),
            self.steel_area,
            k.is_normal(),
            &format!(
                "such that the tendon's stiffness E A / L is a usable number (E {} Pa, L {} m \
                 give {k:e} N/m)",
                self.modulus, self.free_length
            ),
        )?;
        Ok(())
    }
}

/// An anchor as a route follows it: its head about the base point under the centre of mass,
/// in the block's axes, the bond in the rock once the route has fixed it, and whether it has
/// broken.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tendon {
    /// The anchor as given.
    pub anchor: RockAnchor,
    /// Its head from the base point under the centre of mass, in the block's axes (m).
    pub head: Vector3<f64>,
    /// Where its free length ends in the rock (global, m): fixed at the pose the route starts
    /// from; `None` before, when the tendon pulls its prestress along its own direction.
    pub rock: Option<Vector3<f64>>,
    /// Broken at its capacity: it pulls no more.
    pub broken: bool,
}

impl Tendon {
    /// The anchor on `monolith`, not yet fixed in the rock.
    pub fn on(monolith: &Monolith, anchor: RockAnchor) -> Tendon {
        let [x, y, z] = anchor.head;
        Tendon {
            anchor,
            head: Vector3::new(x - monolith.props.cm_from_heel, y, z),
            rock: None,
            broken: false,
        }
    }

    /// The head's place (global, m) where the base point under the centre of mass is at
    /// `origin` and the block's axes are `frame`.
    pub fn head_at(&self, origin: &Vector3<f64>, frame: &LocalFrame) -> Vector3<f64> {
        origin + frame.i * self.head.x + frame.j * self.head.y + frame.k * self.head.z
    }

    /// Fixed in the rock where the block is at (`origin`, `frame`): the free length along the
    /// anchor's direction from the head.
    #[must_use]
    pub fn fixed_at(self, origin: &Vector3<f64>, frame: &LocalFrame) -> Tendon {
        let d = self.anchor.direction();
        let along = frame.i * d.x + frame.j * d.y + frame.k * d.z;
        Tendon {
            rock: Some(self.head_at(origin, frame) + along * self.anchor.free_length),
            ..self
        }
    }

    /// The tendon's force (N) with the block at (`origin`, `frame`): its prestress where it is
    /// not yet fixed, else the prestress and E A / L times the stretch of the head's distance
    /// to the bond (`derivations/11-dam-loads.md` §10); none when broken or slack.
    pub fn tension(&self, origin: &Vector3<f64>, frame: &LocalFrame) -> f64 {
        match (self.broken, self.rock) {
            (true, _) => 0.0,
            (false, None) => self.anchor.prestress,
            (false, Some(rock)) => self
                .anchor
                .force_at_length((rock - self.head_at(origin, frame)).norm()),
        }
    }

    /// Whether the tendon, whole, pulls more than its capacity, by more than `margin` (a
    /// fraction of it, negative for less), with the block at (`origin`, `frame`): it breaks.
    pub fn past_capacity(&self, origin: &Vector3<f64>, frame: &LocalFrame, margin: f64) -> bool {
        !self.broken && self.tension(origin, frame) > self.anchor.capacity * (1.0 + margin)
    }

    /// The pull on the block at (`origin`, `frame`): the arm from `origin` to the head and the
    /// force (N) along the tendon towards the rock.
    pub fn pull(&self, origin: &Vector3<f64>, frame: &LocalFrame) -> (Vector3<f64>, Vector3<f64>) {
        let head = self.head_at(origin, frame);
        let tension = self.tension(origin, frame);
        if !tension.is_finite() {
            return (head - origin, Vector3::zeros());
        }
        let toward = match self.rock {
            // A head on its bond (a tendon of no length) pulls no way.
            Some(rock) => (rock - head)
                .try_normalize(f64::MIN_POSITIVE)
                .unwrap_or_else(Vector3::zeros),
            None => {
                let d = self.anchor.direction();
                frame.i * d.x + frame.j * d.y + frame.k * d.z
            }
        };
        (head - origin, toward * tension)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn section() -> Section {
        Section {
            base_length: 20.0,
            width: 10.0,
            height: 15.0,
            crest_length: 5.0,
            density: 2400.0,
        }
    }

    fn vertical(x: f64, y: f64) -> RockAnchor {
        RockAnchor {
            head: [x, y, 0.0],
            plunge: std::f64::consts::FRAC_PI_2,
            trend: 0.0,
            prestress: 1.0e6,
            capacity: 2.0e6,
            free_length: 20.0,
            steel_area: 1.0e-3,
            modulus: 2.0e11,
        }
    }

    #[test]
    fn a_vertical_anchor_pulls_straight_down_and_one_trending_upstream_pulls_upstream() {
        let d = vertical(1.0, 15.0).direction();
        assert!((d - Vector3::new(0.0, -1.0, 0.0)).norm() < 1e-15);
        let a = RockAnchor {
            plunge: 60f64.to_radians(),
            trend: std::f64::consts::PI,
            ..vertical(1.0, 15.0)
        };
        let d = a.direction();
        assert!((d - Vector3::new(-0.5, -(3f64.sqrt()) / 2.0, 0.0)).norm() < 1e-15);
    }

    #[test]
    fn the_tendon_pulls_its_prestress_plus_ea_over_l_times_the_stretch_and_never_pushes() {
        let a = vertical(1.0, 15.0);
        // E A / L = 2e11 · 1e-3 / 20 = 1e7 N/m.
        assert_eq!(a.stiffness(), 1.0e7);
        assert!((a.force_at_length(20.01) - 1.1e6).abs() < 1e-6);
        assert_eq!(a.force_at_length(19.0), 0.0);
    }

    #[test]
    fn an_anchor_outside_the_section_or_too_short_or_over_its_capacity_is_refused_by_key() {
        let s = section();
        assert!(vertical(1.0, 15.0).check(0, &s).is_ok());
        // At 15 m the section runs from the heel to the crest's edge, 5 m.
        let e = vertical(6.0, 15.0).check(2, &s).unwrap_err();
        assert_eq!(e.key, "anchor[2].x_m");
        let e = vertical(1.0, 16.0).check(0, &s).unwrap_err();
        assert_eq!(e.key, "anchor[0].y_m");
        let short = RockAnchor {
            free_length: 14.0,
            ..vertical(1.0, 15.0)
        };
        assert_eq!(
            short.check(0, &s).unwrap_err().key,
            "anchor[0].free_length_m"
        );
        let over = RockAnchor {
            capacity: 1.0e6,
            ..vertical(1.0, 15.0)
        };
        assert_eq!(over.check(0, &s).unwrap_err().key, "anchor[0].capacity_n");
        let up = RockAnchor {
            plunge: -0.1,
            ..vertical(1.0, 15.0)
        };
        assert_eq!(up.check(0, &s).unwrap_err().key, "anchor[0].plunge_deg");
    }
}
