//! Contacts riding creases (`derivations/10-faces.md` §4): a contact on its own face and a
//! second face at once, one constraint more each, and the rates with every such contact's
//! velocity into its second face removed as a frictionless impulse would.

use super::RigidError;
use super::kinematics::{Inertia, twist};
use crate::mechanics::ContactGeometry;
use crate::model::Block;
use nalgebra::{Matrix3, Vector3};

/// A contact riding the crease between its own face and a second one
/// (`derivations/10-faces.md` §4): a fourth constraint, the contact on the second face too.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crease {
    /// The contact in the crease.
    pub contact: usize,
    /// The second face's upward unit normal.
    pub normal: Vector3<f64>,
    /// The second face's offset e (m·P = e).
    pub offset: f64,
    /// The second face's number in the ground (for the route's rows).
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

    /// Whether no contact rides a crease.
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

/// The rates (Ẋ, Ż, θ̇) with each crease contact's velocity into its crease's second face
/// removed, and the kinetic energy this takes away (J, ≤ 0): the projection a perfectly
/// inelastic, frictionless impulse along those faces' normals makes (in the kinetic-energy
/// metric, as [`pivot_rates`](super::pivot_rates)): r' = r − G⁻¹Rᵀ(RG⁻¹Rᵀ)⁻¹Rr, with G the metric of the rates and
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
