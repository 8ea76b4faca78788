//! A short route enlarged in the panel of the plan view, at equal scales.

use super::{P, Track};
use crate::output::plots::sheet::{self, Area, Res, err};
use plotters::prelude::*;
use std::path::Path;

/// `v` to two significant digits (a magnification needs no more).
fn round_2(v: f64) -> f64 {
    if v <= 0.0 || !v.is_finite() {
        return v;
    }
    let e = 10f64.powi(v.log10().floor() as i32 - 1);
    (v / e).round() * e
}

/// The CM paths enlarged, at equal scales, in the lower part of the panel from `y`; the
/// caption says how much against the plan's `main_scale` (m per pixel).
pub(super) fn draw_inset(
    path: &Path,
    panel: &Area,
    y: i32,
    tracks: &[Track],
    main_scale: f64,
) -> Res<()> {
    let (_, ph) = panel.dim_in_pixel();
    let top = (y.max(0) as u32).min(ph.saturating_sub(200));
    let (_, area) = panel.split_vertically(top);
    let (w, h) = area.dim_in_pixel();
    let cm: Vec<P> = tracks
        .iter()
        .flat_map(|t| t.rows.iter().map(|r| (r.x_m, r.z_m)))
        .collect();
    let (mut x0, mut x1) = sheet::ranges(cm.iter().map(|p| p.0));
    let (mut z0, mut z1) = sheet::ranges(cm.iter().map(|p| p.1));
    let (pw, ph) = (f64::from(w - 60), f64::from(h - 70));
    let scale = ((x1 - x0) / pw).max((z1 - z0) / ph);
    let (cx, cz) = (0.5 * (x0 + x1), 0.5 * (z0 + z1));
    (x0, x1) = (cx - 0.5 * scale * pw, cx + 0.5 * scale * pw);
    (z0, z1) = (cz - 0.5 * scale * ph, cz + 0.5 * scale * ph);
    let zoom = main_scale / scale;
    let mut chart = ChartBuilder::on(&area)
        .caption(
            format!(
                "CM path enlarged {}× (boxed on the plan)",
                sheet::short(round_2(zoom))
            ),
            ("sans-serif", sheet::FONT),
        )
        .margin(4)
        .x_label_area_size(30)
        .y_label_area_size(55)
        .build_cartesian_2d(x0..x1, z1..z0)
        .map_err(err(path))?;
    let (fx, fz) = (sheet::ticks(x0, x1), sheet::ticks(z0, z1));
    chart
        .configure_mesh()
        .label_style(sheet::label_font())
        .axis_desc_style(sheet::label_font())
        .max_light_lines(0)
        .x_labels(4)
        .y_labels(4)
        .x_label_formatter(&fx)
        .y_label_formatter(&fz)
        .draw()
        .map_err(err(path))?;
    for t in tracks {
        chart
            .draw_series(LineSeries::new(
                t.rows.iter().map(|r| (r.x_m, r.z_m)),
                t.color.stroke_width(2),
            ))
            .map_err(err(path))?;
        if let (Some(a), Some(b)) = (t.rows.first(), t.rows.last()) {
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at((a.x_m, a.z_m)) + Circle::new((0, 0), 4, t.color.filled()),
                ))
                .map_err(err(path))?;
            chart
                .draw_series(std::iter::once(
                    EmptyElement::at((b.x_m, b.z_m))
                        + Circle::new((0, 0), 4, WHITE.filled())
                        + Circle::new((0, 0), 4, t.color.stroke_width(2)),
                ))
                .map_err(err(path))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn magnifications_have_two_significant_digits() {
        assert_eq!(sheet::short(round_2(3.043e8)), "3×10⁸");
        assert_eq!(sheet::short(round_2(87.4)), "87");
        assert_eq!(sheet::short(round_2(111.2)), "110");
    }
}
