//! The step of the block on its base held to the tolerance (`derivations/13-base-contact.md`
//! §12): the time-stepping step of `step.rs` taken over an interval H in one, two and three
//! substeps, and the three results extrapolated to a vanishing substep (Aitken–Neville on the
//! harmonic sequence, as Deuflhard's extrapolation of Euler's method). Between contact events the
//! step's error is a series in the substep's length, so the extrapolated state is third-order
//! (exact where the accelerations are constant, as on a plane dipping downstream), and the difference of the last two
//! extrapolations estimates its error. Across an event — a touch made, a slip stopping, a
//! touch lifting off — the substeps part by the first order, the estimate is large, and the
//! controller shortens the step until the event lies within one short enough for the
//! tolerance.

use super::state::{BodyState, turn_between};
use super::step::{Ctx, Stepped};
use nalgebra::{Rotation3, Vector3};

/// The substeps of the interval in each of the tableau's rows.
const SEQUENCE: [usize; 3] = [1, 2, 3];

/// A state as numbers, from the state at the step's start: the CM (m), its velocity (m/s), the
/// angular velocity (rad/s), the turn since the start as a rotation vector (rad), the two
/// works (J) and the path of the point under the CM (m).
const VALUES: usize = 15;

/// The turn within one step past which the step is refused: its rotation vector, the
/// extrapolation's coordinate for the rotation, stays far from its singularity at π.
const LONGEST_TURN: f64 = 0.5;

/// What an extrapolated step gives.
pub(super) struct Extrapolated {
    /// The state at the interval's end.
    pub state: BodyState,
    /// The step's error over the tolerance: at most 1 where the step is within it; infinite
    /// where a substep left a value not finite or turned too far.
    pub ratio: f64,
    /// What the last substep of the finest row found: the next step's warm start and the
    /// touches that carry the block.
    pub last: Stepped,
    /// The motion stopped or turned back within the step.
    pub stopped: bool,
}

/// `s` as numbers from the state at the start, `s0`.
fn numbers(s0: &BodyState, s: &BodyState) -> [f64; VALUES] {
    let turn = turn_between(&s0.pose.rotation, &s.pose.rotation);
    let mut y = [0.0; VALUES];
    y[0..3].copy_from_slice(s.pose.cm.as_slice());
    y[3..6].copy_from_slice(s.v.as_slice());
    y[6..9].copy_from_slice(s.w.as_slice());
    y[9..12].copy_from_slice(turn.as_slice());
    y[12] = s.work_applied;
    y[13] = s.work_contacts;
    y[14] = s.path;
    y
}

/// The state whose numbers from `s0` are `y`.
fn state(s0: &BodyState, y: &[f64; VALUES]) -> BodyState {
    let v3 = |k: usize| Vector3::new(y[k], y[k + 1], y[k + 2]);
    let mut s = *s0;
    s.pose.cm = v3(0);
    s.v = v3(3);
    s.w = v3(6);
    let turn =
        Rotation3::from_scaled_axis(v3(9)) * Rotation3::from_matrix_unchecked(s0.pose.rotation);
    s.pose.rotation = super::state::renormalized(&turn).into_inner();
    s.work_applied = y[12];
    s.work_contacts = y[13];
    s.path = y[14];
    s
}

/// The weight of each value in the step's error: the CM's position and the path against the
/// base's size and the turn in radians, each over the tolerance (as the three-point rigid
/// body's, `derivations/08-rigid-body.md` §4a); the rates and the works are not weighed (a
/// slip stopping within a step makes them jump; the positions' error says how long a step
/// the stop may lie within).
fn weights(size: f64, tolerance: f64) -> [f64; VALUES] {
    let (l, none) = (1.0 / (tolerance * size), 0.0);
    let r = 1.0 / tolerance;
    [
        l, l, l, none, none, none, none, none, none, r, r, r, none, none, l,
    ]
}

/// The Aitken–Neville tableau's last row from the results `rows` of `SEQUENCE`'s substeps: the
/// finest extrapolated as far as the rows allow (its error's terms in H/n and (H/n)² removed),
/// and extrapolated one order less (H/n's only).
fn extrapolate(rows: &[[f64; VALUES]; 3]) -> ([f64; VALUES], [f64; VALUES]) {
    let n = SEQUENCE.map(|n| n as f64);
    // T[j][k] = T[j][k−1] + (T[j][k−1] − T[j−1][k−1]) / (n_j / n_{j−k} − 1).
    let step = |a: &[f64; VALUES], b: &[f64; VALUES], ratio: f64| -> [f64; VALUES] {
        std::array::from_fn(|i| a[i] + (a[i] - b[i]) / (ratio - 1.0))
    };
    let t11 = step(&rows[1], &rows[0], n[1] / n[0]);
    let t21 = step(&rows[2], &rows[1], n[2] / n[1]);
    let t22 = step(&t21, &t11, n[2] / n[0]);
    (t22, t21)
}

