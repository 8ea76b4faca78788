//! Pictures (SVG, pure Rust) an engineer reads at a glance: the plan view
//! like the paper's Figure 12, the CM profile, the angles and the reactions against time, the
//! sweep and the work–precision report. Every picture keeps its legend in a side panel, off the
//! data; a route that does not move gets a picture that says why instead of empty axes; no
//! picture grows with the route's length ([`MAX_POINTS`]).

mod plan;
mod probabilistic;
mod series;
mod sheet;
mod sweep;
mod work_precision;

pub(crate) use probabilistic::write_probabilistic_plots;
pub(crate) use sweep::{Drawn, sweep_drawn};
pub(crate) use work_precision::work_precision;

use super::OutputError;
use super::folder::write_whole;
use crate::FactorOfSafety;
use crate::Scene;
use crate::numeric::{fixed, seconds};
use crate::{Reason, Route, Row};
use plan::{PlanView, Track};
use plotters::style::RGBColor;
use series::Series;
use sheet::{Entry, Mark, Res};
use std::path::{Path, PathBuf};

/// The most points a picture draws of a route: past this, rows are thinned evenly
/// (the first and last always kept), so that no picture grows with the route's length — about
/// 0.5 MB for the largest, the reactions, whatever the number of increments.
const MAX_POINTS: usize = 4000;

/// The rows a picture draws: all of them up to [`MAX_POINTS`], else every k-th and the last.
fn thinned(rows: &[Row]) -> Vec<Row> {
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

const COLORS: [RGBColor; 6] = [
    RGBColor(200, 30, 30),
    RGBColor(30, 90, 200),
    RGBColor(30, 150, 60),
    RGBColor(230, 140, 0),
    RGBColor(140, 40, 170),
    RGBColor(0, 150, 160),
];

/// The factor of safety in a few words.
fn fs_words(fs: Option<FactorOfSafety>) -> String {
    match fs {
        Some(FactorOfSafety::Finite { value }) => format!("factor of safety {value:.4}"),
        Some(FactorOfSafety::Unbounded) => "factor of safety unbounded".into(),
        Some(FactorOfSafety::NotHoldable) => {
            "no factor of safety: the weight alone slides the block".into()
        }
        None => "factor of safety not known".into(),
    }
}

/// How the route ended, its travel and its factor of safety, for a picture's panel.
fn route_notes(route: &Route) -> Vec<Entry> {
    // No-break spaces keep a number with its unit when the panel wraps the line.
    let mut notes = vec![Entry::new(
        Mark::None,
        format!(
            "{} at t\u{a0}=\u{a0}{}\u{a0}s",
            route.termination.reason,
            seconds(route.termination.t_s)
        ),
    )];
    if let Some(last) = route.rows.last() {
        notes.push(Entry::new(
            Mark::None,
            format!(
                "travel {}\u{a0}m; final yaw θ\u{a0}=\u{a0}{}°",
                fixed(route.travel_m, 3),
                fixed(last.theta_deg, 2)
            ),
        ));
    }
    notes.push(Entry::new(Mark::None, fs_words(route.factor_of_safety)));
    notes.push(Entry::new(
        Mark::None,
        format!(
            "{} dynamics, {} mode, {} increments",
            route.dynamics.as_str(),
            route.mode.as_str(),
            route.increments
        ),
    ));
    notes
}

/// Whether the route has anything to draw against time (it moved past its first row).
fn moved(route: &Route) -> bool {
    route.rows.len() > 1
}

/// Why a route has nothing to draw against time, in sentences.
fn still_words(route: &Route, what: &str) -> Vec<String> {
    let t = &route.termination;
    let first = if t.reason == Reason::DoesNotSlide {
        format!(
            "{} does not slide: static friction {} holds the block under its weight and the \
             water load ({}).",
            route.scene,
            if route.base().is_some() {
                "under its base"
            } else {
                "within the three contacts' cones"
            },
            fs_words(route.factor_of_safety)
        )
    } else {
        format!(
            "The route of {} ended at once (t = {} s): {}. {}",
            route.scene,
            seconds(t.t_s),
            t.reason,
            fs_words(route.factor_of_safety)
        )
    };
    let mut lines = vec![first];
    if !t.detail.is_empty() && t.reason != Reason::DoesNotSlide {
        lines.push(t.detail.clone());
    }
    lines.push(format!(
        "The block does not move, so there are no {what} to draw; plan.svg shows the scene at rest."
    ));
    lines
}

impl Route {
    /// The plan view from above (`plan.svg`), like the paper's Figure 12: the foundation's
    /// planes or faces shaded and named, the path of the centre of mass, the block's outline at
    /// the start, every so often and at the end, where a contact changes face, the water's
    /// push on its line, and how the route ended; written whole to `path` (SVG), or not at all.
    /// `scene` is the route's own (its foundation and block).
    ///
    /// ```
    /// let scene = slideroute::Scene::default_scene();
    /// let route = slideroute::run(&scene)?;
    /// let path = std::env::temp_dir().join(format!("slideroute-doc-plan-{}.svg", std::process::id()));
    /// route.plot_plan(&scene, &path)?;
    /// assert!(std::fs::read_to_string(&path)?.starts_with("<svg"));
    /// # std::fs::remove_file(&path)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn plot_plan(&self, scene: &Scene, path: &Path) -> Result<(), OutputError> {
        write_whole(path, |tmp| plan(tmp, scene, self))
    }
}

