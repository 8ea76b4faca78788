//! The water on a monolith from its levels (`derivations/11-dam-loads.md` §2): the reservoir's
//! and the tailwater's pushes, the tailwater's weight on the sloping downstream face, and the
//! uplift on the base with or without drains. Positions are from the heel along x′ and from the
//! base along y′.

use super::error::{ModelError, check, non_negative, positive};
use super::monolith::Section;

/// Reservoir and tailwater levels, and the drains (`[water]`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Levels {
    /// H1: the reservoir's surface above the base at the heel (m).
    pub headwater: f64,
    /// H2: the tailwater's surface above the base at the toe (m).
    pub tailwater: f64,
    /// ρ_w (kg/m³).
    pub density: f64,
    /// E: the drains' efficiency, 0 (none) … 1.
    pub drain_efficiency: f64,
    /// X: the line of drains from the heel along x′ (m).
    pub drain_position: f64,
    /// Whether the guideline's analysis lets the base crack where it would be in tension, the
    /// reservoir's full head entering the crack (`[water] crack`, true by default; the route's
    /// uplift is the uncracked base's).
    pub crack: bool,
    /// The reservoir's sediment against the upstream face, if any.
    pub silt: Option<Silt>,
    /// An ice sheet's thrust, if any.
    pub ice: Option<Ice>,
}

/// Sediment against the upstream face (`[silt]`): its depth above the base (m), its submerged
/// unit weight γ′ (N/m³) and its friction angle φ (rad). It pushes at rest, K0 = 1 − sin φ:
/// ½ K0 γ′ d² w at d/3 (the water over it is the reservoir's own push).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Silt {
    /// d (m).
    pub depth: f64,
    /// γ′ (N/m³).
    pub unit_weight: f64,
    /// φ (rad).
    pub friction_angle: f64,
}

/// An ice sheet's thrust on the upstream face (`[ice]`): a force per metre of the monolith's
/// width (N/m) at its height above the base (m).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Ice {
    /// N/m of width.
    pub force_per_m: f64,
    /// Its height above the base (m).
    pub elevation: f64,
}

impl Levels {
    /// Levels on `section`: none negative, the headwater at most the crest (the loads of water
    /// over the crest are not the guideline's: an overtopped monolith needs the nappe's), the
    /// tailwater at most the headwater (the water pushes the monolith downstream), a positive
    /// density, drains' efficiency from 0 to 1 and their line within the base.
    pub fn check(&self, section: &Section) -> Result<(), ModelError> {
        let headwater = non_negative("water.headwater_m", self.headwater)?;
        if headwater > section.height {
            return Err(ModelError::new(
                "water.headwater_m",
                format!(
                    "must be at most the crest, the monolith's height ({} m), got {} m \
                     (water over the crest pushes and lifts as a nappe, which the guideline's \
                     loads are not)",
                    crate::numeric::given(section.height),
                    crate::numeric::given(headwater)
                ),
            ));
        }
        let tailwater = non_negative("water.tailwater_m", self.tailwater)?;
        if tailwater > headwater {
            return Err(ModelError::new(
                "water.tailwater_m",
                format!(
                    "must be at most the headwater ({} m), got {} m (the water \
                     pushes the monolith downstream)",
                    crate::numeric::given(headwater),
                    crate::numeric::given(tailwater)
                ),
            ));
        }
        if tailwater > section.height {
            return Err(ModelError::new(
                "water.tailwater_m",
                format!(
                    "must be at most the monolith's height ({} m), got {} m",
                    crate::numeric::given(section.height),
                    crate::numeric::given(tailwater)
                ),
            ));
        }
        positive("water.density_kg_m3", self.density)?;
        let e = self.drain_efficiency;
        check(
            "water.drain_efficiency",
            e,
            (0.0..=1.0).contains(&e),
            "between 0 and 1",
        )?;
        let (x, b) = (self.drain_position, section.base_length);
        if e > 0.0 || x != 0.0 {
            check(
                "water.drain_position_m",
                x,
                x > 0.0 && x < b,
                &format!("within the base, between 0 and {b} m from the heel"),
            )?;
        }
        if let Some(s) = &self.silt {
            let d = non_negative("silt.depth_m", s.depth)?;
            check(
                "silt.depth_m",
                d,
                d <= headwater.min(section.height),
                &format!(
                    "at most the headwater and the monolith's height ({} m): silt lies under the \
                     reservoir",
                    headwater.min(section.height)
                ),
            )?;
            positive("silt.unit_weight_n_m3", s.unit_weight)?;
            let phi = s.friction_angle.to_degrees();
            check(
                "silt.friction_angle_deg",
                phi,
                (0.0..90.0).contains(&phi),
                "from 0 to under 90°",
            )?;
        }
        if let Some(i) = &self.ice {
            non_negative("ice.force_n_m", i.force_per_m)?;
            check(
                "ice.elevation_m",
                i.elevation,
                i.elevation >= 0.0 && i.elevation <= section.height,
                &format!(
                    "on the upstream face, from 0 to {} m above the base",
                    crate::numeric::given(section.height)
                ),
            )?;
        }
        Ok(())
    }
}

