//! The one classic fourth-order Runge–Kutta step both dynamics integrate with.

/// One classic RK4 step of length `h` from `y`, whose derivative `k1` is known:
/// y + h/6 (k1 + 2 k2 + 2 k3 + k4) with the stages at y + h/2 k1, y + h/2 k2 and y + h k3.
/// `f(stage)` gives the derivative at a stage (or an error, which ends the step). The one RK4
/// of both dynamics: the paper's on (X, Z, θ, Ẋ, Ż, θ̇), the rigid body's on that state and
/// the two works.
pub fn rk4<const N: usize, E>(
    y: &[f64; N],
    k1: &[f64; N],
    h: f64,
    mut f: impl FnMut(&[f64; N]) -> Result<[f64; N], E>,
) -> Result<[f64; N], E> {
    let axpy = |k: &[f64; N], c: f64| -> [f64; N] { std::array::from_fn(|i| y[i] + c * k[i]) };
    let k2 = f(&axpy(k1, 0.5 * h))?;
    let k3 = f(&axpy(&k2, 0.5 * h))?;
    let k4 = f(&axpy(&k3, h))?;
    Ok(std::array::from_fn(|i| {
        y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
    }))
}
