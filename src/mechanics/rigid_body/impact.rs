//! The perfectly inelastic, frictional impact of a contact meeting a face
//! (`derivations/10-faces.md` §6): impulses that stop every contact's velocity into its faces,
//! each with Coulomb's friction against its contact's slip, taken as a process in stages, and
//! the faces that let their contacts go.

use super::RigidError;
use super::creases::{Crease, Creases};
use super::kinematics::{Inertia, Twist, theta_rate_row, twist, unit};
use crate::mechanics::ContactGeometry;
use crate::model::Block;
use nalgebra::Vector3;

/// A face a contact is held to at an impact: its own (`second == false`) or its crease's
/// second, and the direction of its impulse per unit of normal impulse, n − μ ŝ (ŝ the
/// contact's slip on that face before the impact).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Held {
    contact: usize,
    second: bool,
    normal: Vector3<f64>,
    slip: Vector3<f64>,
    mu: f64,
}

impl Held {
    fn push(&self) -> Vector3<f64> {
        self.normal - self.slip * self.mu
    }
}

/// The faces of an impact from twist `u`: each contact's own, then the creases' second faces in
/// the order of their contacts, each with its friction coefficient `mu`.
fn held_rows(geom: &ContactGeometry, u: &Twist, creases: &Creases, mu: &[f64; 3]) -> Vec<Held> {
    let row = |contact: usize, second: bool, normal: Vector3<f64>| {
        let v = u.at(&geom.r[contact]);
        Held {
            contact,
            second,
            normal,
            slip: unit(v - normal * normal.dot(&v)),
            mu: mu[contact],
        }
    };
    (0..3)
        .map(|i| row(i, false, geom.n[i]))
        .chain(creases.iter().map(|c| row(c.contact, true, c.normal)))
        .collect()
}

/// The impulses (N·s) that bring every held contact's velocity along its face's normal to
/// `target` (m/s, one per row), each impulse along its row's n − μ ŝ (Coulomb's friction
/// against the slip): with J the rows' normals, G their impulse directions and M the mass
/// matrix, p = (J M⁻¹ Gᵀ)⁻¹ (target − J u⁻), and the twist after it u⁻ + M⁻¹ Gᵀ p.
fn impulses(
    geom: &ContactGeometry,
    mass: f64,
    inertia: &Inertia,
    u: &Twist,
    held: &[Held],
    target: &[f64],
) -> Result<(Vec<f64>, Twist), RigidError> {
    let k = held.len();
    let arm = |h: &Held, v: Vector3<f64>| geom.r[h.contact].cross(&v);
    let a = nalgebra::DMatrix::from_fn(k, k, |p, q| {
        let (hp, hq) = (&held[p], &held[q]);
        hp.normal.dot(&hq.push()) / mass
            + arm(hp, hp.normal).dot(&(inertia.inverse * arm(hq, hq.push())))
    });
    let gap = nalgebra::DVector::from_fn(k, |p, _| {
        target[p] - held[p].normal.dot(&u.v) - arm(&held[p], held[p].normal).dot(&u.w)
    });
    let p = a
        .lu()
        .solve(&gap)
        .filter(|p| p.iter().all(|v| v.is_finite()))
        .ok_or(RigidError::Singular("impact impulses"))?;
    let mut after = *u;
    for (h, p) in held.iter().zip(p.iter()) {
        after.v += h.push() * (p / mass);
        after.w += inertia.inverse * arm(h, h.push()) * *p;
    }
    Ok((p.iter().copied().collect(), after))
}