/// Whether the motion stopped or turned back within the step from `s0` to the state `y`, for
/// a body of `size`: its velocities at the end (the turn's at the size) about none of those at
/// the start, or against them. Where a stop lies within the first substep of every row, every
/// row rests from there and the tableau sees no error at all.
fn stopped(s0: &BodyState, y: &[f64; VALUES], size: f64) -> bool {
    let (v1, w1) = (
        Vector3::new(y[3], y[4], y[5]),
        Vector3::new(y[6], y[7], y[8]),
    );
    let start = s0.v.norm_squared() + size * size * s0.w.norm_squared();
    let along = s0.v.dot(&v1) + size * size * s0.w.dot(&w1);
    start > 0.0 && along <= 1e-3 * start
}

/// The step's error where the motion stops or turns back within it, over the `tolerance`: the
/// distance the base moves at its speed at the start (the turn's at the base's `size`) over
/// the step, h (|v₀| + L |ω₀|). Friction in each substep opposes the slip at its end, so a
/// slip that stops or reverses within a substep has its friction reversed over the whole
/// substep in every row alike, and the tableau cannot see it; its error, of order h |v₀|, is
/// then held to the tolerance, locating the stop or the reversal within a step that short.
fn stop_error(s0: &BodyState, h: f64, size: f64, tolerance: f64) -> f64 {
    h * (s0.v.norm() + size * s0.w.norm()) / (tolerance * size)
}

impl Ctx<'_> {
    /// The extrapolated step over `h` from state `s` at time `t`, the substeps started from the
    /// last step's impulses `warm` (scaled to each substep's length), the error weighed against
    /// `tolerance`.
    pub fn extrapolated(
        &self,
        s: &BodyState,
        t: f64,
        h: f64,
        warm: &Stepped,
        tolerance: f64,
    ) -> Extrapolated {
        let mut rows = [[0.0; VALUES]; 3];
        let mut last = warm.clone();
        let mut far = false;
        for (row, &n) in rows.iter_mut().zip(&SEQUENCE) {
            let sub = h / n as f64;
            let mut x = *s;
            last = warm.scaled(sub);
            for i in 0..n {
                last = self.step(&mut x, t + i as f64 * sub, sub, &last);
            }
            *row = numbers(s, &x);
            far |= Vector3::new(row[9], row[10], row[11]).norm() > LONGEST_TURN;
        }
        let (best, before) = extrapolate(&rows);
        let w = weights(self.size, tolerance);
        let mut ratio = (0..VALUES)
            .map(|i| (best[i] - before[i]).abs() * w[i])
            .fold(0.0, f64::max);
        let stops = stopped(s, &best, self.size);
        if stops {
            ratio = ratio.max(stop_error(s, h, self.size, tolerance));
        }
        let finite = best.iter().all(|x| x.is_finite());
        Extrapolated {
            state: state(s, &best),
            ratio: if finite && !far && ratio.is_finite() {
                ratio
            } else {
                f64::INFINITY
            },
            last,
            stopped: stops,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows from a value whose error in the substep H/n is a polynomial of degree ≤ 2 in it:
    /// the tableau's last entry is the value itself.
    #[test]
    fn the_tableau_removes_an_error_of_first_and_second_order_in_the_substep() {
        let exact = 1.25;
        let (c1, c2) = (0.3, -0.7);
        let mut rows = [[0.0; VALUES]; 3];
        for (row, &n) in rows.iter_mut().zip(&SEQUENCE) {
            let h = 0.1 / n as f64;
            row[0] = exact + c1 * h + c2 * h * h;
        }
        let (best, before) = extrapolate(&rows);
        assert!((best[0] - exact).abs() < 1e-15, "{}", best[0]);
        // The one before removes the first order only: off by the second order's term.
        let want = exact - c2 * 0.1 * 0.1 / 6.0;
        assert!((before[0] - exact).abs() > 1e-4);
        assert!(
            (before[0] - want).abs() < 1e-15,
            "{} against {want}",
            before[0]
        );
    }

    #[test]
    fn a_state_turned_into_numbers_and_back_is_itself() {
        let mut s0 = BodyState::at_rest(crate::geometry::BodyPose {
            cm: Vector3::new(1.0, 2.0, 3.0),
            rotation: Rotation3::from_scaled_axis(Vector3::new(0.1, -0.4, 0.2)).into_inner(),
        });
        s0.path = 0.5;
        let mut s = s0;
        s.drift(0.0);
        s.w = Vector3::new(0.2, 0.3, -0.1);
        s.v = Vector3::new(-1.0, 0.0, 2.0);
        s.drift(0.7);
        s.work_applied = 3.0;
        let back = state(&s0, &numbers(&s0, &s));
        assert!((back.pose.rotation - s.pose.rotation).norm() < 1e-14);
        assert!((back.pose.cm - s.pose.cm).norm() < 1e-15);
        assert_eq!((back.v, back.w, back.work_applied), (s.v, s.w, 3.0));
    }
}
