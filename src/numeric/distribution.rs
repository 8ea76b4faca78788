//! Distributions of an uncertain scene value: written `name:p1:p2…` on the command
//! line and in a scene's `[uncertain]` table, sampled by their quantile function so that any
//! design of uniforms — plain Monte Carlo or a Latin hypercube (`uncertainty/sampling.rs`) — maps
//! onto them.

use statrs::distribution::{ContinuousCDF, LogNormal, Normal, Triangular, Uniform};

/// A distribution of one value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Distribution {
    /// `normal:mean:sd`.
    Normal {
        /// The mean.
        mean: f64,
        /// The standard deviation.
        sd: f64,
    },
    /// `truncnormal:mean:sd:lo:hi`: the normal of that mean and standard deviation, kept
    /// within [lo, hi].
    TruncNormal {
        /// The untruncated normal's mean.
        mean: f64,
        /// Its standard deviation.
        sd: f64,
        /// The lowest value kept.
        lo: f64,
        /// The highest value kept.
        hi: f64,
    },
    /// `lognormal:mean:sd`: positive, with that mean and standard deviation of the value itself
    /// (its logarithm normal with σ² = ln(1 + sd²/mean²), μ = ln(mean) − σ²/2).
    LogNormal {
        /// The value's mean.
        mean: f64,
        /// The value's standard deviation.
        sd: f64,
    },
    /// `uniform:lo:hi`.
    Uniform {
        /// The lowest value.
        lo: f64,
        /// The highest value.
        hi: f64,
    },
    /// `triangular:lo:mode:hi`.
    Triangular {
        /// The lowest value.
        lo: f64,
        /// The most likely value.
        mode: f64,
        /// The highest value.
        hi: f64,
    },
}

/// The names a distribution is written with, and their parameters.
pub const FORMS: [&str; 5] = [
    "normal:mean:sd",
    "truncnormal:mean:sd:lo:hi",
    "lognormal:mean:sd",
    "uniform:lo:hi",
    "triangular:lo:mode:hi",
];

impl std::fmt::Display for Distribution {
    /// As it is written: `normal:0.4:0.05`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Distribution::Normal { mean, sd } => write!(f, "normal:{mean}:{sd}"),
            Distribution::TruncNormal { mean, sd, lo, hi } => {
                write!(f, "truncnormal:{mean}:{sd}:{lo}:{hi}")
            }
            Distribution::LogNormal { mean, sd } => write!(f, "lognormal:{mean}:{sd}"),
            Distribution::Uniform { lo, hi } => write!(f, "uniform:{lo}:{hi}"),
            Distribution::Triangular { lo, mode, hi } => write!(f, "triangular:{lo}:{mode}:{hi}"),
        }
    }
}

impl std::str::FromStr for Distribution {
    type Err = String;

    fn from_str(text: &str) -> Result<Distribution, String> {
        Distribution::parse(text)
    }
}

impl Distribution {
    /// In words, for a legend: `normal, mean 0.4, sd 0.05`.
    pub fn words(&self) -> String {
        match *self {
            Distribution::Normal { mean, sd } => format!("normal, mean {mean}, sd {sd}"),
            Distribution::TruncNormal { mean, sd, lo, hi } => {
                format!("normal, mean {mean}, sd {sd}, truncated to [{lo}, {hi}]")
            }
            Distribution::LogNormal { mean, sd } => format!("lognormal, mean {mean}, sd {sd}"),
            Distribution::Uniform { lo, hi } => format!("uniform on [{lo}, {hi}]"),
            Distribution::Triangular { lo, mode, hi } => {
                format!("triangular on [{lo}, {hi}], mode {mode}")
            }
        }
    }

