//! The constrained block's kinematics: its inertia in world axes, its twist from the rates
//! (Ẋ, Ż, θ̇) with every contact kept on its plane (the velocity projection), each contact's
//! velocity map, and the rates with a pivot's slip removed as an impulse would
//! (`derivations/08-rigid-body.md` §1–2).

use super::RigidError;
use crate::mechanics::ContactGeometry;
use crate::model::Block;
use crate::numeric::small_solve;
use nalgebra::{Matrix3, Vector3};

/// The inertia tensor in global axes and its inverse, at one pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertia {
    /// The tensor in global axes (kg·m²).
    pub world: Matrix3<f64>,
    /// Its inverse.
    pub inverse: Matrix3<f64>,
}

impl Inertia {
    /// I_W = R I_B Rᵀ with R = [i' j' k'] (columns).
    pub fn new(block: &Block, geom: &ContactGeometry) -> Result<Self, RigidError> {
        let f = &geom.frame;
        let r = Matrix3::from_columns(&[f.i, f.j, f.k]);
        let body = block.tensor();
        let inv_body = body
            .try_inverse()
            .ok_or(RigidError::Singular("inertia tensor"))?;
        Ok(Inertia {
            world: r * body * r.transpose(),
            inverse: r * inv_body * r.transpose(),
        })
    }
}

/// CM velocity v and angular velocity ω (global, rad/s about the global axes).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Twist {
    /// v (m/s).
    pub v: Vector3<f64>,
    /// ω (rad/s).
    pub w: Vector3<f64>,
}

impl Twist {
    /// Whether the block is at rest: v and ω exactly zero.
    pub fn is_zero(&self) -> bool {
        self.v == Vector3::zeros() && self.w == Vector3::zeros()
    }

    /// Velocity of the body point at arm r from the CM.
    pub fn at(&self, r: &Vector3<f64>) -> Vector3<f64> {
        self.v + self.w.cross(r)
    }

    /// Kinetic energy ½ m v² + ½ ωᵀ I ω (J).
    pub fn kinetic_energy(&self, mass: f64, inertia: &Inertia) -> f64 {
        0.5 * mass * self.v.norm_squared() + 0.5 * self.w.dot(&(inertia.world * self.w))
    }

    /// The kinetic-energy inner product of two twists (sign tells whether motion reversed).
    pub fn energy_dot(&self, other: &Twist, mass: f64, inertia: &Inertia) -> f64 {
        mass * self.v.dot(&other.v) + self.w.dot(&(inertia.world * other.w))
    }
}

/// Unit vector u = i' and θ̇'s linear form in ω: θ = atan2(u_z, u_x), u̇ = ω × u, so
/// θ̇ = (u_x u_y ω_x − ρ² ω_y + u_z u_y ω_z)/ρ² with ρ² = u_x² + u_z².
pub(super) fn theta_rate_row(u: &Vector3<f64>) -> Vector3<f64> {
    let rho2 = u.x * u.x + u.z * u.z;
    Vector3::new(u.x * u.y / rho2, -1.0, u.z * u.y / rho2)
}

/// The twist of the constrained block with rates (Ẋ, Ż, θ̇): six linear equations — v_X = Ẋ,
/// v_Z = Ż, the three contact velocities along their normals vanish, and θ̇ from ω. This is the
/// velocity projection: the twist always satisfies the constraints to round-off.
///
/// The first two equations give v_X and v_Z outright in ω (their pivots are 1), so they are
/// substituted into the other four, which are solved for (v_Y, ω): the same solution as the six
/// by elimination, singular exactly when the six are.
pub fn twist(geom: &ContactGeometry, rates: [f64; 3]) -> Result<Twist, RigidError> {
    // (Ẋ, Ż) are the rates of the frame's origin O, at −c from the point the twist is of
    // (c = `geom.cm_offset`): v_O = v + c × ω, so v_X = Ẋ + p·ω and v_Z = Ż + q·ω.
    let c = geom.cm_offset;
    let p = Vector3::new(0.0, c.z, -c.y);
    let q = Vector3::new(c.y, -c.x, 0.0);
    let mut a = [[0.0; 4]; 4];
    let mut b = [0.0; 4];
    for i in 0..3 {
        // n·v + (r × n)·ω = 0 with v_X, v_Z substituted: unknowns (v_Y, ω).
        let n = geom.n[i];
        let m = geom.r[i].cross(&n) + p * n.x + q * n.z;
        a[i][0] = n.y;
        for k in 0..3 {
            a[i][1 + k] = m[k];
        }
        b[i] = -n.x * rates[0] - n.z * rates[1];
    }
    let row = theta_rate_row(&geom.frame.i);
    for k in 0..3 {
        a[3][1 + k] = row[k];
    }
    b[3] = rates[2];
    let x = small_solve::solve(a, b)
        .filter(|x| x.iter().all(|v| v.is_finite()))
        .ok_or(RigidError::Singular("velocity projection"))?;
    let w = Vector3::new(x[1], x[2], x[3]);
    Ok(Twist {
        v: Vector3::new(rates[0] + p.dot(&w), x[0], rates[1] + q.dot(&w)),
        w,
    })
}

