//! The ground accelerations a block at rest is certainly held under, found once where it comes
//! to rest, so that a record's samples are checked against the friction cones by a few
//! multiplications rather than a cone program each (`derivations/11-dam-loads.md` §7).
//!
//! At rest the loads are affine in the ground's acceleration a (the inertial force −m g a at
//! the centre of mass), and the accelerations under which static friction within the cones
//! holds the block form a convex set K: the rest of a feasibility program whose right-hand side
//! is affine in a. From a centre c in K (no ground acceleration where that is held, else the
//! acceleration at which the block came to rest), the reach s_k along each of a few directions
//! d_k (one cone program each, `mechanics::static_friction::reach`) gives points c + s_k d_k of
//! K, and by convexity their hull is inside K. The directions are those the record moves the
//! ground in: ±X for a record along X alone; twelve in the horizontal plane, 30° apart, for X
//! and Z; ±Y more for a vertical component. The hull is a double pyramid over a polygon, and
//! a sample's membership is its gauge, the sum of the polygon's and the vertical segment's: a
//! sample whose gauge is under 1 is held, and one outside the hull (near the cones) is checked
//! by the cone programs as before. Between two held samples the record's acceleration is
//! linear, on the segment between them, and inside K by convexity: the block is held between
//! them too.
//!
//! Constant friction coefficients only (with or without cohesion): a stress-dependent
//! criterion's cones move with the normal forces, and its block is checked sample by sample.

use super::Model;
use crate::mechanics::ContactGeometry;
use crate::mechanics::loads::Applied;
use crate::mechanics::static_friction::{self, StaticError};
use crate::model::{ContactStrength, ContactStrengths};
use nalgebra::Vector3;

/// The reach along each direction is taken this much short of the cone programs' (whose
/// tolerance is about 1e-8 of the loads), so that the hull is inside K however they round.
const SHORT: f64 = 1e-6;

/// A reach beyond this many g (the direction unbounded, or nearly) is cut to it.
const FAR_G: f64 = 100.0;

/// The directions in the horizontal plane when the ground moves along both X and Z.
const RING: usize = 12;

/// The held accelerations' inner hull at one rest.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct HeldRegion {
    /// The centre c (g along X, Y, Z).
    centre: [f64; 3],
    /// The horizontal polygon: the angle (rad, from X towards Z) of each direction and its
    /// reach (g), in increasing angle. Empty where the ground does not move horizontally.
    ring: Vec<(f64, f64)>,
    /// The reaches up and down (g), where the ground moves vertically.
    vertical: Option<(f64, f64)>,
}

impl HeldRegion {
    /// The region at the block's rest pose `geom` (arms from the base point, as the static
    /// check's), under `strength`, for the directions the record of `sim` moves the ground
    /// in; `held` the ground acceleration it is known to be held under. None for a
    /// stress-dependent criterion.
    pub fn at(
        sim: &Model<'_>,
        geom: &ContactGeometry,
        strength: &[ContactStrength],
        held: [f64; 3],
    ) -> Result<Option<HeldRegion>, StaticError> {
        let Some(record) = sim.foundation().record() else {
            return Ok(None);
        };
        if strength.is_stress_dependent() {
            return Ok(None);
        }
        let loads = |a: [f64; 3]| Applied::of(sim.body(), geom, a);
        let zero = [0.0; 3];
        let centre = if reach(geom, &loads, strength, zero, [1.0, 0.0, 0.0])?.is_some() {
            zero
        } else {
            held
        };
        let moves = record.moves();
        let along = |d: [f64; 3]| -> Result<f64, StaticError> {
            Ok(reach(geom, &loads, strength, centre, d)?.unwrap_or(0.0))
        };
        let ring = match (moves[0], moves[2]) {
            (false, false) => vec![],
            (true, false) => vec![
                (0.0, along([1.0, 0.0, 0.0])?),
                (PI, along([-1.0, 0.0, 0.0])?),
            ],
            (false, true) => {
                let (up, down) = (along([0.0, 0.0, 1.0])?, along([0.0, 0.0, -1.0])?);
                vec![(0.5 * PI, up), (1.5 * PI, down)]
            }
            (true, true) => (0..RING)
                .map(|k| {
                    let angle = 2.0 * PI * k as f64 / RING as f64;
                    Ok((angle, along([angle.cos(), 0.0, angle.sin()])?))
                })
                .collect::<Result<_, StaticError>>()?,
        };
        let vertical = if moves[1] {
            Some((along([0.0, 1.0, 0.0])?, along([0.0, -1.0, 0.0])?))
        } else {
            None
        };
        Ok(Some(HeldRegion {
            centre,
            ring,
            vertical,
        }))
    }

