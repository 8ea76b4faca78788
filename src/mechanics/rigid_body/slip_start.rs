//! The start of slip: the direction in which a contact, or the whole block, starts to slip so
//! that its friction reproduces that direction (the consistent slip-start problem) — from rest,
//! at a pivot whose cone cannot hold it, and for a young slip whose direction is slaved to its
//! quasi-static value.

use super::RigidError;
use super::contact::{Ctx, MAX_FIXED_POINT, Solved, in_cone};
use super::kinematics::unit;
use nalgebra::{Matrix3, Vector3};

/// The generalized acceleration (m/s², of the rates (Ẋ, Ż, L θ̇)) across ŷ below which a
/// direction of slip from rest is settled whatever the angle between them.
///
/// Just past the onset of a slip the block's acceleration is small (it grows from zero with
/// the load's excess over the cones), and its direction ŝ turns through a right angle when ŷ
/// turns by 1e-10: the round-off in the twist of ŷ (1e-16 of the slip rate) then puts |ŝ − ŷ|
/// at 1e-7 and no Newton step lowers it. What the route needs is that the acceleration across
/// ŷ is negligible, and 1e-12 m/s² is (a millimetre in 10⁴ s); `derivations/11-dam-loads.md`
/// §7.
const SETTLED_ACROSS: f64 = 1e-12;

/// Whether a direction |ŝ − ŷ| = `off` from consistent, of an acceleration `size` (m/s²), is
/// settled by [`SETTLED_ACROSS`]. (Asking also that it be within 1e-6 of consistent, so that
/// no direction of an acceleration too small to say is taken, was tried and was no better: the
/// real records of `tests/integration/newmark_exact.rs` then put Northridge at ky = 0.1 g
/// 2.6e-3 off the exact displacement.)
fn settled_across(off: f64, size: f64) -> bool {
    off * size < SETTLED_ACROSS
}

/// Newton steps from a direction near its root (a `within` that is finite): where it has not
/// settled in this many, it is not near.
const NEAR_NEWTON: usize = 10;

/// Solves ŝ(ŷ) = ŷ on the unit sphere by Newton's method (finite-difference Jacobian, halving
/// steps while |ŝ − ŷ| does not fall), from `y`, within `within` of it (it gives up where a
/// step leaves that ball, Newton's estimate of the root lies beyond twice it, or, the ball
/// finite, [`NEAR_NEWTON`] steps have not settled it); `a(ŷ)` is the generalized acceleration
/// whose direction is ŝ. Settled
/// where |ŝ − ŷ| < 1e-14, or where the acceleration across ŷ, |a| |ŝ − ŷ|, is below
/// [`SETTLED_ACROSS`].
pub(super) fn settle_direction(
    mut y: Vector3<f64>,
    within: f64,
    a: impl Fn(&Vector3<f64>) -> Result<Vector3<f64>, RigidError>,
) -> Result<Vector3<f64>, RigidError> {
    let y0 = y;
    let both = |y: &Vector3<f64>| a(y).map(|v| (unit(v) - y, v.norm()));
    let residual = |y: &Vector3<f64>| both(y).map(|(f, _)| f);
    let (mut f, mut size) = both(&y)?;
    let most = if within.is_finite() {
        NEAR_NEWTON
    } else {
        MAX_FIXED_POINT
    };
    for _ in 0..most {
        if f.norm() < 1e-14 || settled_across(f.norm(), size) {
            return Ok(y);
        }
        let h = 1e-7;
        let mut j = Matrix3::zeros();
        for c in 0..3 {
            let mut yc = y;
            yc[c] += h;
            j.set_column(c, &((residual(&yc)? - f) / h));
        }
        // ŝ does not depend on |ŷ|, so J = Dŝ − I has −1 along ŷ: it is regular there.
        let step = j.lu().solve(&(-f)).ok_or(RigidError::SlipFromRest)?;
        if ((y + step).normalize() - y0).norm() > 2.0 * within {
            // Newton's estimate of the root lies well outside the ball.
            return Err(RigidError::SlipFromRest);
        }
        let mut t = 1.0;
        loop {
            let cand = (y + step * t).normalize();
            let (fc, sc) = both(&cand)?;
            if fc.norm() < f.norm() || t < 1e-6 {
                if (cand - y0).norm() > within {
                    return Err(RigidError::SlipFromRest);
                }
                y = cand;
                (f, size) = (fc, sc);
                break;
            }
            t *= 0.5;
        }
    }
    if f.norm() < 1e-10 || settled_across(f.norm(), size) {
        Ok(y)
    } else {
        Err(RigidError::SlipFromRest)
    }
}

