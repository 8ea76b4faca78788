//! Turns polynomials in the parameters into Rust code.
//!
//! Each emitted function reads every input it uses once, computes every shared monomial of
//! degree ≥ 2 once (as a product of a shorter monomial and one symbol, so monomials share their
//! prefixes), folds √2 into the numeric constants, and returns the outputs as a flat array.

use crate::poly::{Monomial, Poly, Sym};
use crate::system::R2;
use proc_macro2::{Ident, Literal, Span, TokenStream};
use quote::quote;
use std::collections::{BTreeMap, BTreeSet};

fn ident(s: &str) -> Ident {
    Ident::new(s, Span::call_site())
}

/// A monomial's binding name, e.g. `m_l2x2_omc`.
fn mono_name(m: &Monomial) -> String {
    let mut s = String::from("m");
    for &(sym, e) in m.factors() {
        s.push('_');
        s.push_str(sym);
        if e > 1 {
            s.push_str(&e.to_string());
        }
    }
    s
}

/// Drops one power of the last factor: the prefix this monomial is built from.
fn parent(m: &Monomial) -> (Monomial, Sym) {
    let f = m.factors();
    let (last, e) = f[f.len() - 1];
    let mut pairs: Vec<(Sym, u32)> = f[..f.len() - 1].to_vec();
    if e > 1 {
        pairs.push((last, e - 1));
    }
    (Monomial::from_pairs(&pairs), last)
}

/// Folds √2 into the coefficient: returns (f64 coefficient, monomial free of √2) terms.
fn fold_sqrt2(p: &Poly) -> BTreeMap<Monomial, f64> {
    let mut out: BTreeMap<Monomial, f64> = BTreeMap::new();
    for (m, c) in p.terms() {
        let (rest, e) = m.take(R2);
        assert!(e <= 1, "√2 must be reduced before emission");
        let k = if e == 1 {
            c.to_f64() * std::f64::consts::SQRT_2
        } else {
            c.to_f64()
        };
        *out.entry(rest).or_insert(0.0) += k;
    }
    out.retain(|_, k| *k != 0.0);
    out
}

fn literal(x: f64) -> TokenStream {
    let lit = Literal::f64_unsuffixed(x);
    quote!(#lit)
}

/// The body of a function returning `[f64; outputs.len()]`: `let` bindings, then the array.
/// `access(sym)` is the expression that reads input `sym` (e.g. `p.x`).
pub fn body(outputs: &[Poly], access: &dyn Fn(Sym) -> TokenStream) -> TokenStream {
    let folded: Vec<BTreeMap<Monomial, f64>> = outputs.iter().map(fold_sqrt2).collect();

    // Every monomial needed, with all its prefixes.
    let mut needed: BTreeSet<Monomial> = BTreeSet::new();
    for f in &folded {
        for m in f.keys() {
            let mut cur = m.clone();
            while cur.total_degree() >= 2 && needed.insert(cur.clone()) {
                cur = parent(&cur).0;
            }
        }
    }
    let mut symbols: BTreeSet<Sym> = BTreeSet::new();
    for f in &folded {
        for m in f.keys() {
            symbols.extend(m.factors().iter().map(|&(s, _)| s));
        }
    }

    let mut lets = TokenStream::new();
    for s in &symbols {
        let name = ident(s);
        let acc = access(s);
        lets.extend(quote!(let #name: f64 = #acc;));
    }
    let mut ordered: Vec<&Monomial> = needed.iter().collect();
    ordered.sort_by_key(|m| (m.total_degree(), (*m).clone()));
    let name_of = |m: &Monomial| -> TokenStream {
        if m.total_degree() == 1 {
            let s = ident(m.factors()[0].0);
            quote!(#s)
        } else {
            let s = ident(&mono_name(m));
            quote!(#s)
        }
    };
    for m in ordered {
        let (par, sym) = parent(m);
        let lhs = ident(&mono_name(m));
        let a = name_of(&par);
        let b = ident(sym);
        lets.extend(quote!(let #lhs = #a * #b;));
    }

    let exprs: Vec<TokenStream> = folded
        .iter()
        .map(|f| {
            let mut expr = TokenStream::new();
            for (i, (m, &k)) in f.iter().enumerate() {
                let mag = k.abs();
                let term = if m.is_one() {
                    literal(mag)
                } else if mag == 1.0 {
                    name_of(m)
                } else {
                    let c = literal(mag);
                    let mm = name_of(m);
                    quote!(#c * #mm)
                };
                expr.extend(match (i, k < 0.0) {
                    (0, false) => term,
                    (0, true) => quote!(-#term),
                    (_, false) => quote!(+ #term),
                    (_, true) => quote!(- #term),
                });
            }
            if expr.is_empty() { literal(0.0) } else { expr }
        })
        .collect();
    quote! {
        #lets
        [#(#exprs),*]
    }
}

/// Formats a token stream as a Rust file with prettyplease.
pub fn format(tokens: TokenStream) -> String {
    let file: syn::File = syn::parse2(tokens).expect("generated code must parse as a Rust file");
    prettyplease::unparse(&file)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rational::Rational;

    #[test]
    fn shared_monomials_are_bound_once() {
        let x = Poly::var("x");
        let y = Poly::var("y");
        let outs = [x.square() * &y, x.square() + y.clone()];
        let code = body(&outs, &|s| {
            let i = ident(s);
            quote!(p.#i)
        })
        .to_string();
        assert_eq!(code.matches("let m_x2 =").count(), 1);
        assert_eq!(code.matches("let m_x2_y =").count(), 1);
        assert_eq!(code.matches("let x : f64 = p . x").count(), 1);
    }

    #[test]
    fn sqrt2_is_folded_into_constants() {
        let p = Poly::var(R2) * Poly::var("x") + Poly::var("x");
        let f = fold_sqrt2(&p);
        let k = f[&Monomial::power("x", 1)];
        assert_eq!(k, 1.0 + std::f64::consts::SQRT_2);
        let p = Poly::var(R2).scale(Rational::new(1, 2));
        assert_eq!(
            fold_sqrt2(&p)[&Monomial::one()],
            std::f64::consts::SQRT_2 / 2.0
        );
    }
}
