//! A ground-motion record (`seismic.record`, issue #16): the foundation's acceleration in time,
//! read from CSV with the columns `t_s, ax_g, ay_g, az_g` (seconds; fractions of g along the
//! scene's X, Y, Z). The route is then the block's motion relative to the foundation: the
//! record enters as the inertial force −m g a(t) on the block (`derivations/11-dam-loads.md`
//! §3).

use std::path::Path;

/// The largest record file (bytes): some million samples.
pub const MAX_RECORD_BYTES: u64 = 64 << 20;

/// The columns a record has, in this order.
pub const COLUMNS: [&str; 4] = ["t_s", "ax_g", "ay_g", "az_g"];

/// Times (s, strictly increasing) and the ground's accelerations (g) at them.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    t: Vec<f64>,
    a: Vec<[f64; 3]>,
}

impl Record {
    /// From samples: at least two, times finite and strictly increasing, accelerations finite
    /// and below 10 g.
    pub fn new(samples: Vec<(f64, [f64; 3])>) -> Result<Record, String> {
        if samples.len() < 2 {
            return Err("a record needs at least two samples".into());
        }
        for (k, (t, a)) in samples.iter().enumerate() {
            if !t.is_finite() || a.iter().any(|v| !v.is_finite()) {
                return Err(format!("sample {k} (line {}): not a finite number", k + 2));
            }
            if a.iter().any(|v| v.abs() > 10.0) {
                return Err(format!(
                    "sample {k} (line {}): an acceleration over 10 g",
                    k + 2
                ));
            }
            if k > 0 && *t <= samples[k - 1].0 {
                return Err(format!(
                    "sample {k} (line {}): time {t} s does not come after {} s",
                    k + 2,
                    samples[k - 1].0
                ));
            }
        }
        let (t, a) = samples.into_iter().unzip();
        Ok(Record { t, a })
    }

    /// Reads a record file (CSV with the header `t_s,ax_g,ay_g,az_g`).
    pub fn read(path: &Path) -> Result<Record, String> {
        let file = super::input::open_bounded(path, MAX_RECORD_BYTES)?;
        let mut r = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .from_reader(file);
        let header = r.headers().map_err(|e| e.to_string())?.clone();
        if header.iter().collect::<Vec<_>>() != COLUMNS {
            return Err(format!(
                "the header must be `{}`, got `{}`",
                COLUMNS.join(","),
                header.iter().collect::<Vec<_>>().join(",")
            ));
        }
        let mut samples = Vec::new();
        for (k, row) in r.records().enumerate() {
            let row = row.map_err(|e| e.to_string())?;
            let mut v = [0.0; 4];
            for (c, cell) in v.iter_mut().enumerate() {
                let text = row.get(c).unwrap_or("");
                *cell = text.parse().map_err(|_| {
                    format!("line {}: `{text}` in {} is not a number", k + 2, COLUMNS[c])
                })?;
            }
            samples.push((v[0], [v[1], v[2], v[3]]));
        }
        Record::new(samples)
    }

    /// The ground's acceleration (g) at time t, linear between samples; none before the first
    /// sample or after the last (the ground at rest).
    pub fn at(&self, t: f64) -> [f64; 3] {
        let (first, last) = (self.t[0], self.t[self.t.len() - 1]);
        if !(first..=last).contains(&t) {
            return [0.0; 3];
        }
        let k = self
            .t
            .partition_point(|&s| s <= t)
            .clamp(1, self.t.len() - 1);
        let (t0, t1) = (self.t[k - 1], self.t[k]);
        let f = (t - t0) / (t1 - t0);
        std::array::from_fn(|c| self.a[k - 1][c] + f * (self.a[k][c] - self.a[k - 1][c]))
    }

    /// The first sample's time after t (s), beyond round-off of t: where the record's slope
    /// may change, so that an integrator steps to it rather than over it.
    pub fn next_sample(&self, t: f64) -> Option<f64> {
        let past = t + 1e-12 * t.abs().max(1.0);
        let k = self.t.partition_point(|&s| s <= past);
        self.t.get(k).copied()
    }

    /// The last sample's time (s): after it the ground is still.
    pub fn end(&self) -> f64 {
        self.t[self.t.len() - 1]
    }
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
    }

    #[test]
    fn a_record_out_of_order_or_not_finite_is_refused_naming_the_line() {
        let e = Record::new(vec![(0.0, [0.0; 3]), (0.0, [0.0; 3])]).unwrap_err();
        assert!(e.contains("line 3"), "{e}");
        let e = Record::new(vec![(0.0, [0.0; 3]), (1.0, [f64::NAN, 0.0, 0.0])]).unwrap_err();
        assert!(e.contains("not a finite number"), "{e}");
        assert!(Record::new(vec![(0.0, [0.0; 3])]).is_err());
    }
}