/// The plan view of one route.
fn plan(path: &Path, scene: &Scene, route: &Route) -> Res<()> {
    let rows = thinned(&route.rows);
    let title = if route.termination.reason == Reason::DoesNotSlide {
        format!(
            "{}: plan view from above — does not slide ({})",
            route.scene,
            fs_words(route.factor_of_safety)
        )
    } else {
        format!(
            "{}: plan view from above — {} at t = {} s",
            route.scene,
            route.termination.reason,
            seconds(route.termination.t_s)
        )
    };
    plan::plan_view(
        path,
        scene,
        &PlanView {
            title: &title,
            tracks: &[Track {
                name: "path of the centre of mass (CM)".into(),
                who: "the route".into(),
                rows: &rows,
                color: COLORS[0],
                base: route.base(),
            }],
            fan: None,
            notes: &route_notes(route),
        },
    )
}

/// Both dynamics' routes of one scene on one plan view (`run --compare-dynamics`).
pub(crate) fn compare_plan(path: &Path, scene: &Scene, c: &crate::compare::Comparison) -> Res<()> {
    let (rigid, paper) = (
        thinned(&c.rigid_body.route.rows),
        thinned(&c.paper.route.rows),
    );
    let name = |what: &str, r: &Route| {
        format!(
            "{what}: CM path ({} at t = {} s, travel {} m)",
            r.termination.reason,
            seconds(r.termination.t_s),
            fixed(r.travel_m, 3)
        )
    };
    plan::plan_view(
        path,
        scene,
        &PlanView {
            title: &format!("{}: plan view of both dynamics", scene.name()),
            tracks: &[
                Track {
                    name: name("rigid body", &c.rigid_body.route),
                    who: "rigid body".into(),
                    rows: &rigid,
                    color: COLORS[0],
                    base: c.rigid_body.route.base(),
                },
                Track {
                    name: name("paper's dynamics", &c.paper.route),
                    who: "paper's dynamics".into(),
                    rows: &paper,
                    color: COLORS[3],
                    base: c.paper.route.base(),
                },
            ],
            fan: None,
            notes: &[Entry::new(
                Mark::None,
                fs_words(c.rigid_body.route.factor_of_safety),
            )],
        },
    )
}

/// A picture against time or distance: its file, title, axes, x values and lines, and what a
/// route that did not move has none of (said instead of empty axes).
struct Chart<'a> {
    file: &'a str,
    title: &'a str,
    axes: series::Axes<'a>,
    x: &'a [f64],
    series: Vec<Series<'a>>,
    lacks: &'a str,
}

