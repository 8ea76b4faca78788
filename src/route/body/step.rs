//! One step of the body on its base (`derivations/13-base-contact.md` §4): the loads at the
//! pose and the free velocities, then the contact pipeline stage by stage — the narrow phase
//! (the touches within reach), the patches where the base lies flush, the contact pairs with
//! their strengths, the rows, the impulse solve — and the velocities it leaves, the drift and
//! the pose moved out of the ground.

use super::state::BodyState;
use crate::contact::{self, Against, ContactPair, ContactRow, Patch, Share, Warm};
use crate::geometry::contact::{self as geometric, Bed, Placed, Quadrature, Reduced, Spot};
use crate::geometry::contact::{Underside, reduce};
use crate::geometry::{BodyPose, Feature, Footprint, Ground, Relief, Touch, Touches};
use crate::mechanics::held::{
    BedPoint, Bedded, Support, held, held_pressing, hull_supports, reach,
};
use crate::mechanics::impulses::{self, Body, Motion, Solved, Until};
use crate::mechanics::loads::Applied;
use crate::mechanics::pressure;
use crate::mechanics::static_friction::{StaticError, YieldAcceleration, least_over_directions};
use crate::model::{self, Simulation, Tendon};
use nalgebra::{Matrix3, Vector3};

/// The body's number among the bodies: the route follows the first.
const BODY: usize = 0;

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
    /// The joint's bonded area (m²) while the bond holds (the block at rest and never yet
    /// slid): its cohesion holds the block then (`derivations/13-base-contact.md` §11). None
    /// once it has slid.
    pub bonded: Option<f64>,
    /// The base's area (m²): what its touches share, a stress-dependent criterion taking each
    /// one's normal stress over its share (`derivations/13-base-contact.md` §11).
    pub area: f64,
}

/// What one step found.
#[derive(Debug, Clone, Default)]
pub(super) struct Stepped {
    /// The touches the step was solved with, each with its impulse (N·s, world): what carries
    /// the block, and the next step's warm start.
    pub impulses: Vec<(Touch, Vector3<f64>)>,
    /// The impulse of each point where the base lay flush (N·s, world; its share of the
    /// normal impulse and its friction): the next step's warm start.
    pub patch: Vec<(Spot, Vector3<f64>)>,
    /// Corners of the base over no ground.
    pub off_ground: Vec<usize>,
    /// The step's length (s).
    pub h: f64,
    /// Every touch and point of a flush patch the step was solved with is on one face of the
    /// rock: the base sliding flush on it, or standing on it, where the extrapolated step holds
    /// the tolerance (`derivations/13-base-contact.md` §12).
    pub one_face: bool,
}

