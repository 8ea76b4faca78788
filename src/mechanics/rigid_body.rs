//! Rigid-body dynamics of the block (issue #7; `derivations/08-rigid-body.md`).
//!
//! We deliberately differ from the paper's §5–7 here: instead of holding the block to
//! translation along x' and rotation about y' and letting the shear directions float, the block
//! is a rigid body with six degrees of freedom whose three contact points stay on their planes
//! (three holonomic constraints, so three degrees of freedom remain: X, Z, θ). The normal
//! reactions are the constraint forces; each shear force is the friction criterion's capacity at
//! its normal force, opposing the slip velocity of its own contact point.
//!
//! At one state the unknowns are the CM acceleration a, the angular acceleration ω̇ and the three
//! normal magnitudes λ. Newton–Euler (with the gyroscopic term ω × Iω) gives a and ω̇ affinely
//! in λ; the three constraint accelerations n_i·(a + ω̇ × r_i + ω × (ω × r_i)) = 0 then leave a
//! 3×3 linear system K λ = b (the Delassus matrix with friction, non-symmetric).
//!
//! A contact with no slip velocity (the start, a restart after a stop) has no direction from its
//! velocity; there the shear opposes the contact's tangential *acceleration* (the Coulomb limit,
//! not a regularising velocity), found by a fixed point.

use super::ContactGeometry;
use super::loads::Applied;
use crate::model::Block;
use crate::model::Strength;
use nalgebra::{Matrix3, Matrix6, SMatrix, SVector, Vector3, Vector6};

/// Why the rigid-body accelerations cannot be had at a state.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum RigidError {
    /// A normal reaction is not positive: the contact lifts off its plane.
    #[error("contact {contact} lifts off (normal reaction {normal_n:.6e} N)")]
    LiftOff { contact: usize, normal_n: f64 },
    /// The contact equations are singular: the velocities are not determined by (Ẋ, Ż, θ̇), or
    /// friction makes the normal forces indeterminate (Painlevé's paradox).
    #[error("the contact equations are singular ({0})")]
    Singular(&'static str),
    /// No consistent way to start slipping was found (all contacts slipping, or one sticking).
    #[error(
        "no consistent start of slip: neither all three contacts slipping nor one sticking fits"
    )]
    SlipFromRest,
    /// A contact whose slip vanished while the block moves can be held by no force inside its
    /// friction cone, and no direction of slip is consistent with its own friction (the
    /// tangential acceleration never points along the slip it would start).
    #[error(
        "contact {contact}: its friction cone cannot hold it, and no slip direction is consistent \
         with its friction (the contact problem has no solution there)"
    )]
    SlipStart { contact: usize },
    /// The contact riding a crease is pulled off its second face (that face's normal force is
    /// not positive): it leaves the crease and goes on along its own face alone.
    #[error("contact {contact} leaves the crease (its second face's reaction {normal_n:.6e} N)")]
    CreaseLetsGo { contact: usize, normal_n: f64 },
    /// The contact riding a crease is pulled off its own face while its second face holds it:
    /// it goes on along the second face alone.
    #[error(
        "contact {contact} leaves its face for the crease's other face (its own face's reaction \
         {normal_n:.6e} N)"
    )]
    CreaseTakesOver { contact: usize, normal_n: f64 },
    /// The equations of one contact sticking while the others slip are singular.
    #[error(
        "contact {contact}: the equations of it sticking while the others slip are singular \
         (its tangential constraints depend on the normal ones at this pose)"
    )]
    StickSingular { contact: usize },
    /// Every contact rides a crease: six constraints hold the block's six degrees of freedom
    /// (`derivations/10-faces.md` §4), it is wedged.
    #[error("every contact rides a crease: the block is wedged")]
    Wedged,
    /// At an impact, contact `contact`, on one face alone, would have to be pulled onto it (its
    /// impulse negative, N·s): the impact lifts it off, at `speed_m_s`.
    #[error(
        "the impact lifts contact {contact} off its face at {speed_m_s:.3e} m/s (held, its \
         impulse would be {impulse_n_s:.6e} N·s)"
    )]
    ImpactLifts {
        contact: usize,
        impulse_n_s: f64,
        speed_m_s: f64,
    },
}

/// The inertia tensor in global axes and its inverse, at one pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertia {
    pub world: Matrix3<f64>,
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
    pub v: Vector3<f64>,
    pub w: Vector3<f64>,
}

impl Twist {
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
fn theta_rate_row(u: &Vector3<f64>) -> Vector3<f64> {
    let rho2 = u.x * u.x + u.z * u.z;
    Vector3::new(u.x * u.y / rho2, -1.0, u.z * u.y / rho2)
}

/// The twist of the constrained block with rates (Ẋ, Ż, θ̇): six linear equations — v_X = Ẋ,
/// v_Z = Ż, the three contact velocities along their normals vanish, and θ̇ from ω. This is the
/// velocity projection: the twist always satisfies the constraints to round-off.
pub fn twist(geom: &ContactGeometry, rates: [f64; 3]) -> Result<Twist, RigidError> {
    let mut a = Matrix6::zeros();
    let mut b = Vector6::zeros();
    // (Ẋ, Ż) are the rates of the frame's origin O, at −c from the point the twist is of
    // (c = `geom.cm_offset`): v_O = v + c × ω.
    let c = geom.cm_offset;
    a[(0, 0)] = 1.0;
    a[(0, 4)] = -c.z;
    a[(0, 5)] = c.y;
    b[0] = rates[0];
    a[(1, 2)] = 1.0;
    a[(1, 3)] = -c.y;
    a[(1, 4)] = c.x;
    b[1] = rates[1];
    for i in 0..3 {
        let n = geom.n[i];
        let m = geom.r[i].cross(&n);
        for c in 0..3 {
            a[(2 + i, c)] = n[c];
            a[(2 + i, 3 + c)] = m[c];
        }
    }
    let row = theta_rate_row(&geom.frame.i);
    for c in 0..3 {
        a[(5, 3 + c)] = row[c];
    }
    b[5] = rates[2];
    let x = a
        .lu()
        .solve(&b)
        .filter(|x| x.iter().all(|v| v.is_finite()))
        .ok_or(RigidError::Singular("velocity projection"))?;
    Ok(Twist {
        v: Vector3::new(x[0], x[1], x[2]),
        w: Vector3::new(x[3], x[4], x[5]),
    })
}

/// A contact riding the crease between its own face and a second one
/// (`derivations/10-faces.md` §4): a fourth constraint, the contact on the second face too.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crease {
    /// The contact in the crease.
    pub contact: usize,
    /// The second face's upward unit normal.
    pub normal: Vector3<f64>,
    /// The second face's offset e (m·P = e) and its number in the ground (for the route).
    pub offset: f64,
    pub face: usize,
}

/// The creases the contacts ride, at most one second face per contact
/// (`derivations/10-faces.md` §4): each a constraint more, so that with two the block keeps one
/// degree of freedom and with three it is wedged.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Creases([Option<Crease>; 3]);

impl Creases {
    /// No contact in a crease.
    pub const NONE: Creases = Creases([None; 3]);

    /// The crease contact `contact` rides, if any.
    pub fn at(&self, contact: usize) -> Option<&Crease> {
        self.0.get(contact).and_then(Option::as_ref)
    }

    /// The creases in the order of their contacts.
    pub fn iter(&self) -> impl Iterator<Item = &Crease> {
        self.0.iter().flatten()
    }