/// Directions sampled round contact `i`'s tangent plane when its slip direction is sought
/// (each a 3×3 solve); sign changes between them are refined by bisection.
const SLIP_START_SAMPLES: usize = 72;

/// Every direction d on contact `i`'s tangent plane whose friction −μλ d (the other contacts
/// slipping along `dir`) gives a tangential acceleration parallel to d, (d × a_t)·n = 0, with
/// all normal forces positive: (d, a_t·d, the solution).
pub(super) fn consistent_directions(
    ctx: &Ctx<'_>,
    dir: &[Vector3<f64>; 3],
    mu: &[f64; 3],
    i: usize,
) -> Result<Vec<(Vector3<f64>, f64, Solved)>, RigidError> {
    let eval = |phi: f64| {
        ctx.slipping_at(dir, mu, i, phi)
            .map(|(_, g, h, s)| (g, h, s))
    };
    let step = 2.0 * std::f64::consts::PI / SLIP_START_SAMPLES as f64;
    let mut out = Vec::new();
    let mut prev = eval(0.0)?;
    for k in 1..=SLIP_START_SAMPLES {
        let phi = k as f64 * step;
        let cur = eval(phi)?;
        if prev.0 == 0.0 || prev.0.signum() != cur.0.signum() {
            // Bisection on the sign of (d × a_t)·n.
            let (mut lo, mut hi, mut g_lo) = (phi - step, phi, prev.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let g = eval(mid)?.0;
                if g == 0.0 {
                    (lo, hi) = (mid, mid);
                    break;
                }
                if g.signum() == g_lo.signum() {
                    (lo, g_lo) = (mid, g);
                } else {
                    hi = mid;
                }
            }
            let phi_r = 0.5 * (lo + hi);
            let (d, _, h, s) = ctx.slipping_at(dir, mu, i, phi_r)?;
            if s.lambda.iter().all(|&l| l > 0.0) {
                out.push((d, h, s));
            }
        }
        prev = cur;
    }
    Ok(out)
}

/// The slaved direction of contact `j`'s young slip (see [`accelerations_slaved`]): the
/// consistent direction ((d × a_t)·n = 0, every normal force positive) nearest `current`,
/// found from `current` outwards — a bracket widened from 2° by half again each time, then the
/// Illinois method — with the contact's tangential acceleration along it there, a_t·d (below
/// zero where friction slows the slip); `None` if there is none. About twenty solves where a scan of the circle takes some three hundred.
pub(super) fn slaved_direction(
    ctx: &Ctx<'_>,
    dir: &[Vector3<f64>; 3],
    mu: &[f64; 3],
    j: usize,
    current: &Vector3<f64>,
) -> Result<Option<(Vector3<f64>, f64)>, RigidError> {
    let (t1, t2) = ctx.geom.tangents(j);
    let eval = |phi: f64| ctx.slipping_at(dir, mu, j, phi).map(|(_, g, _, s)| (g, s));
    let phi0 = current.dot(&t2).atan2(current.dot(&t1));
    let g0 = eval(phi0)?.0;
    let mut bracket = None;
    let mut delta = 2f64.to_radians();
    while bracket.is_none() && delta <= std::f64::consts::PI {
        for side in [1.0, -1.0] {
            let phi = phi0 + side * delta;
            let g = eval(phi)?.0;
            if g0 == 0.0 || g.signum() != g0.signum() {
                bracket = Some((phi0, g0, phi, g));
                break;
            }
        }
        delta *= 1.5;
    }
    let Some((mut a, mut ga, mut b, mut gb)) = bracket else {
        return Ok(None);
    };
    // Illinois: regula falsi that halves the stale end's value.
    let mut side = 0;
    for _ in 0..60 {
        if ga == 0.0 || (b - a).abs() < 1e-13 {
            break;
        }
        let c = (a * gb - b * ga) / (gb - ga);
        let gc = eval(c)?.0;
        if gc.signum() == gb.signum() {
            (b, gb) = (a, ga);
            if side == -1 {
                gb *= 0.5;
            }
            side = -1;
        } else {
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        }
        (a, ga) = (c, gc);
    }
    let (d, _, h, s) = ctx.slipping_at(dir, mu, j, a)?;
    Ok(s.lambda.iter().all(|&l| l > 0.0).then_some((d, h)))
}

