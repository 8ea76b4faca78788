//! `samples.csv`: a probabilistic analysis's samples, one row per sample in order — its values,
//! the factor of safety, how its route ended, the travel, where it ended, and the detail (what
//! ended the route, or why the values made no valid scene).

use slideroute::probabilistic::{Sample, Uncertain};
use slideroute::{NOT_RUN, Outcome};

/// `samples.csv`: one row per sample, in order.
pub fn write_csv(
    out: impl std::io::Write,
    uncertain: &[Uncertain],
    rows: &[Sample],
) -> Result<(), csv::Error> {
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
    for s in rows {
        let mut rec = vec![s.index.to_string()];
        rec.extend(s.values.iter().map(|v| v.to_string()));
        match &s.outcome {
            Outcome::Route(r) => rec.extend([
                r.factor_of_safety_value()
                    .map_or(String::new(), |f| f.to_string()),
                r.reason.as_str().to_string(),
                r.t_s.to_string(),
                r.travel_m.to_string(),
                r.yaw_deg.to_string(),
                r.x_m.to_string(),
                r.z_m.to_string(),
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
        w.write_record(&rec)?;
    }
    w.flush()?;
    Ok(())
}
