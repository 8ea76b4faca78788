//! The work–precision picture of `slideroute report`: error of the route against run time,
//! log–log, one line per scene, dynamics, pose method, mode and integrator (and the paper's
//! dynamics over tolerances apart from its ladder of increments); the legend in the
//! panel. Every series has a colour and a marker of its own: the colour tells the dynamics,
//! method, mode and integrator, the marker (and a dashed line) the scene.

use super::sheet::{self, Entry, Mark, Res, Shape, Sheet, err};
use crate::output::work_precision::ladder::Point;
use plotters::prelude::*;
use std::path::Path;

/// Ten colours apart from each other on white (Tableau's ten, the olive and cyan darkened).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(90, 90, 90),
    RGBColor(160, 160, 20),
    RGBColor(20, 160, 180),
];

/// How a series is drawn: its colour, its marker and whether its line is dashed.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Style {
    color: RGBColor,
    shape: Shape,
    dashed: bool,
}

/// One series: its scene, what else tells it apart (dynamics, method, mode, integrator), and
/// its points (wall time, error).
struct Line {
    scene: String,
    how: String,
    points: Vec<(f64, f64)>,
}

/// The series of `points` with an error and a time above zero, in the order they come.
fn lines(points: &[Point]) -> Vec<Line> {
    let mut out: Vec<Line> = Vec::new();
    for p in points.iter().filter(|p| p.error_m > 0.0 && p.wall_s > 0.0) {
        // The paper's dynamics over tolerances is a series apart from its ladder of increments.
        let by_tolerance = p.dynamics == crate::DynamicsModel::Paper && p.tolerance.is_some();
        let how = format!(
            "{}: {} {} {}{}",
            p.dynamics.as_str(),
            p.method.as_str(),
            p.mode.as_str(),
            p.integrator.as_str(),
            if by_tolerance { " by tolerance" } else { "" }
        );
        match out.iter_mut().find(|l| l.scene == p.scene && l.how == how) {
            Some(l) => l.points.push((p.wall_s, p.error_m)),
            None => out.push(Line {
                scene: p.scene.clone(),
                how,
                points: vec![(p.wall_s, p.error_m)],
            }),
        }
    }
    out
}

/// Each line's style: a colour for each way of running (dynamics, method, mode, integrator),
/// a marker and a dash for each scene; past ten ways the markers move on, so that no two lines
/// share colour and marker while there are fewer than forty of them.
fn styles(lines: &[Line]) -> Vec<Style> {
    let mut hows: Vec<&str> = Vec::new();
    let mut scenes: Vec<&str> = Vec::new();
    for l in lines {
        if !hows.contains(&l.how.as_str()) {
            hows.push(&l.how);
        }
        if !scenes.contains(&l.scene.as_str()) {
            scenes.push(&l.scene);
        }
    }
    let rounds = hows.len().div_ceil(PALETTE.len()).max(1);
    lines
        .iter()
        .map(|l| {
            let c = hows.iter().position(|h| *h == l.how).unwrap_or(0);
            let s = scenes.iter().position(|h| *h == l.scene).unwrap_or(0);
            Style {
                color: PALETTE[c % PALETTE.len()],
                shape: Shape::ALL[(s * rounds + c / PALETTE.len()) % Shape::ALL.len()],
                dashed: s % 2 == 1,
            }
        })
        .collect()
}

/// Log–log error against wall time, one line per series (scene, dynamics, method, mode,
/// integrator), each in its own colour and marker.
pub fn work_precision(path: &Path, points: &[Point]) -> Res<()> {
    let mut lines = lines(points);
    let title = "work–precision: error of the route against run time";
    let all: Vec<(f64, f64)> = lines.iter().flat_map(|l| l.points.clone()).collect();
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
    let sheet = Sheet::new(path, (1300, 1040), title)?;
    let mut chart = ChartBuilder::on(&sheet.chart)
        .margin(10)
        .x_label_area_size(50)
        .y_label_area_size(90)
        .build_cartesian_2d(
            (t0 / 1.5..t1 * 1.5).log_scale(),
            (e0 / 3.0..e1 * 3.0).log_scale(),
        )
        .map_err(err(path))?;
    chart
        .configure_mesh()
        .label_style(sheet::label_font())
        .axis_desc_style(sheet::label_font())
        .max_light_lines(1)
        .x_desc("wall time of the route (s)")
        .y_desc("largest CM error against the reference (m)")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(err(path))?;
    let styles = styles(&lines);
    let mut entries = Vec::new();
    for (line, style) in lines.iter_mut().zip(&styles) {
        line.points.sort_by(|a, b| a.0.total_cmp(&b.0));
        let pts = line.points.clone();
        let stroke = style.color.stroke_width(2);
        if style.dashed {
            chart
                .draw_series(DashedLineSeries::new(pts.clone(), 6, 4, stroke))
                .map_err(err(path))?;
        } else {
            chart
                .draw_series(LineSeries::new(pts.clone(), stroke))
                .map_err(err(path))?;
        }
        let area = chart.plotting_area().strip_coord_spec();
        let (ox, oy) = area.get_base_pixel();
        for p in &pts {
            let (x, y) = chart.backend_coord(p);
            sheet::draw_shape(&area, style.shape, style.color, (x - ox, y - oy))
                .map_err(err(path))?;
        }
        entries.push(Entry::new(
            Mark::Series(style.color, style.shape, style.dashed),
            format!("{}, {}", line.scene, line.how),
        ));
    }
    entries.insert(
        0,
        Entry::new(
            Mark::None,
            "scene, dynamics: pose method, mode, integrator; each dynamics against its own \
             reference",
        ),
    );
    let y = sheet::heading(path, &sheet.panel, "Series", 0)?;
    sheet::legend(path, &sheet.panel, &entries, y)?;
    sheet.root.present().map_err(err(path))
}