    /// Parses `name:p1:p2…`; the error says what is wrong and the forms that are right.
    pub fn parse(text: &str) -> Result<Distribution, String> {
        let mut parts = text.split(':');
        let name = parts.next().unwrap_or("").trim();
        let params: Vec<&str> = parts.collect();
        let values = params
            .iter()
            .map(|p| {
                p.trim()
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| format!("`{p}` in `{text}` is not a finite number"))
            })
            .collect::<Result<Vec<f64>, String>>()?;
        let arity = |n: usize, form: &str| {
            if values.len() == n {
                Ok(())
            } else {
                Err(format!(
                    "`{text}`: {name} takes {n} numbers ({form}), got {}",
                    values.len()
                ))
            }
        };
        let d = match name {
            "normal" => {
                arity(2, FORMS[0])?;
                Distribution::Normal {
                    mean: values[0],
                    sd: values[1],
                }
            }
            "truncnormal" => {
                arity(4, FORMS[1])?;
                Distribution::TruncNormal {
                    mean: values[0],
                    sd: values[1],
                    lo: values[2],
                    hi: values[3],
                }
            }
            "lognormal" => {
                arity(2, FORMS[2])?;
                Distribution::LogNormal {
                    mean: values[0],
                    sd: values[1],
                }
            }
            "uniform" => {
                arity(2, FORMS[3])?;
                Distribution::Uniform {
                    lo: values[0],
                    hi: values[1],
                }
            }
            "triangular" => {
                arity(3, FORMS[4])?;
                Distribution::Triangular {
                    lo: values[0],
                    mode: values[1],
                    hi: values[2],
                }
            }
            other => {
                return Err(format!(
                    "`{text}`: unknown distribution `{other}` (the distributions: {})",
                    FORMS.join(", ")
                ));
            }
        };
        d.check()
            .and_then(|()| d.check_draws())
            .map_err(|why| format!("`{text}`: {why}"))?;
        Ok(d)
    }

    /// Whether every draw is a finite number: the quantiles at the two ends of the (0, 1) that
    /// [`Distribution::quantile`] takes, and at its middle, are finite (the quantile is
    /// monotone, so every other lies between them). A uniform on [−10³⁰⁸, 10³⁰⁸] has a width past
    /// the largest double; a lognormal whose sd/mean squared overflows has σ = ∞.
    fn check_draws(&self) -> Result<(), String> {
        for u in [0.0, 0.5, 1.0] {
            let x = self.quantile(u);
            if !x.is_finite() {
                return Err(format!(
                    "its draws are not all finite numbers (the quantile at {u} is {x}): \
                     parameters too far apart for double precision"
                ));
            }
        }
        Ok(())
    }

    /// Whether the parameters make a distribution.
    fn check(&self) -> Result<(), String> {
        let positive = |what: &str, v: f64| {
            if v > 0.0 {
                Ok(())
            } else {
                Err(format!("{what} must be positive, got {v}"))
            }
        };
        let ordered = |lo: f64, hi: f64| {
            if lo < hi {
                Ok(())
            } else {
                Err(format!("lo must be below hi, got {lo} and {hi}"))
            }
        };
        match *self {
            Distribution::Normal { sd, .. } => positive("sd", sd),
            Distribution::TruncNormal { mean, sd, lo, hi } => {
                positive("sd", sd)?;
                ordered(lo, hi)?;
                // The kept mass must not vanish in round-off.
                let n = Normal::new(mean, sd).map_err(|e| e.to_string())?;
                if n.cdf(hi) - n.cdf(lo) < 1e-12 {
                    let g = super::given;
                    return Err(format!(
                        "[{}, {}] lies too far in the tail of normal({}, {})",
                        g(lo),
                        g(hi),
                        g(mean),
                        g(sd)
                    ));
                }
                Ok(())
            }
            Distribution::LogNormal { mean, sd } => {
                positive("mean", mean)?;
                positive("sd", sd)
            }
            Distribution::Uniform { lo, hi } => ordered(lo, hi),
            Distribution::Triangular { lo, mode, hi } => {
                ordered(lo, hi)?;
                if (lo..=hi).contains(&mode) {
                    Ok(())
                } else {
                    Err(format!("the mode {mode} must lie in [{lo}, {hi}]"))
                }
            }
        }
    }

    /// The value at cumulative probability `u` ∈ (0, 1).
    pub fn quantile(&self, u: f64) -> f64 {
        let u = u.clamp(f64::MIN_POSITIVE, 1.0 - f64::EPSILON);
        // The parameters were checked when parsed: the constructors cannot fail.
        match *self {
            Distribution::Normal { mean, sd } => normal(mean, sd).inverse_cdf(u),
            Distribution::TruncNormal { mean, sd, lo, hi } => {
                let n = normal(mean, sd);
                let (a, b) = (n.cdf(lo), n.cdf(hi));
                n.inverse_cdf(a + u * (b - a)).clamp(lo, hi)
            }
            Distribution::LogNormal { mean, sd } => {
                // ln(1 + r²) without forming r² where it would overflow.
                let r = sd / mean;
                let s2 = if r > 1e150 {
                    2.0 * r.ln()
                } else {
                    r.mul_add(r, 1.0).ln()
                };
                // Not finite where σ is not (a parameter out of range): refused when parsed.
                LogNormal::new(mean.ln() - 0.5 * s2, s2.sqrt())
                    .map_or(f64::NAN, |d| d.inverse_cdf(u))
            }
            Distribution::Uniform { lo, hi } => {
                Uniform::new(lo, hi).map_or(f64::NAN, |d| d.inverse_cdf(u))
            }
            Distribution::Triangular { lo, mode, hi } => {
                Triangular::new(lo, hi, mode).map_or(f64::NAN, |d| d.inverse_cdf(u))
            }
        }
    }
}

