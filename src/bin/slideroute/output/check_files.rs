//! `slideroute check`'s table of load cases: each case's levels, seismic
//! coefficients, water loads, factor of safety, requirement and verdict, as an engineer would
//! file it; and the same as CSV.

use slideroute::check::CaseResult;
use slideroute::internals::numeric::{fixed, seconds};
use std::fmt;

/// A case's value of a scene key it or the scene sets (the levels, the coefficients).
fn level(r: &CaseResult, f: impl Fn(&slideroute::LoadsUsed) -> f64) -> String {
    r.loads
        .as_ref()
        .map_or("—".into(), |l| fixed(f(l), 2).to_string())
}

/// The factor of safety as a cell: three decimals, or the word.
fn fs_cell(r: &CaseResult) -> String {
    match r.factor_of_safety {
        Some(slideroute::FactorOfSafety::Finite { value }) => fixed(value, 3).to_string(),
        Some(other) => other.cell(),
        None => "—".into(),
    }
}

/// The table, headed by the scene and the guideline.
pub struct CheckTable<'a> {
    pub scene: &'a str,
    pub guideline: String,
    pub results: &'a [CaseResult],
}

const COLUMNS: [&str; 11] = [
    "case",
    "category",
    "headwater m",
    "tailwater m",
    "kh",
    "kv",
    "H MN",
    "U MN",
    "FS",
    "required",
    "result",
];

impl CheckTable<'_> {
    fn cells(r: &CaseResult) -> [String; 11] {
        let water = |f: fn(&slideroute::WaterLoads) -> f64| {
            r.loads
                .as_ref()
                .and_then(|l| l.water.as_ref())
                .map_or("—".into(), |w| fixed(f(w), 2).to_string())
        };
        [
            r.case.name.clone(),
            r.case.category.as_str().to_string(),
            water(|w| w.levels.headwater),
            water(|w| w.levels.tailwater),
            level(r, |l| l.kh),
            level(r, |l| l.kv),
            level(r, |l| l.hydraulic_force_n / 1e6),
            level(r, |l| l.uplift_n / 1e6),
            fs_cell(r),
            fixed(r.case.required_fs, 2).to_string(),
            if r.passes { "pass" } else { "FAIL" }.to_string(),
        ]
    }
}

impl fmt::Display for CheckTable<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(f, "check {}: sliding, {}", self.scene, self.guideline)?;
        let rows: Vec<[String; 11]> = self.results.iter().map(Self::cells).collect();
        let width = |k: usize| {
            rows.iter()
                .map(|r| r[k].chars().count())
                .chain([COLUMNS[k].chars().count()])
                .max()
                .unwrap_or(0)
        };
        let widths: Vec<usize> = (0..COLUMNS.len()).map(width).collect();
        let line = |cells: &[String]| {
            let parts: Vec<String> = cells
                .iter()
                .zip(&widths)
                .enumerate()
                .map(|(k, (c, w))| {
                    if k < 2 {
                        format!("{c:<w$}")
                    } else {
                        format!("{c:>w$}")
                    }
                })
                .collect();
            format!("  {}", parts.join("  "))
        };
        let head: Vec<String> = COLUMNS.iter().map(|c| c.to_string()).collect();
        writeln!(f, "{}", line(&head))?;
        for r in &rows {
            writeln!(f, "{}", line(r))?;
        }
        writeln!(
            f,
            "  FS: the driving loads' multiple friction holds (H and its couples, kh W), with W, \
             U and kv W as they are"
        )?;
        for r in self.results.iter().filter(|r| !r.passes) {
            let t = &r.run.route.termination;
            let last = r.run.route.rows.last();
            if r.run.route.increments == 0 {
                writeln!(
                    f,
                    "  {} fails its requirement, but static friction holds the block: {}",
                    r.case.name, t.reason
                )?;
                continue;
            }
            writeln!(
                f,
                "  {} fails and slides: {} at t = {} s, travel {} m, yaw θ = {}°",
                r.case.name,
                t.reason,
                seconds(t.t_s),
                fixed(r.run.route.travel_m, 3),
                fixed(last.map_or(0.0, |l| l.theta_deg), 3)
            )?;
        }
        Ok(())
    }
}

/// One CSV row per case: the table's columns, numbers at full precision.
pub fn write_csv(out: impl std::io::Write, results: &[CaseResult]) -> Result<(), csv::Error> {
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
        "factor_of_safety",
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
            num(l.map(|l| l.uplift_n)),
            num(l.map(|l| l.weight_n)),
            r.factor_of_safety.map_or(String::new(), |f| f.cell()),
            r.case.required_fs.to_string(),
            r.passes.to_string(),
            r.run.route.termination.reason.to_string(),
            r.run.route.travel_m.to_string(),
        ])?;
    }
    w.flush()?;
    Ok(())
}
