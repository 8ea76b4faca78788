//! Sparse multivariate polynomials with exact rational coefficients over named symbols.
//!
//! This is the whole symbolic engine the generator needs: sums and products, integer powers,
//! substitution of a symbol by a polynomial, power-reduction rules (√2² = 2, s² = 1 − c²),
//! exact division by a symbol, and collection by monomials in a chosen set of unknowns.

use crate::rational::Rational;
use std::collections::BTreeMap;
use std::fmt;
use std::ops::{Add, Mul, Neg, Sub};

/// A symbol is a static name: the generator's vocabulary is fixed at compile time.
pub type Sym = &'static str;

/// A product of symbol powers, sorted by symbol name, every exponent positive.
#[derive(Clone, PartialEq, Eq, PartialOrd, Ord, Hash, Debug, Default)]
pub struct Monomial(Vec<(Sym, u32)>);

impl Monomial {
    /// The empty product, 1.
    pub fn one() -> Self {
        Monomial(Vec::new())
    }

    /// `s^e` (the empty product when `e == 0`).
    pub fn power(s: Sym, e: u32) -> Self {
        if e == 0 {
            Monomial::one()
        } else {
            Monomial(vec![(s, e)])
        }
    }

    /// Builds a monomial from `(symbol, exponent)` pairs in any order; zero exponents vanish.
    pub fn from_pairs(pairs: &[(Sym, u32)]) -> Self {
        pairs
            .iter()
            .fold(Monomial::one(), |m, &(s, e)| m.mul(&Monomial::power(s, e)))
    }

    pub fn factors(&self) -> &[(Sym, u32)] {
        &self.0
    }

    pub fn is_one(&self) -> bool {
        self.0.is_empty()
    }

    pub fn degree_in(&self, s: Sym) -> u32 {
        self.0.iter().find(|(t, _)| *t == s).map_or(0, |&(_, e)| e)
    }

    pub fn total_degree(&self) -> u32 {
        self.0.iter().map(|&(_, e)| e).sum()
    }

    pub fn mul(&self, other: &Monomial) -> Monomial {
        let mut out: Vec<(Sym, u32)> = Vec::with_capacity(self.0.len() + other.0.len());
        let (mut i, mut j) = (0, 0);
        while i < self.0.len() || j < other.0.len() {
            match (self.0.get(i), other.0.get(j)) {
                (Some(&(a, ea)), Some(&(b, eb))) if a == b => {
                    out.push((a, ea + eb));
                    i += 1;
                    j += 1;
                }
                (Some(&(a, ea)), Some(&(b, _))) if a < b => {
                    out.push((a, ea));
                    i += 1;
                }
                (Some(_), Some(&(b, eb))) => {
                    out.push((b, eb));
                    j += 1;
                }
                (Some(&f), None) => {
                    out.push(f);
                    i += 1;
                }
                (None, Some(&f)) => {
                    out.push(f);
                    j += 1;
                }
                (None, None) => unreachable!(),
            }
        }
        Monomial(out)
    }

    /// Splits off the power of `s`: `self = rest · s^e`.
    pub fn take(&self, s: Sym) -> (Monomial, u32) {
        let e = self.degree_in(s);
        let rest = Monomial(self.0.iter().copied().filter(|&(t, _)| t != s).collect());
        (rest, e)
    }

    /// Splits into the part in `unknowns` and the rest.
    pub fn split(&self, unknowns: &[Sym]) -> (Monomial, Monomial) {
        let (u, r): (Vec<_>, Vec<_>) = self.0.iter().partition(|(s, _)| unknowns.contains(s));
        (Monomial(u), Monomial(r))
    }
}

impl fmt::Display for Monomial {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.is_empty() {
            return write!(f, "1");
        }
        let parts: Vec<String> = self
            .0
            .iter()
            .map(|&(s, e)| {
                if e == 1 {
                    s.to_string()
                } else {
                    format!("{s}^{e}")
                }
            })
            .collect();
        write!(f, "{}", parts.join("*"))
    }
}

/// A polynomial: a map from monomials to non-zero rational coefficients.
#[derive(Clone, PartialEq, Eq, Debug, Default)]
pub struct Poly(BTreeMap<Monomial, Rational>);

impl Poly {
    pub fn zero() -> Self {
        Poly(BTreeMap::new())
    }

    pub fn constant(r: Rational) -> Self {
        Poly::term(r, Monomial::one())
    }

    pub fn int(n: i128) -> Self {
        Poly::constant(Rational::int(n))
    }

    pub fn var(s: Sym) -> Self {
        Poly::term(Rational::ONE, Monomial::power(s, 1))
    }

    pub fn term(c: Rational, m: Monomial) -> Self {
        let mut p = Poly::zero();
        p.add_term(c, m);
        p
    }

