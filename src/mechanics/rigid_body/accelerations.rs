//! The accelerations at a state, with the contact forces: frictionless, every contact slipping
//! against its slip, a slow block's slip directions settled together, a young slip's direction
//! slaved to its quasi-static value, a pivot that sticks or starts to slip, a block at rest that
//! starts to slip (`slip_start.rs`), contacts in creases; and the checks that every contact
//! stays on its faces.

use super::RigidError;
use super::contact::{Ctx, MAX_FIXED_POINT, Solved, ZERO_SLIP, in_cone};
use super::creases::Creases;
use super::kinematics::{Inertia, Twist, longest_arm, twist, unit};
use super::slip_start::{all_slipping, from_rest, slaved_direction, slip_start};
use crate::mechanics::ContactGeometry;
use crate::mechanics::loads::Applied;
use crate::model::{Block, ContactStrength, ContactStrengths, Settling};
use nalgebra::Vector3;

/// Everything the rigid-body dynamics gives at one state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// The twist the rates give, every contact on its faces.
    pub twist: Twist,
    /// CM acceleration (global, m/s²).
    pub accel: Vector3<f64>,
    /// Angular acceleration (global, rad/s²).
    pub ang_accel: Vector3<f64>,
    /// Normal reaction magnitudes (N).
    pub normal: [f64; 3],
    /// Shear force vectors (N).
    pub shear: [Vector3<f64>; 3],
    /// Slip velocity of each contact (m/s).
    pub slip: [Vector3<f64>; 3],
    /// (Ẍ, Z̈, θ̈).
    pub acc: [f64; 3],
    /// Power of the applied loads other than gravity's pull: the water's, the pseudo-static
    /// forces' and a record's (W).
    pub power_hydraulic: f64,
    /// Power of friction (W, ≤ 0).
    pub power_friction: f64,
    /// The inertia at this pose.
    pub inertia: Inertia,
    /// The contact that sticks while the block turns about it (its slip vanished and its shear
    /// lies inside its cone), if any.
    pub stuck: Option<usize>,
    /// The second face's normal reaction (N) of each contact riding a crease.
    pub crease_normal: [Option<f64>; 3],
    /// The creases the motion was evaluated with.
    pub creases: Creases,
    /// How friction's directions were had (a step crossing from one to another has its
    /// accelerations jump): bit j set where contact j's young slip had its direction slaved,
    /// `SETTLED_TOGETHER` where the slow block's slips were settled together.
    pub regime: u8,
}

/// The bit of [`Motion::regime`] set where a slow block's slips were settled together.
pub const SETTLED_TOGETHER: u8 = 1 << 3;

/// The block at one pose: its contacts and the faces under them, the loads on it (moments
/// about the point the contacts' arms are from), its mass properties, and what its contacts
/// carry in shear.
#[derive(Debug, Clone, Copy)]
pub struct State<'a> {
    /// Where the contacts are, and the faces' normals.
    pub geom: &'a ContactGeometry,
    /// The loads.
    pub applied: &'a Applied,
    /// Mass and inertia.
    pub block: &'a Block,
    /// Each contact's friction criterion and cohesion.
    pub strength: &'a [ContactStrength],
}

