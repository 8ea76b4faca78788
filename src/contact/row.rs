//! The rows the impulse solve sees: one per contact pair, between a body and the rock or two
//! bodies, with each body's arm, the normal, the pair's friction over the step, the speed the
//! gap may close at, and where the solve starts.

use super::pair::{Against, ContactPair};
use crate::geometry::Touch;
use crate::geometry::contact::Spot;
use crate::model::Friction;
use nalgebra::Vector3;

/// One body's side of a row: the body and the arm from its centre of mass to the contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Side {
    /// The body, by number.
    pub body: usize,
    /// r: from its centre of mass to the contact point (m, world axes).
    pub arm: Vector3<f64>,
}

/// The friction a row, or a patch's point, may carry over a step: its pair's criterion, and
/// its share of the joint's cohesion while the joint is bonded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shear {
    /// The pair's criterion.
    pub criterion: Friction,
    /// The step (s): an impulse P over it is a force P / h.
    pub h: f64,
    /// Its share C of the joint's cohesion (N) while the joint is bonded (the block at rest
    /// and never yet slid, `derivations/13-base-contact.md` §11); zero once it has slid.
    pub cohesion_n: f64,
}

impl Shear {
    /// No friction (a step of one second).
    pub fn none() -> Shear {
        Shear {
            criterion: Friction::coulomb(0.0),
            h: 1.0,
            cohesion_n: 0.0,
        }
    }

    /// The radius of the friction disc at normal impulse `pn` (N·s): the criterion's shear
    /// strength at the normal force pn / h, over the step (`derivations/13-base-contact.md`
    /// §4), μ pn for Coulomb's; and, while the joint is bonded, its cohesion over the step,
    /// C h (§11: Mohr–Coulomb's τ = c + σ tan φ over the area the row stands for).
    pub fn radius(&self, pn: f64) -> f64 {
        let friction = match self.criterion {
            Friction::Coulomb { mu_k } => mu_k * pn,
            other => other.shear(pn / self.h) * self.h,
        };
        if self.cohesion_n > 0.0 {
            friction + self.cohesion_n * self.h
        } else {
            friction
        }
    }
}

/// A pair's share of the base's contact with its rock (`derivations/13-base-contact.md` §11):
/// the area it stands for, over which a stress-dependent criterion takes its normal stress
/// (zero: the criterion's own `contact_area_m2`), and its share of a bonded joint's cohesion.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Share {
    /// The area it stands for (m²).
    pub area_m2: f64,
    /// Its share of the cohesion (N) while the joint is bonded; zero once it has slid.
    pub cohesion_n: f64,
}

/// One row of the impulse solve: a contact between body `a` and the rock (`b` none) or body
/// `b`, whose impulse P acts on `a` and −P on `b`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactRow {
    /// The body the normal points into.
    pub a: Side,
    /// The other body; none for the rock.
    pub b: Option<Side>,
    /// n: unit normal into `a`.
    pub normal: Vector3<f64>,
    /// What its friction may carry.
    pub shear: Shear,
    /// g / h: the normal velocity the contact may close at (m/s; negative where they overlap,
    /// asking for the depth to be undone in the step).
    pub closing: f64,
    /// Where the solve starts: the impulse (N·s, world) the contact carried at the last step,
    /// or zero (a warm start; the solution does not depend on it, only the sweeps it takes).
    pub guess: Vector3<f64>,
}

impl ContactRow {
    /// Whether rows `self` and `other` are at one point of the same bodies (a corner in a
    /// crease, on two or three faces of the rock).
    pub fn same_point(&self, other: &ContactRow) -> bool {
        self.a == other.a && self.b == other.b
    }
}

/// What one body's rows and patch points start from: the impulses of its last step.
#[derive(Debug, Clone, Copy)]
pub struct Warm<'a> {
    /// Each touch the last step was solved with, in its order then, with its impulse (N·s).
    pub touches: &'a [(Touch, Vector3<f64>)],
    /// Each patch point's impulse (N·s).
    pub points: &'a [(Spot, Vector3<f64>)],
    /// The body's size (m): how far a touch among points on a plane is sought again.
    pub size: f64,
}