fn normal(mean: f64, sd: f64) -> Normal {
    Normal::new(mean, sd).unwrap_or_else(|_| Normal::standard())
}

/// One uncertain scene value: its key (`friction.mu_k`) and its distribution, written
/// `key=name:p1:p2…`.
#[derive(Debug, Clone, PartialEq)]
pub struct Uncertain {
    /// The scene key (`section.key`).
    pub key: String,
    /// Its distribution.
    pub distribution: Distribution,
}

impl std::str::FromStr for Uncertain {
    type Err = String;

    fn from_str(text: &str) -> Result<Uncertain, String> {
        let (key, spec) = text.split_once('=').ok_or_else(|| {
            format!("`{text}`: write key=distribution, e.g. friction.mu_k=normal:0.40:0.05")
        })?;
        let key = key.trim();
        if key.is_empty() {
            return Err(format!("`{text}`: no key before `=`"));
        }
        Ok(Uncertain {
            key: key.to_string(),
            distribution: Distribution::parse(spec).map_err(|e| format!("{key}: {e}"))?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_distribution_is_written_as_it_is_read() {
        for text in [
            "normal:0.4:0.05",
            "truncnormal:0:0.5:-1:1",
            "lognormal:2:0.3",
            "uniform:18:22",
            "triangular:1:2:4",
        ] {
            let d = Distribution::parse(text).unwrap();
            assert_eq!(d.to_string(), text);
            assert_eq!(Distribution::parse(&d.to_string()).unwrap(), d);
        }
    }

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1.0)
    }

    #[test]
    fn quantiles_match_their_closed_forms() {
        let n = Distribution::parse("normal:0.4:0.05").unwrap();
        assert!(close(
            n.quantile(0.975),
            0.4 + 1.959_963_984_540_054 * 0.05,
            1e-12
        ));
        assert!(close(n.quantile(0.5), 0.4, 1e-14));
        let u = Distribution::parse("uniform:18:22").unwrap();
        assert!(close(u.quantile(0.25), 19.0, 1e-14));
        // Triangular(0, 1, 4): F(x) = x²/4 on [0, 1], so the quantile of 0.0625 is 0.5; on the
        // right 1 − (4 − x)²/12.
        let t = Distribution::parse("triangular:0:1:4").unwrap();
        assert!(close(t.quantile(0.0625), 0.5, 1e-12));
        assert!(close(t.quantile(1.0 - 4.0 / 12.0), 2.0, 1e-12));
        // Lognormal with mean 2, sd 1: median = mean / √(1 + sd²/mean²).
        let l = Distribution::parse("lognormal:2:1").unwrap();
        assert!(close(l.quantile(0.5), 2.0 / 1.25f64.sqrt(), 1e-12));
        // A huge sd/mean: σ² = ln(1 + r²) ≈ 2 ln r where r² would overflow (it gave NaN).
        let wide = Distribution::parse("lognormal:0.4:1e300").unwrap();
        let s2 = 2.0 * 2.5e300f64.ln();
        assert!(close(
            wide.quantile(0.5),
            (0.4f64.ln() - 0.5 * s2).exp(),
            1e-9
        ));
        // Truncated symmetrically about its mean: the median is the mean, every value inside.
        let tn = Distribution::parse("truncnormal:0:0.5:-1:1").unwrap();
        assert!(close(tn.quantile(0.5), 0.0, 1e-12));
        assert!(tn.quantile(1e-300) >= -1.0 && tn.quantile(1.0) <= 1.0);
        // Its quantile of Φ-mass: 0.84 of the kept mass lies below x where
        // (Φ(x/0.5) − Φ(−2)) / (Φ(2) − Φ(−2)) = 0.84.
        let phi = |x: f64| normal(0.0, 1.0).cdf(x);
        let x = tn.quantile(0.84);
        let got = (phi(x / 0.5) - phi(-2.0)) / (phi(2.0) - phi(-2.0));
        // (statrs' inverse normal is good to about 1e-11.)
        assert!(close(got, 0.84, 1e-10), "{got}");
    }

    #[test]
    fn malformed_distributions_say_what_is_wrong() {
        for (text, why) in [
            ("gauss:0:1", "unknown distribution"),
            ("normal:0", "takes 2 numbers"),
            ("normal:0:-1", "sd must be positive"),
            ("normal:0:x", "not a finite number"),
            ("normal:0:inf", "not a finite number"),
            ("uniform:2:1", "lo must be below hi"),
            ("triangular:0:5:4", "the mode 5"),
            ("lognormal:-1:1", "mean must be positive"),
            ("truncnormal:0:1:50:60", "too far in the tail"),
            // Said as given, not in 300 digits.
            (
                "truncnormal:0.4:1e-300:5:6",
                "[5, 6] lies too far in the tail of normal(0.4, 1e-300)",
            ),
            // Draws past the largest double: refused, never written as inf or NaN.
            ("uniform:-1e308:1e308", "not all finite"),
            ("triangular:-1e308:0:1e308", "not all finite"),
            ("normal:1e308:1e307", "not all finite"),
            ("lognormal:1e305:1e306", "not all finite"),
        ] {
            let e = Distribution::parse(text).unwrap_err();
            assert!(e.contains(why), "{text}: {e}");
        }
        // Every error of a key's distribution names the key.
        for text in [
            "normal:0:-1",
            "gauss:0:1",
            "normal:0",
            "normal:x:1",
            "uniform:-1e308:1e308",
        ] {
            let e = format!("friction.mu_k={text}")
                .parse::<Uncertain>()
                .unwrap_err();
            assert!(e.starts_with("friction.mu_k: "), "{e}");
        }
        let u: Uncertain = "friction.mu_k=normal:0.40:0.05".parse().unwrap();
        assert_eq!(u.key, "friction.mu_k");
        assert!(
            "friction.mu_k"
                .parse::<Uncertain>()
                .unwrap_err()
                .contains("key=distribution")
        );
        assert!(
            "=normal:0:1"
                .parse::<Uncertain>()
                .unwrap_err()
                .contains("no key")
        );
    }
}
