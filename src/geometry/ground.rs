//! A foundation of any number of faces (issue #15): the ground at (X, Z) is the highest of its
//! planes there, a valley of rock faces. Faces are numbered from 0 in the order the scene lists
//! them.

use super::plane::Plane;

/// The ground: the upper envelope of its faces.
#[derive(Debug, Clone, PartialEq)]
pub struct Ground {
    faces: Vec<Plane>,
}

impl Ground {
    /// A ground of at least one face.
    pub fn new(faces: Vec<Plane>) -> Ground {
        assert!(!faces.is_empty(), "a ground has at least one face");
        Ground { faces }
    }

    pub fn faces(&self) -> &[Plane] {
        &self.faces
    }

    /// The highest face over (X, Z) and its height there (the first listed, of equal ones).
    pub fn top(&self, x: f64, z: f64) -> (usize, f64) {
        self.faces
            .iter()
            .enumerate()
            .map(|(k, f)| (k, f.height(x, z)))
            .fold((0, f64::NEG_INFINITY), |best, (k, h)| {
                if h > best.1 { (k, h) } else { best }
            })
    }

    /// The face a contact at (X, Z) rests on: the highest there; where several meet within
    /// `tol` (m) (a crease), the one that rises highest a step `step` (m) along the horizontal
    /// direction `dir`, then across it (+90°), then the first listed.
    pub fn face_under(&self, x: f64, z: f64, dir: (f64, f64), step: f64, tol: f64) -> usize {
        let (_, top) = self.top(x, z);
        let tied: Vec<usize> = (0..self.faces.len())
            .filter(|&k| self.faces[k].height(x, z) >= top - tol)
            .collect();
        let ahead = |k: usize, (a, b): (f64, f64)| self.faces[k].height(x + step * a, z + step * b);
        let mut best = tied[0];
        for &k in &tied[1..] {
            let (hk, hb) = (ahead(k, dir), ahead(best, dir));
            let across = (-dir.1, dir.0);
            if hk > hb + tol || (hk >= hb - tol && ahead(k, across) > ahead(best, across) + tol) {
                best = k;
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;
    use std::f64::consts::PI;

    /// The paper's three planes as faces (`docs/conventions.md`).
    fn papers() -> Ground {
        let (xi, zeta, kappa) = (20f64.to_radians(), 25f64.to_radians(), 30f64.to_radians());
        Ground::new(vec![
            Plane::from_dip(0.0, 0.0, Vector3::zeros()),
            Plane::from_dip(xi, PI, Vector3::new(4.0, 0.0, 0.0)),
            Plane::from_dip(zeta, PI - kappa, Vector3::new(4.0, 0.0, -5.0)),
        ])
    }

    #[test]
    fn the_ground_is_the_highest_face() {
        let g = papers();
        assert_eq!(g.top(-6.0, 5.0), (0, 0.0));
        let (k, h) = g.top(6.0, 5.0);
        assert_eq!(k, 1);
        assert!((h - 2.0 * 20f64.to_radians().tan()).abs() < 1e-12);
    }

    #[test]
    fn a_contact_on_a_crease_takes_the_face_that_rises_first_along_the_push() {
        // The paper's contacts: 0 on the level face, 1 on plane 1's strike (plane 1 rises along
        // +X), 2 where the level face and both planes meet (plane 2 rises faster along +X).
        let g = papers();
        let under = |x: f64, z: f64| g.face_under(x, z, (1.0, 0.0), 1e-2, 1e-9);
        assert_eq!(under(-6.0, 5.0), 0);
        assert_eq!(under(4.0, 5.0), 1);
        assert_eq!(under(4.0, -5.0), 2);
    }
}
