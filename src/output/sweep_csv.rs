//! `sweep.csv`: one row per combination (under a ground-motion record, with its permanent
//! displacement: a sweep over records, `--vary seismic.record_x=a.AT2,b.AT2` or a folder's,
//! `records/`, is a table of them).

use super::number;
use super::sweep_row::SweepRow;
use crate::sweep::Vary;
use std::io::Write;

/// Columns after the varied keys.
const SWEEP_COLUMNS: [&str; 10] = [
    "reason",
    "t_end_s",
    "travel_m",
    "final_theta_deg",
    "max_alpha_deg",
    "max_beta_deg",
    "permanent_x_m",
    "permanent_z_m",
    "factor_of_safety",
    "detail",
];

/// `sweep.csv` written as the combinations come: the header (the varied keys, then
/// [`SWEEP_COLUMNS`]) and one row per combination, in order, numbers by [`number`], the factor
/// of safety a number or a word; memory does not grow with their number.
pub(crate) struct SweepCsv<'v, W: Write> {
    w: csv::Writer<W>,
    varies: &'v [Vary],
}

impl<'v, W: Write> SweepCsv<'v, W> {
    /// The file with its header: each varied key, then what the route came to.
    pub fn new(out: W, varies: &'v [Vary]) -> Result<Self, csv::Error> {
        let mut w = csv::Writer::from_writer(out);
        let header: Vec<&str> = varies
            .iter()
            .map(|v| v.key.as_str())
            .chain(SWEEP_COLUMNS)
            .collect();
        w.write_record(&header)?;
        Ok(SweepCsv { w, varies })
    }

    /// The row of combination `r`.
    pub fn push(&mut self, r: &SweepRow) -> Result<(), csv::Error> {
        let opt = |v: Option<f64>| v.map_or(String::new(), number);
        let mut rec: Vec<String> = self
            .varies
            .iter()
            .zip(&r.values)
            .map(|(v, &x)| v.cell(x))
            .collect();
        rec.push(r.reason.clone());
        rec.extend(
            [
                r.t_end_s,
                r.travel_m,
                r.final_theta_deg,
                r.max_alpha_deg,
                r.max_beta_deg,
                r.permanent_x_m,
                r.permanent_z_m,
            ]
            .map(opt),
        );
        // A number, or `unbounded` / `not-holdable` (never an empty cell or an infinity).
        rec.push(r.factor_of_safety.map_or(String::new(), |f| f.cell()));
        rec.push(r.detail.clone());
        self.w.write_record(&rec)
    }

    /// Everything written out.
    pub fn finish(mut self) -> Result<(), csv::Error> {
        self.w.flush()?;
        Ok(())
    }
}

/// `sweep.csv` of `rows`, in order.
#[cfg(test)]
fn write_csv(out: impl Write, varies: &[Vary], rows: &[SweepRow]) -> Result<(), csv::Error> {
    let mut w = SweepCsv::new(out, varies)?;
    for r in rows {
        w.push(r)?;
    }
    w.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::FactorOfSafety;

    #[test]
    fn number_cells_read_back_the_same_and_are_never_inf_or_nan() {
        for v in [
            0.0,
            0.25,
            -1.5,
            1e-300,
            5e-324,
            f64::MAX,
            -f64::MAX,
            1e16,
            12.9,
        ] {
            let cell = number(v);
            assert!(cell.len() < 30, "{cell}");
            assert_eq!(
                cell.parse::<f64>().unwrap().to_bits(),
                v.to_bits(),
                "{cell}"
            );
        }
        for v in [f64::INFINITY, f64::NEG_INFINITY, f64::NAN] {
            assert_eq!(number(v), "");
        }
    }

    #[test]
    fn sweep_csv_writes_words_for_factors_of_safety_and_no_infinity() {
        let varies = [Vary {
            key: "friction.mu_k".into(),
            values: vec![0.0, 0.4],
            words: None,
        }];
        let row = |mu: f64, fs: FactorOfSafety, travel: f64| SweepRow {
            values: vec![mu],
            reason: "stopped".into(),
            t_end_s: Some(1.0),
            travel_m: Some(travel),
            final_theta_deg: Some(0.0),
            max_alpha_deg: Some(0.0),
            max_beta_deg: Some(0.0),
            permanent_x_m: None,
            permanent_z_m: None,
            factor_of_safety: Some(fs),
            detail: String::new(),
        };
        let rows = [
            row(0.0, FactorOfSafety::NotHoldable, f64::INFINITY),
            row(0.4, FactorOfSafety::Unbounded, f64::NAN),
        ];
        let mut out = Vec::new();
        write_csv(&mut out, &varies, &rows).unwrap();
        let text = String::from_utf8(out).unwrap();
        let lower = text.to_lowercase();
        assert!(!lower.contains("inf") && !lower.contains("nan"), "{text}");
        assert!(text.contains(",not-holdable,"), "{text}");
        assert!(text.contains(",unbounded,"), "{text}");
    }
}