/// plan.svg, profile.svg, angles.svg, reactions.svg in `dir`.
pub(crate) fn write_route_plots(dir: &Path, scene: &Scene, route: &Route) -> Res<Vec<PathBuf>> {
    let rows = thinned(&route.rows);
    let t: Vec<f64> = rows.iter().map(|r| r.t_s).collect();
    let s = distance(&rows);
    let notes = route_notes(route);
    let mut out = Vec::new();

    let p = dir.join("plan.svg");
    plan(&p, scene, route)?;
    out.push(p);
    for c in charts(&rows, &t, &s) {
        let p = dir.join(c.file);
        let title = format!("{}: {}", route.scene, c.title);
        if moved(route) {
            series::lines(&p, &title, c.axes, c.x, &c.series, &notes)?;
        } else {
            sheet::message(&p, series::SIZE, &title, &still_words(route, c.lacks))?;
        }
        out.push(p);
    }
    Ok(out)
}

/// The distance travelled by the CM to each row (its 3-D path's length).
fn distance(rows: &[Row]) -> Vec<f64> {
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
    s
}

/// The series `named` (their legends and values), coloured in turn from [`COLORS`].
fn coloured<'a>(named: impl IntoIterator<Item = (&'a str, Vec<f64>)>) -> Vec<Series<'a>> {
    named
        .into_iter()
        .zip(COLORS)
        .map(|((name, values), color)| Series {
            name,
            values,
            color,
        })
        .collect()
}

/// The pictures of `rows` against time `t` or distance `s`: the CM profile, the angles and the
/// reactions.
fn charts<'a>(rows: &[Row], t: &'a [f64], s: &'a [f64]) -> [Chart<'a>; 3] {
    let column = |f: fn(&Row) -> f64| -> Vec<f64> { rows.iter().map(f).collect() };
    let mn = |pick: fn(&Row) -> Option<[f64; 3]>, i: usize| -> Vec<f64> {
        rows.iter()
            .map(|r| pick(r).map_or(f64::NAN, |v| v[i] / 1e6))
            .collect()
    };
    const REACTIONS: [&str; 6] = [
        "N0 normal, contact 0",
        "N1 normal, contact 1",
        "N2 normal, contact 2",
        "S0 shear, contact 0",
        "S1 shear, contact 1",
        "S2 shear, contact 2",
    ];
    [
        Chart {
            file: "profile.svg",
            title: "elevation of the centre of mass",
            axes: series::Axes {
                x: "distance travelled by the CM (m)",
                y: "CM height Y (m)",
            },
            x: s,
            series: coloured([("CM height", column(|r| r.y_m))]),
            lacks: "heights along a path",
        },
        Chart {
            file: "angles.svg",
            title: "tilts and yaw",
            axes: series::Axes {
                x: "time (s)",
                y: "angle (°)",
            },
            x: t,
            series: coloured([
                (
                    "α: tilt of x′ (side 01 of the paper's frame)",
                    column(|r| r.alpha_deg),
                ),
                ("β: tilt of side 02", column(|r| r.beta_deg)),
                ("γ: tilt of side 1→2", column(|r| r.gamma_deg)),
                ("θ: yaw", column(|r| r.theta_deg)),
            ]),
            lacks: "angles over time",
        },
        Chart {
            file: "reactions.svg",
            title: "contact reactions",
            axes: series::Axes {
                x: "time (s)",
                y: "force (MN)",
            },
            x: t,
            series: coloured(REACTIONS.into_iter().enumerate().map(|(k, name)| {
                let values = if k < 3 {
                    mn(|r| r.n_n, k)
                } else {
                    mn(|r| r.s_n, k - 3)
                };
                (name, values)
            })),
            lacks: "reactions over time",
        },
    ]
}

#[cfg(test)]
mod tests;