pub(super) fn unit(v: Vector3<f64>) -> Vector3<f64> {
    let n = v.norm();
    if n > 0.0 { v / n } else { Vector3::zeros() }
}

/// The longest arm from the CM to a contact (m): the length that puts θ̇ among the velocities.
pub(super) fn longest_arm(geom: &ContactGeometry) -> f64 {
    geom.r.iter().map(|r| r.norm()).fold(0.0, f64::max)
}

/// The velocity of contact `i` for each unit rate of (Ẋ, Ż, L θ̇), L = `arm`: the columns of its
/// velocity map (global), through the constrained twist.
pub fn contact_velocity_map(
    geom: &ContactGeometry,
    arm: f64,
    i: usize,
) -> Result<[Vector3<f64>; 3], RigidError> {
    let column = |c: usize| {
        let mut y = [0.0; 3];
        y[c] = if c == 2 { 1.0 / arm } else { 1.0 };
        twist(geom, y).map(|tw| tw.at(&geom.r[i]))
    };
    Ok([column(0)?, column(1)?, column(2)?])
}

/// Rates (Ẋ, Ż, L θ̇), L = `arm`, along which contact `i` does not slip: the null vector of its
/// 2×3 tangential velocity map (unit).
pub(super) fn pivot_direction(
    geom: &ContactGeometry,
    arm: f64,
    i: usize,
) -> Result<Vector3<f64>, RigidError> {
    let (t1, t2) = geom.tangents(i);
    let v = contact_velocity_map(geom, arm, i)?;
    let row = |t: &Vector3<f64>| Vector3::new(v[0].dot(t), v[1].dot(t), v[2].dot(t));
    Ok(unit(row(&t1).cross(&row(&t2))))
}

/// The rates (Ẋ, Ż, θ̇) with the slip of contact `i` removed, and the kinetic energy this
/// takes away (J, ≤ 0). Keeps a sticking contact stuck against the drift of the integrator.
///
/// The projection is the one an impulse at contact i makes: the nearest rates that turn the
/// block about the contact in the kinetic-energy metric, v' = p ⟨p, v⟩_M / ⟨p, p⟩_M with p the
/// pivot direction and ⟨a, b⟩_M = m v_a·v_b + ω_a·I ω_b. It removes kinetic energy only to
/// second order in the slip it removes (½ |Δv|²_M), where a projection in any other metric
/// changes it to first order — at 1e-6 of the speed on a block of 27 MJ, tens of joules
/// — and the route books what it removes as friction work.
pub fn pivot_rates(
    geom: &ContactGeometry,
    block: &Block,
    rates: [f64; 3],
    i: usize,
) -> Result<([f64; 3], f64), RigidError> {
    let arm = longest_arm(geom);
    let p = pivot_direction(geom, arm, i)?;
    let p = [p.x, p.y, p.z / arm];
    let inertia = Inertia::new(block, geom)?;
    let (tp, tv) = (twist(geom, p)?, twist(geom, rates)?);
    let c = tp.energy_dot(&tv, block.mass, &inertia) / tp.energy_dot(&tp, block.mass, &inertia);
    if !c.is_finite() {
        return Err(RigidError::Singular("pivot projection"));
    }
    let projected = p.map(|x| c * x);
    let removed = 0.5 * c * c * tp.energy_dot(&tp, block.mass, &inertia)
        - tv.kinetic_energy(block.mass, &inertia);
    Ok((projected, removed.min(0.0)))
}
