//! Pictures of a route (SVG, pure Rust): the plan view like the paper's Figure 12, the CM
//! profile, the angles and the reactions against time.

use crate::geometry::planes::r as strike_2_distance;
use crate::geometry::{Displacement, Pose};
use crate::route::{Route, Row};
use crate::scene::Scene;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

type Res<T> = Result<T, String>;

fn err(path: &Path) -> impl Fn(String) -> String + '_ {
    move |e| format!("{}: cannot draw: {e}", path.display())
}

fn ranges(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|v| v.is_finite()) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let pad = ((hi - lo) * 0.05)
        .max(1e-9)
        .max(1e-3 * hi.abs().max(lo.abs()));
    (lo - pad, hi + pad)
}

/// The part of the line through `p` with direction `d` inside [x0, x1] × [z0, z1]
/// (Liang–Barsky); plotters would otherwise clamp, not clip, points outside the chart.
fn clip_line(
    p: (f64, f64),
    d: (f64, f64),
    x0: f64,
    x1: f64,
    z0: f64,
    z1: f64,
) -> Option<[(f64, f64); 2]> {
    let (mut t0, mut t1) = (f64::NEG_INFINITY, f64::INFINITY);
    for (pv, dv, lo, hi) in [(p.0, d.0, x0, x1), (p.1, d.1, z0, z1)] {
        if dv == 0.0 {
            if pv < lo || pv > hi {
                return None;
            }
        } else {
            let (a, b) = ((lo - pv) / dv, (hi - pv) / dv);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
    }
    (t0 < t1).then_some([
        (p.0 + t0 * d.0, p.1 + t0 * d.1),
        (p.0 + t1 * d.0, p.1 + t1 * d.1),
    ])
}

fn vertices(scene: &Scene, row: &Row) -> Option<[(f64, f64); 3]> {
    let d = Displacement::new(row.x_m, row.z_m, row.theta_deg.to_radians());
    let p = Pose::from_tilts(
        scene,
        d,
        row.alpha_deg.to_radians(),
        row.beta_deg.to_radians(),
    )
    .ok()?;
    Some(p.vertices.map(|v| (v.x, v.z)))
}

/// Plan view from above: X to the right, Z down the page (so the view is right-handed with
/// Y towards the viewer). CM path, the contact frame at intervals, the strike lines of planes
/// 1 and 2, and the contact points at the start (circles) and end (crosses).
pub fn plan(path: &Path, scene: &Scene, route: &Route) -> Res<()> {
    let title = format!(
        "{}: plan view from above — {} after {:.2} s",
        route.scene, route.termination.reason, route.termination.t_s
    );
    plan_routes(
        path,
        scene,
        &title,
        &[("path of the centre of mass", &route.rows, RED)],
    )
}

/// Frame outlines every 1/8 of a route's rows (and at its end).
fn outlines_of(scene: &Scene, rows: &[Row]) -> Vec<[(f64, f64); 3]> {
    let every = (rows.len() / 8).max(1);
    rows.iter()
        .enumerate()
        .filter(|(k, _)| k % every == 0 || *k + 1 == rows.len())
        .filter_map(|(_, r)| vertices(scene, r))
        .collect()
}

/// The most points a picture draws of a route (issue #13): past this, rows are thinned evenly
/// (the first and last always kept), so that no picture grows with the route's length — about
/// 0.5 MB for the largest, the reactions, whatever the number of increments.
pub const MAX_POINTS: usize = 4000;

/// The rows a picture draws: all of them up to [`MAX_POINTS`], else every k-th and the last.
pub fn thinned(rows: &[Row]) -> Vec<Row> {
    if rows.len() <= MAX_POINTS {
        return rows.to_vec();
    }
    let every = rows.len().div_ceil(MAX_POINTS - 1);
    rows.iter()
        .enumerate()
        .filter(|(k, _)| k % every == 0 || *k + 1 == rows.len())
        .map(|(_, r)| *r)
        .collect()
}

/// The plan view of one or more routes of the same scene, each CM path and its frame outlines
/// in its own colour (the first route's start and end contacts marked).
pub fn plan_routes(
    path: &Path,
    scene: &Scene,
    title: &str,
    routes: &[(&str, &[Row], RGBColor)],
) -> Res<()> {
    let thin: Vec<Vec<Row>> = routes.iter().map(|r| thinned(r.1)).collect();
    let routes: Vec<(&str, &[Row], RGBColor)> = routes
        .iter()
        .zip(&thin)
        .map(|(r, t)| (r.0, t.as_slice(), r.2))
        .collect();
    let routes = routes.as_slice();
    let all_outlines: Vec<Vec<[(f64, f64); 3]>> =
        routes.iter().map(|r| outlines_of(scene, r.1)).collect();
    let outlines: &[[(f64, f64); 3]] = all_outlines.first().map_or(&[], |o| o.as_slice());
    let xs = routes
        .iter()
        .flat_map(|r| r.1.iter().map(|r| r.x_m))
        .chain(all_outlines.iter().flatten().flat_map(|o| o.map(|p| p.0)));
    let zs = routes
        .iter()
        .flat_map(|r| r.1.iter().map(|r| r.z_m))
        .chain(all_outlines.iter().flatten().flat_map(|o| o.map(|p| p.1)));
    let (mut x0, mut x1) = ranges(xs);
    let (mut z0, mut z1) = ranges(zs);
    // Equal scales on both axes.
    let (w, h) = (900u32, 700u32);
    let (plot_w, plot_h) = (f64::from(w) - 90.0, f64::from(h) - 90.0);
    let scale = ((x1 - x0) / plot_w).max((z1 - z0) / plot_h);
    let (cx, cz) = (0.5 * (x0 + x1), 0.5 * (z0 + z1));
    x0 = cx - 0.5 * scale * plot_w;
    x1 = cx + 0.5 * scale * plot_w;
    z0 = cz - 0.5 * scale * plot_h;
    z1 = cz + 0.5 * scale * plot_h;

    let root = SVGBackend::new(path, (w, h)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(path)(e.to_string()))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(x0..x1, z1..z0)
        .map_err(|e| err(path)(e.to_string()))?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .x_desc("X (m), forward")
        .y_desc("Z (m), lateral (down the page)")
        .draw()
        .map_err(|e| err(path)(e.to_string()))?;
    let g = &scene.foundation;
    // Strike of plane 1: X = L2X; strike of plane 2: n·(X, Z) = R, n = (cos κ, −sin κ).
    let l2x = scene.frame.l2x;
    let strike1 = clip_line((l2x, 0.0), (0.0, 1.0), x0, x1, z0, z1);
    chart
        .draw_series(LineSeries::new(
            strike1.into_iter().flatten(),
            BLUE.stroke_width(2),
        ))
        .map_err(|e| err(path)(e.to_string()))?
        .label("int. line 1/horiz (strike of plane 1)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLUE.stroke_width(2)));
    let (sk, ck) = g.kappa.sin_cos();
    let r = strike_2_distance(scene);
    let strike2 = clip_line((r * ck, -r * sk), (sk, ck), x0, x1, z0, z1);
    let dark_green = RGBColor(0, 140, 60);
    chart
        .draw_series(LineSeries::new(
            strike2.into_iter().flatten(),
            dark_green.stroke_width(2),
        ))
        .map_err(|e| err(path)(e.to_string()))?
        .label("int. line 2/horiz (strike of plane 2)")
        .legend(move |(x, y)| {
            PathElement::new(vec![(x, y), (x + 20, y)], dark_green.stroke_width(2))
        });
    for (r, (outlines, &(name, rows, color))) in all_outlines.iter().zip(routes).enumerate() {
        let ink = if r == 0 { BLACK } else { color };
        for (k, o) in outlines.iter().enumerate() {
            let mut pts = o.to_vec();
            pts.push(o[0]);
            let style = if k == 0 || k + 1 == outlines.len() {
                ink.stroke_width(2)
            } else {
                ink.mix(0.35).stroke_width(1)
            };
            chart
                .draw_series(std::iter::once(PathElement::new(pts, style)))
                .map_err(|e| err(path)(e.to_string()))?;
        }
        chart
            .draw_series(LineSeries::new(
                rows.iter().map(|r| (r.x_m, r.z_m)),
                color.stroke_width(2),
            ))
            .map_err(|e| err(path)(e.to_string()))?
            .label(name)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
    }
    if let (Some(first), Some(last)) = (outlines.first(), outlines.last()) {
        chart
            .draw_series(first.iter().map(|&p| Circle::new(p, 5, BLACK.filled())))
            .map_err(|e| err(path)(e.to_string()))?
            .label("contacts 0, 1, 2 at the start (frame outline every 1/8 of the route)")
            .legend(|(x, y)| Circle::new((x + 10, y), 4, BLACK.filled()));
        chart
            .draw_series(
                last.iter()
                    .map(|&p| Cross::new(p, 6, BLACK.stroke_width(2))),
            )
            .map_err(|e| err(path)(e.to_string()))?
            .label("contacts at the end")
            .legend(|(x, y)| Cross::new((x + 10, y), 5, BLACK.stroke_width(2)));
        for (i, &(x, z)) in first.iter().enumerate() {
            chart
                .draw_series(std::iter::once(Text::new(
                    format!("{i}"),
                    (x, z),
                    ("sans-serif", 14),
                )))
                .map_err(|e| err(path)(e.to_string()))?;
        }
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.92))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()
        .map_err(|e| err(path)(e.to_string()))?;
    root.present().map_err(|e| err(path)(e.to_string()))
}

type LinearChart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// A white 900×500 chart with linear axes, a caption and axis descriptions.
fn linear_chart<'a, 'b: 'a>(
    root: &'a DrawingArea<SVGBackend<'b>, plotters::coord::Shift>,
    path: &Path,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Res<LinearChart<'a, 'b>> {
    root.fill(&WHITE).map_err(|e| err(path)(e.to_string()))?;
    let mut chart = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| err(path)(e.to_string()))?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()
        .map_err(|e| err(path)(e.to_string()))?;
    Ok(chart)
}

