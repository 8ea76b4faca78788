//! The paper's relations, fed to the polynomial engine step by step.
//!
//! Everything here follows `derivations/02-law-of-sines.md` (eqs. (2), (3), (8)–(14)),
//! `derivations/03-small-angle.md` (system (15)) and `derivations/04-exact.md` (the exact form).
//! Equation numbers are the paper's (Galic & Glaser). Symbols:
//!
//! * parameters (inputs of the generated code, see [`PARAMETERS`]);
//! * unknown-dependent symbols: `sa, ca` = sin α, cos α; `sb, cb` = sin β, cos β;
//!   `sp, cp` = sin ψ, cos ψ (ψ: roll of the frame about side 01, exact form only);
//!   `pp` = cos α cos β cos h and `qq` = cos α cos β sin h (eq. (2) multiplied out);
//! * `r2` = √2, with the rule r2² = 2.

use crate::poly::{Monomial, Poly, Sym};
use crate::rational::Rational;
use std::collections::BTreeMap;

/// √2 as a symbol (r2² = 2).
pub const R2: Sym = "r2";

/// The parameters of the generated coefficient functions: name and meaning.
///
/// Lengths are canonical (three free ones; L and L1X are derived), and the angle inputs are
/// chosen so that every term of the expanded coefficients vanishes with the displacement:
/// `omc` = 1 − cos θ, `dck` = cos κ − cos(θ+κ), `dsk` = sin(θ+κ) − sin κ. The wrapper computes
/// them without cancellation, so no coefficient is a difference of large, nearly equal terms.
pub const PARAMETERS: &[(Sym, &str)] = &[
    ("x", "X: CM displacement along the global X axis (m)"),
    ("z", "Z: CM displacement along the global Z axis (m)"),
    ("l2x", "L2X: frame dimension, CM to side 12 along x' (m)"),
    ("l1z", "L1Z: frame dimension, CM to side 01 along z' (m)"),
    ("l2z", "L2Z: frame dimension, CM to vertex 2 along -z' (m)"),
    ("omc", "1 - cos θ, computed as 2 sin²(θ/2)"),
    ("st", "sin θ"),
    ("ck", "cos κ"),
    ("sk", "sin κ"),
    (
        "dck",
        "cos κ - cos(θ + κ), computed as 2 sin(θ/2) sin(θ/2 + κ)",
    ),
    (
        "dsk",
        "sin(θ + κ) - sin κ, computed as 2 sin(θ/2) cos(θ/2 + κ)",
    ),
    ("cot_xi", "cot ξ (plane 1)"),
    ("cot_zeta", "cot ζ (plane 2)"),
];

fn v(s: Sym) -> Poly {
    Poly::var(s)
}
fn n(k: i128) -> Poly {
    Poly::int(k)
}
fn half() -> Poly {
    Poly::constant(Rational::new(1, 2))
}

/// Derived parameters, substituted away before anything is emitted.
struct Derived {
    /// L = L1Z + L2Z (frame, eq. (20)).
    l: Poly,
    /// L1X = L − L2X.
    l1x: Poly,
    ct: Poly,
    cphi: Poly,
    sphi: Poly,
    /// R (eq. 4).
    r: Poly,
    /// S (eq. 5).
    s: Poly,
}

fn derived() -> Derived {
    let l = v("l1z") + v("l2z");
    Derived {
        l1x: &l - v("l2x"),
        l,
        ct: n(1) - v("omc"),
        cphi: v("ck") - v("dck"),
        sphi: v("sk") + v("dsk"),
        r: v("l2x") * v("ck") + v("l2z") * v("sk"),
        s: v("x") * v("ck") - v("z") * v("sk"),
    }
}

/// Normal form of the parameters: √2² = 2 and the unit-circle identities of θ, κ and θ + κ in
/// the chosen inputs — sin²θ = 2·omc − omc² (cos θ = 1 − omc), sin²κ = 1 − cos²κ, and
/// dsk² = 2 cos κ·dck − dck² − 2 sin κ·dsk (which is sin²(θ+κ) + cos²(θ+κ) = 1). Each rule
/// lowers a degree, so the form is unique, and none divides by a small quantity.
fn norm(p: &Poly) -> Poly {
    let p = p.reduce_power(R2, 2, &n(2));
    let p = p.reduce_power("st", 2, &(n(2) * v("omc") - v("omc").square()));
    let p = p.reduce_power("sk", 2, &(n(1) - v("ck").square()));
    let p = p.reduce_power(
        "dsk",
        2,
        &(n(2) * v("ck") * v("dck") - v("dck").square() - n(2) * v("sk") * v("dsk")),
    );
    p.reduce_power("sk", 2, &(n(1) - v("ck").square()))
}

