//! Batch poses for `slideroute roots --grid`: read `x_m,z_m,theta_deg` rows, write one result
//! row per pose, in order.

use crate::output::roots_report::RootsReport;
use slideroute::Displacement;
use std::io::{Read, Write};

/// A grid file that cannot be used: names the file, the line and the reason.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}: {place}: {reason}")]
pub struct GridError {
    pub file: String,
    pub place: String,
    pub reason: String,
}

/// One pose of a grid file, as written there (degrees).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridPose {
    pub x_m: f64,
    pub z_m: f64,
    pub theta_deg: f64,
}

impl GridPose {
    pub fn displacement(&self) -> Displacement {
        Displacement::new(self.x_m, self.z_m, self.theta_deg.to_radians())
    }
}

/// Reads poses from CSV with the header `x_m,z_m,theta_deg`.
pub fn read_poses(input: impl Read, file: &str) -> Result<Vec<GridPose>, GridError> {
    let err = |place: String, reason: String| GridError {
        file: file.to_string(),
        place,
        reason,
    };
    let mut rdr = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(input);
    let headers = rdr
        .headers()
        .map_err(|e| err("line 1".into(), format!("cannot read the header: {e}")))?
        .clone();
    let want = ["x_m", "z_m", "theta_deg"];
    if headers.iter().collect::<Vec<_>>() != want {
        return Err(err(
            "line 1".into(),
            format!(
                "the header must be exactly `x_m,z_m,theta_deg`, found `{}`",
                headers.iter().collect::<Vec<_>>().join(",")
            ),
        ));
    }
    let mut out = Vec::new();
    for rec in rdr.records() {
        let rec = rec.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line());
            err(format!("line {line}"), e.to_string())
        })?;
        let line = rec.position().map_or(0, |p| p.line());
        let mut v = [0.0; 3];
        for (k, name) in want.iter().enumerate() {
            let text = rec.get(k).unwrap_or("");
            let x: f64 = text.parse().map_err(|_| {
                err(
                    format!("line {line}, column {name}"),
                    format!("`{text}` is not a number"),
                )
            })?;
            if !x.is_finite() {
                return Err(err(
                    format!("line {line}, column {name}"),
                    format!("must be a finite number, got {text}"),
                ));
            }
            v[k] = x;
        }
        out.push(GridPose {
            x_m: v[0],
            z_m: v[1],
            theta_deg: v[2],
        });
    }
    Ok(out)
}

/// The columns of the batch output.
pub const HEADER: [&str; 12] = [
    "x_m",
    "z_m",
    "theta_deg",
    "status",
    "alpha_deg",
    "beta_deg",
    "gamma_deg",
    "cm_y_m",
    "finite_roots",
    "roots_at_infinity",
    "admissible_roots",
    "note",
];

/// Writes one row per pose (echoed as read) with its report; a pose with no selected root says
/// so in `status` and `note`.
pub fn write_rows(
    out: impl Write,
    poses: &[GridPose],
    reports: &[RootsReport],
) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record(HEADER)?;
    for (p, r) in poses.iter().zip(reports) {
        let admissible = r.roots.iter().filter(|x| x.admissible).count();
        let (status, vals, note) = match (&r.selected, &r.selection_error) {
            (Some(s), _) => (
                "selected",
                [s.alpha_deg, s.beta_deg, s.gamma_deg, s.cm_y_m].map(|v| v.to_string()),
                String::new(),
            ),
            (None, e) => (
                "no admissible root",
                [(); 4].map(|_| String::new()),
                e.clone().unwrap_or_default(),
            ),
        };
        let mut row = vec![
            p.x_m.to_string(),
            p.z_m.to_string(),
            p.theta_deg.to_string(),
            status.to_string(),
        ];
        row.extend(vals);
        row.extend([
            r.finite_roots.to_string(),
            r.roots_at_infinity.to_string(),
            admissible.to_string(),
            note,
        ]);
        w.write_record(&row)?;
    }
    w.flush()?;
    Ok(())
}
