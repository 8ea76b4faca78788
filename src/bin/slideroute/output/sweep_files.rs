//! `sweep.csv`: one row per combination (under a ground-motion record, with its permanent
//! displacement: a sweep over records, `--vary seismic.record_x=a.AT2,b.AT2` or a folder's,
//! `records/`, is a table of them).

use crate::sweep::{SweepRow, Vary};
use std::io::Write;

/// Columns after the varied keys.
pub const SWEEP_COLUMNS: [&str; 10] = [
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

pub fn write_csv(out: impl Write, varies: &[Vary], rows: &[SweepRow]) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    let header: Vec<&str> = varies
        .iter()
        .map(|v| v.key.as_str())
        .chain(SWEEP_COLUMNS)
        .collect();
    w.write_record(&header)?;
    let opt = |v: Option<f64>| v.map_or(String::new(), |x| x.to_string());
    for r in rows {
        let mut rec: Vec<String> = varies
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
        w.write_record(&rec)?;
    }
    w.flush()?;
    Ok(())
}