/// A force in the section's plane and where its line meets the base or the height.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Resultant {
    /// Its size (N).
    pub force_n: f64,
    /// Where it acts: the height above the base of a horizontal force, the distance from the
    /// heel of a vertical one (m).
    pub at_m: f64,
}

/// The water's loads on a monolith from its levels (`derivations/11-dam-loads.md` §2).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct WaterLoads {
    /// The reservoir's push on the upstream face, along +x′, at its height above the base.
    pub headwater: Resultant,
    /// The tailwater's push on the downstream face, along −x′, at its height above the base.
    pub tailwater: Resultant,
    /// The tailwater's weight on the sloping downstream face, along −y′, at its distance from
    /// the heel.
    pub tailwater_weight: Resultant,
    /// Uplift on the base, along +y′, at its distance from the heel.
    pub uplift: Resultant,
    /// The silt's push on the upstream face, along +x′, at its height (zero without silt).
    pub silt: Resultant,
    /// The ice's thrust, along +x′, at its height (zero without ice).
    pub ice: Resultant,
    /// The uplift head at the line of drains (m; the linear head there without drains).
    pub drain_head_m: f64,
    /// The levels these come from.
    #[serde(skip)]
    pub levels: Levels,
}

/// The water's loads from levels, g the gravity (m/s²):
///
/// * the reservoir on the vertical upstream face: the pressure ρ g (H1 − y) over 0 ≤ y ≤
///   min(H1, h) — ½ ρ g H1² w at H1/3 for a reservoir below the crest;
/// * the tailwater on the downstream face of slope s = (b − c)/h horizontal per vertical:
///   ½ ρ g H2² w along −x′ at H2/3, and the water above the face, ½ ρ g H2² s w, along −y′ at
///   b − s H2/3 from the heel (H2 ≤ h);
/// * uplift on the base: the head falls linearly from H1 at the heel to H2 at the toe; with
///   drains of efficiency E at X from the heel it falls linearly from H1 to
///   H3 = H2 + (1 − E)(H1 − H2)(b − X)/b at the drains, then linearly to H2 at the toe — the
///   US Army Corps of Engineers' rule for drains near the heel, EM 1110-2-2100 (Stability
///   Analysis of Concrete Structures, 2005), chapter 3. E = 0 gives the linear distribution.
pub fn water_loads(section: &Section, levels: &Levels, g: f64) -> WaterLoads {
    water_loads_cracked(section, levels, g, 0.0)
}

/// The uplift head along the base (m of water) as a polyline of (x from the heel, head), heel
/// to toe, with the base cracked from the heel over `crack` (m; the rules of
/// `water_loads_cracked`), and the head at the line of drains (the linear head there without
/// them, or past the crack).
pub fn uplift_heads(section: &Section, levels: &Levels, crack: f64) -> (Vec<[f64; 2]>, f64) {
    let b = section.base_length;
    let (h1, h2) = (levels.headwater, levels.tailwater);
    let t = crack.clamp(0.0, b);
    let linear = |x: f64| {
        if b > t {
            h1 + (h2 - h1) * (x - t).max(0.0) / (b - t)
        } else {
            h1
        }
    };
    let x_d = levels.drain_position;
    let drained = levels.drain_efficiency > 0.0 && x_d > t;
    let h3 = if drained {
        h2 + (1.0 - levels.drain_efficiency) * (h1 - h2) * (b - x_d) / (b - t)
    } else {
        linear(x_d)
    };
    let mut points: Vec<[f64; 2]> = vec![[0.0, h1]];
    if t > 0.0 {
        points.push([t, h1]);
    }
    if drained {
        points.push([x_d, h3]);
    }
    points.push([b, h2]);
    (points, h3)
}

