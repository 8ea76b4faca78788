//! The patches the impulse solve sees (`derivations/13-base-contact.md` §9): a body's flush
//! part or points on a plane, its rows' normal impulse spread over its points as a uniform bed
//! spreads it, each point with its friction and where it starts.

use super::pair::rock_strength;
use super::row::{Share, Shear, Warm};
use crate::geometry::contact::{self, Spot};
use crate::model::Strengths;
use nalgebra::Vector3;

/// A touch among others on one plane starts from the last step's friction at the same features
/// within this fraction of the body's size.
const WARM_REACH: f64 = 0.05;

/// A body lying flush on its rock (`derivations/13-base-contact.md` §9): the rows on it carry
/// the body's normal impulse, whose resultant `mechanics::pressure::spread` shares over its
/// points as a rigid base on a uniform bed does; the friction then acts at the points, each
/// within its disc at its share, and not at the rows. Where no such pressure has the rows'
/// resultant (it is at the edge of the points' hull: the base about to tip), the rows carry
/// their own friction, as without a patch.
#[derive(Debug, Clone, PartialEq)]
pub struct Patch {
    /// The body lying there (its rows are against the rock).
    pub body: usize,
    /// The rows on it.
    pub members: Vec<usize>,
    /// Two unit axes in its plane (with the rows' normal, a right-handed frame).
    pub axes: (Vector3<f64>, Vector3<f64>),
    /// Its points.
    pub points: Vec<PatchPoint>,
}

/// One point of a patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchPoint {
    /// r: from the body's centre of mass to the point (m).
    pub arm: Vector3<f64>,
    /// Its weight: the area it stands for (m²), its length along an edge (m), or one.
    pub weight: f64,
    /// What its friction may carry.
    pub shear: Shear,
    /// Where the solve starts: its friction impulse at the last step (N·s, world), or zero.
    pub guess: Vector3<f64>,
}