/// Eqs. (13) and (14) multiplied by cos α, written as LHS − RHS of the paper's (13), (14),
/// in terms of `pp` = cα cβ cos h, `qq` = cα cβ sin h, `sa`, `ca`, `sb`.
///
/// (13) is (3) minus (9)+(11), both multiplied by cos θ·cos α; (14) is (10)+(12) minus (8),
/// both multiplied by cos(h − κ − θ)·cos α. See `derivations/02-law-of-sines.md`.
pub fn law_of_sines_times_cos_alpha() -> [Poly; 2] {
    let d = derived();
    let (sa, ca, sb) = (v("sa"), v("ca"), v("sb"));
    let (pp, qq) = (v("pp"), v("qq"));
    // cα·cβ cos(h − θ) = pp cθ + qq sθ;  cα·cβ cos(h − κ − θ) = pp cφ + qq sφ.
    let cos_h_theta = &pp * &d.ct + &qq * v("st");
    let cos_h_phi = &pp * &d.cphi + &qq * &d.sphi;

    // (3)·cθ... times cα:  cα EG cθ = √2 L1Z (cα cβ cos(h−θ)) + (L1X − L1Z) cα² cθ + cα (L2X − X)
    let eg_from_3 = v(R2) * v("l1z") * &cos_h_theta
        + (&d.l1x - v("l1z")) * &ca * &ca * &d.ct
        + &ca * (v("l2x") - v("x"));
    // (9) with (11): EG sin ξ' = L sin(ξ' − α), cot ξ' = cot ξ / cos θ
    //   ⇒ EG cθ = L (cα cθ − sα cot ξ); times cα.
    let eg_from_9 = &d.l * &ca * (&ca * &d.ct - &sa * v("cot_xi"));
    let e13 = eg_from_3 - eg_from_9;

    // (6): t = (L1X − L1Z) cos α sin(90° − θ − κ) = (L1X − L1Z) cα cφ.
    let t = (&d.l1x - v("l1z")) * &ca * &d.cphi;
    // (8)·cos(h−φ)·cα: cα EF cos(h−φ) = √2 L1Z (cα cβ cos(h−φ)) + cα (R + t − S)
    let ef_from_8 = v(R2) * v("l1z") * &cos_h_phi + &ca * (&d.r + &t - &d.s);
    // (10) with (12): EF sin ζ' = √2 L sin(ζ' − β), cot ζ' = cot ζ / cos(h − φ)
    //   ⇒ EF cos(h−φ) = √2 L (cβ cos(h−φ) − sβ cot ζ); times cα.
    let ef_from_10 = v(R2) * &d.l * (&cos_h_phi - &ca * &sb * v("cot_zeta"));
    let e14 = ef_from_10 - ef_from_8;
    [norm(&e13), norm(&e14)]
}

/// cα cβ cos h from eq. (2): cos 45° − sin α sin β, with cos 45° = √2/2.
fn pp_of_sa_sb() -> Poly {
    v(R2) * half() - v("sa") * v("sb")
}

/// (cα cβ sin h)² = cα² cβ² − (cα cβ cos h)².
fn qq_squared() -> Poly {
    let pp = pp_of_sa_sb();
    norm(&(v("ca").square() * v("cb").square() - pp.square()))
}

/// The unknowns of the small-angle system (15): α and β.
pub const SMALL_UNKNOWNS: [Sym; 2] = ["alpha", "beta"];

/// The monomials of (15a) and (15b) in the paper's order f1–f6 and f7–f12, as (α, β) exponents.
pub const SMALL_ANGLE_MONOMIALS: [[(u32, u32); 6]; 2] = [
    [(0, 0), (1, 0), (1, 1), (2, 0), (2, 1), (2, 2)],
    [(0, 0), (0, 1), (1, 1), (0, 2), (1, 2), (2, 2)],
];

/// The squared relations (13), (14) in exact trigonometric form, before any approximation:
/// `A² − B²·(cα²cβ² − P²)`, where `E·cα = A + B·qq` (isolating and squaring away sin h).
pub fn squared_law_of_sines() -> [Poly; 2] {
    let pp = pp_of_sa_sb();
    let q2 = qq_squared();
    law_of_sines_times_cos_alpha().map(|e| {
        let e = e.subs("pp", &pp);
        let (a, b) = e.isolate("qq").expect("(13), (14) are linear in sin h");
        norm(&(a.square() - b.square() * &q2))
    })
}

