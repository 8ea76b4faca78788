//! Numbers for people: messages give a length, a time or an angle at a sensible
//! precision, not every digit of a double (`t = 1.6260000000000001 s`) nor 300 digits of a huge
//! input (`--x 1e308`). Files (CSV, JSON) keep full precision; these are for messages only.

use std::fmt;

/// `value` with `decimals` decimals; in scientific notation past 1e6 in size (or for a value
/// that is not finite, as Rust writes it); with `trim`, trailing zeros of the decimals dropped
/// (`1.626`, not `1.626000`).
#[derive(Debug, Clone, Copy)]
pub struct Shown {
    value: f64,
    decimals: usize,
    trim: bool,
}

/// A length or an angle at `decimals` decimals.
pub fn fixed(value: f64, decimals: usize) -> Shown {
    Shown {
        value,
        decimals,
        trim: false,
    }
}

/// An angle in degrees for a message: to 1e-9°, trailing zeros dropped (`90`, not
/// `90.00000000000001` from a round trip through radians).
pub fn degrees(value: f64) -> Shown {
    Shown {
        value,
        decimals: 9,
        trim: true,
    }
}

/// A time or a duration: to the microsecond, trailing zeros dropped.
pub fn seconds(value: f64) -> Shown {
    Shown {
        value,
        decimals: 6,
        trim: true,
    }
}

/// A number as given, for a message about it: its shortest form that reads back the same, in
/// scientific notation past 10¹⁶ or below 10⁻⁵ in size (`1e300`, not 301 digits; `1.5e-7`).
#[derive(Debug, Clone, Copy)]
pub struct Given(pub f64);

/// `Given`: `value` as given.
pub fn given(value: f64) -> Given {
    Given(value)
}

impl fmt::Display for Given {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        if v.is_finite() && v != 0.0 && !(1e-5..1e16).contains(&v.abs()) {
            write!(f, "{v:e}")
        } else {
            write!(f, "{v}")
        }
    }
}

impl fmt::Display for Shown {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.value;
        if !v.is_finite() || v.abs() >= 1e6 {
            return write!(f, "{v:.4e}");
        }
        let s = format!("{v:.*}", self.decimals);
        // A value that rounds to zero reads without a sign (`0.00`, not `-0.00`).
        let s = if s.starts_with('-') && s[1..].chars().all(|c| c == '0' || c == '.') {
            s[1..].to_string()
        } else {
            s
        };
        if self.trim && s.contains('.') {
            f.write_str(s.trim_end_matches('0').trim_end_matches('.'))
        } else {
            f.write_str(&s)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_drop_float_noise_and_trailing_zeros() {
        assert_eq!(seconds(1.6260000000000001).to_string(), "1.626");
        assert_eq!(seconds(4.364835837701146).to_string(), "4.364836");
        assert_eq!(seconds(3.0).to_string(), "3");
        assert_eq!(seconds(0.0).to_string(), "0");
    }

    #[test]
    fn a_number_as_given_is_short_and_reads_back_the_same() {
        for (v, text) in [
            (1e300, "1e300"),
            (-1.7976931348623157e308, "-1.7976931348623157e308"),
            (1.5e-7, "1.5e-7"),
            (5e-324, "5e-324"),
            (15.0, "15"),
            (-1.0, "-1"),
            (0.25, "0.25"),
            (0.0, "0"),
            (1e16, "1e16"),
            (9.5e15, "9500000000000000"),
            (f64::NAN, "NaN"),
            (f64::NEG_INFINITY, "-inf"),
        ] {
            let shown = given(v).to_string();
            assert_eq!(shown, text);
            if v.is_finite() {
                assert_eq!(shown.parse::<f64>().unwrap().to_bits(), v.to_bits());
            }
        }
    }

    #[test]
    fn huge_and_non_finite_values_are_short() {
        assert_eq!(fixed(1e308, 6).to_string(), "1.0000e308");
        assert_eq!(fixed(-2.5e7, 3).to_string(), "-2.5000e7");
        assert_eq!(fixed(f64::INFINITY, 6).to_string(), "inf");
        assert_eq!(fixed(0.123456789, 6).to_string(), "0.123457");
    }

    #[test]
    fn values_that_round_to_zero_carry_no_sign() {
        assert_eq!(fixed(-0.001, 2).to_string(), "0.00");
        assert_eq!(fixed(-0.0, 3).to_string(), "0.000");
        assert_eq!(seconds(-1e-9).to_string(), "0");
        assert_eq!(fixed(-0.006, 2).to_string(), "-0.01");
    }
}