/// Body `body`'s patches from geometry's `found` over a step of `h` (s), their members
/// numbered from `first_row` (the body's first row), each point with the criterion between the
/// rock's face under it and the body and the impulse it carried at the last step (`warm`, by
/// point; a touch among others on one plane, at the same features nearest to it within a
/// twentieth of the body's size: a crossing slides along its edges as the block moves).
///
/// `shares` gives each of the body's rows its [`Share`] of the base's contact (by row from
/// `first_row`; empty: none), and `bonded` the bonded fraction of that contact area while the
/// joint is bonded (zero once it has slid). A patch's points, which carry its members'
/// friction, stand for their members' area, spread over them in proportion to their weights: a
/// stress-dependent criterion takes each point's stress over its own part, and each carries the
/// cohesion of the face under it over its bonded part (`derivations/13-base-contact.md` §11).
pub fn patches(
    (body, first_row): (usize, usize),
    found: &[contact::Patch],
    strengths: &Strengths,
    (h, warm): (f64, &Warm<'_>),
    (shares, bonded): (&[Share], f64),
) -> Vec<Patch> {
    found
        .iter()
        .map(|p| {
            let area: f64 = p
                .members
                .iter()
                .filter_map(|&m| shares.get(m))
                .map(|s| s.area_m2)
                .sum();
            let weights: f64 = p.points.iter().map(|q| q.weight).sum();
            let per_weight = if weights > 0.0 { area / weights } else { 0.0 };
            let point = |q: &contact::PatchPoint| {
                let strength = rock_strength(strengths, q.face, body);
                let part = per_weight * q.weight;
                PatchPoint {
                    arm: q.arm,
                    weight: q.weight,
                    shear: Shear {
                        criterion: strength.criterion.over(part),
                        h,
                        cohesion_n: strength.cohesion_pa * part * bonded,
                    },
                    guess: warm_at(&q.spot, warm.points, warm.size),
                }
            };
            Patch {
                body,
                members: p.members.iter().map(|m| m + first_row).collect(),
                axes: p.axes,
                points: p.points.iter().map(point).collect(),
            }
        })
        .collect()
}

/// The last step's impulse at `spot` among `warm`, or zero.
fn warm_at(spot: &Spot, warm: &[(Spot, Vector3<f64>)], size: f64) -> Vector3<f64> {
    match spot {
        Spot::Area(_) | Spot::Edge(..) => warm
            .iter()
            .find(|(w, _)| w == spot)
            .map_or_else(Vector3::zeros, |(_, p)| *p),
        Spot::Touch(feature, face, body) => warm
            .iter()
            .filter_map(|(w, p)| match w {
                Spot::Touch(f, g, at) if f == feature && g == face => {
                    Some(((at - body).norm(), *p))
                }
                _ => None,
            })
            .filter(|(d, _)| *d <= WARM_REACH * size)
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map_or_else(Vector3::zeros, |(_, p)| p),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{FaceStrength, Friction};

    #[test]
    fn a_patchs_points_share_their_members_area_and_bond_by_their_weights_each_at_its_faces() {
        // Rows 1 and 2 (shares 3 m² and 5 m²) are a patch's members; its three points weigh 1,
        // 1 and 2, on faces 0, 0 and 1: each stands for 8 m² × w / 4 = 2, 2, 4 m², its
        // Barton–Choubey stress over that, and, half the area bonded, carries the cohesion of
        // its face over half of it: 100 Pa (face 0) or 300 Pa (face 1).
        let barton = Friction::barton_choubey(10.0, 5.0e7, 0.5, 99.0);
        let mut strengths = Strengths::new(barton);
        strengths.cohesion_pa = 100.0;
        strengths.faces = vec![FaceStrength {
            faces: vec![1],
            friction: barton,
            cohesion_pa: 300.0,
        }];
        let point = |k: usize, weight: f64, face: usize| contact::PatchPoint {
            arm: Vector3::new(k as f64, -1.0, 0.0),
            weight,
            face,
            spot: Spot::Area(k),
        };
        let found = contact::Patch {
            members: vec![1, 2],
            axes: (Vector3::x(), Vector3::z()),
            points: vec![point(0, 1.0, 0), point(1, 1.0, 0), point(2, 2.0, 1)],
        };
        let share = |area_m2: f64| Share {
            area_m2,
            cohesion_n: 0.0,
        };
        let shares = [share(7.0), share(3.0), share(5.0)];
        let warm = Warm {
            touches: &[],
            points: &[],
            size: 1.0,
        };
        let h = 1e-3;
        let p = &patches((0, 10), &[found], &strengths, (h, &warm), (&shares, 0.5))[0];
        assert_eq!(p.members, [11, 12]);
        for (q, (area, c)) in p
            .points
            .iter()
            .zip([(2.0, 100.0), (2.0, 100.0), (4.0, 300.0)])
        {
            assert_eq!(q.shear.criterion, barton.over(area));
            assert!((q.shear.cohesion_n - c * area * 0.5).abs() < 1e-12, "{q:?}");
        }
        // Unbonded: the same areas, no cohesion; no shares: the criterion as given.
        let p = &patches(
            (0, 0),
            &[found_again()],
            &strengths,
            (h, &warm),
            (&shares, 0.0),
        )[0];
        assert!(p.points.iter().all(|q| q.shear.cohesion_n == 0.0));
        let p = &patches((0, 0), &[found_again()], &strengths, (h, &warm), (&[], 0.5))[0];
        assert!(p.points.iter().all(|q| q.shear.criterion == barton));
    }

    /// A patch of members 0 and 1 and one point of weight 1 on face 0.
    fn found_again() -> contact::Patch {
        contact::Patch {
            members: vec![0, 1],
            axes: (Vector3::x(), Vector3::z()),
            points: vec![contact::PatchPoint {
                arm: Vector3::zeros(),
                weight: 1.0,
                face: 0,
                spot: Spot::Area(0),
            }],
        }
    }
}
