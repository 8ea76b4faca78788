//! The monolith from its section and the water on it from levels (issue #16,
//! `derivations/11-dam-loads.md`).
//!
//! The section is a gravity monolith's: in the (x′, y′) plane a vertical upstream face from the
//! heel (x′ = 0 here) to the crest, a crest of length c, and a straight downstream face from the
//! crest's downstream edge (c, h) to the toe (b, 0); extruded over the width w along z′. All
//! positions in this module are from the heel along x′ and from the base along y′; the caller
//! moves them to the centre of mass.

/// A gravity monolith's section (m) and density (kg/m³).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// b: base length along x′, heel to toe.
    pub base_length: f64,
    /// w: width along z′.
    pub width: f64,
    /// h: height.
    pub height: f64,
    /// c: crest length along x′ (0 < c ≤ b).
    pub crest_length: f64,
    pub density: f64,
}

/// Mass properties of a [`Section`]: mass, centre of mass from the heel and the base, and the
/// inertia tensor about the centre of mass in the block axes (x′, y′, z′).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    pub mass: f64,
    /// x̄: the centre of mass from the heel along x′ (m).
    pub cm_from_heel: f64,
    /// ȳ: the centre of mass above the base (m).
    pub cm_height: f64,
    /// ∫(y² + z²) dm, ∫(x² + z²) dm, ∫(x² + y²) dm about the centre of mass (kg·m²).
    pub inertia_x: f64,
    pub inertia_y: f64,
    pub inertia_z: f64,
    /// ∫ x y dm about the centre of mass (kg·m²); ∫ x z dm = ∫ y z dm = 0 by symmetry in z′.
    pub product_xy: f64,
}

impl Section {
    /// The section's corners (x′, y′), counter-clockwise: heel, toe, crest downstream edge,
    /// crest upstream edge.
    fn polygon(&self) -> [[f64; 2]; 4] {
        [
            [0.0, 0.0],
            [self.base_length, 0.0],
            [self.crest_length, self.height],
            [0.0, self.height],
        ]
    }

    /// Mass, centre of mass and inertia: the polygon's area moments (Green's theorem over its
    /// edges), times the density and the width, with ∫ z² dm = m w²/12 across the width.
    pub fn mass_properties(&self) -> MassProperties {
        let p = self.polygon();
        let (mut a, mut sx, mut sy, mut ixx, mut iyy, mut ixy) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for k in 0..p.len() {
            let ([x0, y0], [x1, y1]) = (p[k], p[(k + 1) % p.len()]);
            let cross = x0 * y1 - x1 * y0;
            a += cross / 2.0;
            sx += (x0 + x1) * cross / 6.0;
            sy += (y0 + y1) * cross / 6.0;
            ixx += (x0 * x0 + x0 * x1 + x1 * x1) * cross / 12.0;
            iyy += (y0 * y0 + y0 * y1 + y1 * y1) * cross / 12.0;
            ixy += (x0 * y1 + 2.0 * x0 * y0 + 2.0 * x1 * y1 + x1 * y0) * cross / 24.0;
        }
        let (xc, yc) = (sx / a, sy / a);
        let per_area = self.density * self.width;
        let mass = per_area * a;
        // Second moments about the centre of mass.
        let xx = per_area * (ixx - a * xc * xc);
        let yy = per_area * (iyy - a * yc * yc);
        let xy = per_area * (ixy - a * xc * yc);
        let zz = mass * self.width * self.width / 12.0;
        MassProperties {
            mass,
            cm_from_heel: xc,
            cm_height: yc,
            inertia_x: yy + zz,
            inertia_y: xx + zz,
            inertia_z: xx + yy,
            product_xy: xy,
        }
    }
}

/// Reservoir and tailwater levels, and the drains (issue #16's `[water]`).
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

/// The water's loads on a monolith ([`water_loads`]).
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
    let h2 = levels.tailwater;
    let linear = |x: f64| h1 + (h2 - h1) * x / b;
    let x_d = levels.drain_position;
    let drained = levels.drain_efficiency > 0.0;
    let h3 = if drained {
        h2 + (1.0 - levels.drain_efficiency) * (h1 - h2) * (b - x_d) / b
    } else {
        linear(x_d)
    };
    let points: Vec<[f64; 2]> = if drained {
        vec![[0.0, h1], [x_d, h3], [b, h2]]
    } else {
        vec![[0.0, h1], [b, h2]]
    };
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
    WaterLoads {
        headwater,
        tailwater,
        tailwater_weight,
        uplift,
        drain_head_m: h3,
        levels: *levels,
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

    #[test]
    fn a_rectangular_block_has_the_textbook_mass_properties() {
        // Crest as long as the base: a box b × h × w.
        let s = Section {
            crest_length: 20.0,
            ..section()
        };
        let p = s.mass_properties();
        let m = 2400.0 * 20.0 * 15.0 * 10.0;
        assert!((p.mass - m).abs() < 1e-9 * m);
        assert!((p.cm_from_heel - 10.0).abs() < 1e-12 && (p.cm_height - 7.5).abs() < 1e-12);
        let box_i = |a: f64, b: f64| m * (a * a + b * b) / 12.0;
        assert!((p.inertia_x - box_i(15.0, 10.0)).abs() < 1e-9 * m);
        assert!((p.inertia_y - box_i(20.0, 10.0)).abs() < 1e-9 * m);
        assert!((p.inertia_z - box_i(20.0, 15.0)).abs() < 1e-9 * m);
        assert!(p.product_xy.abs() < 1e-9 * m);
    }

    #[test]
    fn a_gravity_section_is_a_rectangle_and_a_triangle() {
        // c × h rectangle at the heel and a (b − c) × h right triangle beyond it.
        let p = section().mass_properties();
        let (rect, tri) = (5.0 * 15.0, 15.0 * 15.0 / 2.0);
        let area = rect + tri;
        assert!((p.mass - 2400.0 * 10.0 * area).abs() < 1e-6);
        let x = (rect * 2.5 + tri * (5.0 + 15.0 / 3.0)) / area;
        let y = (rect * 7.5 + tri * 5.0) / area;
        assert!((p.cm_from_heel - x).abs() < 1e-12, "{}", p.cm_from_heel);
        assert!((p.cm_height - y).abs() < 1e-12, "{}", p.cm_height);
        // The product of inertia of a right triangle with legs a (along x) and h about its
        // centroid is −a² h² / 72 (the hypotenuse falling with x); the rectangle's is 0; the
        // parallel-axis terms carry each to the section's centre.
        let rho = 2400.0 * 10.0;
        let (xr, yr, xt, yt) = (2.5, 7.5, 5.0 + 15.0 / 3.0, 5.0);
        let want = rho
            * (-15.0f64.powi(2) * 15.0f64.powi(2) / 72.0
                + rect * (xr - x) * (yr - y)
                + tri * (xt - x) * (yt - y));
        assert!(
            (p.product_xy - want).abs() < 1e-9 * want.abs(),
            "{}",
            p.product_xy
        );
    }

    fn levels(head: f64, tail: f64, e: f64) -> Levels {
        Levels {
            headwater: head,
            tailwater: tail,
            density: 1000.0,
            drain_efficiency: e,
            drain_position: 2.0,
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