    pub fn is_zero(&self) -> bool {
        self.0.is_empty()
    }

    pub fn terms(&self) -> impl Iterator<Item = (&Monomial, Rational)> {
        self.0.iter().map(|(m, &c)| (m, c))
    }

    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    fn add_term(&mut self, c: Rational, m: Monomial) {
        if c.is_zero() {
            return;
        }
        let sum = self.0.get(&m).copied().unwrap_or(Rational::ZERO) + c;
        if sum.is_zero() {
            self.0.remove(&m);
        } else {
            self.0.insert(m, sum);
        }
    }

    pub fn scale(&self, c: Rational) -> Poly {
        let mut out = Poly::zero();
        for (m, k) in self.terms() {
            out.add_term(k * c, m.clone());
        }
        out
    }

    pub fn pow(&self, e: u32) -> Poly {
        (0..e).fold(Poly::int(1), |acc, _| &acc * self)
    }

    pub fn square(&self) -> Poly {
        self * self
    }

    /// The highest power of `s` that occurs.
    pub fn degree_in(&self, s: Sym) -> u32 {
        self.0.keys().map(|m| m.degree_in(s)).max().unwrap_or(0)
    }

    /// The symbols that occur, sorted.
    pub fn symbols(&self) -> Vec<Sym> {
        let mut v: Vec<Sym> = self
            .0
            .keys()
            .flat_map(|m| m.factors().iter().map(|&(s, _)| s))
            .collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// Replaces every occurrence of `s` by `by`.
    pub fn subs(&self, s: Sym, by: &Poly) -> Poly {
        let mut powers: Vec<Poly> = vec![Poly::int(1)];
        let mut out = Poly::zero();
        for (m, c) in self.terms() {
            let (rest, e) = m.take(s);
            while powers.len() <= e as usize {
                let next = powers.last().map(|p| p * by).unwrap_or_default();
                powers.push(next);
            }
            out = &out + &(&Poly::term(c, rest) * &powers[e as usize]);
        }
        out
    }

    /// Applies `s^k → by` until no monomial holds `s` to a power `k` or more.
    pub fn reduce_power(&self, s: Sym, k: u32, by: &Poly) -> Poly {
        assert!(
            k > 0 && by.degree_in(s) < k,
            "power rule must lower the degree"
        );
        let mut cur = self.clone();
        while cur.degree_in(s) >= k {
            let mut next = Poly::zero();
            for (m, c) in cur.terms() {
                let (rest, e) = m.take(s);
                if e >= k {
                    let kept = Poly::term(c, rest.mul(&Monomial::power(s, e - k)));
                    next = &next + &(&kept * by);
                } else {
                    next.add_term(c, m.clone());
                }
            }
            cur = next;
        }
        cur
    }

    /// Exact division by `s`; `None` if some term does not contain `s`.
    pub fn div_sym(&self, s: Sym) -> Option<Poly> {
        let mut out = Poly::zero();
        for (m, c) in self.terms() {
            let (rest, e) = m.take(s);
            if e == 0 {
                return None;
            }
            out.add_term(c, rest.mul(&Monomial::power(s, e - 1)));
        }
        Some(out)
    }

    /// Collects by monomials in `unknowns`: `self = Σ key · value`, each value free of them.
    pub fn collect(&self, unknowns: &[Sym]) -> BTreeMap<Monomial, Poly> {
        let mut out: BTreeMap<Monomial, Poly> = BTreeMap::new();
        for (m, c) in self.terms() {
            let (u, rest) = m.split(unknowns);
            out.entry(u).or_default().add_term(c, rest);
        }
        out.retain(|_, p| !p.is_zero());
        out
    }

    /// Writes `self = a + b·s` for a polynomial of degree ≤ 1 in `s` (isolating `s`).
    pub fn isolate(&self, s: Sym) -> Option<(Poly, Poly)> {
        if self.degree_in(s) > 1 {
            return None;
        }
        let mut a = Poly::zero();
        let mut b = Poly::zero();
        for (m, c) in self.terms() {
            let (rest, e) = m.take(s);
            if e == 0 {
                a.add_term(c, rest);
            } else {
                b.add_term(c, rest);
            }
        }
        Some((a, b))
    }

    /// Numerical value for given symbol values (used by tests and self-checks).
    pub fn eval(&self, value: &dyn Fn(Sym) -> f64) -> f64 {
        self.terms()
            .map(|(m, c)| {
                m.factors()
                    .iter()
                    .fold(c.to_f64(), |acc, &(s, e)| acc * value(s).powi(e as i32))
            })
            .sum()
    }
}

impl Add for &Poly {
    type Output = Poly;
    fn add(self, o: &Poly) -> Poly {
        let mut out = self.clone();
        for (m, c) in o.terms() {
            out.add_term(c, m.clone());
        }
        out
    }
}

impl Sub for &Poly {
    type Output = Poly;
    fn sub(self, o: &Poly) -> Poly {
        self + &(-o)
    }
}

impl Neg for &Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        self.scale(-Rational::ONE)
    }
}