    /// How many contacts ride a crease.
    pub fn len(&self) -> usize {
        self.iter().count()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// These creases and `c` (replacing any its contact rode).
    #[must_use]
    pub fn with(mut self, c: Crease) -> Creases {
        self.0[c.contact] = Some(c);
        self
    }

    /// These creases without contact `contact`'s (if `Some`).
    #[must_use]
    pub fn without(mut self, contact: Option<usize>) -> Creases {
        if let Some(slot) = contact.and_then(|i| self.0.get_mut(i)) {
            *slot = None;
        }
        self
    }

    /// The second face of each contact (for the route's rows).
    pub fn faces(&self) -> [Option<u32>; 3] {
        self.0.map(|c| c.map(|c| c.face as u32))
    }
}

impl From<Crease> for Creases {
    fn from(c: Crease) -> Creases {
        Creases::NONE.with(c)
    }
}

/// Everything the rigid-body dynamics gives at one state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    pub twist: Twist,
    /// CM acceleration and angular acceleration (global).
    pub accel: Vector3<f64>,
    pub ang_accel: Vector3<f64>,
    /// Normal reaction magnitudes (N) and shear force vectors (N).
    pub normal: [f64; 3],
    pub shear: [Vector3<f64>; 3],
    /// Slip velocity of each contact (m/s).
    pub slip: [Vector3<f64>; 3],
    /// (Ẍ, Z̈, θ̈).
    pub acc: [f64; 3],
    /// Power of the hydraulic force and couple, and of friction (W; friction's is ≤ 0).
    pub power_hydraulic: f64,
    pub power_friction: f64,
    pub inertia: Inertia,
    /// The contact that sticks while the block turns about it (its slip vanished and its shear
    /// lies inside its cone), if any.
    pub stuck: Option<usize>,
    /// The second face's normal reaction (N) of each contact riding a crease.
    pub crease_normal: [Option<f64>; 3],
    /// The creases the motion was evaluated with.
    pub creases: Creases,
}

/// A slip speed below this fraction of the block's speed scale counts as zero slip.
const ZERO_SLIP: f64 = 1e-9;
/// Iterations of the fixed points (slip directions from rest, stress-dependent criteria).
const MAX_FIXED_POINT: usize = 200;

/// Solves ŝ(ŷ) = ŷ on the unit sphere by Newton's method (finite-difference Jacobian, halving
/// steps while |ŝ − ŷ| does not fall), from `y`.
fn settle_direction(
    mut y: Vector3<f64>,
    s: impl Fn(&Vector3<f64>) -> Result<Vector3<f64>, RigidError>,
) -> Result<Vector3<f64>, RigidError> {
    let residual = |y: &Vector3<f64>| s(y).map(|v| v - y);
    let mut f = residual(&y)?;
    for _ in 0..MAX_FIXED_POINT {
        if f.norm() < 1e-14 {
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
        let mut t = 1.0;
        loop {
            let cand = (y + step * t).normalize();
            let fc = residual(&cand)?;
            if fc.norm() < f.norm() || t < 1e-6 {
                y = cand;
                f = fc;
                break;
            }
            t *= 0.5;
        }
    }
    if f.norm() < 1e-10 {
        Ok(y)
    } else {
        Err(RigidError::SlipFromRest)
    }
}

/// What is fixed at one state while the contact forces are sought.
struct Ctx<'a> {
    geom: &'a ContactGeometry,
    inertia: Inertia,
    mass: f64,
    /// Applied force (F + W) and torque (couple − ω × Iω).
    force: Vector3<f64>,
    torque: Vector3<f64>,
    /// ω × (ω × r_i).
    centripetal: [Vector3<f64>; 3],
    /// Longest arm (m): scales θ̇ against Ẋ, Ż.
    arm: f64,
    /// The contacts riding creases.
    creases: Creases,
}

/// One solution of the contact problem: normals, CM and angular acceleration, shear vectors.
#[derive(Clone, Copy)]
struct Solved {
    lambda: [f64; 3],
    a: Vector3<f64>,
    e: Vector3<f64>,
    shear: [Vector3<f64>; 3],
    /// Each contact's second normal reaction in its crease (zero without).
    crease: [f64; 3],
}

fn unit(v: Vector3<f64>) -> Vector3<f64> {
    let n = v.norm();
    if n > 0.0 { v / n } else { Vector3::zeros() }
}

