//! Polynomial interpolation through a few nodes in barycentric form (Berrut & Trefethen's
//! "second form"): the Lagrange basis at a point, stable for nodes spread like Chebyshev's,
//! and the nodal polynomial ω(s) = Π (s − sⱼ), whose size says where the error is largest
//! (the error of interpolating f is f⁽ᴺ⁾(ξ) ω(s) / N!).

/// `N` distinct nodes and their barycentric weights wⱼ = 1 / Π_{k≠j} (sⱼ − sₖ).
#[derive(Debug, Clone, Copy)]
pub struct Nodes<const N: usize> {
    s: [f64; N],
    w: [f64; N],
}

impl<const N: usize> Nodes<N> {
    /// The nodes `s`, distinct (`None` if two coincide or one is not finite).
    pub fn new(s: [f64; N]) -> Option<Self> {
        let mut w = [1.0; N];
        for j in 0..N {
            for k in 0..N {
                if k != j {
                    w[j] *= s[j] - s[k];
                }
            }
            if !(w[j].is_finite() && w[j] != 0.0) {
                return None;
            }
            w[j] = 1.0 / w[j];
        }
        Some(Nodes { s, w })
    }

    /// The Lagrange basis at `x`: ℓⱼ(x), so that the interpolant of values fⱼ is Σ ℓⱼ fⱼ. At a
    /// node, the unit vector of that node.
    #[inline]
    pub fn basis(&self, x: f64) -> [f64; N] {
        let mut l = [0.0; N];
        if let Some(j) = self.s.iter().position(|&s| s == x) {
            l[j] = 1.0;
            return l;
        }
        for ((l, w), s) in l.iter_mut().zip(&self.w).zip(&self.s) {
            *l = w / (x - s);
        }
        let sum: f64 = l.iter().sum();
        l.map(|v| v / sum)
    }

    /// The nodal polynomial ω(x) = Π (x − sⱼ).
    pub fn nodal(&self, x: f64) -> f64 {
        self.s.iter().map(|s| x - s).product()
    }
}

/// The interpolant of the values `f` (one per node) at the basis `l` (`Nodes::basis`).
#[inline]
pub fn combine<const N: usize>(l: &[f64; N], f: &[f64; N]) -> f64 {
    l.iter().zip(f).map(|(a, b)| a * b).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Interpolation through N nodes is exact for every polynomial of degree below N.
    #[test]
    fn a_polynomial_of_degree_below_the_nodes_is_reproduced_to_round_off() {
        let nodes = Nodes::new([0.0, 0.09, 0.35, 0.64, 0.91, 1.0]).unwrap();
        let p = |x: f64| 3.0 - 2.0 * x + 0.5 * x.powi(3) - 7.0 * x.powi(5);
        let f = [0.0, 0.09, 0.35, 0.64, 0.91, 1.0].map(p);
        for k in 0..=50 {
            let x = f64::from(k) / 50.0;
            let got = combine(&nodes.basis(x), &f);
            assert!((got - p(x)).abs() < 1e-14, "{x}: {got} against {}", p(x));
        }
    }

    /// The error of interpolating eˣ through N nodes is e^ξ ω(x) / N! for some ξ in the
    /// interval: between the bounds that the least and the largest e^ξ give.
    #[test]
    fn the_error_of_interpolating_the_exponential_is_its_derivative_times_the_nodal_polynomial() {
        let s = [0.0, 0.1, 0.3, 0.7, 0.9, 1.0];
        let nodes = Nodes::new(s).unwrap();
        let f = s.map(f64::exp);
        let factorial = 720.0;
        for x in [0.05, 0.2, 0.5, 0.8, 0.95] {
            let err = combine(&nodes.basis(x), &f) - x.exp();
            let w = nodes.nodal(x) / factorial;
            let (lo, hi) = (w.abs(), w.abs() * 1f64.exp());
            assert!(
                err.abs() >= lo * 0.999 && err.abs() <= hi * 1.001,
                "{x}: {err}"
            );
            assert_eq!(err.signum(), -w.signum(), "{x}: the error's sign");
        }
    }

    #[test]
    fn coinciding_nodes_are_refused() {
        assert!(Nodes::new([0.0, 0.5, 0.5]).is_none());
        assert!(Nodes::new([0.0, f64::NAN, 1.0]).is_none());
        let n = Nodes::new([0.0, 0.5, 1.0]).unwrap();
        assert_eq!(n.basis(0.5), [0.0, 1.0, 0.0]);
    }
}