/// The accelerations at a pose with rates (Ẋ, Ż, θ̇), with contacts riding `creases`, for an
/// integrator of step `step` (s; 0 for the accelerations alone).
///
/// Each crease's second face is one more constraint, its reaction one more unknown, and both
/// faces' friction opposes the contact's slip along the crease (`derivations/10-faces.md` §4);
/// `rates` must keep each such contact on its second face (its velocity along that face's
/// normal zero, [`crease_rates`](super::crease_rates)). A second face's reaction falling to zero
/// is [`RigidError::CreaseLetsGo`]; the contact's own face's, while the second holds it,
/// [`RigidError::CreaseTakesOver`]; three creases at once, [`RigidError::Wedged`].
///
/// The direction of a *young, slow* slip — slower than 4 μ λ / m × `step` (the speed friction
/// takes away in four steps) while its tangential acceleration is under a tenth of μ λ / m — is
/// slaved to its quasi-static value instead of being read off the slip velocity (not while a
/// contact rides a crease: `derivations/08-rigid-body.md` §3).
///
/// Why: a slip s of a contact turns towards the direction its friction allows at a rate of
/// order μ λ (e·A e) / |s| (A the contact's tangential inverse mass), which grows without bound
/// as |s| → 0, while its magnitude changes at the rate |a_t| / |s|. Where |a_t| ≪ μ λ / m — a
/// slip just started at the edge of the cone (a release), or dying away towards a pivot — the
/// first rate is far beyond any step's reach for many steps, and an explicit integrator makes
/// the direction swing about and the slip turn round again and again (chatter: hundreds of
/// events, an energy error of a joule that does not converge). A slip from rest, whose
/// acceleration is of the order of μ λ / m, leaves that band within a few steps, and RK4
/// follows it (the band would cost it its order).
///
/// Before that, a block slow as a whole, barely speeding up or slowing down, has all its slips'
/// directions settled together (`Moving::settled_together`).
///
/// The slaved direction d is the one the slip settles to within that time: the tangential
/// acceleration it gives is parallel to it, (d × a_t)·n = 0, the root nearest the slip's own
/// direction; the slip then grows or shrinks along d, and a slip that shrinks passes through
/// zero where the route's pivot event finds it. As `step` → 0 the band vanishes and the law is
/// Coulomb's.
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn accelerations(
    at: &State<'_>,
    rates: [f64; 3],
    step: f64,
    creases: Creases,
) -> Result<Motion, RigidError> {
    accelerations_releasing(at, rates, step, creases, None)
}

/// [`accelerations`] just past the moment contact `released` (if any) stopped being held by its
/// cone: its slip, still zero, starts in the direction that reproduces itself, not held again
/// there unless no direction does (then its cone left it by round-off only, and it is a pivot
/// like any other: held if its cone holds it).
///
/// Why: the release is located where the stuck contact's shear leaves its cone, to within
/// round-off of the cone's edge; evaluated there again its cone may hold it by round-off, the
/// contact stuck once more, and the route met the same release again at once, event after
/// event, until it took the rest of the increment in one plain step with the contact held
/// through it — the release late by that step, whose length the tolerance sets
/// (`derivations/08-rigid-body.md` §4a).
pub fn accelerations_releasing(
    at: &State<'_>,
    rates: [f64; 3],
    step: f64,
    creases: Creases,
    released: Option<usize>,
) -> Result<Motion, RigidError> {
    let (geom, block, friction) = (at.geom, at.block, at.strength);
    if creases.len() == 3 {
        return Err(RigidError::Wedged);
    }
    let inertia = Inertia::new(block, geom)?;
    let tw = twist(geom, rates)?;
    let ctx = Ctx {
        geom,
        inertia,
        mass: block.mass,
        force: at.applied.total_force(),
        torque: at.applied.total_moment() - tw.w.cross(&(inertia.world * tw.w)),
        centripetal: geom.r.map(|r| tw.w.cross(&tw.w.cross(&r))),
        arm: longest_arm(geom),
        creases,
    };
    let frictionless = friction.is_frictionless();
    let coefficients = |lambda: &[f64; 3]| -> [f64; 3] {
        if frictionless {
            [0.0; 3]
        } else {
            friction.coefficients(lambda)
        }
    };
    let slip = ctx.slip_of(&tw);
    let zero = [Vector3::zeros(); 3];
    // The frictionless solution: the answer of a frictionless scene (no friction solve at
    // all), the starting direction from rest, and the first normals of a stress-dependent
    // criterion. A sliding block under Coulomb friction does not need it (μ is constant).
    let needs_frictionless = frictionless || tw.is_zero() || friction.is_stress_dependent();
    let sol = if needs_frictionless {
        ctx.solve(&zero, &[0.0; 3])?
    } else {
        ctx.solve(&slip.map(unit), &coefficients(&[1.0; 3]))?
    };
    let (sol, stuck, regime) = if frictionless {
        (sol, None, 0)
    } else if tw.is_zero() {
        let (s, st) = from_rest(&ctx, &sol, &coefficients)?;
        (s, st, 0)
    } else {
        let moving = Moving {
            ctx: &ctx,
            friction,
            twist: &tw,
            slip: &slip,
            rates,
            step,
            released,
        };
        moving.contact_forces(sol, &coefficients)?
    };
    on_their_faces(&sol, &creases, stuck)?;
    let power_friction = (0..3).map(|i| sol.shear[i].dot(&slip[i])).sum();
    Ok(Motion {
        twist: tw,
        accel: sol.a,
        ang_accel: sol.e,
        normal: sol.lambda,
        shear: sol.shear,
        slip,
        acc: [sol.a.x, sol.a.z, theta_acceleration(geom, &tw, &sol.e)],
        power_hydraulic: at.applied.power(&tw.v, &tw.w),
        power_friction,
        inertia,
        stuck,
        crease_normal: [0, 1, 2].map(|i| creases.at(i).map(|_| sol.crease[i])),
        creases,
        regime,
    })
}