    /// Whether the ground acceleration `a` (g) is inside the hull: certainly held.
    pub fn holds(&self, a: [f64; 3]) -> bool {
        let h = [
            a[0] - self.centre[0],
            a[1] - self.centre[1],
            a[2] - self.centre[2],
        ];
        let vertical = match self.vertical {
            Some((up, down)) => gauge(h[1], up, down),
            None if h[1] == 0.0 => 0.0,
            None => f64::INFINITY,
        };
        self.horizontal_gauge(h[0], h[2]) + vertical < 1.0
    }

    /// The polygon's gauge of the horizontal part (x, z): 0 at the centre, 1 on its edges.
    fn horizontal_gauge(&self, x: f64, z: f64) -> f64 {
        if x == 0.0 && z == 0.0 {
            return 0.0;
        }
        match self.ring.as_slice() {
            [] => f64::INFINITY,
            // Along one axis: its segment.
            [(a0, r0), (_, r1)] if self.ring.len() == 2 => {
                let (along, across) = if *a0 == 0.0 { (x, z) } else { (z, x) };
                if across != 0.0 {
                    f64::INFINITY
                } else {
                    gauge(along, *r0, *r1)
                }
            }
            ring => {
                // The sector between two neighbouring directions: (x, z) = α v_k + β v_k+1.
                let angle = z.atan2(x).rem_euclid(2.0 * PI);
                let k = ((angle / (2.0 * PI) * ring.len() as f64) as usize).min(ring.len() - 1);
                let (a0, r0) = ring[k];
                let (a1, r1) = ring[(k + 1) % ring.len()];
                let (v0, v1) = (
                    [a0.cos() * r0, a0.sin() * r0],
                    [a1.cos() * r1, a1.sin() * r1],
                );
                let det = v0[0] * v1[1] - v0[1] * v1[0];
                if det.is_nan() || det <= 0.0 {
                    return f64::INFINITY;
                }
                let alpha = (x * v1[1] - z * v1[0]) / det;
                let beta = (v0[0] * z - v0[1] * x) / det;
                if alpha < 0.0 || beta < 0.0 {
                    return f64::INFINITY;
                }
                alpha + beta
            }
        }
    }
}

use std::f64::consts::PI;

/// Where the segment of ground accelerations from `from` (held) to `to` (not held) leaves the
/// held set, as a fraction of the segment: one cone program, the reach from `from` along
/// `to − from` (`mechanics::static_friction::reach`). None for a stress-dependent criterion
/// (whose held set is not that program's).
pub(super) fn exit(
    sim: &Model<'_>,
    geom: &ContactGeometry,
    strength: &[ContactStrength],
    from: [f64; 3],
    to: [f64; 3],
) -> Result<Option<f64>, StaticError> {
    if strength.is_stress_dependent() {
        return Ok(None);
    }
    let loads = |a: [f64; 3]| Applied::of(sim.body(), geom, a);
    let along = change(&loads, from, std::array::from_fn(|c| to[c] - from[c]));
    Ok(Some(
        static_friction::reach(geom, &along, strength)?.map_or(0.0, |s| s.max(0.0)),
    ))
}

/// The loads at ground acceleration `centre` held, and their change for the acceleration
/// `centre + d` driving.
fn change(loads: &dyn Fn([f64; 3]) -> Applied, centre: [f64; 3], d: [f64; 3]) -> Applied {
    let at = loads(centre);
    let one = loads(std::array::from_fn(|c| centre[c] + d[c]));
    let total = |a: &Applied| (a.force + a.held_force, a.moment + a.held_moment);
    let (f0, m0) = total(&at);
    let (f1, m1) = total(&one);
    Applied {
        force: f1 - f0,
        moment: m1 - m0,
        weight: at.weight,
        held_force: f0,
        held_moment: m0,
    }
}

/// The gauge of the segment [−down, up] at `v`.
fn gauge(v: f64, up: f64, down: f64) -> f64 {
    let r = if v >= 0.0 { up } else { down };
    if v == 0.0 {
        0.0
    } else if r > 0.0 {
        v.abs() / r
    } else {
        f64::INFINITY
    }
}