impl Stepped {
    /// The same touches and points with their impulses scaled to a step of `h`: a warm start
    /// for a step of another length (the impulses of a steady motion go as the step).
    pub fn scaled(&self, h: f64) -> Stepped {
        let k = if self.h > 0.0 { h / self.h } else { 1.0 };
        Stepped {
            impulses: self.impulses.iter().map(|(t, p)| (*t, p * k)).collect(),
            patch: self.patch.iter().map(|(q, p)| (*q, p * k)).collect(),
            off_ground: self.off_ground.clone(),
            h,
            one_face: self.one_face,
        }
    }

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

/// The body before its contacts in a step: its inverse mass and inertia, its free velocities
/// (the loads alone), the loads' moment and their force without the weight, and how far its
/// touches are sought.
struct Free {
    body: Body,
    motion: Motion,
    moment: Vector3<f64>,
    driving: Vector3<f64>,
    /// The gap within which a touch is a row (m).
    reach: f64,
    /// How far a point of the base may go within the step (m).
    drift: f64,
}

/// What the step's contacts are: the touches kept, the patches geometry found among them, and
/// the rows and patches of the solve.
struct Contacts {
    found: Touches,
    flush: Vec<geometric::Patch>,
    rows: Vec<ContactRow>,
    patches: Vec<Patch>,
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

/// The speed, as a fraction of g h, at which a touch's gap closes (or its depth is undone)
/// within a step that counts it as closed in the static check of the step's law
/// ([`Ctx::held_by_its_law`]): half the speed under which a step leaves a block held.
const CLOSED: f64 = 5e-4;

/// The deepest a base may stay in the ground after a step, as a fraction of its size.
const DEPTH_TOL: f64 = 1e-8;

/// Whether every touch and every point of a flush patch of `c` is on one face of the rock, and
/// there is one.
fn one_face(c: &Contacts) -> bool {
    let touches = c.found.touches.iter().map(|t| t.face);
    let points = c.flush.iter().flat_map(|p| p.points.iter().map(|q| q.face));
    let mut faces = touches.chain(points);
    let Some(first) = faces.next() else {
        return false;
    };
    faces.all(|f| f == first)
}

impl Ctx<'_> {
    /// The body at `pose` as the narrow phase sees it: the flat footprint, or a cast base's
    /// relief.
    fn placed(&self, pose: &BodyPose) -> Placed<'_> {
        Placed {
            body: BODY,
            pose: *pose,
            underside: match self.relief {
                Some(relief) => Underside::Cast(relief),
                None => Underside::Flat(self.base),
            },
        }
    }

    /// The base's touches at `pose` within `reach` (m), each point meeting the faces it may
    /// reach within a `drift` (m).
    fn touches(&self, pose: &BodyPose, reach: f64, drift: f64) -> Touches {
        self.placed(pose).on_rock(self.ground, reach, drift)
    }

    /// The face of the rock the base lies flush on at `pose`, alone
    /// (`derivations/13-base-contact.md` §13): its whole area on that face, every touch within
    /// [`SUPPORT_GAP`] of the base's size on it, no corner over no ground. None for a cast base.
    pub fn flush_face(&self, pose: &BodyPose) -> Option<usize> {
        if self.relief.is_some() {
            return None;
        }
        let found = self.touches(pose, SUPPORT_GAP * self.size, 0.0);
        if !found.off_ground.is_empty() {
            return None;
        }
        let bed = Bed {
            ground: self.ground,
            quadrature: self.quadrature,
            size: self.size,
        };
        let Reduced { touches, patches } = reduce(&bed, pose, found);
        let [patch] = &patches[..] else {
            return None;
        };
        let face = patch.points.first()?.face;
        let whole = patch.points.len() == self.quadrature.area.len()
            && patch
                .points
                .iter()
                .all(|q| q.face == face && matches!(q.spot, Spot::Area(_)));
        (whole && touches.touches.iter().all(|t| t.face == face)).then_some(face)
    }

    /// The contact pairs of the `placed` body's `touches` on the rock.
    fn pairs(&self, placed: &Placed<'_>, touches: &[Touch]) -> Vec<ContactPair> {
        contact::on_rock(placed.body, touches, self.sim.strengths())
    }

    /// The cohesion (Pa) of rock face `face` against the block while the bond holds; zero once
    /// it has slid.
    fn cohesion_pa(&self, face: usize) -> f64 {
        match self.bonded {
            Some(_) => contact::rock_strength(self.sim.strengths(), face, BODY).cohesion_pa,
            None => 0.0,
        }
    }

    /// The bonded fraction of the base's contact area while the bond holds: the joint's bonded
    /// area over the base's (one for a monolith, whose base is its bonded area); zero once it
    /// has slid.
    fn bonded_fraction(&self) -> f64 {
        match self.bonded {
            Some(bond) if self.area > 0.0 => bond / self.area,
            _ => 0.0,
        }
    }