/// A moving block's contact problem: each shear opposes its contact's slip velocity.
struct Moving<'a> {
    ctx: &'a Ctx<'a>,
    friction: &'a [ContactStrength],
    twist: &'a Twist,
    slip: &'a [Vector3<f64>; 3],
    /// The rates (Ẋ, Ż, θ̇).
    rates: [f64; 3],
    /// The integrator's step (s).
    step: f64,
    /// A contact just released from sticking: at a pivot it slips, never sticks.
    released: Option<usize>,
}

impl Moving<'_> {
    /// The contact forces, from the solution `sol` with every contact slipping: a contact whose
    /// slip vanishes while the block moves (a pivot) sticks if its cone allows, or else slips
    /// along its tangential acceleration; a young, slow slip's direction is slaved; a
    /// stress-dependent criterion's coefficients are settled. Also the contact that sticks.
    fn contact_forces(
        &self,
        mut sol: Solved,
        coefficients: &dyn Fn(&[f64; 3]) -> [f64; 3],
    ) -> Result<(Solved, Option<usize>, u8), RigidError> {
        let (ctx, friction) = (self.ctx, self.friction);
        let mut dir = self.slip.map(unit);
        let mut mu = coefficients(&sol.lambda);
        if let Some(s) = self.settled_together(&sol, &mu, coefficients) {
            return Ok((s, None, SETTLED_TOGETHER));
        }
        let (pivot, regime) = self.pivot_or_slaved(&sol, &mut dir, &mu)?;
        let slaved = regime != 0;
        if slaved && pivot.is_none() {
            sol = ctx.solve(&dir, &mu)?;
        }
        // A contact released at this moment slips on in the direction that reproduces itself.
        // Where no direction does (its cone was left by round-off, and holds it after all),
        // it is tested for sticking as any pivot is, as before the release.
        let mut no_direction = None;
        if let Some(i) = pivot.filter(|&i| self.released == Some(i)) {
            let (mut d, mut m) = (dir, mu);
            match slip_start(ctx, &mut d, &mut m, i, coefficients) {
                Ok(s) => return Ok((s, None, regime)),
                Err(e @ RigidError::SlipStart { .. }) => no_direction = Some(e),
                Err(e) => return Err(e),
            }
        }
        let mut stuck = None;
        if let Some(i) = pivot {
            let (s, settled) = friction.settle(
                &mut mu,
                Settling {
                    tol: 1e-13,
                    max_solves: MAX_FIXED_POINT,
                },
                |mu| ctx.solve_stick(&dir, mu, i),
                |s| Some(s.lambda),
            )?;
            if settled && in_cone(&s.shear[i], mu[i], s.lambda[i]) {
                stuck = Some(s);
            }
        }
        let (s, st) = match (stuck, pivot) {
            (Some(s), _) => (s, pivot),
            // The pivot's cone cannot hold it: it starts to slip, in the direction that
            // reproduces itself (as from rest, for the one contact).
            // (A released contact's was sought above: no direction reproduces itself.)
            (None, Some(_)) if let Some(e) = no_direction => return Err(e),
            (None, Some(i)) => (slip_start(ctx, &mut dir, &mut mu, i, coefficients)?, None),
            // Coulomb without a pivot: the solve above is the answer.
            (None, None) if !friction.is_stress_dependent() => (sol, None),
            (None, None) => {
                let (sol, settled) = friction.settle(
                    &mut mu,
                    Settling {
                        tol: 1e-13,
                        max_solves: MAX_FIXED_POINT,
                    },
                    |mu| ctx.solve(&dir, mu),
                    |s| Some(s.lambda),
                )?;
                if !settled {
                    return Err(RigidError::SlipFromRest);
                }
                (sol, None)
            }
        };
        Ok((s, st, regime))
    }

    /// The whole block slow, barely speeding up or slowing down: every slip so slow that
    /// friction turns the slips' directions faster than the step can follow (ρ × step above
    /// [`TURNING`], ρ = Σ μ_j λ_j c_j / max_j |s_j|, c_j = 1/m + |r_j|² |I⁻¹| a bound on
    /// contact j's inverse mass), and the block speeding up at under a tenth of its friction's
    /// acceleration Σ μ_j λ_j / m, or slowing down. Its slips' directions are then settled
    /// together: the rates' direction ŷ
    /// whose friction accelerates the block along ±ŷ itself, as from rest, found within
    /// [`NEARBY`] of the block's own (`derivations/11-dam-loads.md` §7). None where the block
    /// is not such a block or no such ŷ is near (its contacts are then taken one by one).
    ///
    /// Why: just past the onset of a slip from rest, or just before the block stops, its
    /// acceleration is small beside friction's, and friction a little off the consistent
    /// directions pushes it sideways by μλ/m times that angle, which RK4 cannot damp at this
    /// ρ: under a record along X the block turned by 1e-5° and went on beside the exact block
    /// (up to 6e-4 of the displacement off on real records, not falling with dt). Slaving each
    /// contact with the others' directions fixed is no cure: one pass of that does not make
    /// the directions consistent together. A block that starts or stops under a load well
    /// past its cones (accelerating at a tenth of its friction or more) is followed as before:
    /// its directions then turn with it, and slaving them costs RK4 its order.
    fn settled_together(
        &self,
        sol: &Solved,
        mu: &[f64; 3],
        coefficients: &dyn Fn(&[f64; 3]) -> [f64; 3],
    ) -> Option<Solved> {
        let (ctx, slip) = (self.ctx, self.slip);
        if self.step == 0.0 {
            return None;
        }
        let reach = ctx.inertia.inverse.norm();
        let fastest = slip.iter().map(|s| s.norm()).fold(0.0, f64::max);
        let (bound, friction) = (0..3)
            .map(|j| {
                let c = 1.0 / ctx.mass + ctx.geom.r[j].norm_squared() * reach;
                let f = mu[j] * sol.lambda[j].abs();
                (f * c, f / ctx.mass)
            })
            .fold((0.0, 0.0), |(b, f), (bj, fj)| (b + bj, f + fj));
        if bound / fastest * self.step <= TURNING {
            return None;
        }
        let y = unit(Vector3::new(
            self.rates[0],
            self.rates[1],
            ctx.arm * self.rates[2],
        ));
        let a = ctx.generalized_acceleration(sol);
        let sense = a.dot(&y).signum();
        if sense > 0.0 && a.norm() >= 0.1 * friction {
            return None;
        }
        all_slipping(ctx, y, (sense, NEARBY), *mu, coefficients)
            .ok()
            .filter(|s| s.lambda.iter().all(|&l| l > 0.0))
    }

    /// The pivot — a contact whose slip is zero, or a slow slip friction stops within the step —
    /// and which young slips had their directions in `dir` slaved (bit j for contact j,
    /// [`Motion::regime`]).
    fn pivot_or_slaved(
        &self,
        sol: &Solved,
        dir: &mut [Vector3<f64>; 3],
        mu: &[f64; 3],
    ) -> Result<(Option<usize>, u8), RigidError> {
        let (ctx, slip, step) = (self.ctx, self.slip, self.step);
        let scale = self.twist.v.norm() + self.twist.w.norm() * ctx.arm;
        let mut pivot = (0..3).find(|&i| slip[i].norm() <= ZERO_SLIP * scale);
        let mut slaved = 0u8;
        let zero_pivot = pivot;
        for j in (0..3).filter(|&j| Some(j) != zero_pivot) {
            let friction_accel = mu[j] * sol.lambda[j].abs() / ctx.mass;
            // A block riding a crease has two degrees of freedom (one with two creases): one
            // contact's quasi-static direction, sought in its own tangent plane with the
            // others' fixed, is no motion it can take (81° off the slip on a record at a
            // crease, whose friction then had the crease's second face pull while the
            // contact, let go, went back into it). Its slow slips are followed as they are,
            // as is a slip that is the block's own slow sliding ([`YOUNG`]).
            if slip[j].norm() >= 4.0 * friction_accel * step
                || slip[j].norm() > YOUNG * scale
                || !ctx.creases.is_empty()
            {
                continue;
            }
            if let Some((d, a)) = slaved_direction(ctx, dir, mu, j, &dir[j])? {
                if a.abs() < 0.1 * friction_accel {
                    dir[j] = d;
                    slaved |= 1 << j;
                } else if a < 0.0
                    && pivot.is_none()
                    && slip[j].norm() <= -a * step
                    && slip[j].norm() <= PIVOTING * scale
                {
                    // A slip this slow beside the block's own motion, that friction stops
                    // within the step: the contact comes to a pivot here, sticking if its cone
                    // holds it, or slipping from it in the direction that reproduces itself.
                    // Followed as a slip, it overshoots zero step after step and chatters
                    // about it, a few µm/s in size, in substeps of microseconds (a sample of
                    // the default scene: 76 s for a 3.7 s route). A block coming to a stop as
                    // a whole (every slip of the block's size) is left to the stop's event.
                    pivot = Some(j);
                }
            }
        }
        Ok((pivot, slaved))
    }
}

