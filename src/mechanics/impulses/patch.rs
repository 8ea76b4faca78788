//! A base lying flush on its rock within the impulse solve (`derivations/13-base-contact.md`
//! §9): its rows' normal impulse spread over its quadrature points as a uniform bed spreads
//! it, and the friction at the points.

use super::super::pressure;
use super::{Body, Frame, Solved, frame_at, friction_at};
use crate::contact::{ContactRow, Patch, Side};
use nalgebra::Vector3;

/// A flush patch within the sweeps: its points' frames and shares, and whether its points or
/// its rows carry the friction.
pub(super) struct Spreading<'a> {
    pub(super) patch: &'a Patch,
    /// Its number among the patches.
    pub(super) number: usize,
    /// The rows' normal.
    pub(super) normal: Vector3<f64>,
    frames: Vec<Frame>,
    /// The bed under the points; None where they have no extent (then the rows rub).
    bed: Option<pressure::Bed>,
    shares: Vec<f64>,
    nus: Vec<f64>,
    /// The points carry the friction (else the rows do).
    pub(super) on: bool,
}

impl<'a> Spreading<'a> {
    pub(super) fn new(
        bodies: &[Body],
        (number, patch): (usize, &'a Patch),
        rows: &[ContactRow],
    ) -> Spreading<'a> {
        let (e1, e2) = patch.axes;
        let normal = patch
            .members
            .first()
            .map_or(e1.cross(&e2), |&i| rows[i].normal);
        Spreading {
            patch,
            number,
            normal,
            frames: patch
                .points
                .iter()
                .map(|p| {
                    let at = Side {
                        body: patch.body,
                        arm: p.arm,
                    };
                    frame_at(bodies, (&at, None), &normal, (e1, e2))
                })
                .collect(),
            bed: pressure::Bed::new(
                &patch
                    .points
                    .iter()
                    .map(|p| [p.arm.dot(&e1), p.arm.dot(&e2)])
                    .collect::<Vec<_>>(),
                &patch.points.iter().map(|p| p.weight).collect::<Vec<_>>(),
            ),
            shares: Vec::new(),
            nus: vec![0.0; patch.points.len()],
            on: true,
        }
    }

    /// Shares the rows' normal impulse over the points and gives each its friction, or, where
    /// that cannot be, hands the friction back to the rows (true: the rows must take it now).
    ///
    /// Once the rows have the friction back, the points take it again only while `may_return`
    /// (the first sweeps, the normals still settling): a base tipping to and fro over the rim
    /// of its points' hull would keep the sweeps from settling.
    pub(super) fn sweep(
        &mut self,
        out: &mut Solved,
        bodies: &[Body],
        rows: &[ContactRow],
        may_return: bool,
    ) -> bool {
        if !self.on && !may_return {
            return false;
        }
        let (e1, e2) = self.patch.axes;
        let (normal, at) = (self.normal, self.number);
        let total: f64 = self.patch.members.iter().map(|&i| out.normal[i]).sum();
        let mut centre = [0.0; 2];
        for &i in &self.patch.members {
            let share = out.normal[i] / total;
            centre[0] += share * rows[i].a.arm.dot(&e1);
            centre[1] += share * rows[i].a.arm.dot(&e2);
        }
        let fits = self
            .bed
            .as_mut()
            .is_some_and(|bed| bed.spread(total, centre, &mut self.shares));
        if fits {
            if !self.on {
                // The rows' friction goes over to the points.
                for &i in &self.patch.members {
                    let old = std::mem::take(&mut out.tangential[i]);
                    out.apply(bodies, &rows[i].a, rows[i].b.as_ref(), -old);
                }
            }
            for (k, p) in self.patch.points.iter().enumerate() {
                let was = out.patch[at][k];
                let old = was - normal * normal.dot(&was);
                let radius = p.shear.radius(self.shares[k]);
                let point = self.point(p.arm);
                let new = friction_at(
                    out,
                    bodies,
                    (&point, None),
                    &self.frames[k],
                    (radius, old),
                    &mut self.nus[k],
                );
                out.patch[at][k] = normal * self.shares[k] + new;
            }
        } else if self.on {
            for (k, p) in self.patch.points.iter().enumerate() {
                let old = std::mem::take(&mut out.patch[at][k]);
                let point = self.point(p.arm);
                out.apply(bodies, &point, None, -(old - normal * normal.dot(&old)));
            }
        }
        let hand_back = self.on && !fits;
        self.on = fits;
        hand_back
    }

