//! `samples.csv`: a probabilistic analysis's samples, one row per sample in order — its values,
//! the factor of safety, how its route ended, the travel, where it ended, and the detail (what
//! ended the route, or why the values made no valid scene). The factor of safety is written as
//! in `sweep.csv`: a number, `unbounded` (no multiple of the driving loads starts the block) or
//! `not-holdable` (the weight alone does), never an infinity; every other number by
//! [`number`], never `inf` or `NaN`.

use super::number;
use crate::probabilistic::{Sample, Uncertain};
use crate::{NOT_RUN, Outcome};

/// `samples.csv` written as the samples come, one row each, in order: memory does not grow
/// with their number.
pub(crate) struct SamplesCsv<W: std::io::Write> {
    w: csv::Writer<W>,
}

impl<W: std::io::Write> SamplesCsv<W> {
    /// The file with its header: the sample's number, each uncertain key, then what the route
    /// came to.
    pub fn new(out: W, uncertain: &[Uncertain]) -> Result<Self, csv::Error> {
        let mut w = csv::Writer::from_writer(out);
        let mut header = vec!["sample".to_string()];
        header.extend(uncertain.iter().map(|u| u.key.clone()));
        header.extend(
            [
                "factor_of_safety",
                "reason",
                "t_end_s",
                "travel_m",
                "final_yaw_deg",
                "final_x_m",
                "final_z_m",
                "detail",
            ]
            .map(String::from),
        );
        w.write_record(&header)?;
        Ok(SamplesCsv { w })
    }

    /// The row of sample `s`.
    pub fn push(&mut self, s: &Sample) -> Result<(), csv::Error> {
        let mut rec = vec![s.index.to_string()];
        rec.extend(s.values.iter().map(|&v| number(v)));
        match &s.outcome {
            Outcome::Route(r) => rec.extend([
                r.factor_of_safety.map_or(String::new(), |f| f.cell()),
                r.reason.as_str().to_string(),
                number(r.t_s),
                number(r.travel_m),
                number(r.yaw_deg),
                number(r.x_m),
                number(r.z_m),
                r.detail.clone(),
            ]),
            Outcome::Invalid { reason } => {
                rec.extend(["", "invalid scene", "", "", "", "", ""].map(String::from));
                rec.push(reason.clone());
            }
            Outcome::NotRun => {
                rec.extend(["", NOT_RUN, "", "", "", "", "", ""].map(String::from));
            }
        }
        self.w.write_record(&rec)
    }

    /// Everything written out.
    pub fn finish(mut self) -> Result<(), csv::Error> {
        self.w.flush()?;
        Ok(())
    }
}

/// `samples.csv`: one row per sample, in order.
#[cfg(test)]
fn write_csv(
    out: impl std::io::Write,
    uncertain: &[Uncertain],
    rows: &[Sample],
) -> Result<(), csv::Error> {
    let mut w = SamplesCsv::new(out, uncertain)?;
    for s in rows {
        w.push(s)?;
    }
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{FactorOfSafety, Reason, RouteResult};

    /// A sample whose route ran with factor of safety `fs`.
    fn sample(index: usize, mu: f64, fs: FactorOfSafety) -> Sample {
        Sample {
            index,
            values: vec![mu],
            outcome: Outcome::Route(RouteResult {
                factor_of_safety: Some(fs),
                reason: Reason::Stopped,
                t_s: 2.0,
                detail: String::new(),
                travel_m: 1.5,
                x_m: 1.0,
                z_m: 0.5,
                yaw_deg: 3.0,
                max_alpha_deg: 0.0,
                max_beta_deg: 0.0,
                permanent_xz_m: None,
                cm_path_m: Vec::new(),
            }),
        }
    }

    #[test]
    fn samples_csv_writes_the_factor_of_safetys_words_as_sweep_csv_does_never_an_infinity() {
        // A sample with μ near 0 cannot be held: samples.csv wrote `-inf` where sweep.csv
        // writes `not-holdable`.
        let uncertain: Vec<Uncertain> = vec!["friction.mu_k=uniform:0:0.6".parse().unwrap()];
        let rows = [
            sample(0, 1e-300, FactorOfSafety::NotHoldable),
            sample(1, 0.5, FactorOfSafety::Unbounded),
            sample(2, 0.4, FactorOfSafety::Finite { value: 0.8624 }),
        ];
        let mut out = Vec::new();
        write_csv(&mut out, &uncertain, &rows).unwrap();
        let text = String::from_utf8(out).unwrap();
        let lower = text.to_lowercase();
        assert!(!lower.contains("inf") && !lower.contains("nan"), "{text}");
        let fs: Vec<&str> = text
            .lines()
            .skip(1)
            .map(|l| l.split(',').nth(2).unwrap())
            .collect();
        assert_eq!(fs, ["not-holdable", "unbounded", "0.8624"]);
        // Each word is the one sweep.csv writes for the same kind.
        assert_eq!(fs[0], FactorOfSafety::NotHoldable.cell());
        assert_eq!(fs[1], FactorOfSafety::Unbounded.cell());
        // A tiny sampled value is short and reads back the same.
        assert!(
            text.lines().nth(1).unwrap().starts_with("0,1e-300,"),
            "{text}"
        );
    }
}