impl Mul for &Poly {
    type Output = Poly;
    fn mul(self, o: &Poly) -> Poly {
        let mut out = Poly::zero();
        for (ma, ca) in self.terms() {
            for (mb, cb) in o.terms() {
                out.add_term(ca * cb, ma.mul(mb));
            }
        }
        out
    }
}

macro_rules! owned_ops {
    ($($tr:ident $f:ident),*) => {$(
        impl $tr for Poly { type Output = Poly; fn $f(self, o: Poly) -> Poly { (&self).$f(&o) } }
        impl $tr<&Poly> for Poly { type Output = Poly; fn $f(self, o: &Poly) -> Poly { (&self).$f(o) } }
        impl $tr<Poly> for &Poly { type Output = Poly; fn $f(self, o: Poly) -> Poly { self.$f(&o) } }
    )*};
}
owned_ops!(Add add, Sub sub, Mul mul);

impl Neg for Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        -&self
    }
}

impl fmt::Display for Poly {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_zero() {
            return write!(f, "0");
        }
        let parts: Vec<String> = self
            .terms()
            .map(|(m, c)| {
                if m.is_one() {
                    format!("{c}")
                } else if c.is_one() {
                    format!("{m}")
                } else {
                    format!("{c}*{m}")
                }
            })
            .collect();
        write!(f, "{}", parts.join(" + "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn x() -> Poly {
        Poly::var("x")
    }
    fn y() -> Poly {
        Poly::var("y")
    }

    #[test]
    fn binomial_square_expands() {
        let p = (x() + y()).square();
        let expected = x() * x() + (x() * y()).scale(Rational::int(2)) + y() * y();
        assert_eq!(p, expected);
        assert_eq!(p.len(), 3);
    }

    #[test]
    fn difference_of_squares_cancels_exactly() {
        let p = (x() + y()) * (x() - y()) - (x().square() - y().square());
        assert!(p.is_zero());
    }

    #[test]
    fn substitution_composes() {
        // (x + 1)^3 with x := y - 1 is y^3.
        let p = (x() + Poly::int(1)).pow(3);
        assert_eq!(p.subs("x", &(y() - Poly::int(1))), y().pow(3));
    }

    #[test]
    fn power_rule_reduces_sqrt2_and_unit_circle() {
        let r = Poly::var("r2");
        let p = r.pow(5).reduce_power("r2", 2, &Poly::int(2));
        assert_eq!(p, r.scale(Rational::int(4)));
        // s^2 + c^2 reduces to 1 under s^2 -> 1 - c^2.
        let c = Poly::var("c");
        let s = Poly::var("s");
        let one = (s.square() + c.square()).reduce_power("s", 2, &(Poly::int(1) - c.square()));
        assert_eq!(one, Poly::int(1));
    }

    #[test]
    fn collection_groups_by_unknown_monomials() {
        // (a x + b)^2 in x: b^2 + 2ab x + a^2 x^2.
        let p = (Poly::var("a") * x() + Poly::var("b")).square();
        let c = p.collect(&["x"]);
        assert_eq!(c.len(), 3);
        assert_eq!(c[&Monomial::one()], Poly::var("b").square());
        assert_eq!(
            c[&Monomial::power("x", 1)],
            (Poly::var("a") * Poly::var("b")).scale(Rational::int(2))
        );
        assert_eq!(c[&Monomial::power("x", 2)], Poly::var("a").square());
    }

    #[test]
    fn isolate_then_square_removes_the_root_symbol() {
        // a + b q = 0 with q^2 = w  ⇒  a^2 - b^2 w = 0.
        let e = Poly::var("a") + Poly::var("b") * Poly::var("q");
        let (a, b) = e.isolate("q").expect("linear in q");
        let sq = a.square() - b.square() * Poly::var("w");
        assert_eq!(sq.degree_in("q"), 0);
        assert_eq!(sq.len(), 2);
    }

    #[test]
    fn exact_division_by_symbol() {
        let p = x() * y() + x().square();
        assert_eq!(p.div_sym("x"), Some(y() + x()));
        assert_eq!((p + Poly::int(1)).div_sym("x"), None);
    }

    #[test]
    fn eval_matches_hand_value() {
        let p = (x() + y().scale(Rational::new(1, 2))).square();
        let v = p.eval(&|s| if s == "x" { 3.0 } else { 4.0 });
        assert_eq!(v, 25.0);
    }
}
