//! The pose system for any contact triangle and any three planes
//! (`derivations/09-general-pose.md`).
//!
//! The block's orientation is the yaw θ of its x' axis, the tilt α of x' and the roll ψ about
//! it, as in the exact form of the paper's system (`derivations/04-exact.md`):
//!
//! ```text
//! i' = (cα cθ, sα, cα sθ),   w = (−sθ, 0, cθ),   n = (−sα cθ, cα, −sα sθ),   k' = cψ·w + sψ·n.
//! ```
//!
//! Contact k sits at (x_k, z_k) in the base plane (x', z'), so it is placed at
//! P_k = C + x_k i' + z_k k' with C = (X, Y_c, Z) the centre of mass. Plane k has the unit upward
//! normal m_k, and d_k = m_k·S_k − e_k is how far contact k's start S_k = (x_k, 0, z_k) lies off
//! it (zero for a start on the plane). Contact k on plane k reads
//!
//! ```text
//! r_k = m_k·(P_k − S_k) + d_k = 0.
//! ```
//!
//! The CM height enters each r_k as m_k,y·Y_c, so m_0,y r_k − m_k,y r_0 (k = 1, 2) is free of it:
//! two equations in (sα, cα, sψ, cψ), each of degree ≤ 1 in each pair — the same shape, the same
//! half-angle form and the same eight-root bound as the paper's exact (13), (14).

use crate::poly::{Monomial, Poly, Sym};
use std::collections::BTreeMap;

/// The parameters of the generated general coefficient functions: name and meaning.
pub const PARAMETERS: &[(Sym, &str)] = &[
    ("x", "X: CM displacement along the global X axis (m)"),
    ("z", "Z: CM displacement along the global Z axis (m)"),
    ("omc", "1 - cos θ, computed as 2 sin²(θ/2)"),
    ("st", "sin θ"),
    ("x0", "x' of contact 0 (m)"),
    ("z0", "z' of contact 0 (m)"),
    ("x1", "x' of contact 1 (m)"),
    ("z1", "z' of contact 1 (m)"),
    ("x2", "x' of contact 2 (m)"),
    ("z2", "z' of contact 2 (m)"),
    ("m0x", "X part of plane 0's unit upward normal"),
    ("m0y", "Y part of plane 0's unit upward normal (> 0)"),
    ("m0z", "Z part of plane 0's unit upward normal"),
    ("m1x", "X part of plane 1's unit upward normal"),
    ("m1y", "Y part of plane 1's unit upward normal (> 0)"),
    ("m1z", "Z part of plane 1's unit upward normal"),
    ("m2x", "X part of plane 2's unit upward normal"),
    ("m2y", "Y part of plane 2's unit upward normal (> 0)"),
    ("m2z", "Z part of plane 2's unit upward normal"),
    (
        "d0",
        "how far contact 0's start lies off plane 0, along its normal (m)",
    ),
    (
        "d1",
        "how far contact 1's start lies off plane 1, along its normal (m)",
    ),
    (
        "d2",
        "how far contact 2's start lies off plane 2, along its normal (m)",
    ),
];

/// The unknowns of the general exact form: sin/cos of α (tilt of x') and of ψ (roll about x').
pub const UNKNOWNS: [Sym; 4] = ["sa", "ca", "sp", "cp"];

/// The trig-basis monomials of both equations, in the order the generated code uses.
pub const BASIS: [[u32; 4]; 6] = [
    [0, 0, 0, 0], // 1
    [1, 0, 0, 0], // sin α
    [0, 1, 0, 0], // cos α
    [0, 0, 0, 1], // cos ψ
    [1, 0, 1, 0], // sin α sin ψ
    [0, 1, 1, 0], // cos α sin ψ
];

/// The small-angle unknowns: α and ψ themselves.
pub const SMALL_UNKNOWNS: [Sym; 2] = ["al", "ps"];

/// The small-angle monomials of both equations, as (α, ψ) exponents: 1, α, ψ, αψ.
pub const SMALL_BASIS: [(u32, u32); 4] = [(0, 0), (1, 0), (0, 1), (1, 1)];

fn v(s: Sym) -> Poly {
    Poly::var(s)
}

fn n(k: i128) -> Poly {
    Poly::int(k)
}

/// The symbol of contact `k`'s coordinate or plane `k`'s normal component.
fn sym(prefix: &str, k: usize, suffix: &str) -> Sym {
    PARAMETERS
        .iter()
        .map(|(s, _)| *s)
        .find(|s| *s == format!("{prefix}{k}{suffix}"))
        .expect("every contact and plane symbol is a parameter")
}