/// Several series against one x quantity.
fn lines(
    path: &Path,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    x: &[f64],
    series: &[(&str, Vec<f64>, RGBColor)],
) -> Res<()> {
    let root = SVGBackend::new(path, (900, 500)).into_drawing_area();
    let mut chart = linear_chart(
        &root,
        path,
        title,
        x_desc,
        y_desc,
        ranges(x.iter().copied()),
        ranges(series.iter().flat_map(|s| s.1.iter().copied())),
    )?;
    for (name, ys, color) in series {
        let color = *color;
        chart
            .draw_series(LineSeries::new(
                x.iter()
                    .zip(ys)
                    .filter(|(_, y)| y.is_finite())
                    .map(|(&a, &b)| (a, b)),
                color.stroke_width(2),
            ))
            .map_err(|e| err(path)(e.to_string()))?
            .label(*name)
            .legend(move |(a, b)| {
                PathElement::new(vec![(a, b), (a + 20, b)], color.stroke_width(2))
            });
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.92))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperLeft)
        .draw()
        .map_err(|e| err(path)(e.to_string()))?;
    root.present().map_err(|e| err(path)(e.to_string()))
}

const COLORS: [RGBColor; 6] = [
    RGBColor(200, 30, 30),
    RGBColor(30, 90, 200),
    RGBColor(30, 150, 60),
    RGBColor(230, 140, 0),
    RGBColor(140, 40, 170),
    RGBColor(0, 150, 160),
];

