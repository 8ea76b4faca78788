//! Advancing the paper's state over one increment.
//!
//! * [`paper_step`]: eqs. (33)–(38) as printed: with the accelerations of the state at the
//!   start of the increment, v += a·dt and x += v·dt + a·dt²/2 (first order in dt overall,
//!   because the accelerations are frozen over the increment).
//! * [`rk4_step`]: the route's RK4 (`route/integrator.rs`) on y = (X, Z, θ, Ẋ, Ż, θ̇) with the
//!   paper's right-hand side, the accelerations evaluated at the stage positions; with its last
//!   stage, for the error estimate that chooses its substeps (`mod.rs`).

use super::state::State;
use crate::route::integrator::rk4_stages;

/// Eqs. (33)–(38).
pub fn paper_step(s: &State, acc: &[f64; 3], dt: f64) -> State {
    State {
        t: s.t + dt,
        x: s.x + s.vx * dt + 0.5 * acc[0] * dt * dt,
        z: s.z + s.vz * dt + 0.5 * acc[1] * dt * dt,
        theta: s.theta + s.omega * dt + 0.5 * acc[2] * dt * dt,
        vx: s.vx + acc[0] * dt,
        vz: s.vz + acc[1] * dt,
        omega: s.omega + acc[2] * dt,
    }
}

/// [`rk4_stages`] on the paper's state. `acc(state)` gives the accelerations at a stage state.
/// The state at the step's end, and the last stage's derivative k4 (its first three the rates
/// (Ẋ, Ż, θ̇) at y + h k3).
pub fn rk4_step<E>(
    s: &State,
    acc0: &[f64; 3],
    dt: f64,
    mut acc: impl FnMut(&State) -> Result<[f64; 3], E>,
) -> Result<(State, [f64; 6]), E> {
    let y = [s.x, s.z, s.theta, s.vx, s.vz, s.omega];
    let of = |y: &[f64; 6], h: f64| State {
        t: s.t + h,
        x: y[0],
        z: y[1],
        theta: y[2],
        vx: y[3],
        vz: y[4],
        omega: y[5],
    };
    let derivative = |y: &[f64; 6], a: [f64; 3]| [y[3], y[4], y[5], a[0], a[1], a[2]];
    let k1 = derivative(&y, *acc0);
    // The stages' times: the first two at half the step, the last at its end.
    let mut stage = 0;
    let (next, k4) = rk4_stages(&y, &k1, dt, |z| {
        stage += 1;
        let h = if stage < 3 { 0.5 * dt } else { dt };
        acc(&of(z, h)).map(|a| derivative(z, a))
    })?;
    Ok((of(&next, dt), k4))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_acceleration_is_integrated_exactly_by_both() {
        let s = State {
            vx: 1.0,
            ..State::default()
        };
        let a = [2.0, -1.0, 0.5];
        let p = paper_step(&s, &a, 0.1);
        let r = rk4_step::<()>(&s, &a, 0.1, |_| Ok(a)).unwrap().0;
        for q in [p, r] {
            assert!((q.x - (0.1 + 0.5 * 2.0 * 0.01)).abs() < 1e-15);
            assert!((q.vz + 0.1).abs() < 1e-15);
            assert!((q.theta - 0.5 * 0.5 * 0.01).abs() < 1e-15);
        }
    }

    #[test]
    fn rk4_is_fourth_order_on_a_position_dependent_force() {
        // ẍ = −x (harmonic oscillator): error of x(1) falls by ≈ 16 when dt halves.
        let run = |n: usize| {
            let dt = 1.0 / n as f64;
            let mut s = State {
                x: 1.0,
                ..State::default()
            };
            for _ in 0..n {
                let a0 = [-s.x, 0.0, 0.0];
                s = rk4_step::<()>(&s, &a0, dt, |q| Ok([-q.x, 0.0, 0.0]))
                    .unwrap()
                    .0;
            }
            (s.x - 1f64.cos()).abs()
        };
        let ratio = run(20) / run(40);
        assert!((14.0..18.0).contains(&ratio), "{ratio}");
    }
}
