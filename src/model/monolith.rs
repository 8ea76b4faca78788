//! The monolith from its section (`derivations/11-dam-loads.md` §1).
//!
//! The section is a gravity monolith's: in the (x′, y′) plane a vertical upstream face from the
//! heel (x′ = 0 here) to the crest, a crest of length c, and a straight downstream face from the
//! crest's downstream edge (c, h) to the toe (b, 0); extruded over the width w along z′. Positions
//! of the section are from the heel along x′ and from the base along y′; [`Monolith`] moves them
//! to the centre of mass.

use super::block::Block;
use super::error::{ModelError, positive};

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
    /// ρ: the concrete's density (kg/m³).
    pub density: f64,
}

/// Mass properties of a [`Section`]: mass, centre of mass from the heel and the base, and the
/// inertia tensor about the centre of mass in the block axes (x′, y′, z′).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// m (kg).
    pub mass: f64,
    /// x̄: the centre of mass from the heel along x′ (m).
    pub cm_from_heel: f64,
    /// ȳ: the centre of mass above the base (m).
    pub cm_height: f64,
    /// ∫(y² + z²) dm about the centre of mass (kg·m²).
    pub inertia_x: f64,
    /// ∫(x² + z²) dm (kg·m²).
    pub inertia_y: f64,
    /// ∫(x² + y²) dm (kg·m²).
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

/// A monolith: its section and the mass properties that follow from it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Monolith {
    /// The section as given.
    pub section: Section,
    /// Its mass, centre of mass and inertia.
    pub props: MassProperties,
}

impl Monolith {
    /// The monolith of `section`: positive dimensions and density, a crest no longer than the
    /// base (the downstream face runs from the crest down to the toe).
    pub fn new(section: Section) -> Result<Monolith, ModelError> {
        positive("monolith.base_length_m", section.base_length)?;
        positive("monolith.width_m", section.width)?;
        positive("monolith.height_m", section.height)?;
        positive("monolith.crest_length_m", section.crest_length)?;
        positive("monolith.density_kg_m3", section.density)?;
        if section.crest_length > section.base_length {
            return Err(ModelError::new(
                "monolith.crest_length_m",
                format!(
                    "must be at most the base length ({} m), got {} m (the downstream face runs \
                     from the crest down to the toe)",
                    section.base_length, section.crest_length
                ),
            ));
        }
        Ok(Monolith {
            section,
            props: section.mass_properties(),
        })
    }

    /// Its mass properties as a block (the moment about y', the others, and ∫x'y' dm).
    pub fn block(&self) -> Block {
        let p = &self.props;
        Block::plate(p.mass, p.inertia_y)
            .with_axes(p.inertia_x, p.inertia_z, 0.0)
            .with_product_xy(p.product_xy)
    }

    /// The centre of the base (x′, z′) about the centre of mass.
    pub fn base_centre(&self) -> [f64; 2] {
        [
            0.5 * self.section.base_length - self.props.cm_from_heel,
            0.0,
        ]
    }

    /// Each contact (x′, z′ about the centre of mass) must be on the base: x′ from the heel
    /// (−x̄) to the toe (b − x̄) and z′ across the width, to `tol` (m). The error names the first
    /// that is not, under the key `frame`.
    pub fn check_contacts(&self, contacts: &[[f64; 2]; 3], tol: f64) -> Result<(), ModelError> {
        let (b, w) = (self.section.base_length, self.section.width);
        let heel = -self.props.cm_from_heel;
        for (k, [x, z]) in contacts.iter().enumerate() {
            let inside = (heel - tol..=heel + b + tol).contains(x) && z.abs() <= w / 2.0 + tol;
            if !inside {
                return Err(ModelError::new(
                    "frame",
                    format!(
                        "contact {k} at (x', z') = ({x}, {z}) m is off the monolith's base: x' \
                         from {heel:.6} to {:.6} m (heel to toe about the centre of mass, {:.6} m \
                         from the heel) and z' from {:.6} to {:.6} m",
                        heel + b,
                        self.props.cm_from_heel,
                        -w / 2.0,
                        w / 2.0
                    ),
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A section whose mass properties are checked by hand below (the water's tests use it).
    pub(crate) fn section() -> Section {
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
}
