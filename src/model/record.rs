//! A ground-motion record: the foundation's acceleration in time (fractions of g along the
//! scene's X, Y, Z). The route is then the block's motion relative to the foundation: the
//! record enters as the inertial force −m g a(t) on the block (`derivations/11-dam-loads.md`
//! §3). A scene reads it from a CSV file (`scene/files.rs`).

use super::error::ModelError;

/// A fault of the record's samples (line numbers as in its file: the header, then a sample a
/// line).
fn fault(reason: String) -> ModelError {
    ModelError::new("seismic.record", reason)
}

/// Times (s, strictly increasing) and the ground's accelerations (g) at them.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    t: Vec<f64>,
    a: Vec<[f64; 3]>,
}

impl Record {
    /// From samples: at least two, times finite and strictly increasing, accelerations finite
    /// and below 10 g. A fault names the sample and its line as a record file without blank
    /// lines has it (the header, then a sample a line).
    pub fn new(samples: Vec<(f64, [f64; 3])>) -> Result<Record, ModelError> {
        Record::checked(samples, |k| Some(k as u64 + 2))
    }

    /// [`Record::new`] of the samples read from the lines `lines` of a file (`lines[k]` sample
    /// k's, from 1): a fault names the line the sample is on, blank lines counted.
    pub(crate) fn from_lines(
        samples: Vec<(f64, [f64; 3])>,
        lines: &[u64],
    ) -> Result<Record, ModelError> {
        Record::checked(samples, |k| lines.get(k).copied())
    }

    /// [`Record::new`], sample k's fault naming its line `line(k)` where there is one.
    fn checked(
        samples: Vec<(f64, [f64; 3])>,
        line: impl Fn(usize) -> Option<u64>,
    ) -> Result<Record, ModelError> {
        if samples.len() < 2 {
            return Err(fault("a record needs at least two samples".into()));
        }
        let at = |k: usize| match line(k) {
            Some(l) => format!("sample {k} (line {l})"),
            None => format!("sample {k}"),
        };
        for (k, (t, a)) in samples.iter().enumerate() {
            if !t.is_finite() || a.iter().any(|v| !v.is_finite()) {
                return Err(fault(format!("{}: not a finite number", at(k))));
            }
            if a.iter().any(|v| v.abs() > 10.0) {
                return Err(fault(format!("{}: an acceleration over 10 g", at(k))));
            }
            if k > 0 && *t <= samples[k - 1].0 {
                return Err(fault(format!(
                    "{}: time {t} s does not come after {} s",
                    at(k),
                    samples[k - 1].0
                )));
            }
        }
        let (t, a) = samples.into_iter().unzip();
        Ok(Record { t, a })
    }

    /// Along which of X, Y, Z the ground moves at all (some sample not zero).
    pub fn moves(&self) -> [bool; 3] {
        std::array::from_fn(|c| self.a.iter().any(|a| a[c] != 0.0))
    }

    /// The ground's acceleration (g) at time t, linear between samples; none before the first
    /// sample or after the last (the ground at rest).
    pub fn at(&self, t: f64) -> [f64; 3] {
        match bracket(&self.t, t) {
            Some((k, f)) => {
                std::array::from_fn(|c| self.a[k - 1][c] + f * (self.a[k][c] - self.a[k - 1][c]))
            }
            None => [0.0; 3],
        }
    }

    /// The first sample's time after t (s), beyond round-off of t: where the record's slope
    /// may change, so that an integrator steps to it rather than over it.
    pub fn next_sample(&self, t: f64) -> Option<f64> {
        let past = t + 1e-12 * t.abs().max(1.0);
        let k = self.t.partition_point(|&s| s <= past);
        self.t.get(k).copied()
    }

    /// The same record with every acceleration times `k` (a scale, a polarity): refused where
    /// a sample then exceeds 10 g.
    pub fn scaled(&self, k: f64) -> Result<Record, ModelError> {
        // No line: the fault is the factor's, whatever line of a file the sample was on.
        Record::checked(
            self.t
                .iter()
                .zip(&self.a)
                .map(|(t, a)| (*t, a.map(|v| v * k)))
                .collect(),
            |_| None,
        )
    }

