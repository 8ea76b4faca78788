//! The work of a step's contact impulses (`derivations/13-base-contact.md` §7).

use super::{Motion, Solved};
use crate::contact::{ContactRow, Patch, Side};
use nalgebra::Vector3;

/// The velocity of side `a`'s point less side `b`'s, the bodies moving as `m`.
fn relative(m: &[Motion], a: &Side, b: Option<&Side>) -> Vector3<f64> {
    let u = m[a.body].at(&a.arm);
    match b {
        None => u,
        Some(b) => u - m[b.body].at(&b.arm),
    }
}

/// The work of a step's contact impulses (J, ≤ 0), the bodies moving as `before` at the step's
/// start: friction's at the mean of the slip before the step and the slip it leaves,
/// ½ P_t · (u_t + u_t⁺) (exact for a rigid body whose velocities the impulse takes from u to
/// u⁺: a block braked by friction at its base, and an impact that stops or turns the slip), and
/// an impact's, ½ P_n (u_n + u_n⁺) with u_n the contact's approach before the step
/// (−½ m_eff u_n² for a contact closed inelastically; zero for one that stays closed, whose
/// impulse only holds the weight). The energy balance's residual is then the step's own error,
/// of the order of the loads' change of velocity in a step: nothing at rest.
pub fn work(rows: &[ContactRow], patches: &[Patch], solved: &Solved, before: &[Motion]) -> f64 {
    let after = &solved.motion;
    // The flush patches' friction at their points (their normal shares are the rows').
    let rubbed: f64 = patches
        .iter()
        .zip(&solved.patch)
        .flat_map(|(p, imps)| {
            let n = p.axes.0.cross(&p.axes.1);
            p.points.iter().zip(imps).map(move |(q, imp)| {
                let at = Side {
                    body: p.body,
                    arm: q.arm,
                };
                let after = relative(after, &at, None);
                let before = relative(before, &at, None);
                0.5 * (imp - n * n.dot(imp)).dot(&(after + before))
            })
        })
        .sum();
    rubbed
        + rows
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let after = relative(after, &c.a, c.b.as_ref());
                let before = relative(before, &c.a, c.b.as_ref());
                let pn = solved.normal[i];
                let approach = c.normal.dot(&before).min(0.0);
                0.5 * solved.tangential[i].dot(&(after + before))
                    + 0.5 * pn * (approach + c.normal.dot(&after))
            })
            .sum::<f64>()
}
