//! `check.csv`: one row per load case, the printed table's columns with numbers at full
//! precision.

use super::check_tables::horizontal;
use crate::check::CaseResult;

/// One CSV row per case: the table's columns, numbers at full precision.
pub(crate) fn write_csv(
    out: impl std::io::Write,
    results: &[CaseResult],
) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record([
        "case",
        "category",
        "headwater_m",
        "tailwater_m",
        "kh",
        "kv",
        "hydraulic_force_n",
        "uplift_n",
        "weight_n",
        "horizontal_n",
        "sliding_fs",
        "resultant_from_heel_m",
        "base_in_compression_pct",
        "heel_pressure_pa",
        "toe_pressure_pa",
        "crack_length_m",
        "load_multiple",
        "load_multiple_limit",
        "anchor_force_n",
        "required_fs",
        "passes",
        "route_end",
        "travel_m",
    ])?;
    let num = |v: Option<f64>| v.map_or(String::new(), |v| v.to_string());
    for r in results {
        let l = r.loads.as_ref();
        let water = l.and_then(|l| l.water.as_ref());
        w.write_record([
            r.case.name.clone(),
            r.case.category.as_str().to_string(),
            num(water.map(|w| w.levels.headwater)),
            num(water.map(|w| w.levels.tailwater)),
            num(l.map(|l| l.kh)),
            num(l.map(|l| l.kv)),
            num(l.map(|l| l.hydraulic_force_n)),
            num(r.gravity.map(|g| g.uplift_n).or(l.map(|l| l.uplift_n))),
            num(l.map(|l| l.weight_n)),
            num(horizontal(r)),
            match r.gravity {
                Some(g) => g.sliding_fs.map_or("unbounded".into(), |v| v.to_string()),
                None => String::new(),
            },
            num(r.gravity.and_then(|g| g.resultant_from_heel_m)),
            num(r.gravity.map(|g| g.base_in_compression_pct)),
            num(r.gravity.map(|g| g.heel_pressure_pa)),
            num(r.gravity.map(|g| g.toe_pressure_pa)),
            num(r.gravity.map(|g| g.crack_length_m)),
            r.factor_of_safety.map_or(String::new(), |f| f.cell()),
            r.run
                .route
                .factor_of_safety_limit
                .map_or("", |l| l.as_str())
                .to_string(),
            num(r.gravity.map(|g| g.anchor_force_n)),
            r.case.required_fs.to_string(),
            r.passes.to_string(),
            r.run.route.termination.reason.to_string(),
            r.run.route.travel_m.to_string(),
        ])?;
    }
    w.flush()?;
    Ok(())
}