/// The sides of pair `c` with the bodies' centres of mass `cms` (world, by body number).
fn sides(c: &ContactPair, cms: &[Vector3<f64>]) -> (Side, Option<Side>) {
    let a = Side {
        body: c.body,
        arm: c.point - cms[c.body],
    };
    // The other body's point is the gap below the first's along the normal.
    let b = c.other_body().map(|b| Side {
        body: b,
        arm: c.point - c.normal * c.gap - cms[b],
    });
    (a, b)
}

/// The rows of a step of `h` (s) of one body's `pairs`, in their order, with the bodies'
/// centres of mass `cms`: a gap closes at most to zero within the step, a depth (round-off,
/// the curvature of a turn) is undone over a few steps, not thrown out in one. Each starts
/// from the impulse the same touch carried at the last step (`warm`): found in the same place
/// while the touches stay the same (a base at rest on hundreds of surface vertices), else
/// sought. `shares` gives each pair's [`Share`] of the base's contact, in their order (empty,
/// or a pair past its end: the criterion as it is, no cohesion).
pub fn rows(
    pairs: &[ContactPair],
    cms: &[Vector3<f64>],
    h: f64,
    warm: &Warm<'_>,
    shares: &[Share],
) -> Vec<ContactRow> {
    let warm = warm.touches;
    pairs
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let closing = if c.gap >= 0.0 { c.gap } else { 0.2 * c.gap } / h;
            let same =
                |t: &Touch| t.feature == c.feature && Against::Rock { face: t.face } == c.against;
            let guess = warm
                .get(i)
                .filter(|(t, _)| same(t))
                .or_else(|| warm.iter().find(|(t, _)| same(t)))
                .map_or_else(Vector3::zeros, |(_, p)| *p);
            let (a, b) = sides(c, cms);
            let share = shares.get(i).copied().unwrap_or_default();
            ContactRow {
                a,
                b,
                normal: c.normal,
                shear: Shear {
                    criterion: c.criterion.over(share.area_m2),
                    h,
                    cohesion_n: share.cohesion_n,
                },
                closing,
                guess,
            }
        })
        .collect()
}