impl Ctx<'_> {
    fn tangential(&self, i: usize, v: Vector3<f64>) -> Vector3<f64> {
        v - self.geom.n[i] * v.dot(&self.geom.n[i])
    }

    fn slip_of(&self, t: &Twist) -> [Vector3<f64>; 3] {
        [0, 1, 2].map(|i| self.tangential(i, t.at(&self.geom.r[i])))
    }

    /// Unit direction of the rates (Ẋ, Ż, L θ̇) of an acceleration (a, ω̇).
    fn generalized(&self, s: &Solved) -> Vector3<f64> {
        let row = theta_rate_row(&self.geom.frame.i);
        unit(Vector3::new(s.a.x, s.a.z, self.arm * row.dot(&s.e)))
    }

    fn tangential_accel(&self, i: usize, s: &Solved) -> Vector3<f64> {
        self.tangential(i, s.a + s.e.cross(&self.geom.r[i]) + self.centripetal[i])
    }

    /// All contacts slip: shear −μ_j λ_j dir_j. K λ = b (3×3), then a and ω̇. Each contact in
    /// a crease adds its second face as a row and a reaction (4×4, 5×5), and that contact's
    /// friction −μ (λ + λ_B) dir opposes its slip on both faces.
    fn solve(&self, dir: &[Vector3<f64>; 3], mu: &[f64; 3]) -> Result<Solved, RigidError> {
        match self.creases.len() {
            0 => self.solve_n::<3>(dir, mu),
            1 => self.solve_n::<4>(dir, mu),
            2 => self.solve_n::<5>(dir, mu),
            _ => Err(RigidError::Wedged),
        }
    }

    /// Constraint row k of N: its contact and normal — the three contacts' own faces, then the
    /// creases' second faces in the order of their contacts.
    fn rows<const N: usize>(&self, creases: &Creases) -> ([usize; N], [Vector3<f64>; N]) {
        let mut contact = [0; N];
        let mut normal = [Vector3::zeros(); N];
        let own = (0..3).map(|k| (k, self.geom.n[k]));
        let second = creases.iter().map(|c| (c.contact, c.normal));
        for (k, (i, n)) in own.chain(second).take(N).enumerate() {
            (contact[k], normal[k]) = (i, n);
        }
        (contact, normal)
    }

    /// [`Ctx::solve`] with N constraint rows ([`Ctx::rows`]).
    fn solve_n<const N: usize>(
        &self,
        dir: &[Vector3<f64>; 3],
        mu: &[f64; 3],
    ) -> Result<Solved, RigidError>
    where
        nalgebra::Const<N>: nalgebra::DimMin<nalgebra::Const<N>, Output = nalgebra::Const<N>>,
    {
        let geom = self.geom;
        // Constraint k: its contact, normal and force direction g (normal and friction).
        let (contact, normal) = self.rows::<N>(&self.creases);
        let g: [Vector3<f64>; N] =
            std::array::from_fn(|k| normal[k] - dir[contact[k]] * mu[contact[k]]);
        let arm_n: [Vector3<f64>; N] =
            std::array::from_fn(|k| geom.r[contact[k]].cross(&normal[k]));
        let arm_g: [Vector3<f64>; N] =
            std::array::from_fn(|k| self.inertia.inverse * geom.r[contact[k]].cross(&g[k]));
        let mut kk = SMatrix::<f64, N, N>::zeros();
        let mut b = SVector::<f64, N>::zeros();
        let free_ang = self.inertia.inverse * self.torque;
        for r in 0..N {
            for q in 0..N {
                kk[(r, q)] = normal[r].dot(&g[q]) / self.mass + arm_n[r].dot(&arm_g[q]);
            }
            b[r] = -normal[r].dot(&self.centripetal[contact[r]])
                - normal[r].dot(&self.force) / self.mass
                - arm_n[r].dot(&free_ang);
        }
        let lambda = kk
            .lu()
            .solve(&b)
            .filter(|x| x.iter().all(|v| v.is_finite()))
            .ok_or(RigidError::Singular("normal reactions"))?;
        let mut f = self.force;
        let mut t = self.torque;
        let mut second = [0.0; 3];
        for k in 0..N {
            f += g[k] * lambda[k];
            t += geom.r[contact[k]].cross(&g[k]) * lambda[k];
            if k >= 3 {
                second[contact[k]] = lambda[k];
            }
        }
        let shear = [0, 1, 2].map(|j| -dir[j] * (mu[j] * (lambda[j] + second[j])));
        Ok(Solved {
            lambda: [lambda[0], lambda[1], lambda[2]],
            a: f / self.mass,
            e: self.inertia.inverse * t,
            shear,
            crease: second,
        })
    }

    /// Contact `i` sticks (its tangential acceleration vanishes, its shear is unknown), the
    /// others slip along `dir`: Newton–Euler, three normal and two tangential constraint
    /// accelerations, eleven linear equations in (a, ω̇, λ, f_i).
    fn solve_stick(
        &self,
        dir: &[Vector3<f64>; 3],
        mu: &[f64; 3],
        i: usize,
    ) -> Result<Solved, RigidError> {
        // The sticking contact, held in place, stays on its crease's second face too if it
        // rides one, and its reaction (normal and shear on its own face) carries both faces'
        // forces; each crease at another contact is one more constraint row and reaction.
        let creases = self.creases.without(Some(i));
        match creases.len() {
            0 => self.solve_stick_n::<11>(dir, mu, i, &creases),
            1 => self.solve_stick_n::<12>(dir, mu, i, &creases),
            2 => self.solve_stick_n::<13>(dir, mu, i, &creases),
            _ => Err(RigidError::Wedged),
        }
    }

    /// [`Ctx::solve_stick`] with N = 11 unknowns (a, ω̇, three normals, two shear components)
    /// and one more for the second normal of each crease in `creases`.
    fn solve_stick_n<const N: usize>(
        &self,
        dir: &[Vector3<f64>; 3],
        mu: &[f64; 3],
        i: usize,
        creases: &Creases,
    ) -> Result<Solved, RigidError>
    where
        nalgebra::Const<N>: nalgebra::DimMin<nalgebra::Const<N>, Output = nalgebra::Const<N>>,
    {
        let geom = self.geom;
        let (t1, t2) = geom.tangents(i);
        let mut a = SMatrix::<f64, N, N>::zeros();
        let mut b = SVector::<f64, N>::zeros();
        let iw = self.inertia.world;
        for k in 0..3 {
            a[(k, k)] = self.mass;
            b[k] = self.force[k];
            b[3 + k] = self.torque[k];
            for c in 0..3 {
                a[(3 + k, 3 + c)] = iw[(k, c)];
            }
        }
        // Unknown `col` is the reaction along n (normal n − μ dir, or n alone at the sticking
        // contact) at contact j, and row `col` its constraint n·(contact acceleration) = 0.
        let mut constraint = |col: usize, j: usize, n: Vector3<f64>, g: Vector3<f64>| {
            let m = geom.r[j].cross(&g);
            for k in 0..3 {
                a[(k, col)] = -g[k];
                a[(3 + k, col)] = -m[k];
            }
            let arm = geom.r[j].cross(&n);
            for c in 0..3 {
                a[(col, c)] = n[c];
                a[(col, 3 + c)] = arm[c];
            }
            b[col] = -n.dot(&self.centripetal[j]);
        };
        for j in 0..3 {
            let n = geom.n[j];
            let g = if j == i { n } else { n - dir[j] * mu[j] };
            constraint(6 + j, j, n, g);
        }
        for (q, t) in [t1, t2].into_iter().enumerate() {
            constraint(9 + q, i, t, t);
        }
        // A crease contact carries its second face's friction too: μ (λ_j + λ_B) against its
        // slip.
        for (q, c) in creases.iter().enumerate() {
            let j = c.contact;
            constraint(11 + q, j, c.normal, c.normal - dir[j] * mu[j]);
        }
        let x = a
            .lu()
            .solve(&b)
            .filter(|x| x.iter().all(|v| v.is_finite()))
            .ok_or(RigidError::StickSingular { contact: i })?;
        let lambda = [x[6], x[7], x[8]];
        let mut second = [0.0; 3];
        for (q, c) in creases.iter().enumerate() {
            second[c.contact] = x[11 + q];
        }
        let shear = [0, 1, 2].map(|j| {
            if j == i {
                t1 * x[9] + t2 * x[10]
            } else {
                -dir[j] * (mu[j] * (lambda[j] + second[j]))
            }
        });
        Ok(Solved {
            lambda,
            a: Vector3::new(x[0], x[1], x[2]),
            e: Vector3::new(x[3], x[4], x[5]),
            shear,
            crease: second,
        })
    }

    /// Rates (Ẋ, Ż, L θ̇) along which contact `i` does not slip.
    fn pivot_direction(&self, i: usize) -> Result<Vector3<f64>, RigidError> {
        pivot_direction(self.geom, self.arm, i)
    }

    /// Contact `i` slipping along the direction at angle `phi` on its tangent plane (the others
    /// along `dir`): the direction d, (d × a_t)·n (zero where the tangential acceleration is
    /// parallel to d), a_t·d, and the solution.
    fn slipping_at(
        &self,
        dir: &[Vector3<f64>; 3],
        mu: &[f64; 3],
        i: usize,
        phi: f64,
    ) -> Result<(Vector3<f64>, f64, f64, Solved), RigidError> {
        let (t1, t2) = self.geom.tangents(i);
        let d = t1 * phi.cos() + t2 * phi.sin();
        let mut dd = *dir;
        dd[i] = d;
        let s = self.solve(&dd, mu)?;
        let a = self.tangential_accel(i, &s);
        Ok((d, self.geom.n[i].dot(&d.cross(&a)), d.dot(&a), s))
    }
}