/// System (15): the squared relations under sin α ≈ α, sin β ≈ β, cos α ≈ cos β ≈ 1,
/// collected into the twelve coefficients f1–f12 (each a polynomial in the parameters).
pub fn small_angle() -> [Poly; 12] {
    let squared = squared_law_of_sines();
    let mut out: Vec<Poly> = Vec::with_capacity(12);
    for (eq, mons) in squared.iter().zip(SMALL_ANGLE_MONOMIALS.iter()) {
        let small = eq
            .subs("sa", &v("alpha"))
            .subs("sb", &v("beta"))
            .subs("ca", &n(1))
            .subs("cb", &n(1));
        let collected = small.collect(&SMALL_UNKNOWNS);
        let expected: Vec<Monomial> = mons
            .iter()
            .map(|&(i, j)| Monomial::from_pairs(&[("alpha", i), ("beta", j)]))
            .collect();
        let found: Vec<&Monomial> = collected.keys().collect();
        assert!(
            found.len() == expected.len() && expected.iter().all(|m| collected.contains_key(m)),
            "system (15) changed shape: found monomials {found:?}"
        );
        out.extend(expected.iter().map(|m| collected[m].clone()));
    }
    out.try_into().expect("twelve coefficients")
}

/// The unsquared small-angle relations: (13)·cos α and (14)·cos α under the small-angle
/// substitutions, written E = A + B·Q with Q = cos α cos β sin h ≈ √(1 − (1/√2 − αβ)²) ≥ 0.
/// Returns, per equation, A collected in (α, β) and B (free of α, β). A root of (15) is spurious
/// when it satisfies A − B·Q = 0 instead of A + B·Q = 0 (the other sign of sin h).
pub fn small_angle_unsquared() -> [(Vec<(Monomial, Poly)>, Poly); 2] {
    let pp = pp_of_sa_sb();
    law_of_sines_times_cos_alpha().map(|e| {
        let e = e
            .subs("pp", &pp)
            .subs("sa", &v("alpha"))
            .subs("sb", &v("beta"))
            .subs("ca", &n(1))
            .subs("cb", &n(1));
        let (a, b) = e.isolate("qq").expect("linear in sin h");
        assert!(
            b.degree_in("alpha") == 0 && b.degree_in("beta") == 0,
            "B of the small-angle relations must be free of α, β"
        );
        (
            norm(&a).collect(&SMALL_UNKNOWNS).into_iter().collect(),
            norm(&b),
        )
    })
}

/// The unknowns of the exact form: sin/cos of α (tilt of side 01) and of ψ (roll about side 01).
pub const EXACT_UNKNOWNS: [Sym; 4] = ["sa", "ca", "sp", "cp"];

/// sin β in terms of (α, ψ): √2 sin β = sin α − cos α sin ψ (heights of vertices 1, 2).
fn sb_of_alpha_psi() -> Poly {
    v(R2) * half() * (v("sa") - v("ca") * v("sp"))
}

/// cα cβ sin h in terms of (α, ψ): cos α cos ψ / √2 (the branch with sin h ≥ 0 ⇔ cos ψ ≥ 0).
fn qq_of_alpha_psi() -> Poly {
    v(R2) * half() * v("ca") * v("cp")
}

/// Unit-circle normal form for the exact unknowns: sin² → 1 − cos².
fn circle(p: &Poly) -> Poly {
    let p = norm(p);
    let p = p.reduce_power("sa", 2, &(n(1) - v("ca").square()));
    let p = p.reduce_power("sp", 2, &(n(1) - v("cp").square()));
    p.reduce_power("sb", 2, &(n(1) - v("cb").square()))
}

/// Checks, in exact arithmetic, that the substitution sβ(α, ψ), qq(α, ψ) satisfies
/// qq² = cα² cβ² − pp² (the definition of sin h through eq. (2)). Returns the remainder (zero).
pub fn exact_substitution_remainder() -> Poly {
    let sb = sb_of_alpha_psi();
    let lhs = qq_of_alpha_psi().square();
    let cb2 = n(1) - sb.square();
    let pp = pp_of_sa_sb().subs("sb", &sb);
    let rhs = v("ca").square() * cb2 - pp.square();
    circle(&(lhs - rhs))
}

