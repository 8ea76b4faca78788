//! `[friction]`'s cohesion and `[[friction.face]]` (issue #16, `derivations/11-dam-loads.md`
//! §8): what each face of the foundation carries in shear, and each contact's share of the
//! joint's cohesion.

use super::Friction;

/// What the three contacts can carry in shear at one state: each contact's friction criterion —
/// the one of the face it rests on — and its share of the joint's cohesion, held while the joint
/// is bonded (the block at rest and never yet slid) and lost once it slides. Its arithmetic is
/// in `mechanics::strength`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strength {
    /// The friction criterion of the face under each contact.
    pub criteria: [Friction; 3],
    /// Each contact's share of the cohesion c·A (N); zero once the joint has slid.
    pub cohesion_n: [f64; 3],
}

/// One `[[friction.face]]`: faces with their own criterion and cohesion.
#[derive(Debug, Clone, PartialEq)]
pub struct FaceStrength {
    /// Face numbers as in route.csv's `face` columns (the paper's planes 0, 1, 2; a list of
    /// planes or a surface's triangles in their order).
    pub faces: Vec<u32>,
    pub friction: Friction,
    /// Cohesion (Pa).
    pub cohesion_pa: f64,
}

/// What every face carries.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Strengths {
    /// `[friction]`'s cohesion (Pa), for faces without their own.
    pub cohesion_pa: f64,
    /// The bonded area (m²) each contact stands for: the area times the contact's barycentric
    /// weight of the area's centroid, so that a uniform cohesion's resultant acts there.
    pub shares_m2: [f64; 3],
    /// `[[friction.face]]`, in the file's order (the first that names a face is its).
    pub faces: Vec<FaceStrength>,
}

impl Strengths {
    /// The strength of the contacts on `faces` with the default criterion `friction`; with
    /// cohesion when `bonded` (the block at rest and never yet slid).
    pub fn at(&self, friction: &Friction, faces: [u32; 3], bonded: bool) -> Strength {
        let own = |face: u32| self.faces.iter().find(|f| f.faces.contains(&face));
        let criteria = faces.map(|f| own(f).map_or(*friction, |s| s.friction));
        let cohesion_n = std::array::from_fn(|i| {
            let c = own(faces[i]).map_or(self.cohesion_pa, |s| s.cohesion_pa);
            if bonded { c * self.shares_m2[i] } else { 0.0 }
        });
        Strength {
            criteria,
            cohesion_n,
        }
    }

    /// True when some face has cohesion.
    pub fn has_cohesion(&self) -> bool {
        self.cohesion_pa > 0.0 || self.faces.iter().any(|f| f.cohesion_pa > 0.0)
    }
}

/// The barycentric weights of `p` in the triangle `c` (x′, z′), or `None` for a degenerate
/// triangle.
pub fn barycentric(c: &[[f64; 2]; 3], p: [f64; 2]) -> Option<[f64; 3]> {
    let (a, b) = (
        [c[1][0] - c[0][0], c[1][1] - c[0][1]],
        [c[2][0] - c[0][0], c[2][1] - c[0][1]],
    );
    let d = a[0] * b[1] - a[1] * b[0];
    if d.abs() < 1e-12 * (a[0].hypot(a[1]) * b[0].hypot(b[1])) {
        return None;
    }
    let q = [p[0] - c[0][0], p[1] - c[0][1]];
    let w1 = (q[0] * b[1] - q[1] * b[0]) / d;
    let w2 = (a[0] * q[1] - a[1] * q[0]) / d;
    Some([1.0 - w1 - w2, w1, w2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weights_rebuild_the_point_and_the_faces_their_strength() {
        let c = [[-6.0, 5.0], [4.0, 5.0], [4.0, -5.0]];
        // The monolith's base centre, 3 m downstream of its centre of mass (README).
        let w = barycentric(&c, [3.0, 0.0]).unwrap();
        for (got, want) in w.iter().zip([0.1, 0.4, 0.5]) {
            assert!((got - want).abs() < 1e-12, "{w:?}");
        }
        assert!(barycentric(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], [0.0, 0.0]).is_none());
        let s = Strengths {
            cohesion_pa: 100.0,
            shares_m2: [1.0, 2.0, 3.0],
            faces: vec![FaceStrength {
                faces: vec![2, 7],
                friction: Friction::Coulomb { mu_k: 0.9 },
                cohesion_pa: 0.0,
            }],
        };
        let base = Friction::Coulomb { mu_k: 0.4 };
        let st = s.at(&base, [0, 7, 1], true);
        assert_eq!(st.criteria, [base, Friction::Coulomb { mu_k: 0.9 }, base]);
        assert_eq!(st.cohesion_n, [100.0, 0.0, 300.0]);
        assert_eq!(s.at(&base, [0, 7, 1], false).cohesion_n, [0.0; 3]);
        assert!(s.has_cohesion());
    }
}