/// The rows that move bodies out of what they overlap ([`rows`]' to undo a depth): without
/// friction, each gap the distance to close, from nothing.
pub fn closing_rows(pairs: &[ContactPair], cms: &[Vector3<f64>]) -> Vec<ContactRow> {
    pairs
        .iter()
        .map(|c| {
            let (a, b) = sides(c, cms);
            ContactRow {
                a,
                b,
                normal: c.normal,
                shear: Shear::none(),
                closing: c.gap,
                guess: Vector3::zeros(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Feature;

    #[test]
    fn coulombs_disc_is_mu_times_the_normal_impulse_and_another_criterions_its_shear_over_the_step()
    {
        let h = 1e-3;
        for (mu, pn) in [(0.4, 9.81), (0.3, 1e-300), (0.7, 0.0), (0.1, 123.456e3)] {
            let c = Shear {
                criterion: Friction::coulomb(mu),
                h,
                cohesion_n: 0.0,
            };
            assert_eq!(c.radius(pn).to_bits(), (mu * pn).to_bits());
        }
        let barton = Friction::barton_choubey(10.0, 5.0e7, 30f64.to_radians(), 2.0);
        let c = Shear {
            criterion: barton,
            h,
            cohesion_n: 0.0,
        };
        let pn = 4.0e6 * h;
        assert_eq!(c.radius(pn), barton.shear(4.0e6) * h);
        assert!((c.radius(pn) / pn - barton.coefficient(4.0e6)).abs() < 1e-15);
        assert_eq!(c.radius(0.0), 0.0);
        assert_eq!(Shear::none().radius(5.0), 0.0);
        // A bonded row's disc is wider by its cohesion over the step, pressed or not.
        let bonded = Shear {
            criterion: Friction::coulomb(0.4),
            h,
            cohesion_n: 2.5e4,
        };
        assert_eq!(bonded.radius(0.0), 2.5e4 * h);
        assert!((bonded.radius(10.0) - (4.0 + 25.0)).abs() < 1e-12);
    }

    /// A pair of body `body` on rock face `face` at `point` (world), by corner `k`.
    fn pair(body: usize, face: usize, point: Vector3<f64>, k: usize, gap: f64) -> ContactPair {
        ContactPair {
            body,
            against: Against::Rock { face },
            point,
            on_body: Vector3::zeros(),
            normal: Vector3::y(),
            gap,
            feature: Feature::Corner(k),
            criterion: Friction::coulomb(0.5),
        }
    }

    #[test]
    fn a_row_starts_from_the_same_touchs_last_impulse_and_closes_its_gap_within_the_step() {
        let h = 1e-3;
        let cm = Vector3::new(1.0, 2.0, 3.0);
        let pairs = [
            pair(0, 2, Vector3::new(0.0, 0.0, 0.0), 0, 1e-4),
            pair(0, 2, Vector3::new(2.0, 0.0, 0.0), 1, -1e-4),
            pair(0, 3, Vector3::new(2.0, 0.0, 6.0), 2, 0.0),
        ];
        let touch = |k: usize, face: usize, p: f64| {
            let t = Touch {
                on_base: Vector3::zeros(),
                body: Vector3::zeros(),
                normal: Vector3::y(),
                gap: 0.0,
                face,
                feature: Feature::Corner(k),
            };
            (t, Vector3::new(0.0, p, 0.0))
        };
        // The last step's: corner 1 and 0 on face 2 (in another order), corner 2 on face 4.
        let warm = [touch(1, 2, 5.0), touch(0, 2, 7.0), touch(2, 4, 9.0)];
        let warm = Warm {
            touches: &warm,
            points: &[],
            size: 1.0,
        };
        let r = rows(&pairs, &[cm], h, &warm, &[]);
        assert_eq!(r[0].guess.y, 7.0);
        assert_eq!(r[1].guess.y, 5.0);
        assert_eq!(r[2].guess, Vector3::zeros());
        // A gap closes to zero in the step; a depth a fifth a step.
        assert_eq!(r[0].closing, 1e-4 / h);
        assert_eq!(r[1].closing, 0.2 * -1e-4 / h);
        assert_eq!(r[2].a.arm, Vector3::new(1.0, -2.0, 3.0));
        assert!(r.iter().all(|c| c.b.is_none() && c.shear.h == h));
        let out = closing_rows(&pairs, &[cm]);
        assert_eq!(out[1].closing, -1e-4);
        assert!(out.iter().all(|c| c.shear.radius(1.0) == 0.0));
    }

    #[test]
    fn a_row_between_two_bodies_has_each_ones_arm_to_its_own_point() {
        // Body 1's corner 0.01 m above body 0's top face, at (1, 2.01, 0): body 0's point is
        // 0.01 m below it.
        let c = ContactPair {
            against: Against::Body {
                body: 0,
                feature: Feature::Corner(3),
            },
            ..pair(1, 0, Vector3::new(1.0, 2.01, 0.0), 0, 0.01)
        };
        let cms = [Vector3::new(0.0, 1.0, 0.0), Vector3::new(0.5, 3.0, 0.0)];
        let none = Warm {
            touches: &[],
            points: &[],
            size: 1.0,
        };
        let r = rows(&[c], &cms, 1e-3, &none, &[])[0];
        assert_eq!(r.a.body, 1);
        assert!((r.a.arm - Vector3::new(0.5, -0.99, 0.0)).norm() < 1e-15);
        let b = r.b.unwrap();
        assert_eq!(b.body, 0);
        assert!((b.arm - Vector3::new(1.0, 1.0, 0.0)).norm() < 1e-15);
    }
}
