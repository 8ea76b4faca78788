//! Rows of many routes — a sweep's combinations, a design's samples — as columns of NumPy
//! arrays and lists (as `sweep.csv` and `samples.csv` have them), and back; and the rows of one
//! route as `route.csv`'s columns ([`RouteColumns`]).

use crate::errors::input_error;
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use slideroute::probabilistic::Sample;
use slideroute::{FactorOfSafety, NOT_RUN, Outcome, Reason, RouteResult};

/// One row: its number, its values (one per key), and what its route came to.
pub struct Row<'a> {
    pub index: usize,
    pub values: &'a [f64],
    pub outcome: &'a Outcome,
}

impl<'a> From<&'a Sample> for Row<'a> {
    fn from(s: &'a Sample) -> Row<'a> {
        Row {
            index: s.index,
            values: &s.values,
            outcome: &s.outcome,
        }
    }
}

/// A route's rows as `route.csv`'s columns (`Row::COLUMNS`, in its order: `body`, the number of
/// the body a row is of, first), filled a row at a time: float arrays, NaN where a value could
/// not be had.
pub struct RouteColumns(Vec<Vec<f64>>);

impl RouteColumns {
    /// No rows yet, room for `rows` of them.
    pub fn with_capacity(rows: usize) -> Self {
        RouteColumns(vec![
            Vec::with_capacity(rows);
            slideroute::Row::COLUMNS.len()
        ])
    }

    /// One row more.
    pub fn push(&mut self, row: &slideroute::Row) {
        for (col, v) in self.0.iter_mut().zip(row.values()) {
            col.push(v.unwrap_or(f64::NAN));
        }
    }

    /// The columns by name, as NumPy arrays.
    pub fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let out = PyDict::new(py);
        for (name, v) in slideroute::Row::COLUMNS.iter().zip(self.0) {
            out.set_item(*name, PyArray1::from_vec(py, v))?;
        }
        Ok(out)
    }
}

/// A column of numbers: its name and how a route gives it.
type Column<'a> = (&'a str, &'a dyn Fn(&RouteResult) -> f64);

/// Rows as columns: `sample`, each key's values, then what each route came to (NaN where no
/// route ran; the factor of safety ±∞ where unbounded or not holdable), how it ended —
/// `reason`, a machine name ([`reason_code`]), and `reason_text`, the sentence the command
/// line's tables write — and the detail.
pub fn columns_of<'py>(
    py: Python<'py>,
    keys: &[&str],
    rows: &[Row<'_>],
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item(
        "sample",
        PyArray1::from_vec(py, rows.iter().map(|s| s.index as i64).collect()),
    )?;
    for (k, key) in keys.iter().enumerate() {
        out.set_item(
            *key,
            PyArray1::from_vec(py, rows.iter().map(|s| s.values[k]).collect()),
        )?;
    }
    let route = |f: &dyn Fn(&RouteResult) -> f64| -> Vec<f64> {
        rows.iter()
            .map(|s| s.outcome.route().map_or(f64::NAN, f))
            .collect()
    };
    let float_columns: [Column; 10] = [
        ("factor_of_safety", &|r| {
            r.factor_of_safety_value().unwrap_or(f64::NAN)
        }),
        ("t_end_s", &|r| r.t_s),
        ("travel_m", &|r| r.travel_m),
        ("final_yaw_deg", &|r| r.yaw_deg),
        ("final_x_m", &|r| r.x_m),
        ("final_z_m", &|r| r.z_m),
        ("max_alpha_deg", &|r| r.max_alpha_deg),
        ("max_beta_deg", &|r| r.max_beta_deg),
        ("permanent_x_m", &|r| {
            r.permanent_xz_m.map_or(f64::NAN, |d| d[0])
        }),
        ("permanent_z_m", &|r| {
            r.permanent_xz_m.map_or(f64::NAN, |d| d[1])
        }),
    ];
    for (name, f) in float_columns {
        out.set_item(name, PyArray1::from_vec(py, route(f)))?;
    }
    let codes: Vec<String> = rows.iter().map(|s| outcome_code(s.outcome)).collect();
    let texts: Vec<&str> = rows.iter().map(|s| s.outcome.reason()).collect();
    let details: Vec<String> = rows
        .iter()
        .map(|s| match s.outcome {
            Outcome::Route(r) => r.detail.clone(),
            Outcome::Invalid { reason } => reason.clone(),
            Outcome::NotRun => String::new(),
        })
        .collect();
    out.set_item("reason", codes)?;
    out.set_item("reason_text", texts)?;
    out.set_item("detail", details)?;
    Ok(out)
}

/// The machine name of an end: kebab-case, as `summary.json`'s `termination.reason` writes it
/// (`contact0-reached-inclined-plane`, `time-limit`).
pub fn reason_code(reason: Reason) -> String {
    match serde_json::to_value(reason) {
        Ok(serde_json::Value::String(s)) => s,
        _ => reason.as_str().replace(' ', "-"),
    }
}

