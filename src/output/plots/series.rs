//! Quantities of a route against time or distance: the CM profile, the angles, the reactions.
//! The legend is in the side panel, never on the data.

use super::sheet::{self, Entry, Mark, Res, Sheet, err};
use plotters::prelude::*;
use std::path::Path;

/// Sheet size of a time series (pixels).
pub(super) const SIZE: (u32, u32) = (1200, 520);

/// One line: its legend, its values (NaN where it has none) and its colour.
pub(super) struct Series<'a> {
    pub name: &'a str,
    pub values: Vec<f64>,
    pub color: RGBColor,
}

/// What the axes of a time series say: the x quantity and the y quantity, with units.
#[derive(Debug, Clone, Copy)]
pub(super) struct Axes<'a> {
    pub x: &'a str,
    pub y: &'a str,
}

/// Several series against one x quantity; `notes` under the legend.
pub(super) fn lines(
    path: &Path,
    title: &str,
    axes: Axes,
    x: &[f64],
    series: &[Series],
    notes: &[Entry],
) -> Res<()> {
    let sheet = Sheet::new(path, SIZE, title)?;
    let (x0, x1) = sheet::ranges(x.iter().copied());
    let (y0, y1) = sheet::ranges(series.iter().flat_map(|s| s.values.iter().copied()));
    let mut chart = ChartBuilder::on(&sheet.chart)
        .margin(10)
        .x_label_area_size(50)
        .y_label_area_size(85)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err(path))?;
    let (fx, fy) = (sheet::ticks(x0, x1), sheet::ticks(y0, y1));
    chart
        .configure_mesh()
        .label_style(sheet::label_font())
        .axis_desc_style(sheet::label_font())
        .max_light_lines(1)
        .x_desc(axes.x)
        .y_desc(axes.y)
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .draw()
        .map_err(err(path))?;
    for s in series {
        // A NaN breaks the line (a reaction the route could not have at its last row).
        let mut run: Vec<(f64, f64)> = Vec::new();
        let points = x.iter().zip(&s.values);
        for (&a, &b) in points {
            if b.is_finite() {
                run.push((a, b));
            } else if !run.is_empty() {
                chart
                    .draw_series(LineSeries::new(
                        std::mem::take(&mut run),
                        s.color.stroke_width(2),
                    ))
                    .map_err(err(path))?;
            }
        }
        chart
            .draw_series(LineSeries::new(run, s.color.stroke_width(2)))
            .map_err(err(path))?;
    }
    let entries: Vec<Entry> = series
        .iter()
        .map(|s| Entry::new(Mark::Line(s.color), s.name))
        .collect();
    let mut y = sheet::heading(path, &sheet.panel, "Legend", 0)?;
    y = sheet::legend(path, &sheet.panel, &entries, y)?;
    if !notes.is_empty() {
        y = sheet::heading(path, &sheet.panel, "Route", y + 6)?;
        sheet::legend(path, &sheet.panel, notes, y)?;
    }
    sheet.root.present().map_err(err(path))
}