/// The longest arm from the CM to a contact (m): the length that puts θ̇ among the velocities.
fn longest_arm(geom: &ContactGeometry) -> f64 {
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
fn pivot_direction(geom: &ContactGeometry, arm: f64, i: usize) -> Result<Vector3<f64>, RigidError> {
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
/// (issue #12) — and the route books what it removes as friction work.
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

/// The rates (Ẋ, Ż, θ̇) with each crease contact's velocity into its crease's second face
/// removed, and the kinetic energy this takes away (J, ≤ 0): the projection a perfectly
/// inelastic, frictionless impulse along those faces' normals makes (in the kinetic-energy
/// metric, as [`pivot_rates`]): r' = r − G⁻¹Rᵀ(RG⁻¹Rᵀ)⁻¹Rr, with G the metric of the rates and
/// R the rows n_B · v_i. Keeps contacts riding creases on both faces against the integrator's
/// drift, and takes the velocity into a face a contact meets.
pub fn crease_rates(
    geom: &ContactGeometry,
    block: &Block,
    rates: [f64; 3],
    creases: &Creases,
) -> Result<([f64; 3], f64), RigidError> {
    let k = creases.len();
    if k == 0 {
        return Ok((rates, 0.0));
    }
    if k == 3 {
        return Err(RigidError::Wedged);
    }
    let inertia = Inertia::new(block, geom)?;
    let unit_rates = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let basis = unit_rates.map(|u| twist(geom, u));
    let basis = [basis[0]?, basis[1]?, basis[2]?];
    let singular = RigidError::Singular("crease projection");
    // Kinetic-energy metric of the rates, and the constraint rows n_B · v_i.
    let g = Matrix3::from_fn(|a, b| basis[a].energy_dot(&basis[b], block.mass, &inertia));
    let g_lu = g.lu();
    let rows: Vec<Vector3<f64>> = creases
        .iter()
        .map(|c| Vector3::from_fn(|q, _| c.normal.dot(&basis[q].at(&geom.r[c.contact]))))
        .collect();
    let ginv_rows = rows
        .iter()
        .map(|r| g_lu.solve(r).ok_or(singular))
        .collect::<Result<Vec<_>, _>>()?;
    let s = nalgebra::DMatrix::from_fn(k, k, |a, b| rows[a].dot(&ginv_rows[b]));
    let r = Vector3::new(rates[0], rates[1], rates[2]);
    let into = nalgebra::DVector::from_fn(k, |a, _| rows[a].dot(&r));
    let m = s
        .lu()
        .solve(&into)
        .filter(|m| m.iter().all(|v| v.is_finite()))
        .ok_or(singular)?;
    let projected = r - (0..k).map(|a| ginv_rows[a] * m[a]).sum::<Vector3<f64>>();
    let removed = -0.5 * into.dot(&m);
    if !(removed.is_finite() && removed <= 1e-12 * r.norm_squared().max(f64::MIN_POSITIVE)) {
        return Err(singular);
    }
    Ok(([projected.x, projected.y, projected.z], removed.min(0.0)))
}

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
/// twist after it is the one [`crease_rates`] gives.
pub fn impact(
    geom: &ContactGeometry,
    block: &Block,
    rates: [f64; 3],
    creases: &Creases,
    law: &ImpactLaw,
) -> Result<Impact, RigidError> {
    impact_onto(geom, geom, block, rates, creases, law)
}

/// [`impact`] where a contact's own face changes at the impact (a contact running over a ridge
/// onto the face beyond it): the block moves with rates (Ẋ, Ż, θ̇) on the faces of `before`
/// (its twist, and the kinetic energy the impact takes, are those), and the impulses hold it
/// to the faces of `after` (the same pose, other normals).
pub fn impact_onto(
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

/// Coulomb's cone with a little room for round-off.
fn in_cone(shear: &Vector3<f64>, mu: f64, lambda: f64) -> bool {
    shear.norm() <= mu * lambda * (1.0 + 1e-9)
}

/// The accelerations at a pose with rates (Ẋ, Ż, θ̇).
pub fn accelerations(
    geom: &ContactGeometry,
    applied: &Applied,
    block: &Block,
    friction: &Strength,
    rates: [f64; 3],
) -> Result<Motion, RigidError> {
    accelerations_slaved(geom, applied, block, friction, rates, 0.0)
}

/// [`accelerations`] for an integrator of step `step` (s): the direction of a *young, slow*
/// slip — slower than 4 μ λ / m × `step` (the speed friction takes away in four steps) while
/// its tangential acceleration is under a tenth of μ λ / m — is slaved to its quasi-static
/// value instead of being read off the slip velocity (issue #12).
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
/// The slaved direction d is the one the slip settles to within that time: the tangential
/// acceleration it gives is parallel to it, (d × a_t)·n = 0, the root nearest the slip's own
/// direction; the slip then grows or shrinks along d, and a slip that shrinks passes through
/// zero where the route's pivot event finds it. As `step` → 0 the band vanishes and the law is
/// Coulomb's.
pub fn accelerations_slaved(
    geom: &ContactGeometry,
    applied: &Applied,
    block: &Block,
    friction: &Strength,
    rates: [f64; 3],
    step: f64,
) -> Result<Motion, RigidError> {
    accelerations_in_crease(geom, applied, block, friction, rates, step, Creases::NONE)
}

/// [`accelerations_slaved`] with contacts riding creases (`derivations/10-faces.md` §4): each
/// crease's second face is one more constraint, its reaction one more unknown, and both faces'
/// friction opposes the contact's slip along the crease. `rates` must keep each such contact on
/// its second face (its velocity along that face's normal zero, [`crease_rates`]). A second
/// face's reaction falling to zero is [`RigidError::CreaseLetsGo`]; the contact's own face's,
/// while the second holds it, [`RigidError::CreaseTakesOver`]; three creases at once,
/// [`RigidError::Wedged`].
pub fn accelerations_in_crease(
    geom: &ContactGeometry,
    applied: &Applied,
    block: &Block,
    friction: &Strength,
    rates: [f64; 3],
    step: f64,
    creases: Creases,
) -> Result<Motion, RigidError> {
    if creases.len() == 3 {
        return Err(RigidError::Wedged);
    }
    let inertia = Inertia::new(block, geom)?;
    let tw = twist(geom, rates)?;
    let ctx = Ctx {
        geom,
        inertia,
        mass: block.mass,
        force: applied.total_force(),
        torque: applied.total_moment() - tw.w.cross(&(inertia.world * tw.w)),
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
    let stress_dependent = friction.is_stress_dependent();

    let slip = ctx.slip_of(&tw);
    let zero = [Vector3::zeros(); 3];
    // The frictionless solution: the answer of a frictionless scene (no friction solve at
    // all), the starting direction from rest, and the first normals of a stress-dependent
    // criterion. A sliding block under Coulomb friction does not need it (μ is constant).
    let needs_frictionless = frictionless || tw.is_zero() || stress_dependent;
    let mut stuck_contact = None;
    let mut sol = if needs_frictionless {
        ctx.solve(&zero, &[0.0; 3])?
    } else {
        ctx.solve(&slip.map(unit), &coefficients(&[1.0; 3]))?
    };
    if frictionless {
        // Done.
    } else if tw.is_zero() {
        (sol, stuck_contact) = from_rest(&ctx, &sol, &coefficients)?;
    } else {
        // Moving: each shear opposes its contact's slip velocity. A contact whose slip
        // vanishes while the block moves (a pivot) sticks if its cone allows, or else slips
        // along its tangential acceleration.
        let scale = tw.v.norm() + tw.w.norm() * ctx.arm;
        let mut pivot = (0..3).find(|&i| slip[i].norm() <= ZERO_SLIP * scale);
        let mut dir = slip.map(unit);
        let mut mu = coefficients(&sol.lambda);
        let mut slaved = false;
        let zero_pivot = pivot;
        for j in (0..3).filter(|&j| Some(j) != zero_pivot) {
            let friction_accel = mu[j] * sol.lambda[j].abs() / block.mass;
            if slip[j].norm() >= 4.0 * friction_accel * step {
                continue;
            }
            if let Some((d, a)) = slaved_direction(&ctx, &dir, &mu, j, &dir[j])? {
                if a.abs() < 0.1 * friction_accel {
                    dir[j] = d;
                    slaved = true;
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
        if slaved && pivot.is_none() {
            sol = ctx.solve(&dir, &mu)?;
        }
        let mut stuck = None;
        if let Some(i) = pivot {
            let (s, settled) = friction.settle(
                &mut mu,
                (1e-13, MAX_FIXED_POINT),
                |mu| ctx.solve_stick(&dir, mu, i),
                |s| Some(s.lambda),
            )?;
            if settled && in_cone(&s.shear[i], mu[i], s.lambda[i]) {
                stuck = Some(s);
            }
        }
        sol = match (stuck, pivot) {
            (Some(s), _) => {
                stuck_contact = pivot;
                s
            }
            // The pivot's cone cannot hold it: it starts to slip, in the direction that
            // reproduces itself (as from rest, for the one contact).
            (None, Some(i)) => slip_start(&ctx, &mut dir, &mut mu, i, &coefficients)?,
            // Coulomb without a pivot: the solve above is the answer.
            (None, None) if !stress_dependent => sol,
            (None, None) => {
                let (sol, settled) = friction.settle(
                    &mut mu,
                    (1e-13, MAX_FIXED_POINT),
                    |mu| ctx.solve(&dir, mu),
                    |s| Some(s.lambda),
                )?;
                if !settled {
                    return Err(RigidError::SlipFromRest);
                }
                sol
            }
        };
    }
    for c in creases.without(stuck_contact).iter() {
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

    // θ̈ from u = i': θ = atan2(u_z, u_x).
    let u = geom.frame.i;
    let du = tw.w.cross(&u);
    let ddu = sol.e.cross(&u) + tw.w.cross(&du);
    let rho2 = u.x * u.x + u.z * u.z;
    let theta_dot = (u.x * du.z - u.z * du.x) / rho2;
    let theta_ddot =
        (u.x * ddu.z - u.z * ddu.x) / rho2 - 2.0 * theta_dot * (u.x * du.x + u.z * du.z) / rho2;

    let power_friction = (0..3).map(|i| sol.shear[i].dot(&slip[i])).sum();
    Ok(Motion {
        twist: tw,
        accel: sol.a,
        ang_accel: sol.e,
        normal: sol.lambda,
        shear: sol.shear,
        slip,
        acc: [sol.a.x, sol.a.z, theta_ddot],
        power_hydraulic: applied.power(&tw.v, &tw.w),
        power_friction,
        inertia,
        stuck: stuck_contact,
        crease_normal: [0, 1, 2].map(|i| creases.at(i).map(|_| sol.crease[i])),
        creases,
    })
}

/// A young slip this small a fraction of the block's speed, that friction stops within the
/// step, is a pivot (see [`accelerations_in_crease`]).
const PIVOTING: f64 = 1e-3;

/// Directions sampled round contact `i`'s tangent plane when its slip direction is sought
/// (each a 3×3 solve); sign changes between them are refined by bisection.
const SLIP_START_SAMPLES: usize = 72;

/// Every direction d on contact `i`'s tangent plane whose friction −μλ d (the other contacts
/// slipping along `dir`) gives a tangential acceleration parallel to d, (d × a_t)·n = 0, with
/// all normal forces positive: (d, a_t·d, the solution).
fn consistent_directions(
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
fn slaved_direction(
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

/// A pivot whose cone cannot hold it starts to slip while the block moves (issue #12): the
/// direction d of its slip is the one whose friction −μλ d makes its tangential acceleration
/// point along d itself (the slip then grows from zero along d: the consistent slip-start
/// problem, as from rest, for one contact): a consistent direction
/// ([`consistent_directions`]) with a_t·d ≥ 0. Of several such directions the one nearest to the
/// opposite of the shear that would hold the contact is taken: where the stick force reaches the
/// cone's edge, that is the direction in which the contact gives way, so the forces are
/// continuous. The other contacts keep their slip directions `dir`; a stress-dependent
/// criterion's coefficients `mu` are settled by a fixed point around the search.
fn slip_start(
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

/// Slip from rest (the block is not held; `mechanics::static_friction` decided that). The
/// modes, tried in order, the first consistent one taken:
///
/// 1. all three contacts slip: the direction ŷ of the rates (Ẋ, Ż, L θ̇) whose slip directions
///    give accelerations along ŷ itself (Newton on the sphere from the frictionless direction,
///    then from the best of a spread of starting directions);
/// 2. one contact i sticks and the block turns about it: rates ±ŷ_i along which contact i does
///    not slip, consistent when the acceleration points along them, all normals are positive
///    and contact i's shear lies inside its cone.
fn from_rest(
    ctx: &Ctx<'_>,
    frictionless: &Solved,
    coefficients: &dyn Fn(&[f64; 3]) -> [f64; 3],
) -> Result<(Solved, Option<usize>), RigidError> {
    let direction = |y: &Vector3<f64>, mu: &[f64; 3]| {
        let t = twist(ctx.geom, [y.x, y.y, y.z / ctx.arm])?;
        let dir = ctx.slip_of(&t).map(unit);
        let s = ctx.solve(&dir, mu)?;
        Ok::<_, RigidError>((ctx.generalized(&s), s))
    };
    let all_slip = |y0: Vector3<f64>| -> Result<Solved, RigidError> {
        let mut mu = coefficients(&frictionless.lambda);
        let mut y = y0;
        for _ in 0..MAX_FIXED_POINT / 10 {
            y = settle_direction(y, |y| direction(y, &mu).map(|d| d.0))?;
            let (_, s) = direction(&y, &mu)?;
            let new_mu = coefficients(&s.lambda);
            if (0..3).all(|i| (new_mu[i] - mu[i]).abs() < 1e-13) {
                return Ok(s);
            }
            mu = new_mu;
        }
        Err(RigidError::SlipFromRest)
    };
    let positive = |s: &Solved| s.lambda.iter().all(|&l| l > 0.0);
    if let Some(s) = all_slip(ctx.generalized(frictionless))
        .ok()
        .filter(positive)
    {
        return Ok((s, None));
    }
    // A spread of starting directions (Fibonacci sphere), best residual first.
    let mu0 = coefficients(&frictionless.lambda);
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
            let t = twist(ctx.geom, [y.x, y.y, y.z / ctx.arm])?;
            let dir = ctx.slip_of(&t).map(unit);
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
    use crate::geometry::{Displacement, Pose, direct};
    use crate::model::Friction;
    use crate::scene::Scene;

    fn at(scene: &Scene, d: Displacement) -> ContactGeometry {
        let p = direct::solve(&scene.site, d).unwrap();
        let l = scene.l();
        let pose =
            Pose::from_tilts(scene.site.as_paper().unwrap(), d, p.alpha(l), p.beta(l)).unwrap();
        ContactGeometry::new(&scene.site().normals(), &pose)
    }

    #[test]
    fn pivot_rates_leave_the_contact_at_rest_and_project() {
        // At a pose from the direct solver: the rates with contact i's slip removed move it
        // neither along its plane nor off it, and removing it again changes nothing.
        let scene = Scene::default_scene();
        let geom = at(&scene, Displacement::new(0.7, 0.2, 0.1));
        let block = scene.block.as_ref().unwrap();
        let inertia = Inertia::new(block, &geom).unwrap();
        let rates = [1.5, -0.4, 0.3];
        for i in 0..3 {
            let (p, removed) = pivot_rates(&geom, block, rates, i).unwrap();
            let v = twist(&geom, p).unwrap().at(&geom.r[i]);
            assert!(v.norm() < 1e-14 * 1.5, "contact {i}: {v:?}");
            let (q, again) = pivot_rates(&geom, block, p, i).unwrap();
            for k in 0..3 {
                assert!((q[k] - p[k]).abs() < 1e-14, "{q:?} {p:?}");
            }
            // The energy it removes is the kinetic energy of the removed motion (an impulse's
            // loss): ½|v − v'|²_M, Pythagoras in the kinetic-energy metric.
            let k = |r: [f64; 3]| {
                twist(&geom, r)
                    .unwrap()
                    .kinetic_energy(block.mass, &inertia)
            };
            let gap = k([rates[0] - p[0], rates[1] - p[1], rates[2] - p[2]]);
            assert!(
                removed < 0.0 && (removed + gap).abs() < 1e-9 * k(rates),
                "{removed} {gap}"
            );
            assert!(again.abs() < 1e-9 * k(rates), "{again}");
        }
    }

    #[test]
    fn the_projected_twist_keeps_contacts_on_their_planes_and_gives_the_rates() {
        let scene = Scene::default_scene();
        let geom = at(&scene, Displacement::new(0.7, 0.2, 0.1));
        let tw = twist(&geom, [1.5, -0.4, 0.3]).unwrap();
        for i in 0..3 {
            assert!(geom.n[i].dot(&tw.at(&geom.r[i])).abs() < 1e-14);
        }
        assert_eq!((tw.v.x, tw.v.z), (1.5, -0.4));
        // θ̇ by finite differences of the yaw of i' rotated by ω dt.
        let u = geom.frame.i;
        let h = 1e-7;
        let u2 = u + tw.w.cross(&u) * h;
        let dtheta = (u2.z.atan2(u2.x) - u.z.atan2(u.x)) / h;
        assert!((dtheta - 0.3).abs() < 1e-6, "{dtheta}");
    }

    #[test]
    fn frictionless_accelerations_keep_contact_accelerations_on_the_planes() {
        let scene = Scene::default_scene().with("friction.mu_k", 0.0).unwrap();
        let d = scene.simulation().unwrap();
        let geom = at(&scene, Displacement::new(0.7, 0.2, 0.1));
        let applied = Applied::new(d.loads(), d.block(), &geom.frame);
        let m = accelerations(
            &geom,
            &applied,
            d.block(),
            &d.strength([0, 1, 2], false),
            [1.0, 0.1, 0.2],
        )
        .unwrap();
        for i in 0..3 {
            let r = geom.r[i];
            let acc = m.accel + m.ang_accel.cross(&r) + m.twist.w.cross(&m.twist.w.cross(&r));
            assert!(geom.n[i].dot(&acc).abs() < 1e-12, "{i}");
            assert_eq!(m.shear[i], Vector3::zeros());
        }
        // Newton: m a = F + W + Σ N.
        let total = applied.force
            + applied.weight
            + (0..3)
                .map(|i| geom.n[i] * m.normal[i])
                .sum::<Vector3<f64>>();
        assert!((total / d.block().mass - m.accel).norm() < 1e-12);
    }

    #[test]
    fn shear_opposes_slip_with_the_criterion_magnitude() {
        let scene = Scene::default_scene();
        let d = scene.simulation().unwrap();
        let geom = at(&scene, Displacement::new(0.5, 0.0, -0.05));
        let applied = Applied::new(d.loads(), d.block(), &geom.frame);
        let m = accelerations(
            &geom,
            &applied,
            d.block(),
            &d.strength([0, 1, 2], false),
            [1.0, 0.1, 0.2],
        )
        .unwrap();
        for i in 0..3 {
            let s = m.slip[i];
            assert!((m.shear[i].norm() - 0.4 * m.normal[i]).abs() < 1e-6);
            assert!((m.shear[i].normalize() + s.normalize()).norm() < 1e-12);
        }
        assert!(m.power_friction < 0.0);
    }

    #[test]
    fn from_rest_each_shear_opposes_its_contacts_tangential_acceleration() {
        let scene = Scene::default_scene();
        let d = scene.simulation().unwrap();
        let geom = at(&scene, Displacement::new(0.0, 0.0, 0.0));
        let applied = Applied::new(d.loads(), d.block(), &geom.frame);
        let m = accelerations(
            &geom,
            &applied,
            d.block(),
            &d.strength([0, 1, 2], false),
            [0.0; 3],
        )
        .unwrap();
        for i in 0..3 {
            let r = geom.r[i];
            let acc = m.accel + m.ang_accel.cross(&r);
            let t = acc - geom.n[i] * acc.dot(&geom.n[i]);
            assert!(
                (m.shear[i].normalize() + t.normalize()).norm() < 1e-10,
                "{i}"
            );
        }
        // About 1 m/s² forward at the start (issue #7's prototype).
        assert!((0.8..1.3).contains(&m.accel.x), "{}", m.accel.x);
    }

    #[test]
    fn a_pivot_its_cone_cannot_hold_slips_along_its_own_tangential_acceleration() {
        // Issue #12: while the block moves, a contact whose slip is zero and whose cone cannot
        // hold it starts to slip along d with its friction −μλ d, where the tangential
        // acceleration this gives points along d itself (a_t ∥ d, a_t·d ≥ 0). Checked by
        // recomputing a_t from the returned accelerations.
        let scene = Scene::default_scene().with("friction.mu_k", 0.05).unwrap();
        let d = scene.simulation().unwrap();
        let geom = at(&scene, Displacement::new(0.5, 0.1, 0.05));
        let applied = Applied::new(d.loads(), d.block(), &geom.frame);
        let arm = longest_arm(&geom);
        let mut checked = 0;
        for i in 0..3 {
            let p = pivot_direction(&geom, arm, i).unwrap() * 2.0;
            let rates = [p.x, p.y, p.z / arm];
            let m = accelerations(
                &geom,
                &applied,
                d.block(),
                &d.strength([0, 1, 2], false),
                rates,
            )
            .unwrap();
            assert!(
                m.slip[i].norm() < 1e-12,
                "contact {i} does not slip at the start"
            );
            if m.stuck == Some(i) {
                continue;
            }
            let r = geom.r[i];
            let acc = m.accel + m.ang_accel.cross(&r) + m.twist.w.cross(&m.twist.w.cross(&r));
            let a_t = acc - geom.n[i] * acc.dot(&geom.n[i]);
            let dir = -m.shear[i] / m.shear[i].norm();
            assert!((m.shear[i].norm() - 0.05 * m.normal[i]).abs() < 1e-9 * m.normal[i]);
            assert!(
                dir.cross(&a_t).norm() < 1e-8 * a_t.norm().max(1e-12),
                "{i}: {a_t:?} {dir:?}"
            );
            assert!(a_t.dot(&dir) >= 0.0, "{i}: the slip grows along d");
            checked += 1;
        }
        assert!(
            checked > 0,
            "no contact's cone failed: the test checks nothing"
        );
    }

    #[test]
    fn one_contact_stick_satisfies_newton_euler_and_its_constraints() {
        // The 11-equation stick mode, checked by recomputing the forces it returns.
        let scene = Scene::default_scene();
        let d = scene.simulation().unwrap();
        let geom = at(&scene, Displacement::new(0.5, 0.1, 0.05));
        let applied = Applied::new(d.loads(), d.block(), &geom.frame);
        let inertia = Inertia::new(d.block(), &geom).unwrap();
        let ctx = Ctx {
            geom: &geom,
            inertia,
            mass: d.block().mass,
            force: applied.force + applied.weight,
            torque: applied.moment,
            centripetal: [Vector3::zeros(); 3],
            arm: 10.0,
            creases: Creases::NONE,
        };
        let rates = ctx.pivot_direction(1).unwrap();
        let t = twist(&geom, [rates.x, rates.y, rates.z / ctx.arm]).unwrap();
        let dir = ctx.slip_of(&t).map(unit);
        assert!(ctx.slip_of(&t)[1].norm() < 1e-12, "contact 1 does not slip");
        let s = ctx.solve_stick(&dir, &[0.4; 3], 1).unwrap();
        let mut f = ctx.force;
        let mut m = ctx.torque;
        for j in 0..3 {
            let c = geom.n[j] * s.lambda[j] + s.shear[j];
            f += c;
            m += geom.r[j].cross(&c);
            let acc = s.a + s.e.cross(&geom.r[j]);
            assert!(geom.n[j].dot(&acc).abs() < 1e-10, "normal {j}");
            if j == 1 {
                assert!(ctx.tangential(1, acc).norm() < 1e-10, "contact 1 sticks");
            } else {
                assert!((s.shear[j].norm() - 0.4 * s.lambda[j]).abs() < 1e-6 * s.lambda[j]);
            }
        }
        assert!((f - s.a * d.block().mass).norm() < 1e-6 * f.norm().max(1.0));
        assert!((m - inertia.world * s.e).norm() < 1e-6 * m.norm().max(1.0));
    }

    /// The default scene's block flat at the start with contacts 0 and 1 on a level face and
    /// contact 2 at the bottom of a groove along X, its faces dipping `dip` to either side: the
    /// contact geometry (contact 2 on face A, normal leaning to +Z) and the crease (face B).
    fn groove(dip: f64) -> (crate::model::Simulation, ContactGeometry, Crease, Applied) {
        let scene = Scene::default_scene();
        let pose = Pose::from_tilt_roll(&scene.site, Displacement::default(), 0.0, 0.0).unwrap();
        let (s, c) = dip.sin_cos();
        let level = Vector3::y();
        let geom = ContactGeometry::new(&[level, level, Vector3::new(0.0, c, s)], &pose);
        let crease = Crease {
            contact: 2,
            normal: Vector3::new(0.0, c, -s),
            offset: Vector3::new(0.0, c, -s).dot(&pose.vertices[2]),
            face: 1,
        };
        let sim = scene.simulation().unwrap();
        let applied = Applied::new(sim.loads(), sim.block(), &geom.frame);
        (sim, geom, crease, applied)
    }

    #[test]
    fn frictionless_in_a_groove_the_block_slides_along_it_and_turns_about_its_contact() {
        // Contacts 0, 1 on Y = 0 and contact 2 on the groove's bottom line keep the block flat
        // with contact 2 on the line Z = z2: two degrees of freedom, X and θ. At rest,
        // frictionless, F along x' and the couple cF (θ up): m Ẍ = F, and the groove's lateral
        // reaction R at contact 2 (x2 = 4 m ahead of the CM) gives m Z̈ = R with Z̈ = −x2 θ̈ and
        // I θ̈ = cF + x2 R, so θ̈ = cF / (I + m x2²).
        let (d, geom, crease, applied) = groove(30f64.to_radians());
        let (block, loads) = (d.block(), d.loads());
        let frictionless = Strength::from(Friction::Coulomb { mu_k: 0.0 });
        let m = accelerations_in_crease(
            &geom,
            &applied,
            block,
            &frictionless,
            [0.0; 3],
            0.0,
            crease.into(),
        )
        .unwrap();
        let (f, c, x2) = (loads.hydraulic_force, loads.eccentricity, 4.0);
        let theta_ddot = c * f / (block.inertia + block.mass * x2 * x2);
        let want = [f / block.mass, -x2 * theta_ddot, theta_ddot];
        for k in 0..3 {
            assert!(
                (m.acc[k] - want[k]).abs() < 1e-12 * want[0],
                "{:?} vs {want:?}",
                m.acc
            );
        }
        // Both groove faces push, and their lateral parts give R.
        let second = m.crease_normal[2].unwrap();
        assert!(m.normal[2] > 0.0 && second > 0.0);
        let r = (m.normal[2] - second) * 30f64.to_radians().sin();
        assert!((r + block.mass * x2 * theta_ddot).abs() < 1e-6 * f, "{r}");
        // Without the crease the block is free to move sideways: another motion.
        let free = accelerations(&geom, &applied, block, &frictionless, [0.0; 3]).unwrap();
        assert!((free.acc[2] - theta_ddot).abs() > 1e-3 * theta_ddot);
    }

    #[test]
    fn sliding_in_a_groove_both_faces_rub_and_every_constraint_holds() {
        // Moving along the groove with friction: Newton–Euler from the returned forces, the
        // four constraint accelerations zero, and contact 2's friction μ(λ_A + λ_B) against its
        // slip — the wedge: per unit of vertical load, μ / cos δ instead of μ.
        let dip = 35f64.to_radians();
        let (d, geom, crease, applied) = groove(dip);
        let (block, loads) = (d.block(), d.loads());
        let mu = 0.4;
        let friction = Strength::from(Friction::Coulomb { mu_k: mu });
        let m = accelerations_in_crease(
            &geom,
            &applied,
            block,
            &friction,
            [1.0, 0.0, 0.0],
            0.0,
            crease.into(),
        )
        .unwrap();
        let second = m.crease_normal[2].unwrap();
        let normal_force = |j: usize| {
            let mut f = geom.n[j] * m.normal[j];
            if j == 2 {
                f += crease.normal * second;
            }
            f
        };
        let mut force = applied.force + applied.weight;
        let mut torque = applied.moment - m.twist.w.cross(&(m.inertia.world * m.twist.w));
        for j in 0..3 {
            let c = normal_force(j) + m.shear[j];
            force += c;
            torque += geom.r[j].cross(&c);
        }
        assert!((force - m.accel * block.mass).norm() < 1e-6 * loads.hydraulic_force);
        assert!((torque - m.inertia.world * m.ang_accel).norm() < 1e-6 * loads.hydraulic_force);
        let w = m.twist.w;
        for (j, n) in [
            (0, geom.n[0]),
            (1, geom.n[1]),
            (2, geom.n[2]),
            (2, crease.normal),
        ] {
            let r = geom.r[j];
            let acc = m.accel + m.ang_accel.cross(&r) + w.cross(&w.cross(&r));
            assert!(
                n.dot(&acc).abs() < 1e-9,
                "constraint of contact {j} along {n}"
            );
        }
        let slip = m.slip[2];
        assert!(slip.norm() > 0.9 && slip.y.abs() < 1e-12 && slip.z.abs() < 1e-12);
        let want = -slip.normalize() * (mu * (m.normal[2] + second));
        assert!((m.shear[2] - want).norm() < 1e-9 * want.norm());
        let vertical = m.normal[2] * geom.n[2].y + second * crease.normal.y;
        assert!((m.shear[2].norm() - mu * vertical / dip.cos()).abs() < 1e-6 * vertical);
    }

    #[test]
    fn a_crease_lets_go_of_the_face_that_pulls() {
        // A shallow groove (2°) cannot hold the lateral push of a strong turn: one face's
        // reaction would pull. Which one depends on which face is the crease's second.
        let (d, geom, crease, applied) = groove(2f64.to_radians());
        let block = d.block();
        let frictionless = Strength::from(Friction::Coulomb { mu_k: 0.0 });
        let run = |geom: &ContactGeometry, crease: Crease| {
            accelerations_in_crease(
                geom,
                &applied,
                block,
                &frictionless,
                [0.0; 3],
                0.0,
                crease.into(),
            )
        };
        let first = run(&geom, crease).unwrap_err();
        let mut swapped = geom;
        swapped.n[2] = crease.normal;
        let other = Crease {
            normal: geom.n[2],
            ..crease
        };
        let second = run(&swapped, other).unwrap_err();
        let kinds = [&first, &second].map(|e| match e {
            RigidError::CreaseLetsGo { contact: 2, .. } => "lets go",
            RigidError::CreaseTakesOver { contact: 2, .. } => "takes over",
            _ => "other",
        });
        let mut sorted = kinds;
        sorted.sort_unstable();
        assert_eq!(sorted, ["lets go", "takes over"], "{first} / {second}");
    }

    #[test]
    fn a_frictionless_impact_is_the_crease_projection_and_friction_takes_more() {
        // Contact 2 meets the groove's second face: frictionless, the impact leaves the motion
        // the crease projection gives (two routes to the same inelastic impact: impulses and a
        // projection in the kinetic-energy metric); with friction, every contact is still on
        // its faces after it, and it takes more kinetic energy, never adding any.
        let (d, geom, crease, _) = groove(30f64.to_radians());
        let block = d.block();
        let inertia = Inertia::new(block, &geom).unwrap();
        let creases = Creases::from(crease);
        let law = |mu: f64| ImpactLaw {
            mu: [mu; 3],
            release_speed: f64::INFINITY,
            crease_release_speed: f64::INFINITY,
        };
        for rates in [[1.0, 0.3, 0.0], [0.2, 0.5, 0.05], [0.5, 0.1, 0.1]] {
            let before = twist(&geom, rates).unwrap();
            let k0 = before.kinetic_energy(block.mass, &inertia);
            let plain = impact(&geom, block, rates, &creases, &law(0.0)).unwrap();
            let (projected, removed) = crease_rates(&geom, block, rates, &creases).unwrap();
            for (a, b) in plain.rates.iter().zip(projected) {
                assert!((a - b).abs() < 1e-9, "{plain:?}");
            }
            assert!((plain.removed - removed).abs() < 1e-9 * k0);
            assert_eq!(plain.creases, creases);
            let rough = impact(&geom, block, rates, &creases, &law(0.4)).unwrap();
            let after = twist(&geom, rough.rates).unwrap();
            let v2 = after.at(&geom.r[2]);
            let scale = before.at(&geom.r[2]).norm();
            assert!(crease.normal.dot(&v2).abs() < 1e-9 * scale, "{v2}");
            assert!(geom.n[2].dot(&v2).abs() < 1e-9 * scale, "{v2}");
            let k1 = after.kinetic_energy(block.mass, &inertia);
            assert!((k1 - k0 - rough.removed).abs() < 1e-9 * k0);
            assert!(
                rough.removed < plain.removed && rough.removed >= -k0,
                "{rough:?}"
            );
        }
    }

    #[test]
    fn an_impact_with_friction_takes_energy_and_stops_the_contacts_on_their_faces() {
        // The impact as a process (friction turning with each slip within it): whatever the
        // motion into the groove's face and however rough, every held contact ends with no
        // velocity into its faces, and the kinetic energy taken is what it books, more than
        // none and at most all there was.
        let (d, geom, crease, _) = groove(30f64.to_radians());
        let block = d.block();
        let inertia = Inertia::new(block, &geom).unwrap();
        let creases = Creases::from(crease);
        for mu in [0.2, 0.8, 2.0] {
            let law = ImpactLaw {
                mu: [mu; 3],
                release_speed: f64::INFINITY,
                crease_release_speed: f64::INFINITY,
            };
            for rates in [
                [1.0, 0.3, 0.0],
                [0.2, 0.5, 0.05],
                [0.5, 0.1, 0.1],
                [0.0, 0.4, -0.2],
            ] {
                let before = twist(&geom, rates).unwrap();
                let k0 = before.kinetic_energy(block.mass, &inertia);
                let after = impact(&geom, block, rates, &creases, &law).unwrap();
                let u = twist(&geom, after.rates).unwrap();
                let k1 = u.kinetic_energy(block.mass, &inertia);
                assert!(
                    (k1 - k0 - after.removed).abs() < 1e-9 * k0,
                    "{mu} {rates:?}"
                );
                assert!(after.removed < 0.0 && after.removed >= -k0 * (1.0 + 1e-9));
                let v2 = u.at(&geom.r[2]);
                let scale = before.at(&geom.r[2]).norm();
                assert!(
                    crease.normal.dot(&v2).abs() < 1e-9 * scale,
                    "{mu} {rates:?}"
                );
            }
        }
    }

    #[test]
    fn an_impact_lets_a_face_go_only_if_its_contact_would_leave_it_fast_enough() {
        // A block moving along −Z meets the groove's face B at contact 2 from the side it
        // leaves: the impulse that would hold contact 2 on B pulls. Let go if the release is
        // faster than the law's crease release speed; otherwise held (the forces just after
        // decide).
        let (d, geom, crease, _) = groove(30f64.to_radians());
        let block = d.block();
        let creases = Creases::from(crease);
        let rates = [0.0, -1.0, 0.0];
        let go = |crease_release_speed: f64| {
            let law = ImpactLaw {
                mu: [0.0; 3],
                release_speed: f64::INFINITY,
                crease_release_speed,
            };
            impact(&geom, block, rates, &creases, &law).unwrap()
        };
        let let_go = go(1e-3);
        assert_eq!(let_go.creases, Creases::NONE);
        assert!(let_go.removed.abs() < 1e-9, "{let_go:?}");
        assert!((0..3).all(|c| (let_go.rates[c] - rates[c]).abs() < 1e-12));
        let held = go(f64::INFINITY);
        assert_eq!(held.creases, creases);
        assert!(held.removed < 0.0);
    }

    #[test]
    fn running_over_a_ridge_is_a_hop_kept_on_the_face_beyond_or_a_lift_at_the_speed_off_it() {
        // The block slides flat along +X at v on level faces; contact 1's face becomes one that
        // falls away ahead at δ (a convex edge): the contact leaves it at v sin δ. With a release
        // speed above that, the impact keeps it on the face (every contact's velocity along its
        // face's normal zero after it, the kinetic energy lost what the impact books); below,
        // it lifts off at exactly v sin δ.
        let scene = Scene::default_scene();
        let pose = Pose::from_tilt_roll(&scene.site, Displacement::default(), 0.0, 0.0).unwrap();
        let level = Vector3::y();
        let delta = 5f64.to_radians();
        let beyond = Vector3::new(delta.sin(), delta.cos(), 0.0);
        let before = ContactGeometry::new(&[level; 3], &pose);
        let after = ContactGeometry::new(&[level, beyond, level], &pose);
        let sim = scene.simulation().unwrap();
        let block = sim.block();
        let v = 2.0;
        let law = |release_speed| ImpactLaw {
            mu: [0.0; 3],
            release_speed,
            crease_release_speed: f64::INFINITY,
        };
        let onto = |release_speed| {
            impact_onto(
                &before,
                &after,
                block,
                [v, 0.0, 0.0],
                &Creases::NONE,
                &law(release_speed),
            )
        };
        match onto(0.9 * v * delta.sin()) {
            Err(RigidError::ImpactLifts {
                contact, speed_m_s, ..
            }) => {
                assert_eq!(contact, 1);
                assert!((speed_m_s - v * delta.sin()).abs() < 1e-12, "{speed_m_s}");
            }
            other => panic!("{other:?}"),
        }
        let kept = onto(1.1 * v * delta.sin()).unwrap();
        let inertia = Inertia::new(block, &after).unwrap();
        let u0 = twist(&before, [v, 0.0, 0.0]).unwrap();
        let u1 = twist(&after, kept.rates).unwrap();
        for k in 0..3 {
            assert!(after.n[k].dot(&u1.at(&after.r[k])).abs() < 1e-12);
        }
        let (k0, k1) = (
            u0.kinetic_energy(block.mass, &inertia),
            u1.kinetic_energy(block.mass, &inertia),
        );
        assert!(kept.removed < 0.0);
        assert!(
            (k1 - k0 - kept.removed).abs() < 1e-9 * k0,
            "{k0} {k1} {kept:?}"
        );
        // At most the energy of the velocity off the face, as if contact 1 were the whole mass.
        let off = 0.5 * block.mass * (v * delta.sin()).powi(2);
        assert!(-kept.removed < off, "{} {off}", kept.removed);
    }

    #[test]
    fn the_crease_projection_stops_the_contact_at_the_second_face_and_takes_only_that_energy() {
        // Rates that drive contact 2 into the groove's second face: after the projection its
        // velocity along that face's normal is zero, and the kinetic energy lost is exactly what
        // the projection says it removed (a projection in the kinetic-energy metric keeps the
        // part of the motion that is free and drops the rest, ½|Δv|²_M).
        let (d, geom, crease, _) = groove(30f64.to_radians());
        let block = d.block();
        let inertia = Inertia::new(block, &geom).unwrap();
        for rates in [[1.0, 0.3, 0.0], [0.2, -0.5, 0.05], [0.0, 0.0, 0.1]] {
            let before = twist(&geom, rates).unwrap();
            let into = crease.normal.dot(&before.at(&geom.r[2]));
            assert!(into.abs() > 1e-3, "the test rates must push into the face");
            let (projected, removed) = crease_rates(&geom, block, rates, &crease.into()).unwrap();
            let after = twist(&geom, projected).unwrap();
            assert!(crease.normal.dot(&after.at(&geom.r[2])).abs() < 1e-12);
            let (k0, k1) = (
                before.kinetic_energy(block.mass, &inertia),
                after.kinetic_energy(block.mass, &inertia),
            );
            assert!(removed < 0.0);
            assert!((k1 - k0 - removed).abs() < 1e-9 * k0, "{k0} {k1} {removed}");
            // Rates already on the face are left as they are.
            let (again, none) = crease_rates(&geom, block, projected, &crease.into()).unwrap();
            assert!((0..3).all(|k| (again[k] - projected[k]).abs() < 1e-12));
            assert!(none.abs() < 1e-9 * k0);
        }
    }
}