/// Every contact on its faces: each crease's second face (of the contacts not sticking) still
/// pushing, and its own face too; every normal reaction positive.
fn on_their_faces(sol: &Solved, creases: &Creases, stuck: Option<usize>) -> Result<(), RigidError> {
    for c in creases.without(stuck).iter() {
        if sol.crease[c.contact] <= 0.0 {
            return Err(RigidError::CreaseLetsGo {
                contact: c.contact,
                normal_n: sol.crease[c.contact],
            });
        }
        if sol.lambda[c.contact] <= 0.0 {
            return Err(RigidError::CreaseTakesOver {
                contact: c.contact,
                normal_n: sol.lambda[c.contact],
            });
        }
    }
    for (i, &l) in sol.lambda.iter().enumerate() {
        if l <= 0.0 {
            return Err(RigidError::LiftOff {
                contact: i,
                normal_n: l,
            });
        }
    }
    Ok(())
}

/// θ̈ from u = i' (θ = atan2(u_z, u_x)), the twist `tw` and the angular acceleration `e`.
fn theta_acceleration(geom: &ContactGeometry, tw: &Twist, e: &Vector3<f64>) -> f64 {
    let u = geom.frame.i;
    let du = tw.w.cross(&u);
    let ddu = e.cross(&u) + tw.w.cross(&du);
    let rho2 = u.x * u.x + u.z * u.z;
    let theta_dot = (u.x * du.z - u.z * du.x) / rho2;
    (u.x * ddu.z - u.z * ddu.x) / rho2 - 2.0 * theta_dot * (u.x * du.x + u.z * du.z) / rho2
}

/// Where the bound on the slips' turning rate times the step is above this, a slow block's
/// slips' directions are settled together ([`Moving::settled_together`]): RK4 is unstable
/// past ρ h ≈ 2.8, and the bound is above the true rate, so every state RK4 cannot follow is
/// settled. (At 1 the kicked scene's stop moved by 1.7e-5°: there RK4 follows the block's
/// turning, which settling together would take out of it.)
const TURNING: f64 = 2.5;

/// How far (on the unit sphere of the rates' direction) the directions settled together may
/// lie from the block's own: farther, the block is turning, not settling.
const NEARBY: f64 = 1e-2;

/// A young slip this small a fraction of the block's speed, that friction stops within the
/// step, is a pivot (see [`accelerations`]).
const PIVOTING: f64 = 1e-3;

/// A slow slip has its direction slaved only where it is at most this fraction of the block's
/// own speed, |v| + |ω| L: a contact near a pivot of a turning block. A slip as fast as the
/// block is the block sliding slowly as a whole, followed as it is (slaved, a block shaken
/// along X and Z at once slid 5.3e-3 off the two-directional Newmark distance;
/// `derivations/08-rigid-body.md` §3).
const YOUNG: f64 = 0.1;