/// Contact `k`'s residual on its plane without the CM height term: m_k·(P_k − S_k) + d_k −
/// m_k,y Y_c, with P_k − S_k = (X + x_k (i'_x − 1) + z_k k'_x, x_k i'_y + z_k k'_y,
/// Z + x_k i'_z + z_k (k'_z − 1)).
fn residual_without_height(k: usize) -> Poly {
    let (sa, ca, sp, cp) = (v("sa"), v("ca"), v("sp"), v("cp"));
    let ct = n(1) - v("omc");
    let st = v("st");
    let i = [&ca * &ct, sa.clone(), &ca * &st];
    let kk = [
        -(&cp * &st) - &sp * &sa * &ct,
        &sp * &ca,
        &cp * &ct - &sp * &sa * &st,
    ];
    let (xk, zk) = (v(sym("x", k, "")), v(sym("z", k, "")));
    let dx = v("x") + &xk * &(&i[0] - &n(1)) + &zk * &kk[0];
    let dy = &xk * &i[1] + &zk * &kk[1];
    let dz = v("z") + &xk * &i[2] + &zk * &(&kk[2] - &n(1));
    v(sym("m", k, "x")) * dx
        + v(sym("m", k, "y")) * dy
        + v(sym("m", k, "z")) * dz
        + v(sym("d", k, ""))
}

/// The two equations m_0,y r_k − m_k,y r_0 (k = 1, 2), free of the CM height, in the unknowns
/// (sα, cα, sψ, cψ) and the parameters.
pub fn exact_trig() -> [Poly; 2] {
    let r0 = residual_without_height(0);
    [1, 2].map(|k| v("m0y") * residual_without_height(k) - v(sym("m", k, "y")) * &r0)
}

/// The CM height from contact 0 on its plane: Y_c = −(m_0·(P_0 − S_0 − Y_c ĵ) + d_0) / m_0,y,
/// returned as the numerator polynomial N (Y_c = −N / m_0,y).
pub fn height_numerator() -> Poly {
    residual_without_height(0)
}

/// Both equations collected in [`BASIS`]: per equation, the coefficient of each basis monomial
/// (zero where it does not occur).
pub fn exact_collected() -> [Vec<Poly>; 2] {
    exact_trig().map(|e| {
        let c: BTreeMap<Monomial, Poly> = e.collect(&UNKNOWNS);
        let basis: Vec<Monomial> = BASIS.iter().map(monomial).collect();
        assert!(
            c.keys().all(|m| basis.contains(m)),
            "the general system changed shape: {:?}",
            c.keys().collect::<Vec<_>>()
        );
        basis
            .iter()
            .map(|m| c.get(m).cloned().unwrap_or_default())
            .collect()
    })
}

/// The basis monomial of (sα, cα, sψ, cψ) exponents.
pub fn monomial(e: &[u32; 4]) -> Monomial {
    Monomial::from_pairs(&[("sa", e[0]), ("ca", e[1]), ("sp", e[2]), ("cp", e[3])])
}

