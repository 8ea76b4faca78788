//! slideroute's build-time coefficient generator.
//!
//! [`generate`] expands the paper's law-of-sines relations (eqs. (2), (3), (8)–(14)) with our own
//! exact polynomial engine ([`poly`], [`rational`]), removes sin h by isolating and squaring for
//! the small-angle system (15), builds the exact (α, ψ) form, and emits Rust source for
//! `include!` from slideroute's `coeffs` module. The derivation is written out for people in
//! `derivations/` at the repository root; the tests there and here keep the two in step.

pub mod emit;
pub mod general;
pub mod poly;
pub mod rational;
pub mod system;

use poly::{Monomial, Poly, Sym};
use proc_macro2::{Ident, Span, TokenStream};
use quote::quote;

fn ident(s: &str) -> Ident {
    Ident::new(s, Span::call_site())
}

fn leak(s: String) -> Sym {
    Box::leak(s.into_boxed_str())
}

fn param_access(s: Sym) -> TokenStream {
    let i = ident(s);
    quote!(p.#i)
}

/// The trig-basis exponents (sa, ca, sp, cp) of a monomial of the exact form.
fn trig_exponents(m: &Monomial) -> [u32; 4] {
    system::EXACT_UNKNOWNS.map(|s| m.degree_in(s))
}

/// The body of a function from trig coefficients `g` (equation by equation, in the order of
/// `bases`) to the tangent half-angle form: ta = tan(α/2), tp = tan(ψ/2), each equation
/// multiplied by (1 + ta²)(1 + tp²), entry `9·eq + 3·i + j` the coefficient of ta^i tp^j.
fn half_angle_body(bases: &[Vec<Monomial>]) -> TokenStream {
    let mut half_outs: Vec<Poly> = Vec::new();
    let mut offset = 0usize;
    for basis in bases {
        let mut sym_poly = Poly::zero();
        for (k, m) in basis.iter().enumerate() {
            let g = leak(format!("g{}", offset + k));
            sym_poly = sym_poly + Poly::var(g) * Poly::term(rational::Rational::ONE, m.clone());
        }
        offset += basis.len();
        let h = system::half_angle(&sym_poly, "sa", "ca", "ta");
        let h = system::half_angle(&h, "sp", "cp", "tp");
        let c = h.collect(&["ta", "tp"]);
        for i in 0..3u32 {
            for j in 0..3u32 {
                let m = Monomial::from_pairs(&[("ta", i), ("tp", j)]);
                half_outs.push(c.get(&m).cloned().unwrap_or_default());
            }
        }
    }
    emit::body(&half_outs, &|s: Sym| {
        let k: usize = s[1..].parse().expect("g index");
        let k = proc_macro2::Literal::usize_unsuffixed(k);
        quote!(g[#k])
    })
}

/// The general pose system (`general.rs`): its inputs, the exact form in the trig basis, its
/// tangent half-angle form and its small-angle form.
fn general_system() -> TokenStream {
    let fields = general::PARAMETERS.iter().map(|(s, doc)| {
        let i = ident(s);
        quote!(#[doc = #doc] pub #i: f64,)
    });
    let collected = general::exact_collected();
    let outs: Vec<Poly> = collected.iter().flatten().cloned().collect();
    let n_all = proc_macro2::Literal::usize_unsuffixed(outs.len());
    let exact_body = emit::body(&outs, &param_access);
    let basis = general::BASIS.map(|e| {
        let e = e.map(proc_macro2::Literal::u32_unsuffixed);
        quote!([#(#e),*])
    });
    let n_basis = proc_macro2::Literal::usize_unsuffixed(general::BASIS.len());

    // Tangent half-angle form, linear in the trig coefficients g.
    let trig: Vec<Monomial> = general::BASIS.iter().map(general::monomial).collect();
    let half_body = half_angle_body(&[trig.clone(), trig]);

    let small: Vec<Poly> = general::small_angle_collected()
        .into_iter()
        .flatten()
        .collect();
    let n_small = proc_macro2::Literal::usize_unsuffixed(small.len());
    let small_body = emit::body(&small, &param_access);
    let small_basis = general::SMALL_BASIS.map(|(i, j)| {
        let (i, j) = (
            proc_macro2::Literal::u32_unsuffixed(i),
            proc_macro2::Literal::u32_unsuffixed(j),
        );
        quote!((#i, #j))
    });
    let n_small_basis = proc_macro2::Literal::usize_unsuffixed(general::SMALL_BASIS.len());
    quote! {
        /// Parameters of the general pose system (any contact triangle, any three planes;
        /// built by `GeneralInputs::new`).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct GeneralInputs { #(#fields)* }
        /// (sin α, cos α, sin ψ, cos ψ) exponents of the terms of both general equations.
        pub const GENERAL_BASIS: [[u32; 4]; #n_basis] = [#(#basis),*];
        /// The general equations m₀,y r_k − m_k,y r₀ (k = 1, 2) in the trig basis above, contact 1's
        /// then contact 2's (see `derivations/09-general-pose.md`), in metres.
        #[allow(clippy::too_many_lines, clippy::neg_multiply)]
        pub fn general_exact_trig(p: &GeneralInputs) -> [f64; #n_all] { #exact_body }
        /// The general equations in tangent half-angles ta = tan(α/2), tp = tan(ψ/2), multiplied
        /// by (1 + ta²)(1 + tp²): entry `9·eq + 3·i + j` multiplies ta^i tp^j.
        #[allow(clippy::too_many_lines, clippy::neg_multiply)]
        pub fn general_half_angle(g: &[f64; #n_all]) -> [f64; 18] { #half_body }
        /// (α, ψ) exponents of the terms of both small-angle general equations.
        pub const GENERAL_SMALL_BASIS: [(u32, u32); #n_small_basis] = [#(#small_basis),*];
        /// The general equations with sin α → α, cos α → 1, sin ψ → ψ, cos ψ → 1, in the basis
        /// above, contact 1's then contact 2's.
        #[allow(clippy::too_many_lines, clippy::neg_multiply)]
        pub fn general_small_angle(p: &GeneralInputs) -> [f64; #n_small] { #small_body }
    }
}

/// The Rust source of the generated coefficient module, formatted.
pub fn generate() -> String {
    assert!(
        system::exact_substitution_remainder().is_zero(),
        "the exact (α, ψ) substitution does not satisfy eq. (2)"
    );
    let inputs = inputs_struct();
    let small = small_angle_items();
    let unsquared = unsquared_items();
    let collected = system::exact_collected();
    let exact = exact_trig_items(&collected);
    let half = exact_half_angle_items(&collected);
    let general = general_system();
    let file = quote! {
        // @generated by slideroute-codegen from the paper's eqs. (2), (3), (8)–(14). Do not edit.
        #inputs
        #small
        #unsquared
        #exact
        #half
        #general
    };
    let mut text = String::from(
        "// @generated by slideroute-codegen (codegen/src/system.rs). Do not edit by hand.\n",
    );
    text.push_str(&emit::format(file));
    text
}

/// The `CoeffInputs` struct: one field per parameter of the generated functions.
fn inputs_struct() -> TokenStream {
    let fields = system::PARAMETERS.iter().map(|(s, doc)| {
        let i = ident(s);
        quote!(#[doc = #doc] pub #i: f64,)
    });
    quote! {
        /// Parameters of the generated coefficient functions (built by `CoeffInputs::new`).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct CoeffInputs { #(#fields)* }
    }
}

/// The small-angle system (15): its monomials and f1–f12.
fn small_angle_items() -> TokenStream {
    let f = system::small_angle();
    let small_body = emit::body(&f, &param_access);
    let mons = system::SMALL_ANGLE_MONOMIALS.map(|eq| {
        let pairs = eq.map(|(i, j)| {
            let (i, j) = (
                proc_macro2::Literal::u32_unsuffixed(i),
                proc_macro2::Literal::u32_unsuffixed(j),
            );
            quote!((#i, #j))
        });
        quote!([#(#pairs),*])
    });
    quote! {
        /// (α, β) exponents of the monomials multiplying f1–f6 in (15a) and f7–f12 in (15b).
        pub const SMALL_ANGLE_MONOMIALS: [[(u32, u32); 6]; 2] = [#(#mons),*];
        /// f1–f12 of system (15) (re-derived; see `derivations/03-small-angle.md`), in SI units.
        #[allow(clippy::too_many_lines, clippy::neg_multiply)]
        pub fn small_angle(p: &CoeffInputs) -> [f64; 12] { #small_body }
    }
}

/// The small-angle unsquared pieces A (by monomials in α, β) and B of (13) and (14).
fn unsquared_items() -> TokenStream {
    let unsq = system::small_angle_unsquared();
    let mut unsq_outs: Vec<Poly> = Vec::new();
    let mut unsq_exps = Vec::new();
    for (a, b) in &unsq {
        let exps = a.iter().map(|(m, _)| {
            let (i, j) = (
                proc_macro2::Literal::u32_unsuffixed(m.degree_in("alpha")),
                proc_macro2::Literal::u32_unsuffixed(m.degree_in("beta")),
            );
            quote!((#i, #j))
        });
        unsq_exps.push(quote!(&[#(#exps),*]));
        unsq_outs.extend(a.iter().map(|(_, p)| p.clone()));
        unsq_outs.push(b.clone());
    }
    let n_a13 = proc_macro2::Literal::usize_unsuffixed(unsq[0].0.len());
    let n_unsq = proc_macro2::Literal::usize_unsuffixed(unsq_outs.len());
    let unsq_body = emit::body(&unsq_outs, &param_access);
    let (e13, e14) = (&unsq_exps[0], &unsq_exps[1]);
    quote! {
        /// (α, β) exponents of the terms of A in the unsquared small-angle (13).
        pub const SMALL_ANGLE_UNSQUARED_A13: &[(u32, u32)] = #e13;
        /// (α, β) exponents of the terms of A in the unsquared small-angle (14).
        pub const SMALL_ANGLE_UNSQUARED_A14: &[(u32, u32)] = #e14;
        /// Number of A-terms of (13); the output is A13 terms, B13, A14 terms, B14.
        pub const SMALL_ANGLE_UNSQUARED_SPLIT: usize = #n_a13;
        /// The unsquared small-angle relations E = A + B·Q, Q = √(1 − (1/√2 − αβ)²):
        /// coefficients of A13's terms, B13, A14's terms, B14.
        #[allow(clippy::too_many_lines, clippy::neg_multiply)]
        pub fn small_angle_unsquared(p: &CoeffInputs) -> [f64; #n_unsq] { #unsq_body }
    }
}

/// The exact form (13), (14) in the trig basis: its terms, their names and coefficients.
fn exact_trig_items(collected: &[Vec<(Monomial, Poly)>]) -> TokenStream {
    let n13 = proc_macro2::Literal::usize_unsuffixed(collected[0].len());
    let n14 = proc_macro2::Literal::usize_unsuffixed(collected[1].len());
    let mut outs: Vec<Poly> = Vec::new();
    let mut basis_tokens = Vec::new();
    let mut name_tokens = Vec::new();
    for eq in collected {
        let exps = eq.iter().map(|(m, _)| {
            let e = trig_exponents(m).map(proc_macro2::Literal::u32_unsuffixed);
            quote!([#(#e),*])
        });
        let names = eq.iter().map(|(m, _)| system::basis_name(m));
        basis_tokens.push(quote!([#(#exps),*]));
        name_tokens.push(quote!([#(#names),*]));
        outs.extend(eq.iter().map(|(_, p)| p.clone()));
    }
    let exact_body = emit::body(&outs, &param_access);
    let n_all = proc_macro2::Literal::usize_unsuffixed(collected[0].len() + collected[1].len());
    let (b13, b14) = (&basis_tokens[0], &basis_tokens[1]);
    let (nm13, nm14) = (&name_tokens[0], &name_tokens[1]);
    quote! {
        /// Number of trig-basis terms of exact (13) and (14).
        pub const EXACT_TERMS: [usize; 2] = [#n13, #n14];
        /// (sin α, cos α, sin ψ, cos ψ) exponents of each term of exact (13).
        pub const EXACT_BASIS_13: [[u32; 4]; #n13] = #b13;
        /// (sin α, cos α, sin ψ, cos ψ) exponents of each term of exact (14).
        pub const EXACT_BASIS_14: [[u32; 4]; #n14] = #b14;
        /// Readable names of the basis monomials of (13) (`one`, `sa`, `ca_sp`, …).
        pub const EXACT_NAMES_13: [&str; #n13] = #nm13;
        /// Readable names of the basis monomials of (14).
        pub const EXACT_NAMES_14: [&str; #n14] = #nm14;
        /// Coefficients of exact (13), then (14), in the trig basis above
        /// (see `derivations/04-exact.md`).
        #[allow(clippy::too_many_lines, clippy::neg_multiply)]
        pub fn exact_trig(p: &CoeffInputs) -> [f64; #n_all] { #exact_body }
    }
}

/// The exact form in tangent half-angles: coefficients of ta^i tp^j, linear in the trig ones.
fn exact_half_angle_items(collected: &[Vec<(Monomial, Poly)>]) -> TokenStream {
    let n_all = proc_macro2::Literal::usize_unsuffixed(collected[0].len() + collected[1].len());
    let bases: Vec<Vec<Monomial>> = collected
        .iter()
        .map(|eq| eq.iter().map(|(m, _)| m.clone()).collect())
        .collect();
    let half_body = half_angle_body(&bases);
    quote! {
        /// Exact (13), (14) in tangent half-angles ta = tan(α/2), tp = tan(ψ/2), multiplied by
        /// (1 + ta²)(1 + tp²): entry `9·eq + 3·i + j` multiplies ta^i tp^j.
        #[allow(clippy::too_many_lines, clippy::neg_multiply)]
        pub fn exact_half_angle(g: &[f64; #n_all]) -> [f64; 18] { #half_body }
    }
}