/// plan.svg, profile.svg, angles.svg, reactions.svg in `dir`.
pub fn write_route_plots(dir: &Path, scene: &Scene, route: &Route) -> Res<Vec<PathBuf>> {
    let thin = thinned(&route.rows);
    let rows = &thin;
    let t: Vec<f64> = rows.iter().map(|r| r.t_s).collect();
    let mut out = Vec::new();

    let p = dir.join("plan.svg");
    plan(&p, scene, route)?;
    out.push(p);

    // Distance travelled by the CM (3-D path length).
    let mut s = Vec::with_capacity(rows.len());
    let mut acc = 0.0;
    for (k, r) in rows.iter().enumerate() {
        if k > 0 {
            let q = &rows[k - 1];
            acc += ((r.x_m - q.x_m).powi(2) + (r.y_m - q.y_m).powi(2) + (r.z_m - q.z_m).powi(2))
                .sqrt();
        }
        s.push(acc);
    }
    let p = dir.join("profile.svg");
    lines(
        &p,
        &format!("{}: elevation of the centre of mass", route.scene),
        "distance travelled by the CM (m)",
        "CM height Y (m)",
        &s,
        &[("CM height", rows.iter().map(|r| r.y_m).collect(), COLORS[0])],
    )?;
    out.push(p);

    let p = dir.join("angles.svg");
    lines(
        &p,
        &format!("{}: tilts and yaw", route.scene),
        "time (s)",
        "angle (°)",
        &t,
        &[
            (
                "α: tilt of side 01",
                rows.iter().map(|r| r.alpha_deg).collect(),
                COLORS[0],
            ),
            (
                "β: tilt of side 02",
                rows.iter().map(|r| r.beta_deg).collect(),
                COLORS[1],
            ),
            (
                "γ: tilt of side 1→2",
                rows.iter().map(|r| r.gamma_deg).collect(),
                COLORS[2],
            ),
            (
                "θ: yaw",
                rows.iter().map(|r| r.theta_deg).collect(),
                COLORS[3],
            ),
        ],
    )?;
    out.push(p);

    let mn = |pick: fn(&Row) -> Option<[f64; 3]>, i: usize| -> Vec<f64> {
        rows.iter()
            .map(|r| pick(r).map_or(f64::NAN, |v| v[i] / 1e6))
            .collect()
    };
    let p = dir.join("reactions.svg");
    lines(
        &p,
        &format!("{}: contact reactions", route.scene),
        "time (s)",
        "force (MN)",
        &t,
        &[
            ("N0 normal, contact 0", mn(|r| r.n_n, 0), COLORS[0]),
            ("N1 normal, contact 1", mn(|r| r.n_n, 1), COLORS[1]),
            ("N2 normal, contact 2", mn(|r| r.n_n, 2), COLORS[2]),
            ("S0 shear, contact 0", mn(|r| r.s_n, 0), COLORS[3]),
            ("S1 shear, contact 1", mn(|r| r.s_n, 1), COLORS[4]),
            ("S2 shear, contact 2", mn(|r| r.s_n, 2), COLORS[5]),
        ],
    )?;
    out.push(p);
    Ok(out)
}