/// How far (g) from the ground acceleration `centre` along the unit direction `d` the block
/// stays held, a little short of the cone program's answer and at most [`FAR_G`]; None when it
/// is not held at `centre` itself.
fn reach(
    geom: &ContactGeometry,
    loads: &dyn Fn([f64; 3]) -> Applied,
    strength: &[ContactStrength],
    centre: [f64; 3],
    d: [f64; 3],
) -> Result<Option<f64>, StaticError> {
    // The change for one g along d drives; the loads at the centre are held.
    let along = change(loads, centre, d);
    let zero = Vector3::zeros();
    let still = Applied {
        force: zero,
        moment: zero,
        ..along
    };
    // Held at the centre at all: with nothing driving, any multiple is held or none.
    if static_friction::reach(geom, &still, strength)?.is_none() {
        return Ok(None);
    }
    let s = static_friction::reach(geom, &along, strength)?.unwrap_or(0.0);
    Ok(Some((s.max(0.0) * (1.0 - SHORT)).min(FAR_G)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Pose;
    use crate::model::Simulation;
    use crate::route::three_point::faces_of;
    use crate::scene::Scene;

    /// A scene of the repository with `keys` set, its simulation, its contact geometry at the
    /// start and the region there.
    fn region(file: &str, keys: &[(&str, f64)]) -> (Simulation, ContactGeometry, HeldRegion) {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(file);
        let s = Scene::from_file(&path)
            .unwrap()
            .with_keys(keys.iter().copied())
            .unwrap();
        let sim = s.simulation().unwrap();
        let pose =
            Pose::from_tilts(s.site.as_paper().unwrap(), Default::default(), 0.0, 0.0).unwrap();
        let geom = ContactGeometry::new(&s.site().normals(), &pose);
        let model = Model::new(&sim);
        let strength = model.frame_strength(faces_of(s.site()), true);
        let r = HeldRegion::at(&model, &geom, &strength, [0.0; 3])
            .unwrap()
            .unwrap();
        (sim, geom, r)
    }

    /// Whether the cone program holds the block under ground acceleration `a` (g).
    fn cones_hold(sim: &Simulation, geom: &ContactGeometry, a: [f64; 3]) -> bool {
        let body = sim.first_body();
        let applied = Applied::shaken(body.loads(), body.block(), &geom.frame, a);
        let strength = body.frame_strength(sim.strengths(), faces_of(body.site()), true);
        static_friction::at_rest(geom, &applied, &strength)
            .unwrap()
            .holds()
    }

    /// Ground accelerations spread over a box of ±`size` g (a fixed sequence).
    fn spread(n: usize, size: f64) -> impl Iterator<Item = [f64; 3]> {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
        };
        (0..n).map(move |_| [next() * size, next() * size * 0.3, next() * size])
    }

    #[test]
    fn every_acceleration_the_region_holds_the_friction_cones_hold() {
        // scenes/shaken.toml: the paper-like planes, water off the CM, a record along X, Y, Z.
        let (sim, geom, r) = region("scenes/shaken.toml", &[]);
        let (mut inside, mut held) = (0, 0);
        for a in spread(600, 0.4) {
            let cones = cones_hold(&sim, &geom, a);
            held += usize::from(cones);
            if r.holds(a) {
                inside += 1;
                assert!(cones, "{a:?} g: in the region, not held by the cones");
            }
        }
        // Most of what is held is certified without a cone program.
        assert!(held > 100 && inside * 10 > held * 6, "{inside} of {held}");
    }

    #[test]
    fn along_one_axis_the_region_is_the_band_the_cones_hold() {
        // Level planes, friction 1 and a push of 0.9 of the weight through the CM, the ground
        // along X: the block is held for a_x in [0.9 − 1, 0.9 + 1] g, to the cone
        // program's tolerance.
        let keys = [
            ("foundation.xi_deg", 0.01),
            ("foundation.zeta_deg", 0.01),
            ("foundation.kappa_deg", 0.0),
            ("friction.mu_k", 1.0),
            ("loads.eccentricity_m", 0.0),
            ("loads.hydraulic_force_n", 0.9e6 * 9.81),
        ];
        let (_, _, r) = region("scenes/shaken.toml", &keys);
        // scenes/shaken.toml's record moves X, Y and Z: take its X ring only.
        let (lo, hi) = (-0.1, 1.9);
        let band = |x: f64| r.holds([x, 0.0, 0.0]);
        assert!(band(0.0) && band(lo + 1e-3) && band(hi - 1e-3));
        assert!(!band(lo - 1e-3) && !band(hi + 1e-3));
    }
}
