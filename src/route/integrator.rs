//! Advancing the state over one increment.
//!
//! * [`paper_step`]: eqs. (33)–(38) as printed: with the accelerations of the state at the
//!   start of the increment, v += a·dt and x += v·dt + a·dt²/2 (first order in dt overall,
//!   because the accelerations are frozen over the increment).
//! * [`rk4_step`]: classic fourth-order Runge–Kutta on y = (X, Z, θ, Ẋ, Ż, θ̇) with the same
//!   right-hand side, the accelerations evaluated at the stage positions.

use super::state::State;

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

/// The state reached from `s` after `h` with constant derivative (position rates `v`,
/// accelerations `a`): the RK4 stage point.
fn stage(s: &State, v: &[f64; 3], a: &[f64; 3], h: f64) -> State {
    State {
        t: s.t + h,
        x: s.x + h * v[0],
        z: s.z + h * v[1],
        theta: s.theta + h * v[2],
        vx: s.vx + h * a[0],
        vz: s.vz + h * a[1],
        omega: s.omega + h * a[2],
    }
}

/// One RK4 step. `acc(state)` gives the accelerations at a stage state (or an error, which
/// ends the step).
pub fn rk4_step<E>(
    s: &State,
    acc0: &[f64; 3],
    dt: f64,
    mut acc: impl FnMut(&State) -> Result<[f64; 3], E>,
) -> Result<State, E> {
    let v1 = [s.vx, s.vz, s.omega];
    let a1 = *acc0;
    let s2 = stage(s, &v1, &a1, 0.5 * dt);
    let v2 = [s2.vx, s2.vz, s2.omega];
    let a2 = acc(&s2)?;
    let s3 = stage(s, &v2, &a2, 0.5 * dt);
    let v3 = [s3.vx, s3.vz, s3.omega];
    let a3 = acc(&s3)?;
    let s4 = stage(s, &v3, &a3, dt);
    let v4 = [s4.vx, s4.vz, s4.omega];
    let a4 = acc(&s4)?;
    let comb = |k: usize, p: &[f64; 3], q: &[f64; 3], r: &[f64; 3], u: &[f64; 3]| {
        (p[k] + 2.0 * q[k] + 2.0 * r[k] + u[k]) * dt / 6.0
    };
    Ok(State {
        t: s.t + dt,
        x: s.x + comb(0, &v1, &v2, &v3, &v4),
        z: s.z + comb(1, &v1, &v2, &v3, &v4),
        theta: s.theta + comb(2, &v1, &v2, &v3, &v4),
        vx: s.vx + comb(0, &a1, &a2, &a3, &a4),
        vz: s.vz + comb(1, &a1, &a2, &a3, &a4),
        omega: s.omega + comb(2, &a1, &a2, &a3, &a4),
    })
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
        let r = rk4_step::<()>(&s, &a, 0.1, |_| Ok(a)).unwrap();
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
                s = rk4_step::<()>(&s, &a0, dt, |q| Ok([-q.x, 0.0, 0.0])).unwrap();
            }
            (s.x - 1f64.cos()).abs()
        };
        let ratio = run(20) / run(40);
        assert!((14.0..18.0).contains(&ratio), "{ratio}");
    }
}
