//! One step of the body on its base (`derivations/13-base-contact.md` §4): the loads at the
//! pose, the free velocities, the touches within reach, the contact impulses, the drift.

use super::flush::{Bed, Quadrature, Spot, flush, hull_across};
use super::state::BodyState;
use crate::geometry::{
    BodyPose, Feature, Footprint, Ground, Relief, Touch, Touches, relief_touches, touches,
};
use crate::mechanics::held::{Support, held, reach};
use crate::mechanics::impulses::{self, Body, ContactRow, Patch};
use crate::mechanics::loads::Applied;
use crate::mechanics::static_friction::{StaticError, YieldAcceleration, least_over_directions};
use crate::model::{self, Simulation, Tendon};
use nalgebra::{Matrix3, Vector3};

/// What a step is taken with: the simulation, the body, the ground, the base, the body's
/// inertia.
pub(super) struct Ctx<'a> {
    pub sim: &'a Simulation,
    pub body: &'a model::Body,
    pub ground: &'a Ground,
    pub base: Footprint<'a>,
    /// A base cast onto its rock: its underside, which then touches the ground in place of the
    /// flat footprint (`derivations/13-base-contact.md` §10).
    pub relief: Option<&'a Relief>,
    /// The inertia tensor about the CM in the body's axes (kg·m²).
    pub inertia: Matrix3<f64>,
    /// The base's reach from the CM (m): the largest corner distance, or the depth.
    pub size: f64,
    /// The base's quadrature over its area and along its edges, where a base lying flush on
    /// its rock presses and rubs (`derivations/13-base-contact.md` §9).
    pub quadrature: &'a Quadrature,
    /// The impulse solve's tolerance (a fraction of the largest impulse) and its most sweeps.
    pub solve: (f64, usize),
    /// The anchors' tendons as the route has them (fixed in the rock where the block rests,
    /// broken).
    pub tendons: &'a [Tendon],
}

/// What one step found.
#[derive(Debug, Clone, Default)]
pub(super) struct Stepped {
    /// The touches the step was solved with, each with its impulse (N·s, world): what carries
    /// the block, and the next step's warm start.
    pub impulses: Vec<(Touch, Vector3<f64>)>,
    /// The impulse of each quadrature point where the base lay flush (N·s, world; its share of
    /// the normal impulse and its friction): the next step's warm start.
    pub patch: Vec<(Spot, Vector3<f64>)>,
    /// Corners of the base over no ground.
    pub off_ground: Vec<usize>,
    /// The step's length (s).
    pub h: f64,
}

impl Stepped {
    /// The touches whose normal impulse is not zero: those that carry the block (`scale`, N·s,
    /// the weight's impulse over the step, sets what is zero).
    pub fn carrying(&self, scale: f64) -> impl Iterator<Item = &Touch> {
        self.impulses
            .iter()
            .filter(move |(t, p)| t.normal.dot(p) > 1e-9 * scale)
            .map(|(t, _)| t)
    }

    /// The corners that carry, as the sum of 2^k, and how many points carry.
    pub fn carrying_summary(&self, scale: f64) -> (u32, u32) {
        let mut corners = 0u32;
        let mut points = 0u32;
        for t in self.carrying(scale) {
            points += 1;
            if let Feature::Corner(k) = t.feature {
                corners |= 1u32.checked_shl(k as u32).unwrap_or(0);
            }
        }
        (corners, points)
    }
}

/// The impulse solve's row of touch `c` of the body in state `s`.
fn row_of(c: &Touch, s: &BodyState, mu: f64, closing: f64, guess: Vector3<f64>) -> ContactRow {
    ContactRow {
        arm: c.on_base - s.pose.cm,
        normal: c.normal,
        mu,
        closing,
        guess,
    }
}

