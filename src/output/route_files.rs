//! `route.csv` and `summary.json` for a computed route.

use crate::route::{ROUTE_HEADER, Route, Row};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes the rows with the header [`ROUTE_HEADER`]; reactions that could not be had are empty.
pub fn write_csv(out: impl Write, rows: &[Row]) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record(ROUTE_HEADER)?;
    for r in rows {
        let mut rec: Vec<String> = [
            r.t_s,
            r.x_m,
            r.y_m,
            r.z_m,
            r.theta_deg,
            r.alpha_deg,
            r.beta_deg,
            r.gamma_deg,
            r.vx_m_s,
            r.vz_m_s,
            r.omega_deg_s,
        ]
        .iter()
        .map(|v| v.to_string())
        .collect();
        for group in [r.n_n, r.s_n] {
            match group {
                Some(v) => rec.extend(v.iter().map(|x| x.to_string())),
                None => rec.extend(std::iter::repeat_n(String::new(), 3)),
            }
        }
        w.write_record(&rec)?;
    }
    w.flush()?;
    Ok(())
}

/// Writes `route.csv` and `summary.json` into `dir` (created if needed); returns their paths.
pub fn write(dir: &Path, route: &Route) -> Result<[PathBuf; 2], String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: cannot create: {e}", dir.display()))?;
    let csv_path = dir.join("route.csv");
    let file = std::fs::File::create(&csv_path)
        .map_err(|e| format!("{}: cannot write: {e}", csv_path.display()))?;
    write_csv(file, &route.rows).map_err(|e| format!("{}: {e}", csv_path.display()))?;
    let json_path = dir.join("summary.json");
    let text = serde_json::to_string_pretty(route).map_err(|e| format!("summary: {e}"))?;
    std::fs::write(&json_path, text + "\n")
        .map_err(|e| format!("{}: cannot write: {e}", json_path.display()))?;
    Ok([csv_path, json_path])
}