/// A pivot whose cone cannot hold it starts to slip while the block moves: the
/// direction d of its slip is the one whose friction −μλ d makes its tangential acceleration
/// point along d itself (the slip then grows from zero along d: the consistent slip-start
/// problem, as from rest, for one contact): a consistent direction
/// ([`consistent_directions`]) with a_t·d ≥ 0. Of several such directions the one nearest to the
/// opposite of the shear that would hold the contact is taken: where the stick force reaches the
/// cone's edge, that is the direction in which the contact gives way, so the forces are
/// continuous. The other contacts keep their slip directions `dir`; a stress-dependent
/// criterion's coefficients `mu` are settled by a fixed point around the search.
pub(super) fn slip_start(
    ctx: &Ctx<'_>,
    dir: &mut [Vector3<f64>; 3],
    mu: &mut [f64; 3],
    i: usize,
    coefficients: &dyn Fn(&[f64; 3]) -> [f64; 3],
) -> Result<Solved, RigidError> {
    let no_direction = RigidError::SlipStart { contact: i };
    for _ in 0..MAX_FIXED_POINT {
        // The shear that would hold contact i: the direction it gives way in is its opposite.
        let hold = ctx.solve_stick(dir, mu, i)?.shear[i];
        let give = if hold.norm() > 0.0 {
            -hold / hold.norm()
        } else {
            ctx.geom.tangents(i).0
        };
        let (d, s) = consistent_directions(ctx, dir, mu, i)?
            .into_iter()
            .filter(|(_, h, s)| {
                let scale = ctx.tangential_accel(i, s).norm();
                *h >= -1e-9 * scale.max(f64::MIN_POSITIVE)
            })
            .max_by(|a, b| a.0.dot(&give).total_cmp(&b.0.dot(&give)))
            .map(|(d, _, s)| (d, s))
            .ok_or(no_direction)?;
        dir[i] = d;
        let new_mu = coefficients(&s.lambda);
        let change = (0..3)
            .map(|j| (new_mu[j] - mu[j]).abs())
            .fold(0.0, f64::max);
        if change < 1e-13 {
            return Ok(s);
        }
        *mu = new_mu;
    }
    Err(no_direction)
}

/// The whole block slipping, every contact along the slip that the rates ŷ = (Ẋ, Ż, L θ̇)
/// give it, with ŷ the direction whose friction accelerates the block along `sense` × ŷ
/// (`sense` 1: the consistent slip-start problem for the whole block; −1: the block slowing
/// straight down to rest along ŷ): [`settle_direction`] from `y0`, within `within` of it. A
/// stress-dependent criterion's coefficients, from `mu`, are settled by a fixed point around it.
pub(super) fn all_slipping(
    ctx: &Ctx<'_>,
    y0: Vector3<f64>,
    (sense, within): (f64, f64),
    mut mu: [f64; 3],
    coefficients: &dyn Fn(&[f64; 3]) -> [f64; 3],
) -> Result<Solved, RigidError> {
    let solve = |y: &Vector3<f64>, mu: &[f64; 3]| ctx.solve(&ctx.directions_along(y)?, mu);
    let mut y = y0;
    for _ in 0..MAX_FIXED_POINT / 10 {
        y = settle_direction(y, within, |y| {
            Ok(ctx.generalized_acceleration(&solve(y, &mu)?) * sense)
        })?;
        let s = solve(&y, &mu)?;
        let new_mu = coefficients(&s.lambda);
        if (0..3).all(|i| (new_mu[i] - mu[i]).abs() < 1e-13) {
            return Ok(s);
        }
        mu = new_mu;
    }
    Err(RigidError::SlipFromRest)
}