/// The work of a step's contact impulses (J, ≤ 0): friction's at the mean of the slip before
/// the step and the slip it leaves, ½ P_t · (u_t + u_t⁺) (exact for a rigid body whose
/// velocities the impulse takes from u to u⁺: a block braked by friction at its base, and an
/// impact that stops or turns the slip), and an impact's, ½ P_n (u_n + u_n⁺) with u_n the
/// contact's approach before the step (−½ m_eff u_n² for a contact closed inelastically; zero
/// for one that stays closed, whose impulse only holds the weight). The energy balance's
/// residual is then the step's own error, of the order of the loads' change of velocity in a
/// step: nothing at rest.
fn contact_work(
    rows: &[ContactRow],
    patches: &[Patch],
    solved: &impulses::Solved,
    (v0, w0): (Vector3<f64>, Vector3<f64>),
) -> f64 {
    // The flush patches' friction at their points (their normal shares are the rows').
    let rubbed: f64 = patches
        .iter()
        .zip(&solved.patch)
        .flat_map(|(p, imps)| {
            let n = p.axes.0.cross(&p.axes.1);
            p.points.iter().zip(imps).map(move |(q, imp)| {
                let after = solved.v + solved.w.cross(&q.arm);
                let before = v0 + w0.cross(&q.arm);
                0.5 * (imp - n * n.dot(imp)).dot(&(after + before))
            })
        })
        .sum();
    rubbed
        + rows
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let after = solved.v + solved.w.cross(&c.arm);
                let before = v0 + w0.cross(&c.arm);
                let pn = solved.normal[i];
                let approach = c.normal.dot(&before).min(0.0);
                0.5 * solved.tangential[i].dot(&(after + before))
                    + 0.5 * pn * (approach + c.normal.dot(&after))
            })
            .sum::<f64>()
}

/// The impulse solve of a step: it stops when a sweep changes no impulse by more than this
/// fraction of the largest, or after so many sweeps.
pub(super) const STEP_SOLVE: (f64, usize) = (1e-7, 400);

/// The impulse solve of the one trial step that asks whether the block is held where it rests:
/// converged, however many touches share the weight (a base cast onto its rock rests on
/// hundreds at once, and a step's solve leaves a creep of a micrometre that then stops).
pub(super) const HELD_SOLVE: (f64, usize) = (1e-10, 40_000);

/// The widest gap, as a fraction of the base's size, of a touch that supports a block at rest
/// ([`Ctx::equilibrium`]): the depth a route may reach (`derivations/13-base-contact.md` §5).
const SUPPORT_GAP: f64 = 1e-6;

/// The deepest a base may stay in the ground after a step, as a fraction of its size.
const DEPTH_TOL: f64 = 1e-8;