/// The exact form: (13) and (14) with (sα, cα, sψ, cψ) as unknowns, divided by cos α.
/// Each is of degree ≤ 1 in each pair (sα, cα) and (sψ, cψ); no squaring, no approximation.
pub fn exact_trig() -> [Poly; 2] {
    let sb = sb_of_alpha_psi();
    let pp = pp_of_sa_sb().subs("sb", &sb);
    let qq = qq_of_alpha_psi();
    law_of_sines_times_cos_alpha().map(|e| {
        let e = circle(&e.subs("pp", &pp).subs("qq", &qq).subs("sb", &sb));
        e.div_sym("ca")
            .expect("(13)·cos α and (14)·cos α are divisible by cos α in the exact form")
    })
}

/// Tangent half-angle form of a polynomial of degree ≤ 1 in the circle pair (`s`, `c`):
/// s = 2t/(1+t²), c = (1−t²)/(1+t²), multiplied through by (1+t²).
pub fn half_angle(p: &Poly, s: Sym, c: Sym, t: Sym) -> Poly {
    let mut out = Poly::zero();
    for (m, k) in p.terms() {
        let (rest, es) = m.take(s);
        let (rest, ec) = rest.take(c);
        assert!(es + ec <= 1, "half_angle needs degree ≤ 1 in ({s}, {c})");
        let factor = match (es, ec) {
            (1, 0) => n(2) * v(t),
            (0, 1) => n(1) - v(t).square(),
            _ => n(1) + v(t).square(),
        };
        out = out + Poly::term(k, rest) * factor;
    }
    out
}

/// A name for a trig-basis monomial, e.g. `sa_sp`, or `one`.
pub fn basis_name(m: &Monomial) -> String {
    if m.is_one() {
        "one".to_string()
    } else {
        m.factors()
            .iter()
            .map(|&(s, _)| s)
            .collect::<Vec<_>>()
            .join("_")
    }
}

/// The exact form collected in its trig basis: per equation, (basis monomial, coefficient).
pub fn exact_collected() -> [Vec<(Monomial, Poly)>; 2] {
    exact_trig().map(|e| {
        let c: BTreeMap<Monomial, Poly> = e.collect(&EXACT_UNKNOWNS);
        c.into_iter().collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_substitution_is_consistent_with_eq2() {
        assert!(exact_substitution_remainder().is_zero());
    }

    #[test]
    fn exact_form_is_bilinear_in_the_circle_pairs() {
        for e in exact_trig() {
            for (m, _) in e.terms() {
                let a = m.degree_in("sa") + m.degree_in("ca");
                let p = m.degree_in("sp") + m.degree_in("cp");
                assert!(a <= 1 && p <= 1, "monomial {m} is not bilinear");
            }
        }
    }

    #[test]
    fn small_angle_has_exactly_the_papers_twelve_coefficients() {
        let f = small_angle();
        assert!(f.iter().all(|p| !p.is_zero()));
    }

    #[test]
    fn f6_and_f12_are_twice_the_squared_lengths() {
        let f = small_angle();
        assert_eq!(f[5], n(2) * v("l1z").square());
        assert_eq!(f[11], n(2) * v("l2z").square());
    }

    #[test]
    fn f4_is_l_squared_cot_squared() {
        // f4 = L² cot² ξ with L = L1Z + L2Z.
        let f = small_angle();
        let l = v("l1z") + v("l2z");
        assert_eq!(f[3], (l * v("cot_xi")).square());
    }

    #[test]
    fn squaring_the_unsquared_pieces_gives_system_15() {
        // (A + BQ)(A − BQ) = A² − B²Q² with Q² = 1 − P²: the small-angle (15) again.
        let f = small_angle();
        let q2 = n(1) - (v(R2) * half() - v("alpha") * v("beta")).square();
        for (eq, (a, b)) in small_angle_unsquared().iter().enumerate() {
            let a: Poly = a.iter().fold(Poly::zero(), |acc, (m, c)| {
                acc + c * &Poly::term(Rational::ONE, m.clone())
            });
            let sq = norm(&(a.square() - b.square() * &q2));
            let coll = sq.collect(&SMALL_UNKNOWNS);
            for (k, &(i, j)) in SMALL_ANGLE_MONOMIALS[eq].iter().enumerate() {
                let m = Monomial::from_pairs(&[("alpha", i), ("beta", j)]);
                assert_eq!(coll[&m], f[6 * eq + k], "f{}", 6 * eq + k + 1);
            }
            assert_eq!(coll.len(), 6);
        }
    }

    #[test]
    fn half_angle_of_unit_circle_identity() {
        // s² + c² − 1 has degree 2, so check s·(1) instead: s → 2t, c → 1 − t², 1 → 1 + t².
        let p = v("s") + v("c") + n(1);
        let h = half_angle(&p, "s", "c", "t");
        assert_eq!(h, n(2) * v("t") + n(2));
    }
}