    /// The patch's body's side at `arm`.
    fn point(&self, arm: Vector3<f64>) -> Side {
        Side {
            body: self.patch.body,
            arm,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::Body;
    use super::super::tests::{coulomb, ground_row, one_body};
    use super::*;
    use crate::contact::PatchPoint;
    use crate::geometry::contact::tangents;
    use crate::model::Base;
    use nalgebra::Matrix3;

    /// A 2 m cube of 1000 kg spinning at `w` rad/s about the vertical on level ground (μ 0.5),
    /// its base corners the rows: the impulses of one step of 1 ms with its base flush (the
    /// patch over its quadrature) and without.
    fn spun(w: f64) -> (f64, f64, f64) {
        let (m, h, g, mu) = (1000.0, 1e-3, 9.81, 0.5);
        let i = m * 8.0 / 12.0;
        let body = Body {
            inv_mass: 1.0 / m,
            inv_inertia: Matrix3::identity() / i,
        };
        let base = Base::rectangle([-1.0, 1.0], [-1.0, 1.0], 1.0).unwrap();
        let rows: Vec<ContactRow> = base
            .outline()
            .iter()
            .map(|&[x, z]| ground_row(Vector3::new(x, -1.0, z), Vector3::y(), coulomb(mu)))
            .collect();
        let points: Vec<PatchPoint> = base
            .quadrature(2)
            .into_iter()
            .map(|([x, z], weight)| PatchPoint {
                arm: Vector3::new(x, -1.0, z),
                weight,
                shear: coulomb(mu),
                guess: Vector3::zeros(),
            })
            .collect();
        // The friction's moment of the points' quadrature: μ m g Σ w |r| / A.
        let moment = mu
            * m
            * g
            * points
                .iter()
                .map(|p| p.weight * p.arm.xz().norm())
                .sum::<f64>()
            / base.area();
        let patch = Patch {
            body: 0,
            members: (0..4).collect(),
            axes: tangents(&Vector3::y()),
            points,
        };
        let (v, spin) = (Vector3::new(0.0, -g * h, 0.0), Vector3::new(0.0, w, 0.0));
        let flush = one_body(&body, (v, spin), &rows, &[patch], 1e-12, 400);
        let corners = one_body(&body, (v, spin), &rows, &[], 1e-12, 400);
        (
            (w - flush.motion[0].w.y) * i / h,
            (w - corners.motion[0].w.y) * i / h,
            moment,
        )
    }

    #[test]
    fn a_flush_base_spinning_is_slowed_by_its_friction_over_its_area_not_its_corners() {
        // Fast enough that one step does not stop it: the whole friction acts.
        let (flush, corners, moment) = spun(2.0);
        assert!(
            (flush - moment).abs() < 1e-6 * moment,
            "{flush} against {moment}"
        );
        // At the corners the arm is √2 m: μ m g √2.
        let at_corners = 0.5 * 1000.0 * 9.81 * 2f64.sqrt();
        assert!(
            (corners - at_corners).abs() < 1e-6 * at_corners,
            "{corners}"
        );
        // The area's mean arm, (√2 + ln(1 + √2))/3 m for this square, to the rule's 0.2 %.
        let exact = 0.5 * 1000.0 * 9.81 * (2f64.sqrt() + (1.0 + 2f64.sqrt()).ln()) / 3.0;
        assert!(
            (moment - exact).abs() < 3e-3 * exact,
            "{moment} against {exact}"
        );
    }
}