/// The machine name of a row's end: its route's ([`reason_code`]), [`INVALID`] or
/// [`NOT_RUN_CODE`].
pub fn outcome_code(outcome: &Outcome) -> String {
    match outcome {
        Outcome::Route(r) => reason_code(r.reason),
        Outcome::Invalid { .. } => INVALID.to_string(),
        Outcome::NotRun => NOT_RUN_CODE.to_string(),
    }
}

/// The machine name of a row whose values make no valid scene (its sentence `invalid scene`).
pub const INVALID: &str = "invalid-scene";

/// The machine name of a row a stopped run did not start (its sentence [`NOT_RUN`]).
pub const NOT_RUN_CODE: &str = "not-run";

/// Every end a row can have: (machine name, sentence), the routes' in the library's order.
pub fn reasons() -> Vec<(String, &'static str)> {
    Reason::ALL
        .into_iter()
        .map(|r| (reason_code(r), r.as_str()))
        .chain([
            (INVALID.to_string(), "invalid scene"),
            (NOT_RUN_CODE.to_string(), NOT_RUN),
        ])
        .collect()
}

/// Samples back from their columns (as [`columns_of`] wrote them, gathered from anywhere).
pub fn samples_from<'py>(
    py: Python<'py>,
    keys: &[String],
    columns: &Bound<'py, PyDict>,
) -> PyResult<Vec<Sample>> {
    let get = |name: &str| -> PyResult<Bound<'py, PyAny>> {
        columns
            .get_item(name)?
            .ok_or_else(|| input_error(py, name, format!("the samples have no column `{name}`")))
    };
    let floats = |name: &str| -> PyResult<Vec<f64>> {
        let a = get(name)?;
        a.extract::<Vec<f64>>()
            .map_err(|_| input_error(py, name, format!("`{name}`: numbers")))
    };
    let index: Vec<i64> = get("sample")?.extract()?;
    let n = index.len();
    let values: Vec<Vec<f64>> = keys.iter().map(|k| floats(k)).collect::<PyResult<_>>()?;
    let fs = floats("factor_of_safety")?;
    let t = floats("t_end_s")?;
    let travel = floats("travel_m")?;
    let yaw = floats("final_yaw_deg")?;
    let x = floats("final_x_m")?;
    let z = floats("final_z_m")?;
    let max_alpha = floats("max_alpha_deg")?;
    let max_beta = floats("max_beta_deg")?;
    // Older tables have no permanent displacement: none.
    let permanent: Vec<Option<[f64; 2]>> = match (floats("permanent_x_m"), floats("permanent_z_m"))
    {
        (Ok(px), Ok(pz)) if px.len() == n && pz.len() == n => px
            .iter()
            .zip(&pz)
            .map(|(&a, &b)| (!a.is_nan() && !b.is_nan()).then_some([a, b]))
            .collect(),
        _ => vec![None; n],
    };
    let reason: Vec<String> = get("reason")?.extract()?;
    let detail: Vec<String> = get("detail")?.extract()?;
    let lengths = [
        fs.len(),
        t.len(),
        travel.len(),
        yaw.len(),
        x.len(),
        z.len(),
        max_alpha.len(),
        max_beta.len(),
        reason.len(),
        detail.len(),
    ];
    if lengths
        .into_iter()
        .chain(values.iter().map(|v| v.len()))
        .any(|l| l != n)
    {
        return Err(input_error(py, "samples", "the columns differ in length"));
    }
    (0..n)
        .map(|k| {
            // The machine name, or the sentence (a table the command line wrote).
            let outcome = match reason[k].as_str() {
                INVALID | "invalid scene" => Outcome::Invalid {
                    reason: detail[k].clone(),
                },
                r if r == NOT_RUN_CODE || r == NOT_RUN => Outcome::NotRun,
                r => Outcome::Route(RouteResult {
                    factor_of_safety: (!fs[k].is_nan())
                        .then(|| FactorOfSafety::from_multiple(fs[k])),
                    reason: Reason::ALL
                        .into_iter()
                        .find(|&e| reason_code(e) == r)
                        .or_else(|| Reason::parse(r))
                        .ok_or_else(|| {
                            input_error(py, "reason", format!("`{r}` is no route's end"))
                        })?,
                    t_s: t[k],
                    detail: detail[k].clone(),
                    travel_m: travel[k],
                    x_m: x[k],
                    z_m: z[k],
                    yaw_deg: yaw[k],
                    max_alpha_deg: max_alpha[k],
                    max_beta_deg: max_beta[k],
                    permanent_xz_m: permanent[k],
                    cm_path_m: vec![],
                }),
            };
            Ok(Sample {
                index: index[k] as usize,
                values: values.iter().map(|v| v[k]).collect(),
                outcome,
            })
        })
        .collect()
}