/// [`impulses`], with the friction of a row whose slip the impact would turn round (the slip
/// after it against the slip before) cut back, by bisection on its coefficient, to the one that
/// just stops it: Coulomb's friction cannot reverse a slip, and a slip stopped within the
/// impact stays stopped to its end (the contact sticks; its cone is not checked).
fn impulses_without_reversal(
    geom: &ContactGeometry,
    mass: f64,
    inertia: &Inertia,
    u: &Twist,
    held: &mut [Held],
    target: &[f64],
) -> Result<(Vec<f64>, Twist), RigidError> {
    let reversed = |held: &[Held], after: &Twist| {
        held.iter().position(|h| {
            let v = after.at(&geom.r[h.contact]);
            h.mu > 0.0 && (v - h.normal * h.normal.dot(&v)).dot(&h.slip) < 0.0
        })
    };
    for _ in 0..held.len() {
        let (p, after) = impulses(geom, mass, inertia, u, held, target)?;
        let Some(k) = reversed(held, &after) else {
            return Ok((p, after));
        };
        let (mut lo, mut hi) = (0.0, held[k].mu);
        for _ in 0..60 {
            held[k].mu = 0.5 * (lo + hi);
            let (_, after) = impulses(geom, mass, inertia, u, held, target)?;
            if reversed(held, &after) == Some(k) {
                hi = held[k].mu;
            } else {
                lo = held[k].mu;
            }
        }
        held[k].mu = lo;
    }
    impulses(geom, mass, inertia, u, held, target)
}

/// How many stages the impact is taken in ([`impact_process`]).
const IMPACT_STAGES: usize = 64;

/// The perfectly inelastic impact as a process (Darboux and Keller's: the contacts' velocities
/// change continuously along the impulse), in [`IMPACT_STAGES`] stages: at each, every held
/// contact's velocity along its face's normal moves a stage's share of the way from its value
/// before the impact to zero, by impulses whose friction opposes each contact's slip *at that
/// stage* ([`impulses_without_reversal`]). A contact's slip may so turn, or stop and stick,
/// within the impact, as a compliant contact's would; taken at once, the friction of the whole
/// impact would keep the direction of the slip before it. Returns the total impulse of each
/// row and the twist after the impact.
fn impact_process(
    geom: &ContactGeometry,
    mass: f64,
    inertia: &Inertia,
    u0: &Twist,
    held: &[Held],
) -> Result<(Vec<f64>, Twist), RigidError> {
    let speed = |u: &Twist, h: &Held| h.normal.dot(&u.at(&geom.r[h.contact]));
    let v0: Vec<f64> = held.iter().map(|h| speed(u0, h)).collect();
    // Slips slower than round-off of the motion's own speed have no direction.
    let scale = (0..3).fold(0.0f64, |a, i| a.max(u0.at(&geom.r[i]).norm()));
    let mut u = *u0;
    let mut total = vec![0.0; held.len()];
    for stage in 1..=IMPACT_STAGES {
        let left = 1.0 - stage as f64 / IMPACT_STAGES as f64;
        let target: Vec<f64> = v0.iter().map(|v| v * left).collect();
        let mut rows: Vec<Held> = held
            .iter()
            .map(|h| {
                let v = u.at(&geom.r[h.contact]);
                let t = v - h.normal * h.normal.dot(&v);
                let slip = if t.norm() > 1e-9 * scale {
                    unit(t)
                } else {
                    Vector3::zeros()
                };
                Held { slip, ..*h }
            })
            .collect();
        let (p, after) = impulses_without_reversal(geom, mass, inertia, &u, &mut rows, &target)?;
        for (t, p) in total.iter_mut().zip(&p) {
            *t += p;
        }
        u = after;
    }
    Ok((total, u))
}

/// The state just after an impact ([`impact`]): every contact still on a face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impact {
    /// The rates (Ẋ, Ż, θ̇) after the impact.
    pub rates: [f64; 3],
    /// The kinetic energy the impact took (J, ≤ 0).
    pub removed: f64,
    /// The creases ridden after it.
    pub creases: Creases,
    /// The contacts that left their own face for their crease's second (the impact put them on
    /// that face alone).
    pub moved: [Option<Crease>; 3],
}

/// The law of an impact ([`impact`]): each contact's friction coefficient, and the slowest
/// release that lets a face go.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactLaw {
    /// Each contact's friction coefficient.
    pub mu: [f64; 3],
    /// A face that would have to pull its contact at the impact lets it go only if the contact,
    /// let go, would leave the face faster than this (m/s): a slower release is a hop of a few
    /// micrometres that gravity ends within milliseconds, or a contact at the crease it is
    /// pressed into, which the contact forces just after the impact decide; the face's pull is
    /// kept.
    pub release_speed: f64,
    /// A face of a crease that would have to pull its contact at the impact lets it go (the
    /// contact goes on along the crease's other face) only if the contact would leave the face
    /// faster than this (m/s). Slower, the impact grazes the face: the crease holds and the
    /// contact forces just after decide (letting go would start a chatter of impacts that only
    /// approximates the ride along the crease). Faster, holding the crease would stop the
    /// contact's whole motion across it.
    pub crease_release_speed: f64,
}