/// Travel against the first varied key, one line per combination of the other keys (at most
/// six; beyond that, points only). `keys` are the varied keys, `rows` (values, travel, reason).
#[cfg(feature = "cli")]
pub fn sweep(
    path: &Path,
    varies: &[crate::sweep::Vary],
    rows: &[crate::sweep::SweepRow],
) -> Res<()> {
    use std::collections::BTreeMap;
    let Some(first) = varies.first() else {
        return Ok(());
    };
    let mut groups: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for r in rows {
        let label = varies[1..]
            .iter()
            .zip(&r.values[1..])
            .map(|(v, &x)| match v.words {
                Some(_) => format!("{} = {}", v.key, v.cell(x)),
                None => format!("{} = {x:.4}", v.key),
            })
            .collect::<Vec<_>>()
            .join(", ");
        if let Some(t) = r.travel_m {
            groups.entry(label).or_default().push((r.values[0], t));
        }
    }
    let title = if varies.len() > 1 && rows.len() > COLORS.len() * first.values.len() {
        format!(
            "travel of the centre of mass against {} (all combinations of the other keys)",
            first.key
        )
    } else {
        format!("travel of the centre of mass against {}", first.key)
    };
    let root = SVGBackend::new(path, (900, 500)).into_drawing_area();
    let mut chart = linear_chart(
        &root,
        path,
        &title,
        &match &first.words {
            Some(w) => format!(
                "{} ({})",
                first.key,
                w.iter()
                    .enumerate()
                    .map(|(k, w)| format!("{k} = {w}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            None => first.key.clone(),
        },
        "travel (m)",
        ranges(rows.iter().map(|r| r.values[0])),
        ranges(rows.iter().filter_map(|r| r.travel_m).chain([0.0])),
    )?;
    let few = groups.len() <= COLORS.len();
    for (k, (label, mut pts)) in groups.into_iter().enumerate() {
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        // Beyond six groups colours would need a legend too long to read: one colour.
        let color = if few {
            COLORS[k % COLORS.len()]
        } else {
            COLORS[1]
        };
        if few {
            let s = chart
                .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                .map_err(|e| err(path)(e.to_string()))?;
            if !label.is_empty() {
                s.label(label).legend(move |(a, b)| {
                    PathElement::new(vec![(a, b), (a + 20, b)], color.stroke_width(2))
                });
            }
        }
        chart
            .draw_series(pts.into_iter().map(|p| Circle::new(p, 3, color.filled())))
            .map_err(|e| err(path)(e.to_string()))?;
    }
    if few && varies.len() > 1 {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.92))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperLeft)
            .draw()
            .map_err(|e| err(path)(e.to_string()))?;
    }
    root.present().map_err(|e| err(path)(e.to_string()))
}