/// Slip from rest (the block is not held; `mechanics::static_friction` decided that). The
/// modes, tried in order, the first consistent one taken:
///
/// 1. all three contacts slip: the direction ŷ of the rates (Ẋ, Ż, L θ̇) whose slip directions
///    give accelerations along ŷ itself (Newton on the sphere from the frictionless direction,
///    then from the best of a spread of starting directions);
/// 2. one contact i sticks and the block turns about it: rates ±ŷ_i along which contact i does
///    not slip, consistent when the acceleration points along them, all normals are positive
///    and contact i's shear lies inside its cone.
pub(super) fn from_rest(
    ctx: &Ctx<'_>,
    frictionless: &Solved,
    coefficients: &dyn Fn(&[f64; 3]) -> [f64; 3],
) -> Result<(Solved, Option<usize>), RigidError> {
    let direction = |y: &Vector3<f64>, mu: &[f64; 3]| {
        let s = ctx.solve(&ctx.directions_along(y)?, mu)?;
        Ok::<_, RigidError>((ctx.generalized(&s), s))
    };
    let mu0 = coefficients(&frictionless.lambda);
    let all_slip =
        |y0: Vector3<f64>| all_slipping(ctx, y0, (1.0, f64::INFINITY), mu0, coefficients);
    let positive = |s: &Solved| s.lambda.iter().all(|&l| l > 0.0);
    if let Some(s) = all_slip(ctx.generalized(frictionless))
        .ok()
        .filter(positive)
    {
        return Ok((s, None));
    }
    // A spread of starting directions (Fibonacci sphere), best residual first.
    let mut seeds: Vec<(f64, Vector3<f64>)> = (0..200)
        .filter_map(|k| {
            let z = 1.0 - (2.0 * k as f64 + 1.0) / 200.0;
            let phi = k as f64 * std::f64::consts::PI * (3.0 - 5f64.sqrt());
            let rxy = (1.0 - z * z).sqrt();
            let y = Vector3::new(rxy * phi.cos(), rxy * phi.sin(), z);
            let (s, _) = direction(&y, &mu0).ok()?;
            Some(((s - y).norm(), y))
        })
        .collect();
    seeds.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (_, y) in seeds.iter().take(6) {
        if let Some(s) = all_slip(*y).ok().filter(positive) {
            return Ok((s, None));
        }
    }
    // One contact sticks.
    for i in 0..3 {
        let yi = ctx.pivot_direction(i)?;
        for sign in [1.0, -1.0] {
            let y = yi * sign;
            let dir = ctx.directions_along(&y)?;
            let mut mu = coefficients(&frictionless.lambda);
            let mut s = ctx.solve_stick(&dir, &mu, i)?;
            for _ in 0..MAX_FIXED_POINT {
                let new_mu = coefficients(&s.lambda);
                let change = (0..3)
                    .map(|j| (new_mu[j] - mu[j]).abs())
                    .fold(0.0, f64::max);
                mu = new_mu;
                s = ctx.solve_stick(&dir, &mu, i)?;
                if change < 1e-13 {
                    break;
                }
            }
            let along = ctx.generalized(&s).dot(&y) > 0.0;
            if along && positive(&s) && in_cone(&s.shear[i], mu[i], s.lambda[i]) {
                return Ok((s, Some(i)));
            }
        }
    }
    Err(RigidError::SlipFromRest)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An acceleration of size `size` along −X whose small part along L θ̇ flips with the sign
    /// of ŷ's (at 5e-17): the map just past an onset, where round-off in ŷ's twist decides it.
    fn flipping(size: f64) -> impl Fn(&Vector3<f64>) -> Result<Vector3<f64>, RigidError> {
        move |y: &Vector3<f64>| {
            let across = if y.z > 5e-17 { -3e-7 } else { 3e-7 };
            Ok(Vector3::new(-1.0, 0.0, across).normalize() * size)
        }
    }

    #[test]
    fn a_slip_direction_whose_acceleration_across_it_is_negligible_is_settled() {
        // A block 1e-6 m/s² past its onset: 3e-7 of that across ŷ is 3e-13 m/s².
        let y = settle_direction(Vector3::new(-1.0, 0.0, 0.0), 1.0, flipping(1e-6)).unwrap();
        assert!((y - Vector3::new(-1.0, 0.0, 0.0)).norm() < 1e-12, "{y:?}");
    }

    #[test]
    fn a_slip_direction_the_acceleration_leaves_by_more_than_round_off_is_refused() {
        // The same map at 1 m/s²: 3e-7 m/s² across ŷ is a direction that does not settle.
        let r = settle_direction(Vector3::new(-1.0, 0.0, 0.0), 1.0, flipping(1.0));
        assert!(matches!(r, Err(RigidError::SlipFromRest)), "{r:?}");
    }

    #[test]
    fn a_consistent_direction_farther_than_asked_is_given_up() {
        // a = diag(2, 1, 0.5) ŷ is consistent along X only, 20° from the start: within 0.1
        // of it nothing is found; within 1, X.
        let a = |y: &Vector3<f64>| Ok(Vector3::new(2.0 * y.x, y.y, 0.5 * y.z));
        let start = Vector3::new(1.0, 0.3, 0.2).normalize();
        let r = settle_direction(start, 0.1, a);
        assert!(matches!(r, Err(RigidError::SlipFromRest)), "{r:?}");
        let y = settle_direction(start, 1.0, a).unwrap();
        assert!((y - Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-12, "{y:?}");
    }

    #[test]
    fn a_smooth_map_settles_on_its_consistent_direction() {
        // a = diag(2, 1, 0.5) ŷ: consistent along X, found from 20° away.
        let a = |y: &Vector3<f64>| Ok(Vector3::new(2.0 * y.x, y.y, 0.5 * y.z));
        let y = settle_direction(Vector3::new(1.0, 0.3, 0.2).normalize(), 1.0, a).unwrap();
        assert!((y - Vector3::new(1.0, 0.0, 0.0)).norm() < 1e-12, "{y:?}");
    }
}
