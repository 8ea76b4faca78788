//! The contact problem at one state: what is fixed while the contact forces are sought
//! ([`Ctx`]), and its linear solves — every contact slipping along given directions (K λ = b,
//! the Delassus matrix with friction), or one contact sticking while the others slip.

use super::RigidError;
use super::creases::Creases;
use super::kinematics::{Inertia, Twist, pivot_direction, theta_rate_row, twist, unit};
use crate::mechanics::ContactGeometry;
use crate::numeric::small_solve;
use nalgebra::{SMatrix, SVector, Vector3};

/// A slip speed below this fraction of the block's speed scale counts as zero slip.
pub(super) const ZERO_SLIP: f64 = 1e-9;

/// Iterations of the fixed points (slip directions from rest, stress-dependent criteria).
pub(super) const MAX_FIXED_POINT: usize = 200;

/// What is fixed at one state while the contact forces are sought.
pub(super) struct Ctx<'a> {
    pub(super) geom: &'a ContactGeometry,
    pub(super) inertia: Inertia,
    pub(super) mass: f64,
    /// Applied force (F + W) and torque (couple − ω × Iω).
    pub(super) force: Vector3<f64>,
    pub(super) torque: Vector3<f64>,
    /// ω × (ω × r_i).
    pub(super) centripetal: [Vector3<f64>; 3],
    /// Longest arm (m): scales θ̇ against Ẋ, Ż.
    pub(super) arm: f64,
    /// The contacts riding creases.
    pub(super) creases: Creases,
}

/// One solution of the contact problem: normals, CM and angular acceleration, shear vectors.
#[derive(Clone, Copy)]
pub(super) struct Solved {
    pub(super) lambda: [f64; 3],
    pub(super) a: Vector3<f64>,
    pub(super) e: Vector3<f64>,
    pub(super) shear: [Vector3<f64>; 3],
    /// Each contact's second normal reaction in its crease (zero without).
    pub(super) crease: [f64; 3],
}

impl Ctx<'_> {
    pub(super) fn tangential(&self, i: usize, v: Vector3<f64>) -> Vector3<f64> {
        v - self.geom.n[i] * v.dot(&self.geom.n[i])
    }

    pub(super) fn slip_of(&self, t: &Twist) -> [Vector3<f64>; 3] {
        [0, 1, 2].map(|i| self.tangential(i, t.at(&self.geom.r[i])))
    }

    /// Each contact's slip direction when the block moves at the rates (Ẋ, Ż, L θ̇) along `y`.
    pub(super) fn directions_along(
        &self,
        y: &Vector3<f64>,
    ) -> Result<[Vector3<f64>; 3], RigidError> {
        let t = twist(self.geom, [y.x, y.y, y.z / self.arm])?;
        Ok(self.slip_of(&t).map(unit))
    }

    /// Unit direction of the rates (Ẋ, Ż, L θ̇) of an acceleration (a, ω̇).
    pub(super) fn generalized(&self, s: &Solved) -> Vector3<f64> {
        unit(self.generalized_acceleration(s))
    }

    /// The rates (Ẋ, Ż, L θ̇) of an acceleration (a, ω̇): (m/s²).
    pub(super) fn generalized_acceleration(&self, s: &Solved) -> Vector3<f64> {
        let row = theta_rate_row(&self.geom.frame.i);
        Vector3::new(s.a.x, s.a.z, self.arm * row.dot(&s.e))
    }

    pub(super) fn tangential_accel(&self, i: usize, s: &Solved) -> Vector3<f64> {
        self.tangential(i, s.a + s.e.cross(&self.geom.r[i]) + self.centripetal[i])
    }

    /// All contacts slip: shear −μ_j λ_j dir_j. K λ = b (3×3), then a and ω̇. Each contact in
    /// a crease adds its second face as a row and a reaction (4×4, 5×5), and that contact's
    /// friction −μ (λ + λ_B) dir opposes its slip on both faces.
    pub(super) fn solve(
        &self,
        dir: &[Vector3<f64>; 3],
        mu: &[f64; 3],
    ) -> Result<Solved, RigidError> {
        match self.creases.len() {
            0 => self.solve_n::<3>(dir, mu),
            1 => self.solve_n::<4>(dir, mu),
            2 => self.solve_n::<5>(dir, mu),
            _ => Err(RigidError::Wedged),
        }
    }

    /// Constraint row k of N: its contact and normal — the three contacts' own faces, then the
    /// creases' second faces in the order of their contacts.
    pub(super) fn rows<const N: usize>(
        &self,
        creases: &Creases,
    ) -> ([usize; N], [Vector3<f64>; N]) {
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
    pub(super) fn solve_n<const N: usize>(
        &self,
        dir: &[Vector3<f64>; 3],
        mu: &[f64; 3],
    ) -> Result<Solved, RigidError> {
        let geom = self.geom;
        // Constraint k: its contact, normal and force direction g (normal and friction).
        let (contact, normal) = self.rows::<N>(&self.creases);
        let g: [Vector3<f64>; N] =
            std::array::from_fn(|k| normal[k] - dir[contact[k]] * mu[contact[k]]);
        let arm_n: [Vector3<f64>; N] =
            std::array::from_fn(|k| geom.r[contact[k]].cross(&normal[k]));
        let arm_g: [Vector3<f64>; N] =
            std::array::from_fn(|k| self.inertia.inverse * geom.r[contact[k]].cross(&g[k]));
        let mut kk = [[0.0; N]; N];
        let mut b = [0.0; N];
        let free_ang = self.inertia.inverse * self.torque;
        for r in 0..N {
            for q in 0..N {
                kk[r][q] = normal[r].dot(&g[q]) / self.mass + arm_n[r].dot(&arm_g[q]);
            }
            b[r] = -normal[r].dot(&self.centripetal[contact[r]])
                - normal[r].dot(&self.force) / self.mass
                - arm_n[r].dot(&free_ang);
        }
        let lambda = small_solve::solve(kk, b)
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
    pub(super) fn solve_stick(
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
    pub(super) fn solve_stick_n<const N: usize>(
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
    pub(super) fn pivot_direction(&self, i: usize) -> Result<Vector3<f64>, RigidError> {
        pivot_direction(self.geom, self.arm, i)
    }

    /// Contact `i` slipping along the direction at angle `phi` on its tangent plane (the others
    /// along `dir`): the direction d, (d × a_t)·n (zero where the tangential acceleration is
    /// parallel to d), a_t·d, and the solution.
    pub(super) fn slipping_at(
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

/// Coulomb's cone with a little room for round-off.
pub(super) fn in_cone(shear: &Vector3<f64>, mu: f64, lambda: f64) -> bool {
    shear.norm() <= mu * lambda * (1.0 + 1e-9)
}