/// The perfectly inelastic, frictional impact at the moment a contact meets a face and rides
/// its crease (`creases`; `derivations/10-faces.md` §6): the impulses that stop every contact's
/// velocity into its faces, each with Coulomb's friction impulse μ p against its contact's slip
/// on that face, turning with the slip within the impact (taken in stages; a slip the impact
/// would turn round is stopped instead). A face that would have to pull its contact lets it go,
/// the most negative first, if the contact would leave it fast enough were it let go: a
/// crease's face faster than `law.crease_release_speed` — its second face lets the contact go
/// on along its own (the impact only grazed the face just met), its own face lets it go on along
/// the second alone (it climbs onto the face it met) — and a contact on one face alone faster
/// than `law.release_speed`: it lifts off ([`RigidError::ImpactLifts`]). Frictionless, the
/// twist after it is the one [`crease_rates`](super::crease_rates) gives.
///
/// The block moves with rates (Ẋ, Ż, θ̇) on the faces of `before` (its twist, and the kinetic
/// energy the impact takes, are those), and the impulses hold it to the faces of `geom`: the
/// same faces where a contact meets a face and rides its crease, other normals where a
/// contact's own face changes at the impact (a contact running over a ridge onto the face
/// beyond it).
pub fn impact(
    before: &ContactGeometry,
    geom: &ContactGeometry,
    block: &Block,
    rates: [f64; 3],
    creases: &Creases,
    law: &ImpactLaw,
) -> Result<Impact, RigidError> {
    let inertia = Inertia::new(block, geom)?;
    let u = twist(before, rates)?;
    let mut held = held_rows(geom, &u, creases, &law.mu);
    // Rows whose pull is kept (their contact's release too slow to count).
    let mut kept = vec![false; held.len()];
    loop {
        let (p, after) = impact_process(geom, block.mass, &inertia, &u, &held)?;
        // A pull below round-off of the impact's own size is none.
        let scale = p.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let pull = (0..held.len())
            .filter(|&k| !kept[k])
            .filter(|&k| p[k] < -1e-9 * scale)
            .min_by(|&a, &b| p[a].total_cmp(&p[b]));
        let Some(k) = pull else {
            let origin = after.v + geom.cm_offset.cross(&after.w);
            let rates = [
                origin.x,
                origin.z,
                theta_rate_row(&geom.frame.i).dot(&after.w),
            ];
            let removed =
                after.kinetic_energy(block.mass, &inertia) - u.kinetic_energy(block.mass, &inertia);
            let on =
                |i: usize, second: bool| held.iter().any(|h| h.contact == i && h.second == second);
            let mut left = Creases::NONE;
            let mut moved = [None; 3];
            for c in creases.iter() {
                match (on(c.contact, false), on(c.contact, true)) {
                    (true, true) => left = left.with(*c),
                    (false, true) => moved[c.contact] = Some(*c),
                    _ => {}
                }
            }
            return Ok(Impact {
                rates,
                removed: removed.min(0.0),
                creases: left,
                moved,
            });
        };
        let h = held[k];
        // How fast the contact would leave the face if let go.
        let mut without = held.clone();
        without.remove(k);
        let (_, released) = impact_process(geom, block.mass, &inertia, &u, &without)?;
        let speed = h.normal.dot(&released.at(&geom.r[h.contact]));
        let in_crease = held.iter().filter(|o| o.contact == h.contact).count() > 1;
        // A crease's face lets go of a contact that would leave it faster than a graze: the
        // contact goes on along its other face.
        if in_crease && speed > law.crease_release_speed {
            held.remove(k);
            kept.remove(k);
            continue;
        }
        // Slower, the face's pull is kept (a graze, or a hop not followed): no contact force,
        // so no friction.
        if in_crease || speed <= law.release_speed {
            kept[k] = true;
            held[k].mu = 0.0;
            continue;
        }
        return Err(RigidError::ImpactLifts {
            contact: h.contact,
            impulse_n_s: p[k],
            speed_m_s: speed,
        });
    }
}