impl Ctx<'_> {
    /// The base's touches at `pose` within `reach` (m), each point meeting the faces it may
    /// reach within a `drift` (m): the flat footprint's, or a cast base's relief's.
    fn touches(&self, pose: &BodyPose, reach: f64, drift: f64) -> Touches {
        match self.relief {
            Some(relief) => relief_touches(self.ground, relief, pose, reach, drift),
            None => touches(self.ground, self.base, pose, reach, drift),
        }
    }

    /// Moves the pose out of the ground where the step's drift left it in (by the curvature of
    /// a turn within the step, of order h² ω² r): the smallest mass-weighted displacement that
    /// closes every gap, found as the step's impulses are, frictionless and with the gaps as
    /// the distances to close; the velocities are kept (post-stabilisation).
    fn project_out(&self, s: &mut BodyState, body: &Body) {
        for _ in 0..4 {
            let found = self.touches(&s.pose, 0.0, 0.0);
            let worst = found.touches.iter().map(|t| t.gap).fold(0.0, f64::min);
            if worst >= -DEPTH_TOL * self.size {
                return;
            }
            // Frictionless, each gap the distance to close.
            let rows: Vec<ContactRow> = found
                .touches
                .iter()
                .map(|c| row_of(c, s, 0.0, c.gap, Vector3::zeros()))
                .collect();
            let body = Body {
                inv_inertia: s
                    .world_inertia(&self.inertia)
                    .try_inverse()
                    .unwrap_or(body.inv_inertia),
                ..*body
            };
            let moved =
                impulses::solve(&body, Vector3::zeros(), Vector3::zeros(), &rows, 1e-12, 400);
            let (v, w) = (s.v, s.w);
            s.v = moved.v;
            s.w = moved.w;
            s.drift(1.0);
            s.v = v;
            s.w = w;
        }
    }

    /// The loads at `pose` and time `t`: the force (N) and the moment about the CM (N·m), and
    /// the force without the weight.
    pub fn loads(&self, pose: &BodyPose, t: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let (force, moment) = self.loads_under(pose, self.sim.foundation().acceleration(t));
        let weight = Vector3::new(
            0.0,
            -self.body.block().mass * self.body.loads().gravity,
            0.0,
        );
        (force, moment, force - weight)
    }

    /// μ of face `face`: its Coulomb coefficient (a base takes no stress-dependent criterion;
    /// `Simulation::builder` refuses one).
    fn mu(&self, face: usize) -> f64 {
        match self.sim.strengths().face(face as u32).criterion {
            crate::model::Friction::Coulomb { mu_k } => mu_k,
            other => other.coefficient(1.0),
        }
    }

    /// Whether a rigid equilibrium of the block at rest at `pose` under the loads at time `t`
    /// exists (`mechanics::held`): forces at the touches within [`SUPPORT_GAP`] of the base's
    /// size, each within its cone, that balance the loads. Necessary for static friction to
    /// hold it, whatever the law that shares the pressure over a flush base (§9 of
    /// `derivations/13-base-contact.md`); whether that law holds it too is the step's to say.
    pub fn equilibrium(&self, pose: &BodyPose, t: f64) -> Result<bool, StaticError> {
        let (force, moment, _) = self.loads(pose, t);
        let weight = self.body.block().mass * self.body.loads().gravity;
        held(&self.supports(pose), force, moment, weight, self.size)
    }

    /// The touches within [`SUPPORT_GAP`] of the base's size at `pose`, as supports free to
    /// carry any force within their cones.
    fn supports(&self, pose: &BodyPose) -> Vec<Support> {
        let reach = SUPPORT_GAP * self.size;
        let all: Vec<Support> = self
            .touches(pose, reach, 0.0)
            .touches
            .iter()
            .filter(|c| c.gap <= reach)
            .map(|c| Support {
                arm: c.on_base - pose.cm,
                normal: c.normal,
                mu: self.mu(c.face),
            })
            .collect();
        // Supports of one normal (to 10⁻⁹ rad) and one μ hold what the corners of their hull
        // (across the normal) hold: a force at a point inside is the convex combination of the
        // same force, within the same cone, at the corners, with the same resultant and moment.
        // So the static check's program has the corners only, however finely the rock under a
        // flat part of the base is meshed.
        let mut rest: Vec<usize> = (0..all.len()).collect();
        let mut out = Vec::new();
        while let Some(&first) = rest.first() {
            let (n, mu) = (all[first].normal, all[first].mu);
            let same = |m: &Vector3<f64>| m.dot(&n) > 0.0 && m.cross(&n).norm() <= 1e-9;
            let (group, others): (Vec<usize>, Vec<usize>) = rest
                .iter()
                .partition(|&&i| same(&all[i].normal) && all[i].mu == mu);
            rest = others;
            let corners = hull_across(&n, group.iter().map(|&i| all[i].arm));
            out.extend(corners.into_iter().map(|k| all[group[k]]));
        }
        out
    }

    /// The yield acceleration of the block at rest at `pose` (`derivations/11-dam-loads.md`
    /// §7, `derivations/13-base-contact.md` §6): the least horizontal ground acceleration, in
    /// any direction, that its supports cannot hold with the scene's loads — one cone program
    /// per direction (`mechanics::held::reach`), the least found as the frame's is
    /// (`static_friction::least_over_directions`). Sliding or tipping, whichever comes first.
    pub fn yield_acceleration(
        &self,
        pose: &BodyPose,
    ) -> Result<Option<YieldAcceleration>, StaticError> {
        let supports = self.supports(pose);
        let weight = self.body.block().mass * self.body.loads().gravity;
        let (force, moment) = self.loads_under(pose, [0.0; 3]);
        least_over_directions(|angle: f64| {
            // The ground accelerating along −u pushes the block along u.
            let (f, m) = self.loads_under(pose, [-angle.cos(), 0.0, -angle.sin()]);
            let extra = (f - force, m - moment);
            Ok::<_, StaticError>(
                reach(&supports, force, moment, extra, weight, self.size)?.unwrap_or(f64::INFINITY),
            )
        })
    }

    /// The loads at `pose` with the foundation accelerating at `acceleration` (g along X, Y, Z):
    /// the force (N) and the moment about the CM (N·m).
    fn loads_under(&self, pose: &BodyPose, acceleration: [f64; 3]) -> (Vector3<f64>, Vector3<f64>) {
        let frame = pose.frame();
        let origin = pose.point(&Vector3::new(0.0, -self.base.depth, 0.0));
        let applied = Applied::shaken(self.body.loads(), self.body.block(), &frame, acceleration)
            .with_tendons(self.tendons, &frame, &origin)
            .about(&(frame.j * self.base.depth));
        (applied.total_force(), applied.total_moment())
    }

    /// The weight's impulse over a step `h` (N·s): the scale of a step's impulses.
    pub fn weight_impulse(&self, h: f64) -> f64 {
        self.body.block().mass * self.body.loads().gravity * h
    }

    /// One step of `h` (s) from state `s` at time `t`, the impulses started from those of the
    /// last step, `warm`.
    pub fn step(&self, s: &mut BodyState, t: f64, h: f64, warm: &Stepped) -> Stepped {
        let mass = self.body.block().mass;
        let inertia = s.world_inertia(&self.inertia);
        let inv_inertia = inertia.try_inverse().unwrap_or_else(Matrix3::zeros);
        let (force, moment, driving) = self.loads(&s.pose, t);
        // The free velocities: the loads alone (the gyroscopic couple explicit).
        let v_free = s.v + force * (h / mass);
        let w_free = s.w + inv_inertia * (moment - s.w.cross(&(inertia * s.w))) * h;
        let reach_speed = v_free.norm() + w_free.norm() * self.size;
        let reach = 1e-3 * self.size + 2.0 * h * reach_speed;
        let found = self.touches(&s.pose, reach, h * reach_speed);
        let body = Body {
            inv_mass: 1.0 / mass,
            inv_inertia,
        };
        let mu = |f: usize| self.mu(f);
        let bed = Bed {
            ground: self.ground,
            quadrature: self.quadrature,
            size: self.size,
            mu: &mu,
        };
        // Where the base (or a cast base's relief) lies flush on its rock, it presses over the
        // area lying there.
        let mut flushes = flush(&bed, s, &found.touches, &warm.patch);
        // The touches inside a flush patch's hull are left out (`flush`): the rows are the
        // rest, the patches' members renumbered.
        let mut found = found;
        if flushes.iter().any(|f| !f.dropped.is_empty()) {
            let mut keep = vec![true; found.touches.len()];
            for f in &flushes {
                for &i in &f.dropped {
                    keep[i] = false;
                }
            }
            // Each kept touch's number among the kept.
            let new_index: Vec<usize> = keep
                .iter()
                .scan(0, |n, &k| {
                    let here = *n;
                    *n += usize::from(k);
                    Some(here)
                })
                .collect();
            for f in flushes.iter_mut() {
                for m in f.patch.members.iter_mut() {
                    *m = new_index[*m];
                }
                f.dropped.clear();
            }
            let mut k = keep.iter().copied();
            found.touches.retain(|_| k.next().unwrap_or(true));
        }
        let rows: Vec<ContactRow> = found
            .touches
            .iter()
            .enumerate()
            .map(|(i, c)| {
                // A gap closes at most to zero within the step; a depth (round-off, the
                // curvature of a turn) is undone over a few steps, not thrown out in one.
                let closing = if c.gap >= 0.0 { c.gap } else { 0.2 * c.gap } / h;
                // The same touch at the last step: found in the same place while the touches
                // stay the same (a base at rest on hundreds of surface vertices), else sought.
                let same = |t: &Touch| t.feature == c.feature && t.face == c.face;
                let guess = warm
                    .impulses
                    .get(i)
                    .filter(|(t, _)| same(t))
                    .or_else(|| warm.impulses.iter().find(|(t, _)| same(t)))
                    .map_or_else(Vector3::zeros, |(_, p)| *p);
                row_of(c, s, self.mu(c.face), closing, guess)
            })
            .collect();
        let patches: Vec<Patch> = flushes.iter().map(|f| f.patch.clone()).collect();
        let (tol, sweeps) = self.solve;
        let solved =
            impulses::solve_with_patches(&body, (v_free, w_free), &rows, &patches, tol, sweeps);
        let (v0, w0) = (s.v, s.w);
        s.v = solved.v;
        s.w = solved.w;
        s.work_applied += h * (driving.dot(&s.v) + moment.dot(&s.w));
        s.work_contacts += contact_work(&rows, &patches, &solved, (v0, w0));
        s.drift(h);
        self.project_out(s, &body);
        Stepped {
            impulses: found
                .touches
                .into_iter()
                .zip(&solved.normal)
                .zip(&solved.tangential)
                .map(|((t, pn), pt)| (t, t.normal * *pn + pt))
                .collect(),
            patch: flushes
                .iter()
                .zip(&solved.patch)
                .flat_map(|(f, imps)| f.spots.iter().copied().zip(imps.iter().copied()))
                .collect(),
            off_ground: found.off_ground,
            h,
        }
    }
}