    /// The peak ground acceleration (g): the largest |a| of a horizontal component (X or Z)
    /// at any sample.
    pub fn pga(&self) -> f64 {
        self.a
            .iter()
            .map(|a| a[0].abs().max(a[2].abs()))
            .fold(0.0, f64::max)
    }

    /// The samples: their times (s) and the accelerations (g) along X, Y, Z.
    pub fn samples(&self) -> (&[f64], &[[f64; 3]]) {
        (&self.t, &self.a)
    }

    /// The last sample's time (s): after it the ground is still.
    pub fn end(&self) -> f64 {
        self.t[self.t.len() - 1]
    }
}

/// Where `t` falls among the increasing `times` (at least two): the sample k ≥ 1 that ends its
/// interval and the fraction of the interval from sample k − 1; none before the first or after
/// the last.
pub(crate) fn bracket(times: &[f64], t: f64) -> Option<(usize, f64)> {
    let n = times.len();
    if n < 2 || !(times[0]..=times[n - 1]).contains(&t) {
        return None;
    }
    let k = times.partition_point(|&s| s <= t).clamp(1, n - 1);
    let (t0, t1) = (times[k - 1], times[k]);
    Some((k, (t - t0) / (t1 - t0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_is_linear_between_samples_and_still_outside_them() {
        let r = Record::new(vec![
            (0.0, [0.0, 0.0, 0.0]),
            (1.0, [1.0, -0.5, 0.2]),
            (3.0, [-1.0, 0.5, 0.2]),
        ])
        .unwrap();
        assert_eq!(r.at(0.5), [0.5, -0.25, 0.1]);
        assert_eq!(r.at(2.0), [0.0, 0.0, 0.2]);
        assert_eq!(r.at(3.0), [-1.0, 0.5, 0.2]);
        assert_eq!(r.at(3.5), [0.0; 3]);
        assert_eq!(r.at(-1.0), [0.0; 3]);
        assert_eq!(r.end(), 3.0);
        assert_eq!(r.next_sample(-1.0), Some(0.0));
        assert_eq!(r.next_sample(0.0), Some(1.0));
        assert_eq!(r.next_sample(1.0 - 1e-15), Some(3.0));
        assert_eq!(r.next_sample(3.0), None);
        assert_eq!(r.pga(), 1.0);
        let reversed = r.scaled(-2.0).unwrap();
        assert_eq!(reversed.at(0.5), [-1.0, 0.5, -0.2]);
        assert_eq!(reversed.pga(), 2.0);
        assert!(r.scaled(11.0).is_err());
    }

    #[test]
    fn a_record_out_of_order_or_not_finite_is_refused_naming_the_line() {
        let e = Record::new(vec![(0.0, [0.0; 3]), (0.0, [0.0; 3])]).unwrap_err();
        assert!(e.reason.contains("line 3"), "{e}");
        let e = Record::new(vec![(0.0, [0.0; 3]), (1.0, [f64::NAN, 0.0, 0.0])]).unwrap_err();
        assert!(e.reason.contains("not a finite number"), "{e}");
        assert!(Record::new(vec![(0.0, [0.0; 3])]).is_err());
    }

    #[test]
    fn a_records_fault_names_the_line_its_sample_was_read_from() {
        // Samples read from lines 2, 5 and 9 (blank lines between): the third's time goes back.
        let samples = vec![(0.0, [0.0; 3]), (1.0, [0.1, 0.0, 0.0]), (0.5, [0.0; 3])];
        let e = Record::from_lines(samples, &[2, 5, 9]).unwrap_err();
        assert!(e.reason.starts_with("sample 2 (line 9): time 0.5 s"), "{e}");
        // A scale that takes a sample over 10 g is the scale's fault: no line.
        let r = Record::new(vec![(0.0, [0.0; 3]), (1.0, [2.0, 0.0, 0.0])]).unwrap();
        let e = r.scaled(6.0).unwrap_err();
        assert!(
            e.reason.starts_with("sample 1: an acceleration over 10 g"),
            "{e}"
        );
    }
}