/// The small-angle form: sα → α, cα → 1, sψ → ψ, cψ → 1 in the exact equations (errors of
/// second order in the angles, as in the paper's (15)), collected in [`SMALL_BASIS`].
pub fn small_angle_collected() -> [Vec<Poly>; 2] {
    exact_trig().map(|e| {
        let s = e
            .subs("sa", &v("al"))
            .subs("ca", &n(1))
            .subs("sp", &v("ps"))
            .subs("cp", &n(1));
        let c = s.collect(&SMALL_UNKNOWNS);
        let basis: Vec<Monomial> = SMALL_BASIS
            .iter()
            .map(|&(i, j)| Monomial::from_pairs(&[("al", i), ("ps", j)]))
            .collect();
        assert!(c.keys().all(|m| basis.contains(m)));
        basis
            .iter()
            .map(|m| c.get(m).cloned().unwrap_or_default())
            .collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Parameter values of the paper's default site (L = 10 m, ξ = 20°, ζ = 25°, κ = 30°) at a
    /// displacement, with the planes through the contacts' starts.
    fn paper_value(s: Sym, d: (f64, f64, f64)) -> f64 {
        let (xi, zeta, kappa) = (20f64.to_radians(), 25f64.to_radians(), 30f64.to_radians());
        let c = [[-6.0, 5.0], [4.0, 5.0], [4.0, -5.0]];
        let m = [
            [0.0, 1.0, 0.0],
            [-xi.sin(), xi.cos(), 0.0],
            [
                -zeta.sin() * kappa.cos(),
                zeta.cos(),
                zeta.sin() * kappa.sin(),
            ],
        ];
        let idx = |t: &str| t[1..2].parse::<usize>().unwrap();
        match s {
            "x" => d.0,
            "z" => d.1,
            "omc" => 1.0 - d.2.cos(),
            "st" => d.2.sin(),
            _ if s.starts_with('x') => c[idx(s)][0],
            _ if s.starts_with('z') => c[idx(s)][1],
            _ if s.starts_with('m') => {
                m[idx(s)][match &s[2..] {
                    "x" => 0,
                    "y" => 1,
                    _ => 2,
                }]
            }
            _ if s.starts_with('d') => 0.0,
            _ => panic!("no value for {s}"),
        }
    }

    #[test]
    fn the_general_system_is_bilinear_in_the_circle_pairs() {
        for e in exact_trig() {
            for (m, _) in e.terms() {
                let a = m.degree_in("sa") + m.degree_in("ca");
                let p = m.degree_in("sp") + m.degree_in("cp");
                assert!(a <= 1 && p <= 1, "monomial {m:?} is not bilinear");
            }
        }
        // And of the six basis monomials only.
        let c = exact_collected();
        assert!(c.iter().all(|eq| eq.len() == 6));
    }

    #[test]
    fn the_flat_start_on_the_planes_solves_it() {
        // At X = Z = θ = 0 the flat frame (α = ψ = 0) has every contact on its plane.
        let value = |s: Sym| match s {
            "sa" | "sp" => 0.0,
            "ca" | "cp" => 1.0,
            _ => paper_value(s, (0.0, 0.0, 0.0)),
        };
        for e in exact_trig() {
            assert!(e.eval(&value).abs() < 1e-12);
        }
    }

    #[test]
    fn on_the_papers_planes_it_is_the_papers_exact_form_times_the_sines_of_the_dips() {
        // Contact 1 on plane 1 reads sin ξ·(13) and contact 2 on plane 2 −sin ζ·(14)
        // (derivations/09-general-pose.md): compared at arbitrary (α, ψ) and displacement.
        let (xi, zeta) = (20f64.to_radians(), 25f64.to_radians());
        let d = (1.3, -0.4, 0.2);
        let paper = crate::system::exact_trig();
        for (sa_, sp_) in [(0.1f64, -0.3f64), (0.5, 0.2), (-0.2, 0.9)] {
            let general_value = |s: Sym| match s {
                "sa" => sa_.sin(),
                "ca" => sa_.cos(),
                "sp" => sp_.sin(),
                "cp" => sp_.cos(),
                _ => paper_value(s, d),
            };
            let kappa = 30f64.to_radians();
            let paper_value_of = |s: Sym| match s {
                "sa" => sa_.sin(),
                "ca" => sa_.cos(),
                "sp" => sp_.sin(),
                "cp" => sp_.cos(),
                "x" => d.0,
                "z" => d.1,
                "l2x" => 4.0,
                "l1z" => 5.0,
                "l2z" => 5.0,
                "omc" => 1.0 - d.2.cos(),
                "st" => d.2.sin(),
                "ck" => kappa.cos(),
                "sk" => kappa.sin(),
                "dck" => kappa.cos() - (d.2 + kappa).cos(),
                "dsk" => (d.2 + kappa).sin() - kappa.sin(),
                "cot_xi" => 1.0 / xi.tan(),
                "cot_zeta" => 1.0 / zeta.tan(),
                "r2" => std::f64::consts::SQRT_2,
                _ => panic!("{s}"),
            };
            let g = exact_trig().map(|e| e.eval(&general_value));
            let p = paper.clone().map(|e| e.eval(&paper_value_of));
            assert!((g[0] - xi.sin() * p[0]).abs() < 1e-12, "{g:?} {p:?}");
            assert!((g[1] + zeta.sin() * p[1]).abs() < 1e-12, "{g:?} {p:?}");
        }
    }

    #[test]
    fn the_small_angle_form_is_the_exact_one_to_second_order() {
        let d = (0.3, 0.1, 0.05);
        let small = small_angle_collected();
        let exact = exact_trig();
        for eps in [1e-2f64, 5e-3] {
            let (a, p) = (eps, -0.7 * eps);
            let value = |s: Sym| match s {
                "sa" => a.sin(),
                "ca" => a.cos(),
                "sp" => p.sin(),
                "cp" => p.cos(),
                _ => paper_value(s, d),
            };
            for (eq, e) in exact.iter().enumerate() {
                let at = |s: Sym| paper_value(s, d);
                let s: f64 = SMALL_BASIS
                    .iter()
                    .zip(&small[eq])
                    .map(|(&(i, j), c)| c.eval(&at) * a.powi(i as i32) * p.powi(j as i32))
                    .sum();
                let diff = (e.eval(&value) - s).abs();
                assert!(diff < 10.0 * 10.0 * eps * eps, "{diff} at ε = {eps}");
            }
        }
    }
}