/// [`water_loads`] with the base cracked from the heel over `crack` (m, 0 ≤ crack < b): the
/// reservoir's full head H1 in the crack, then, from its tip T, the head falls as on an
/// uncracked base of length b − T: linearly to H2 at the toe where there are no drains or the
/// crack reaches past them (they no longer relieve it), else to H3 = H2 + (1 − E)(H1 − H2)
/// (b − X)/(b − T) at the drains and on to H2 — the US Army Corps of Engineers' rules for a
/// cracked base (EM 1110-2-2100 chapter 3; `derivations/11-dam-loads.md` §9). T = 0 is the
/// uncracked base.
pub fn water_loads_cracked(section: &Section, levels: &Levels, g: f64, crack: f64) -> WaterLoads {
    let (b, w, h) = (section.base_length, section.width, section.height);
    let gamma = levels.density * g;
    // The reservoir: ∫_0^a (H1 − y) dy and ∫_0^a y (H1 − y) dy with a = min(H1, h).
    let h1 = levels.headwater;
    let a = h1.min(h);
    let push = h1 * a - a * a / 2.0;
    let moment = h1 * a * a / 2.0 - a * a * a / 3.0;
    let headwater = Resultant {
        force_n: gamma * w * push,
        at_m: if push > 0.0 { moment / push } else { 0.0 },
    };
    let h2 = levels.tailwater.min(h);
    let slope = (b - section.crest_length) / h;
    let tailwater = Resultant {
        force_n: gamma * w * h2 * h2 / 2.0,
        at_m: h2 / 3.0,
    };
    let tailwater_weight = Resultant {
        force_n: gamma * w * h2 * h2 * slope / 2.0,
        at_m: b - slope * h2 / 3.0,
    };
    // Uplift: the head along the base as a polyline of (x, head), integrated piece by piece.
    let (points, h3) = uplift_heads(section, levels, crack);
    let (mut area, mut first) = (0.0, 0.0);
    for pair in points.windows(2) {
        let ([x0, p0], [x1, p1]) = (pair[0], pair[1]);
        let dx = x1 - x0;
        area += dx * (p0 + p1) / 2.0;
        // ∫ x p dx over a trapezoid.
        first += dx * (p0 * (2.0 * x0 + x1) + p1 * (x0 + 2.0 * x1)) / 6.0;
    }
    let uplift = Resultant {
        force_n: gamma * w * area,
        at_m: if area > 0.0 { first / area } else { b / 2.0 },
    };
    let silt = levels.silt.map_or(
        Resultant {
            force_n: 0.0,
            at_m: 0.0,
        },
        |s| Resultant {
            force_n: 0.5 * (1.0 - s.friction_angle.sin()) * s.unit_weight * s.depth * s.depth * w,
            at_m: s.depth / 3.0,
        },
    );
    let ice = levels.ice.map_or(
        Resultant {
            force_n: 0.0,
            at_m: 0.0,
        },
        |i| Resultant {
            force_n: i.force_per_m * w,
            at_m: i.elevation,
        },
    );
    WaterLoads {
        headwater,
        tailwater,
        tailwater_weight,
        uplift,
        silt,
        ice,
        drain_head_m: h3,
        levels: *levels,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::monolith::tests::section;

    fn levels(head: f64, tail: f64, e: f64) -> Levels {
        Levels {
            headwater: head,
            tailwater: tail,
            density: 1000.0,
            drain_efficiency: e,
            drain_position: 2.0,
            crack: false,
            silt: None,
            ice: None,
        }
    }

    #[test]
    fn the_reservoir_pushes_half_rho_g_h_squared_at_a_third_of_its_depth() {
        let s = section();
        let l = water_loads(&s, &levels(12.0, 0.0, 0.0), 9.81);
        let want = 0.5 * 1000.0 * 9.81 * 144.0 * 10.0;
        assert!((l.headwater.force_n - want).abs() < 1e-9 * want);
        assert!((l.headwater.at_m - 4.0).abs() < 1e-12);
        // Over the crest the face is wetted to its top only: ρ g w (H h − h²/2), its centre
        // of pressure ∫ y p / ∫ p.
        let over = water_loads(&s, &levels(18.0, 0.0, 0.0), 9.81);
        let want = 1000.0 * 9.81 * 10.0 * (18.0 * 15.0 - 112.5);
        assert!((over.headwater.force_n - want).abs() < 1e-9 * want);
        let at = (18.0 * 112.5 - 1125.0) / (18.0 * 15.0 - 112.5);
        assert!((over.headwater.at_m - at).abs() < 1e-12);
    }

    #[test]
    fn uplift_is_the_area_of_the_head_diagram_with_or_without_drains() {
        let s = section();
        let g = 9.81;
        // Linear from 12 m at the heel to 3 m at the toe: a trapezoid.
        let l = water_loads(&s, &levels(12.0, 3.0, 0.0), g);
        let want = 1000.0 * g * 10.0 * 20.0 * (12.0 + 3.0) / 2.0;
        assert!((l.uplift.force_n - want).abs() < 1e-9 * want);
        let at = 20.0 * (12.0 + 2.0 * 3.0) / (3.0 * (12.0 + 3.0));
        assert!((l.uplift.at_m - at).abs() < 1e-12);
        // Drains at 2 m, 50 % efficient: H3 = 3 + 0.5 · 9 · 18/20 = 7.05 m.
        let d = water_loads(&s, &levels(12.0, 3.0, 0.5), g);
        assert!((d.drain_head_m - 7.05).abs() < 1e-12);
        let area = 2.0 * (12.0 + 7.05) / 2.0 + 18.0 * (7.05 + 3.0) / 2.0;
        let want = 1000.0 * g * 10.0 * area;
        assert!((d.uplift.force_n - want).abs() < 1e-9 * want);
        // Fully efficient drains leave the tailwater's head from the drains on.
        let full = water_loads(&s, &levels(12.0, 3.0, 1.0), g);
        assert!((full.drain_head_m - 3.0).abs() < 1e-12);
    }

    #[test]
    fn a_cracked_base_takes_the_reservoir_s_head_in_the_crack_and_loses_its_drains_past_them() {
        let s = section();
        let g = 9.81;
        let gamma_w = 1000.0 * g * 10.0;
        // b = 20, H1 = 12, H2 = 3, drains at 2 m, 50 %. Cracked to 1 m (short of the drains):
        // 12 m over the crack, H3 = 3 + 0.5 · 9 · 18/19 at the drains, then down to 3 m.
        let short = water_loads_cracked(&s, &levels(12.0, 3.0, 0.5), g, 1.0);
        let h3 = 3.0 + 0.5 * 9.0 * 18.0 / 19.0;
        assert!((short.drain_head_m - h3).abs() < 1e-12);
        let area = 12.0 + (12.0 + h3) / 2.0 + 18.0 * (h3 + 3.0) / 2.0;
        assert!((short.uplift.force_n - gamma_w * area).abs() < 1e-9 * gamma_w * area);
        // Cracked to 5 m (past the drains): 12 m over the crack, then linear to 3 m.
        let past = water_loads_cracked(&s, &levels(12.0, 3.0, 0.5), g, 5.0);
        let area = 5.0 * 12.0 + 15.0 * (12.0 + 3.0) / 2.0;
        assert!((past.uplift.force_n - gamma_w * area).abs() < 1e-9 * gamma_w * area);
        let first = 12.0 * 12.5 + 15.0 * (12.0 * (2.0 * 5.0 + 20.0) + 3.0 * (5.0 + 40.0)) / 6.0;
        assert!((past.uplift.at_m - first / area).abs() < 1e-12);
        // Through the base: the reservoir's head under all of it.
        let through = water_loads_cracked(&s, &levels(12.0, 3.0, 0.5), g, 20.0);
        assert!((through.uplift.force_n - gamma_w * 240.0).abs() < 1e-9 * gamma_w * 240.0);
        assert!(through.drain_head_m.is_finite());
        // Uncracked, as before.
        assert_eq!(
            water_loads_cracked(&s, &levels(12.0, 3.0, 0.5), g, 0.0),
            water_loads(&s, &levels(12.0, 3.0, 0.5), g)
        );
    }

    #[test]
    fn the_tailwater_pushes_back_and_weighs_on_the_sloping_face() {
        let s = section();
        let l = water_loads(&s, &levels(12.0, 3.0, 0.0), 9.81);
        let push = 0.5 * 1000.0 * 9.81 * 9.0 * 10.0;
        assert!((l.tailwater.force_n - push).abs() < 1e-9 * push);
        assert!((l.tailwater.at_m - 1.0).abs() < 1e-12);
        // Slope 15/15 = 1 horizontal per vertical: the water above the face is a right
        // triangle of legs 3 m and 3 m, its centroid 1 m in from the toe.
        let weight = 1000.0 * 9.81 * 10.0 * 4.5;
        assert!((l.tailwater_weight.force_n - weight).abs() < 1e-9 * weight);
        assert!((l.tailwater_weight.at_m - 19.0).abs() < 1e-12);
    }
}
