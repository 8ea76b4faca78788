//! The work–precision picture of `slideroute report`: error of the route against run time,
//! log–log, one line per scene, pose method, mode and integrator; the legend in the panel.

use super::sheet::{self, Entry, Mark, Res, Sheet, err};
use plotters::prelude::*;
use std::collections::BTreeMap;
use std::path::Path;

/// The route pictures' six colours and two more.
const PALETTE: [RGBColor; 8] = [
    super::COLORS[0],
    super::COLORS[1],
    super::COLORS[2],
    super::COLORS[3],
    super::COLORS[4],
    super::COLORS[5],
    RGBColor(120, 80, 40),
    RGBColor(90, 90, 90),
];
/// Log–log error against wall time, one line per series (scene, method, mode, integrator);
/// past eight series the colours repeat with dashed lines.
pub fn work_precision(path: &Path, points: &[crate::report::Point]) -> Res<()> {
    let mut series: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for p in points.iter().filter(|p| p.error_m > 0.0 && p.wall_s > 0.0) {
        let key = format!(
            "{} {} {} {}",
            p.scene,
            p.method.as_str(),
            p.mode.as_str(),
            p.integrator.as_str()
        );
        series.entry(key).or_default().push((p.wall_s, p.error_m));
    }
    let title = "work–precision: error of the route against run time";
    let all: Vec<(f64, f64)> = series.values().flatten().copied().collect();
    if all.is_empty() {
        return sheet::message(
            path,
            (900, 300),
            title,
            &["No point has both an error and a run time above zero: nothing to plot.".into()],
        );
    }
    let (t0, t1) = all
        .iter()
        .fold((f64::INFINITY, 0.0f64), |a, p| (a.0.min(p.0), a.1.max(p.0)));
    let (e0, e1) = all
        .iter()
        .fold((f64::INFINITY, 0.0f64), |a, p| (a.0.min(p.1), a.1.max(p.1)));
    let sheet = Sheet::new(path, (1300, 760), title)?;
    let mut chart = ChartBuilder::on(&sheet.chart)
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(
            (t0 / 1.5..t1 * 1.5).log_scale(),
            (e0 / 3.0..e1 * 3.0).log_scale(),
        )
        .map_err(err(path))?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .x_desc("wall time of the route (s)")
        .y_desc("largest CM error against the reference (m)")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(err(path))?;
    let mut entries = Vec::new();
    for (k, (name, mut pts)) in series.into_iter().enumerate() {
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let color = PALETTE[k % PALETTE.len()];
        let dashed = k >= PALETTE.len();
        if dashed {
            chart
                .draw_series(DashedLineSeries::new(
                    pts.clone(),
                    6,
                    4,
                    color.stroke_width(2),
                ))
                .map_err(err(path))?;
        } else {
            chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(err(path))?;
        }
        chart
            .draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))
            .map_err(err(path))?;
        let mark = if dashed {
            Mark::Dashed(color)
        } else {
            Mark::Line(color)
        };
        entries.push(Entry::new(mark, name));
    }
    let y = sheet::heading(path, &sheet.panel, "scene, method, mode, integrator", 0)?;
    sheet::legend(path, &sheet.panel, &entries, y)?;
    sheet.root.present().map_err(err(path))
}