    /// Each pair's [`Share`] of the base's contact (`derivations/13-base-contact.md` §11): the
    /// pairs closed on the rock (within [`SUPPORT_GAP`] of the base's size) share the base's
    /// area equally, as they share the weight at the start of a settling (`mechanics::held`),
    /// and its bonded fraction carries their face's cohesion while the bond holds; an open
    /// pair stands for the same area should it close in the step, and carries no cohesion (a
    /// bond across a gap is no bond).
    fn shares(&self, pairs: &[ContactPair]) -> Vec<Share> {
        let closed = |c: &ContactPair| c.gap <= SUPPORT_GAP * self.size;
        let n = pairs.iter().filter(|c| closed(c)).count().max(1);
        let area = self.area / n as f64;
        let bonded = self.bonded_fraction();
        pairs
            .iter()
            .map(|c| {
                let cohesion_pa = match c.against {
                    Against::Rock { face } if closed(c) => self.cohesion_pa(face),
                    _ => 0.0,
                };
                Share {
                    area_m2: area,
                    cohesion_n: cohesion_pa * area * bonded,
                }
            })
            .collect()
    }

    /// Moves the pose out of the ground where the step's drift left it in (by the curvature of
    /// a turn within the step, of order h² ω² r): the smallest mass-weighted displacement that
    /// closes every gap, found as the step's impulses are, frictionless and with the gaps as
    /// the distances to close; the velocities are kept (post-stabilisation).
    fn project_out(&self, s: &mut BodyState, body: &Body) {
        for _ in 0..4 {
            let placed = self.placed(&s.pose);
            let found = placed.on_rock(self.ground, 0.0, 0.0);
            let worst = found.touches.iter().map(|t| t.gap).fold(0.0, f64::min);
            if worst >= -DEPTH_TOL * self.size {
                return;
            }
            let pairs = self.pairs(&placed, &found.touches);
            let rows = contact::closing_rows(&pairs, &[s.pose.cm]);
            let body = Body {
                inv_inertia: s
                    .world_inertia(&self.inertia)
                    .try_inverse()
                    .unwrap_or(body.inv_inertia),
                ..*body
            };
            let still = Motion {
                v: Vector3::zeros(),
                w: Vector3::zeros(),
            };
            let until = Until {
                tol: 1e-12,
                max_sweeps: 400,
            };
            let moved = impulses::solve(&[body], &[still], &rows, &[], until).motion[BODY];
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

    /// Whether a trial step of `h` from rest at `pose` under the loads at time `t` certainly
    /// leaves the block at rest (`derivations/13-base-contact.md` §6): its own law has a static
    /// solution — its touches closed, each patch pressing as a uniform bed over all its points
    /// (`mechanics::held::held_pressing`). False where it has none, or cannot say (a touch
    /// open or deep by more than [`CLOSED`] g h over the step within a patch, a criterion that
    /// depends on the normal stress): then the trial step is to say.
    pub fn held_by_its_law(&self, pose: &BodyPose, t: f64, h: f64, warm: &Stepped) -> bool {
        // A bonded joint's cohesion over the beds' points is not in the program: the trial step
        // decides (`derivations/13-base-contact.md` §11).
        if self.bonded_fraction() > 0.0 {
            return false;
        }
        let Some((free, beds)) = self.pressing_parts(pose, t, h, warm) else {
            return false;
        };
        let (force, moment, _) = self.loads(pose, t);
        let weight = self.body.block().mass * self.body.loads().gravity;
        held_pressing(&free, &beds, force, moment, weight, self.size).unwrap_or(false)
    }

    /// The parts of the step's contacts at rest at `pose` (time `t`, a step `h`, started from
    /// `warm`) as the static check of the step's law takes them: the rows outside a patch that
    /// is a bed, closed within [`CLOSED`] g h, as supports free within their cones; each patch
    /// with a bed as one; None where it cannot say.
    fn pressing_parts(
        &self,
        pose: &BodyPose,
        t: f64,
        h: f64,
        warm: &Stepped,
    ) -> Option<(Vec<Support>, Vec<Bedded>)> {
        let free = self.free(&BodyState::at_rest(*pose), t, h);
        let c = self.contacts(pose, h, &free, warm);
        let closed = CLOSED * self.body.loads().gravity * h;
        let mut in_bed = vec![false; c.rows.len()];
        let mut beds = Vec::new();
        for p in &c.patches {
            let (e1, e2) = p.axes;
            let plan: Vec<[f64; 2]> = p
                .points
                .iter()
                .map(|q| [q.arm.dot(&e1), q.arm.dot(&e2)])
                .collect();
            let weights: Vec<f64> = p.points.iter().map(|q| q.weight).collect();
            if p.members.is_empty() || pressure::Bed::new(&plan, &weights).is_none() {
                continue;
            }
            if p.members.iter().any(|&i| c.rows[i].closing.abs() > closed) {
                return None;
            }
            let points = p.points.iter().map(|q| {
                let mu = q.shear.criterion.constant_mu()?;
                Some(BedPoint {
                    arm: q.arm,
                    weight: q.weight,
                    mu,
                })
            });
            beds.push(Bedded {
                normal: c.rows[p.members[0]].normal,
                axes: p.axes,
                points: points.collect::<Option<Vec<_>>>()?,
            });
            p.members.iter().for_each(|&i| in_bed[i] = true);
        }
        let mut supports = Vec::new();
        for (row, _) in c.rows.iter().zip(&in_bed).filter(|(_, b)| !**b) {
            if row.b.is_some() || row.closing < -closed {
                return None;
            }
            if row.closing <= closed {
                row.shear.criterion.constant_mu()?;
                supports.push(Support {
                    arm: row.a.arm,
                    normal: row.normal,
                    criterion: row.shear.criterion,
                    cohesion_n: 0.0,
                });
            }
        }
        Some((hull_supports(&supports), beds))
    }

    /// The touches within [`SUPPORT_GAP`] of the base's size at `pose`, as supports free to
    /// carry any force within their cones: of those with one normal, one criterion and one
    /// cohesion, their hull's corners (`mechanics::held::hull_supports`). The corners share the
    /// base's area equally: a stress-dependent criterion takes each one's stress over its
    /// share, and while the bond holds each carries its face's cohesion over its share of the
    /// bonded area (`derivations/13-base-contact.md` §11).
    fn supports(&self, pose: &BodyPose) -> Vec<Support> {
        let reach = SUPPORT_GAP * self.size;
        let bonded = self.bonded_fraction() * self.area;
        let all: Vec<Support> = self
            .touches(pose, reach, 0.0)
            .touches
            .iter()
            .filter(|c| c.gap <= reach)
            .map(|c| Support {
                arm: c.on_base - pose.cm,
                normal: c.normal,
                criterion: contact::rock_criterion(self.sim.strengths(), c.face, BODY),
                // The whole bonded area's worth here, which keys the hull's groups; its share
                // below.
                cohesion_n: self.cohesion_pa(c.face) * bonded,
            })
            .collect();
        let mut corners = hull_supports(&all);
        let n = corners.len() as f64;
        for s in &mut corners {
            s.cohesion_n /= n;
            s.criterion = s.criterion.over(self.area / n);
        }
        corners
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

    /// The body in state `s` at time `t` over a step `h` before its contacts: the loads alone
    /// give its free velocities (the gyroscopic couple explicit), and its speed how far its
    /// touches are sought.
    fn free(&self, s: &BodyState, t: f64, h: f64) -> Free {
        let mass = self.body.block().mass;
        let inertia = s.world_inertia(&self.inertia);
        let inv_inertia = inertia.try_inverse().unwrap_or_else(Matrix3::zeros);
        let (force, moment, driving) = self.loads(&s.pose, t);
        let v = s.v + force * (h / mass);
        let w = s.w + inv_inertia * (moment - s.w.cross(&(inertia * s.w))) * h;
        let reach_speed = v.norm() + w.norm() * self.size;
        Free {
            body: Body {
                inv_mass: 1.0 / mass,
                inv_inertia,
            },
            motion: Motion { v, w },
            moment,
            driving,
            reach: 1e-3 * self.size + 2.0 * h * reach_speed,
            drift: h * reach_speed,
        }
    }

    /// The contact pipeline of a step of `h` at `pose`, the touches sought within `reach` and
    /// `drift` of the free motion, each row and point started from the last step's, `warm`:
    /// the narrow phase, the patches where the base lies flush (their inner touches left out),
    /// the pairs with their strengths, the rows and the solve's patches.
    fn contacts(&self, pose: &BodyPose, h: f64, free: &Free, warm: &Stepped) -> Contacts {
        // The narrow phase: the touches within reach.
        let placed = self.placed(pose);
        let found = placed.on_rock(self.ground, free.reach, free.drift);
        // The patches where the base lies flush, the touches inside a face's hull left out.
        let bed = Bed {
            ground: self.ground,
            quadrature: self.quadrature,
            size: self.size,
        };
        let Reduced {
            touches: found,
            patches: flush,
        } = reduce(&bed, pose, found);
        // The pairs, each with its face's criterion; the rows and the solve's patches, each
        // started from the last step.
        let pairs = self.pairs(&placed, &found.touches);
        let warm = Warm {
            touches: &warm.impulses,
            points: &warm.patch,
            size: self.size,
        };
        // Each pair's share of the base's area, and of its cohesion while the bond holds: at
        // the pair, or at the points of its patch.
        let shares = self.shares(&pairs);
        let rows = contact::rows(&pairs, &[pose.cm], h, &warm, &shares);
        let strengths = self.sim.strengths();
        let bonded = (&shares[..], self.bonded_fraction());
        let patches = contact::patches((placed.body, 0), &flush, strengths, (h, &warm), bonded);
        Contacts {
            found,
            flush,
            rows,
            patches,
        }
    }

    /// One step of `h` (s) from state `s` at time `t`, the impulses started from those of the
    /// last step, `warm`.
    pub fn step(&self, s: &mut BodyState, t: f64, h: f64, warm: &Stepped) -> Stepped {
        let free = self.free(s, t, h);
        let c = self.contacts(&s.pose, h, &free, warm);
        let (tol, max_sweeps) = self.solve;
        let until = Until { tol, max_sweeps };
        let solved = impulses::solve(&[free.body], &[free.motion], &c.rows, &c.patches, until);
        self.integrate(s, h, &free, (&c, &solved));
        let one_face = one_face(&c);
        Stepped {
            impulses: c
                .found
                .touches
                .into_iter()
                .zip(&solved.normal)
                .zip(&solved.tangential)
                .map(|((t, pn), pt)| (t, t.normal * *pn + pt))
                .collect(),
            patch: c
                .flush
                .iter()
                .zip(&solved.patch)
                .flat_map(|(p, imps)| p.points.iter().map(|q| q.spot).zip(imps.iter().copied()))
                .collect(),
            one_face,
            off_ground: c.found.off_ground,
            h,
        }
    }

    /// The state `s` after a step of `h` whose contacts `c` were solved as `solved`: the
    /// velocities they leave, the work of the loads and of the contacts, the drift, the pose
    /// moved out of the ground.
    fn integrate(&self, s: &mut BodyState, h: f64, free: &Free, (c, solved): (&Contacts, &Solved)) {
        let before = Motion { v: s.v, w: s.w };
        let after = solved.motion[BODY];
        s.v = after.v;
        s.w = after.w;
        s.work_applied += h * (free.driving.dot(&s.v) + free.moment.dot(&s.w));
        s.work_contacts += impulses::work(&c.rows, &c.patches, solved, &[before]);
        // The path of the point under the CM, at its velocity over the step.
        let under = s.pose.rotation * Vector3::new(0.0, -self.base.depth, 0.0);
        s.path += h * (s.v + s.w.cross(&under)).norm();
        s.drift(h);
        self.project_out(s, &free.body);
    }
}
