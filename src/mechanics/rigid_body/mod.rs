//! Rigid-body dynamics of the block (`derivations/08-rigid-body.md`).
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
//!
//! The parts: the constrained kinematics (`kinematics.rs`), contacts riding creases
//! (`creases.rs`), the contact problem's solves (`contact.rs`), the start of slip
//! (`slip_start.rs`), the accelerations at a state (`accelerations.rs`) and the impact of a
//! contact meeting a face (`impact.rs`).

mod accelerations;
mod contact;
mod creases;
mod impact;
mod kinematics;
mod slip_start;

pub use accelerations::{Motion, State, accelerations_releasing};
// The plain form, for the tests and `internals`: the route evaluates with a release in view.
#[cfg_attr(not(feature = "internals"), allow(unused_imports))]
pub use accelerations::accelerations;
pub use creases::{Crease, Creases, crease_rates};
pub use impact::{Impact, ImpactLaw, impact};
pub use kinematics::{Inertia, Twist, contact_velocity_map, pivot_rates};

/// Why the rigid-body accelerations cannot be had at a state.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum RigidError {
    /// A normal reaction is not positive: the contact lifts off its plane.
    #[error("contact {contact} lifts off (normal reaction {normal_n:.6e} N)")]
    LiftOff {
        /// The contact.
        contact: usize,
        /// Its normal reaction (N).
        normal_n: f64,
    },
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
    SlipStart {
        /// The contact.
        contact: usize,
    },
    /// The contact riding a crease is pulled off its second face (that face's normal force is
    /// not positive): it leaves the crease and goes on along its own face alone.
    #[error("contact {contact} leaves the crease (its second face's reaction {normal_n:.6e} N)")]
    CreaseLetsGo {
        /// The contact.
        contact: usize,
        /// Its second face's reaction (N).
        normal_n: f64,
    },
    /// The contact riding a crease is pulled off its own face while its second face holds it:
    /// it goes on along the second face alone.
    #[error(
        "contact {contact} leaves its face for the crease's other face (its own face's reaction \
         {normal_n:.6e} N)"
    )]
    CreaseTakesOver {
        /// The contact.
        contact: usize,
        /// Its own face's reaction (N).
        normal_n: f64,
    },
    /// The equations of one contact sticking while the others slip are singular.
    #[error(
        "contact {contact}: the equations of it sticking while the others slip are singular \
         (its tangential constraints depend on the normal ones at this pose)"
    )]
    StickSingular {
        /// The contact that would stick.
        contact: usize,
    },
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
        /// The contact.
        contact: usize,
        /// The impulse that would hold it (N·s, negative: a pull).
        impulse_n_s: f64,
        /// How fast it leaves its face, let go (m/s).
        speed_m_s: f64,
    },
}

#[cfg(test)]
mod tests;