/// Log–log error against wall time, one line per series (scene, method, mode, integrator).
#[cfg(feature = "cli")]
pub fn work_precision(path: &Path, points: &[crate::report::Point]) -> Res<()> {
    use std::collections::BTreeMap;
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
    let all: Vec<(f64, f64)> = series.values().flatten().copied().collect();
    let (t0, t1) = all
        .iter()
        .fold((f64::INFINITY, 0.0f64), |a, p| (a.0.min(p.0), a.1.max(p.0)));
    let (e0, e1) = all
        .iter()
        .fold((f64::INFINITY, 0.0f64), |a, p| (a.0.min(p.1), a.1.max(p.1)));
    if all.is_empty() {
        return Ok(());
    }
    let root = SVGBackend::new(path, (1000, 700)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(path)(e.to_string()))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "work–precision: error of the route against run time",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(
            (t0 / 1.5..t1 * 1.5).log_scale(),
            (e0 / 3.0..e1 * 3.0).log_scale(),
        )
        .map_err(|e| err(path)(e.to_string()))?;
    chart
        .configure_mesh()
        .max_light_lines(1)
        .x_desc("wall time of the route (s)")
        .y_desc("largest CM error against the reference (m)")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(|e| err(path)(e.to_string()))?;
    let palette = [
        RGBColor(200, 30, 30),
        RGBColor(30, 90, 200),
        RGBColor(30, 150, 60),
        RGBColor(230, 140, 0),
        RGBColor(140, 40, 170),
        RGBColor(0, 150, 160),
        RGBColor(120, 80, 40),
        RGBColor(90, 90, 90),
    ];
    for (k, (name, mut pts)) in series.into_iter().enumerate() {
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        let color = palette[k % palette.len()];
        let dashed = k >= palette.len();
        let style = if dashed {
            color.stroke_width(1)
        } else {
            color.stroke_width(2)
        };
        chart
            .draw_series(LineSeries::new(pts.clone(), style))
            .map_err(|e| err(path)(e.to_string()))?
            .label(name)
            .legend(move |(a, b)| PathElement::new(vec![(a, b), (a + 20, b)], style));
        chart
            .draw_series(
                pts.into_iter()
                    .map(|p| Circle::new(p, if dashed { 2 } else { 3 }, color.filled())),
            )
            .map_err(|e| err(path)(e.to_string()))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.92))
        .border_style(BLACK)
        .label_font(("sans-serif", 11))
        .position(SeriesLabelPosition::LowerLeft)
        .draw()
        .map_err(|e| err(path)(e.to_string()))?;
    root.present().map_err(|e| err(path)(e.to_string()))
}
