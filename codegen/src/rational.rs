//! Exact rational numbers over `i128`, enough for the small integer coefficients that the
//! paper's relations produce. Overflow is a bug in the generator and stops the build with a
//! message rather than producing a wrong coefficient.

use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A reduced fraction `num / den` with `den > 0`.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct Rational {
    num: i128,
    den: i128,
}

fn gcd(mut a: i128, mut b: i128) -> i128 {
    a = a.abs();
    b = b.abs();
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

const OVERFLOW: &str = "rational coefficient overflowed i128 in slideroute-codegen";

impl Rational {
    pub const ZERO: Rational = Rational { num: 0, den: 1 };
    pub const ONE: Rational = Rational { num: 1, den: 1 };

    /// `num / den`, reduced. Panics if `den == 0` (a generator bug, never user input).
    pub fn new(num: i128, den: i128) -> Self {
        assert!(den != 0, "zero denominator in slideroute-codegen");
        let g = gcd(num, den).max(1);
        let sign = if den < 0 { -1 } else { 1 };
        Rational {
            num: sign * num / g,
            den: sign * den / g,
        }
    }

    pub fn int(n: i128) -> Self {
        Rational { num: n, den: 1 }
    }

    pub fn numer(self) -> i128 {
        self.num
    }

    pub fn denom(self) -> i128 {
        self.den
    }

    pub fn is_zero(self) -> bool {
        self.num == 0
    }

    pub fn is_one(self) -> bool {
        self.num == 1 && self.den == 1
    }

    pub fn to_f64(self) -> f64 {
        self.num as f64 / self.den as f64
    }

    pub fn abs(self) -> Self {
        Rational {
            num: self.num.abs(),
            den: self.den,
        }
    }
}

impl Add for Rational {
    type Output = Rational;
    fn add(self, o: Rational) -> Rational {
        let g = gcd(self.den, o.den);
        let l = (self.den / g).checked_mul(o.den).expect(OVERFLOW);
        let a = self.num.checked_mul(l / self.den).expect(OVERFLOW);
        let b = o.num.checked_mul(l / o.den).expect(OVERFLOW);
        Rational::new(a.checked_add(b).expect(OVERFLOW), l)
    }
}

impl Neg for Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        Rational {
            num: -self.num,
            den: self.den,
        }
    }
}

impl Sub for Rational {
    type Output = Rational;
    fn sub(self, o: Rational) -> Rational {
        self + (-o)
    }
}

impl Mul for Rational {
    type Output = Rational;
    fn mul(self, o: Rational) -> Rational {
        let g1 = gcd(self.num, o.den).max(1);
        let g2 = gcd(o.num, self.den).max(1);
        let n = (self.num / g1).checked_mul(o.num / g2).expect(OVERFLOW);
        let d = (self.den / g2).checked_mul(o.den / g1).expect(OVERFLOW);
        Rational::new(n, d)
    }
}

impl Div for Rational {
    type Output = Rational;
    fn div(self, o: Rational) -> Rational {
        assert!(!o.is_zero(), "division by zero in slideroute-codegen");
        self * Rational::new(o.den, o.num)
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Rational {
    fn cmp(&self, o: &Self) -> Ordering {
        (self.num * o.den).cmp(&(o.num * self.den))
    }
}

impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.den == 1 {
            write!(f, "{}", self.num)
        } else {
            write!(f, "{}/{}", self.num, self.den)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fractions_are_reduced_with_positive_denominator() {
        let r = Rational::new(6, -4);
        assert_eq!((r.numer(), r.denom()), (-3, 2));
    }

    #[test]
    fn field_operations_are_exact() {
        let a = Rational::new(1, 3);
        let b = Rational::new(1, 6);
        assert_eq!(a + b, Rational::new(1, 2));
        assert_eq!(a - b, Rational::new(1, 6));
        assert_eq!(a * b, Rational::new(1, 18));
        assert_eq!(a / b, Rational::int(2));
        assert_eq!((a - a), Rational::ZERO);
        assert!(Rational::new(-1, 2) < Rational::new(1, 3));
    }
}
