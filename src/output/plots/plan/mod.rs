//! The plan view from above, like the paper's Figure 12: the foundation's regions shaded and
//! named with their dips and down-dip arrows ([`regions`]), the strike lines or creases, the
//! hydraulic force on its line of action at the start, the contact frame along the route with
//! the contacts numbered at the start and the end ([`route`]), the CM path — enlarged in an
//! inset when it is short beside the frame ([`inset`]) — and the legend ([`legend`]). Names go
//! where they keep off the data ([`labels`]).
//!
//! [`plan_view`] draws in named steps, each over the last: the regions, their edges, a route
//! fan, the frames (a block on its base: its base's outlines) and CM paths, the changes of
//! face, the force, the contacts' numbers, where a base touched the ground, the regions'
//! names, the inset's box; then the panel.

mod inset;
mod labels;
mod legend;
mod regions;
mod route;

use super::sheet::{self, Entry, Res, Sheet, err};
use crate::{BaseReport, Row, Scene};
use labels::{along, arrow, free_spot};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use regions::{Region, area_of, foundation_regions};
use route::{Force, Outlines, face_changes, line_of_action, outlines_of};
use std::path::Path;

pub(super) const PLANE_1: RGBColor = RGBColor(30, 90, 200);
pub(super) const PLANE_2: RGBColor = RGBColor(0, 140, 60);
pub(super) const HORIZONTAL: RGBColor = RGBColor(150, 130, 100);
const FORCE: RGBColor = RGBColor(150, 30, 150);
/// The marks of a contact's change of face.
const FACE_CHANGE: RGBColor = RGBColor(200, 30, 30);
/// Where a block on its base touched the ground.
pub(super) const TOUCH: RGBColor = RGBColor(230, 120, 0);
/// The colour of a route fan.
const FAN: RGBColor = RGBColor(200, 30, 30);

/// The width of the frame's line at the start (px), over the others' 1 and 2: the legend's
/// thick line.
const START_W: u32 = sheet::THICK;
/// Font size of the contacts' numbers (16 px in the picture, above the ticks' 14.5).
const NUMBER: f64 = 20.0;
/// Font size of the regions' names (16 px).
const NAME: f64 = 20.0;
/// Sheet size of a plan view (pixels).
pub(super) const SIZE: (u32, u32) = (1200, 860);
const MARGIN: u32 = 10;
const X_LABELS: u32 = 50;
const Y_LABELS: u32 = 75;

/// A point of the plan, (X, Z) in m.
type P = (f64, f64);

/// One route on a plan view: its name in the legend, who it is where several share the plan
/// (its frames' legend says so: "rigid body"), its rows (thinned), its colour, and for a block
/// on its base its base's report (where it rested and what carried it there).
pub(super) struct Track<'r> {
    pub name: String,
    pub who: String,
    pub rows: &'r [Row],
    pub color: RGBColor,
    pub base: Option<&'r BaseReport>,
}

/// Many CM paths drawn thin under the tracks (a probabilistic analysis's route fan): each a
/// polyline in plan (X, Z in m), with what the legend says of them.
pub(super) struct Fan<'f> {
    pub paths: &'f [Vec<[f64; 2]>],
    pub name: String,
}

/// What one plan view shows: its title, the routes (the first one's frame in black), a route
/// fan if any, and the notes in the panel.
pub(super) struct PlanView<'a> {
    pub title: &'a str,
    pub tracks: &'a [Track<'a>],
    pub fan: Option<&'a Fan<'a>>,
    pub notes: &'a [Entry],
}

/// The part of the plan a chart shows (m): X across, Z down the page.
#[derive(Debug, Clone, Copy, PartialEq)]
struct View {
    x0: f64,
    x1: f64,
    z0: f64,
    z1: f64,
}

impl View {
    /// The view's corners, anticlockwise from (x0, z0).
    fn corners(&self) -> Vec<P> {
        let View { x0, x1, z0, z1 } = *self;
        vec![(x0, z0), (x1, z0), (x1, z1), (x0, z1)]
    }

    /// Whether the segment p–q runs along the view's border (and so is not an edge of the
    /// foundation).
    fn on_border(&self, p: P, q: P) -> bool {
        let View { x0, x1, z0, z1 } = *self;
        let eps = 1e-9 * (x1 - x0);
        [(p.0, q.0, x0), (p.0, q.0, x1)]
            .iter()
            .any(|&(a, b, c)| (a - c).abs() < eps && (b - c).abs() < eps)
            || [(p.1, q.1, z0), (p.1, q.1, z1)]
                .iter()
                .any(|&(a, b, c)| (a - c).abs() < eps && (b - c).abs() < eps)
    }
}

/// Whether outlines `a` and `b` are one shape on the plan (each corner within half a pixel of
/// `scale` metres).
fn same_shape(a: &[P], b: &[P], scale: f64) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(p, q)| (p.0 - q.0).hypot(p.1 - q.1) <= 0.5 * scale)
}

/// The chart of a plan view: data (X, Z) in metres on the sheet's left part.
type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draws the plan view `shown` of `scene` into `path`.
pub(super) fn plan_view(path: &Path, scene: &Scene, shown: &PlanView) -> Res<()> {
    let sheet = Sheet::new(path, SIZE, shown.title)?;
    let plan = Plan::new(scene, shown, sheet.chart.dim_in_pixel());
    let mut chart = plan.chart(path, &sheet.chart)?;
    let regions = foundation_regions(scene, plan.view);
    let surface = scene.site().ground().is_some_and(|(g, _)| g.is_surface());
    let draw = |e| err(path)(e);
    plan.shade(&mut chart, &regions, surface).map_err(draw)?;
    plan.draw_edges(&mut chart, &regions, surface)
        .map_err(draw)?;
    plan.draw_fan(&mut chart).map_err(draw)?;
    plan.draw_routes(&mut chart).map_err(draw)?;
    let first_rows = shown.tracks.first().map_or(&[][..], |t| t.rows);
    // A block on its base has no three contacts to follow from face to face.
    let changes = match plan.on_base {
        true => Vec::new(),
        false => face_changes(scene, first_rows),
    };
    plan.mark_face_changes(&mut chart, &changes).map_err(draw)?;
    let mut obstacles = plan.draw_force(&mut chart).map_err(draw)?;
    plan.number_contacts(&mut chart).map_err(draw)?;
    plan.mark_touches(&mut chart).map_err(draw)?;
    plan.name_regions(&mut chart, &regions, &mut obstacles)
        .map_err(draw)?;
    let inset = plan.box_short_route(&mut chart).map_err(draw)?;

    let drawn = legend::Drawn {
        regions: &regions,
        surface,
        force: plan.force,
        changes: &changes,
        on_base: plan.on_base,
        footprint: plan.footprint,
        touches: !plan.touches.is_empty(),
        resting: !plan.resting.is_empty(),
    };
    let entries = legend::entries(scene, shown, &drawn);
    let mut y = sheet::heading(path, &sheet.panel, "Legend", 0)?;
    y = sheet::legend(path, &sheet.panel, &entries, y)?;
    if !shown.notes.is_empty() {
        y = sheet::heading(path, &sheet.panel, "Route", y + 6)?;
        y = sheet::legend(path, &sheet.panel, shown.notes, y)?;
    }
    if inset {
        inset::draw_inset(path, &sheet.panel, y + 8, shown.tracks, plan.scale)?;
    }
    sheet.root.present().map_err(err(path))
}

/// The error of one drawing step.
type Drawing = DrawingAreaErrorKind<<SVGBackend<'static> as DrawingBackend>::ErrorType>;

/// A plan view laid out: what it shows, the frames' outlines, the force at the start, and the
/// view at equal scales on both axes.
struct Plan<'a> {
    scene: &'a Scene,
    tracks: &'a [Track<'a>],
    fan: Option<&'a Fan<'a>>,
    /// Each track's outlines ([`outlines_of`]): the frame's triangle, or the block's footprint
    /// where it has one (a block on its base: its base's polygon).
    outlines: Vec<Vec<Vec<P>>>,
    /// Each track's numbered points at the same rows: the frame's contacts, or a block on its
    /// base its base's corners.
    points: Vec<Vec<Vec<P>>>,
    /// Whether the first track's outlines are the block's footprint about a frame.
    footprint: bool,
    /// Whether the first track is a block on its base (its outlines are its base's, its
    /// numbers its corners').
    on_base: bool,
    /// Where a block on its base touched the ground at those rows: its carrying corners.
    touches: Vec<P>,
    /// What else carried a block on its base at rest: ground vertices and edges under it.
    resting: Vec<P>,
    /// The frame's side length L (m).
    l: f64,
    /// The first track's first row.
    start: Option<Row>,
    force: Option<Force>,
    /// The force arrow's length (m) and tail.
    arrow_len: f64,
    force_tail: Option<P>,
    view: View,
    /// Metres per pixel, on both axes.
    scale: f64,
}

impl<'a> Plan<'a> {
    /// The layout on a chart area of `(cw, ch)` pixels: every path, outline and the force
    /// arrow in view, with room round the frame for the regions' names.
    fn new(scene: &'a Scene, shown: &PlanView<'a>, (cw, ch): (u32, u32)) -> Self {
        let tracks = shown.tracks;
        let drawn: Vec<Outlines> = tracks
            .iter()
            .map(|t| outlines_of(scene, t.rows, t.base))
            .collect();
        let on_base = drawn.first().is_some_and(|o| o.on_base);
        let footprint = drawn.first().is_some_and(|o| o.footprint);
        let points: Vec<Vec<Vec<P>>> = drawn.iter().map(|o| o.points.clone()).collect();
        let touches: Vec<P> = drawn.iter().flat_map(|o| o.touches.clone()).collect();
        let resting: Vec<P> = drawn.iter().flat_map(|o| o.resting.clone()).collect();
        let outlines: Vec<Vec<Vec<P>>> = drawn.into_iter().map(|o| o.shapes).collect();
        let l = scene.l();
        let start = tracks.first().and_then(|t| t.rows.first()).copied();
        let force = start.as_ref().and_then(|s| line_of_action(scene, s));
        let arrow_len = 0.3 * l;
        let force_tail =
            force.map(|f| (f.at.0 - arrow_len * f.dir.0, f.at.1 - arrow_len * f.dir.1));
        let mut plan = Plan {
            scene,
            tracks,
            fan: shown.fan,
            outlines,
            points,
            footprint,
            on_base,
            touches,
            resting,
            l,
            start,
            force,
            arrow_len,
            force_tail,
            view: View {
                x0: 0.0,
                x1: 0.0,
                z0: 0.0,
                z1: 0.0,
            },
            scale: 0.0,
        };
        let mut pts: Vec<P> = tracks
            .iter()
            .flat_map(|t| t.rows.iter().map(|r| (r.x_m, r.z_m)))
            .chain(plan.outlines.iter().flatten().flatten().copied())
            .chain(plan.points.iter().flatten().flatten().copied())
            .chain(force_tail)
            .chain(force.map(|f| f.at))
            .chain(plan.fan_points())
            .collect();
        let pad = 0.15 * l;
        let plot_w = f64::from(cw - 2 * MARGIN - Y_LABELS);
        let plot_h = f64::from(ch - 2 * MARGIN - X_LABELS);
        // The force's label is as wide in pixels whatever the scale: the view grows until its
        // box is inside, clear of the axes (a few rounds; the scale grows less each time).
        for _ in 0..6 {
            let (x0, x1) = sheet::ranges(pts.iter().map(|p| p.0));
            let (z0, z1) = sheet::ranges(pts.iter().map(|p| p.1));
            let (x0, x1, z0, z1) = (x0 - pad, x1 + pad, z0 - pad, z1 + pad);
            let scale = ((x1 - x0) / plot_w).max((z1 - z0) / plot_h) * 1.04;
            let (cx, cz) = (0.5 * (x0 + x1), 0.5 * (z0 + z1));
            plan.view = View {
                x0: cx - 0.5 * scale * plot_w,
                x1: cx + 0.5 * scale * plot_w,
                z0: cz - 0.5 * scale * plot_h,
                z1: cz + 0.5 * scale * plot_h,
            };
            plan.scale = scale;
            let Some((_, [a, b])) = plan.force_label() else {
                break;
            };
            let room = 6.0 * scale;
            let v = plan.view;
            if a.0 - room >= v.x0 && b.0 + room <= v.x1 && a.1 - room >= v.z0 && b.1 + room <= v.z1
            {
                break;
            }
            pts.extend([(a.0 - room, a.1 - room), (b.0 + room, b.1 + room)]);
        }
        plan
    }

    /// The force's label: its text, where it is anchored (its right end, at mid-height) and
    /// its box's corners (least X and Z, greatest X and Z) at the current scale, about: its
    /// characters at 0.62 of the font's size.
    fn force_label(&self) -> Option<(String, [P; 2])> {
        let (force, tail) = (self.force?, self.force_tail?);
        let text = format!("F = {}", sheet::force(force.size));
        let px = sheet::FONT / 1.24;
        let (w, h) = (
            0.62 * px * text.chars().count() as f64 * self.scale,
            1.2 * px * self.scale,
        );
        let at = self.force_label_at(tail, force.dir);
        Some((text, [(at.0 - w, at.1 - 0.5 * h), (at.0, at.1 + 0.5 * h)]))
    }

    /// Where the force's label is anchored: 8 px behind the arrow's tail.
    fn force_label_at(&self, tail: P, d: P) -> P {
        let gap = 8.0 * self.scale;
        (tail.0 - gap * d.0, tail.1 - gap * d.1)
    }

    /// Every point of the route fan's paths.
    fn fan_points(&self) -> impl Iterator<Item = P> + '_ {
        self.fan
            .into_iter()
            .flat_map(|f| f.paths.iter().flatten().map(|p| (p[0], p[1])))
    }

    /// The chart and its mesh, X across and Z down the page.
    fn chart<'c, 'b>(&self, path: &Path, area: &'c sheet::Area<'b>) -> Res<Chart<'c, 'b>> {
        let View { x0, x1, z0, z1 } = self.view;
        let mut chart = ChartBuilder::on(area)
            .margin(MARGIN)
            .x_label_area_size(X_LABELS)
            .y_label_area_size(Y_LABELS)
            .build_cartesian_2d(x0..x1, z1..z0)
            .map_err(err(path))?;
        let (fx, fz) = (sheet::ticks(x0, x1), sheet::ticks(z0, z1));
        chart
            .configure_mesh()
            .label_style(sheet::label_font())
            .axis_desc_style(sheet::label_font())
            .max_light_lines(1)
            .x_desc("X (m), forward")
            .y_desc("Z (m), lateral (down the page)")
            .x_label_formatter(&fx)
            .y_label_formatter(&fz)
            .light_line_style(BLACK.mix(0.05))
            .bold_line_style(BLACK.mix(0.12))
            .draw()
            .map_err(err(path))?;
        Ok(chart)
    }

    /// The foundation's regions, shaded (a surface's triangles fully, by dip).
    fn shade(&self, chart: &mut Chart, regions: &[Region], surface: bool) -> Result<(), Drawing> {
        for r in regions.iter().filter(|r| r.poly.len() >= 3) {
            let fill = if surface {
                r.color.filled()
            } else {
                r.color.mix(0.10).filled()
            };
            chart.draw_series(std::iter::once(Polygon::new(r.poly.clone(), fill)))?;
        }
        Ok(())
    }

    /// The regions' edges inside the view: the paper's strike lines (the inclined regions'
    /// edges, in their colours), or the creases between faces (in grey).
    fn draw_edges(
        &self,
        chart: &mut Chart,
        regions: &[Region],
        surface: bool,
    ) -> Result<(), Drawing> {
        let (edged, grey) = match self.scene.site().as_paper() {
            Some(_) => (&regions[1..], false),
            None => (regions, true),
        };
        let view = self.view;
        let edges: Vec<(Vec<P>, RGBColor)> = edged
            .iter()
            .flat_map(|r| {
                let n = r.poly.len();
                let color = if grey { RGBColor(90, 90, 90) } else { r.color };
                (0..n)
                    .map(|k| (r.poly[k], r.poly[(k + 1) % n]))
                    .filter(|&(p, q)| !view.on_border(p, q))
                    .map(move |(p, q)| (vec![p, q], color))
                    .collect::<Vec<_>>()
            })
            .collect();
        let width = if surface { 1 } else { 2 };
        for (line, color) in edges {
            let color = if surface {
                color.mix(0.35)
            } else {
                color.into()
            };
            chart.draw_series(LineSeries::new(line, color.stroke_width(width)))?;
        }
        Ok(())
    }

    /// The route fan, thin and pale enough that where many paths run together reads darker,
    /// with a dot where each ended.
    fn draw_fan(&self, chart: &mut Chart) -> Result<(), Drawing> {
        let Some(f) = self.fan else {
            return Ok(());
        };
        let alpha = (3.0 / (f.paths.len().max(1) as f64).sqrt()).clamp(0.05, 0.6);
        for p in f.paths.iter().filter(|p| p.len() > 1) {
            chart.draw_series(LineSeries::new(
                p.iter().map(|q| (q[0], q[1])),
                FAN.mix(alpha).stroke_width(1),
            ))?;
        }
        chart.draw_series(
            f.paths
                .iter()
                .filter_map(|p| p.last())
                .map(|q| Circle::new((q[0], q[1]), 2, FAN.mix(alpha.max(0.25)).filled())),
        )?;
        Ok(())
    }

    /// The frame along each route: thin every 1/8 of it, thick at its end, in the route's ink
    /// (the first route's black); then the frame at the start over them all, thick, in black
    /// (another route's own in its ink where it starts elsewhere); then the CM paths with a
    /// dot at the start and a ring at the end.
    fn draw_routes(&self, chart: &mut Chart) -> Result<(), Drawing> {
        let closed = |o: &Vec<P>| {
            let mut pts = o.clone();
            pts.extend(o.first());
            pts
        };
        for (k, outlines) in self.outlines.iter().enumerate() {
            let ink = self.ink(k);
            for (j, o) in outlines.iter().enumerate().skip(1) {
                let style = if j + 1 == outlines.len() {
                    ink.stroke_width(2)
                } else {
                    ink.mix(0.3).stroke_width(1)
                };
                chart.draw_series(std::iter::once(PathElement::new(closed(o), style)))?;
            }
        }
        let first = self.outlines.first().and_then(|o| o.first());
        for (k, outlines) in self.outlines.iter().enumerate().rev() {
            let Some(start) = outlines.first() else {
                continue;
            };
            if k > 0 && first.is_some_and(|f| same_shape(f, start, self.scale)) {
                continue;
            }
            chart.draw_series(std::iter::once(PathElement::new(
                closed(start),
                self.ink(k).stroke_width(START_W),
            )))?;
        }
        for track in self.tracks {
            chart.draw_series(LineSeries::new(
                track.rows.iter().map(|r| (r.x_m, r.z_m)),
                track.color.stroke_width(2),
            ))?;
            if let (Some(a), Some(b)) = (track.rows.first(), track.rows.last()) {
                chart.draw_series(std::iter::once(
                    EmptyElement::at((a.x_m, a.z_m)) + Circle::new((0, 0), 4, track.color.filled()),
                ))?;
                if a == b {
                    continue;
                }
                chart.draw_series(std::iter::once(
                    EmptyElement::at((b.x_m, b.z_m))
                        + Circle::new((0, 0), 4, WHITE.filled())
                        + Circle::new((0, 0), 4, track.color.stroke_width(2)),
                ))?;
            }
        }
        Ok(())
    }

    /// Where a block on its base touched the ground: a dot on each corner that carried it at
    /// the drawn poses (over the corners' marks at the start and the end), and a ring where
    /// a ground vertex or edge carried it at rest.
    fn mark_touches(&self, chart: &mut Chart) -> Result<(), Drawing> {
        if !self.resting.is_empty() {
            chart.draw_series(
                self.resting
                    .iter()
                    .map(|&p| Circle::new(p, 3, TOUCH.mix(0.8).stroke_width(1))),
            )?;
        }
        if !self.touches.is_empty() {
            chart.draw_series(
                self.touches
                    .iter()
                    .map(|&p| Circle::new(p, 3, TOUCH.filled())),
            )?;
        }
        Ok(())
    }

    /// A square where a contact of the first route changed face or went into or out of a
    /// crease.
    fn mark_face_changes(&self, chart: &mut Chart, changes: &[(P, String)]) -> Result<(), Drawing> {
        for (at, _) in changes {
            chart.draw_series(std::iter::once(
                EmptyElement::at(*at)
                    + Rectangle::new([(-4, -4), (4, 4)], FACE_CHANGE.stroke_width(2)),
            ))?;
        }
        Ok(())
    }

    /// The hydraulic force on its line of action at the start (dashed), its arrow, the offset
    /// from the CM and its size; returns the points the regions' names keep away from.
    fn draw_force(&self, chart: &mut Chart) -> Result<Vec<P>, Drawing> {
        let mut obstacles: Vec<P> = Vec::new();
        let (Some(force), Some(tail), Some(s)) = (self.force, self.force_tail, self.start) else {
            return Ok(obstacles);
        };
        let Force {
            at: q,
            dir: d,
            size: f,
            eccentricity: e,
        } = force;
        let l = self.l;
        let far = (q.0 + 0.5 * l * d.0, q.1 + 0.5 * l * d.1);
        chart.draw_series(DashedLineSeries::new(
            [tail, far],
            6,
            4,
            FORCE.mix(0.8).stroke_width(1),
        ))?;
        for part in arrow(tail, d, self.arrow_len) {
            chart.draw_series(std::iter::once(PathElement::new(
                part,
                FORCE.stroke_width(3),
            )))?;
        }
        if e != 0.0 {
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(s.x_m, s.z_m), q],
                FORCE.stroke_width(1),
            )))?;
        }
        let label = ("sans-serif", sheet::FONT)
            .into_font()
            .color(&FORCE)
            .pos(Pos::new(HPos::Right, VPos::Center));
        chart.draw_series(std::iter::once(Text::new(
            format!("F = {}", sheet::force(f)),
            self.force_label_at(tail, d),
            label,
        )))?;
        obstacles.extend(along(tail, far, 20));
        if let Some((_, [a, b])) = self.force_label() {
            obstacles.extend(along(a, (b.0, a.1), 8));
            obstacles.extend(along((a.0, b.1), b, 8));
        }
        Ok(obstacles)
    }

    /// The ink of route `k`'s frames: the first route's black, another's its colour.
    fn ink(&self, k: usize) -> RGBColor {
        match (k, self.tracks.get(k)) {
            (0, _) | (_, None) => BLACK,
            (_, Some(t)) => t.color,
        }
    }

    /// Contacts numbered at the start (dots, the first route's) and at the end (crosses) of
    /// every route that moved: not where a contact has hardly moved (its start number is
    /// there), and below and to the left where a start number stands close by.
    fn number_contacts(&self, chart: &mut Chart) -> Result<(), Drawing> {
        let starts: Vec<P> = self
            .points
            .first()
            .and_then(|o| o.first())
            .map_or(vec![], |o| o.to_vec());
        for (k, (outlines, track)) in self.points.iter().zip(self.tracks).enumerate() {
            let ink = self.ink(k);
            let number = |i: usize| {
                Text::new(
                    format!("{i}"),
                    (7, -15),
                    ("sans-serif", NUMBER).into_font().color(&ink),
                )
            };
            let moved = track.rows.len() > 1 && track.rows.first() != track.rows.last();
            if let Some(first) = outlines.first().filter(|_| k == 0) {
                chart.draw_series(first.iter().enumerate().map(|(i, &p)| {
                    EmptyElement::at(p) + Circle::new((0, 0), 5, ink.filled()) + number(i)
                }))?;
            }
            let Some(last) = outlines.last().filter(|_| moved) else {
                continue;
            };
            let first = outlines.first().cloned().unwrap_or_else(|| last.clone());
            chart.draw_series(
                last.iter()
                    .map(|&p| EmptyElement::at(p) + Cross::new((0, 0), 6, ink.stroke_width(2))),
            )?;
            let starts: Vec<P> = starts.iter().chain(first.iter()).copied().collect();
            let scale = self.scale;
            let near = |p: &P, q: &P, px: f64| (p.0 - q.0).hypot(p.1 - q.1) <= px * scale;
            chart.draw_series(
                last.iter()
                    .enumerate()
                    .filter(|(i, p)| !near(p, &first[*i], 3.0))
                    .map(|(i, &p)| {
                        let crowded = starts.iter().any(|q| near(&p, q, 14.0));
                        let at = if crowded { (-16, 4) } else { (7, -15) };
                        EmptyElement::at(p)
                            + Text::new(
                                format!("{i}"),
                                at,
                                ("sans-serif", NUMBER).into_font().color(&ink),
                            )
                    }),
            )?;
        }
        Ok(())
    }

    /// Names, dips and down-dip arrows of the regions, where they keep off the data: the
    /// routes, the fan, the frames and the force (`obstacles`), and the names already placed.
    fn name_regions(
        &self,
        chart: &mut Chart,
        regions: &[Region],
        obstacles: &mut Vec<P>,
    ) -> Result<(), Drawing> {
        for t in self.tracks {
            let every = (t.rows.len() / 400).max(1);
            obstacles.extend(t.rows.iter().step_by(every).map(|r| (r.x_m, r.z_m)));
        }
        obstacles.extend(self.fan_points().step_by(7));
        for o in self.outlines.iter().flatten() {
            for k in 0..o.len() {
                obstacles.extend(along(o[k], o[(k + 1) % o.len()], 12));
            }
        }
        let scale = self.scale;
        let label_room = 45.0 * scale;
        let View { x0, x1, z0, z1 } = self.view;
        let view_area = (x1 - x0) * (z1 - z0);
        for r in regions.iter().filter(|r| !r.name.is_empty()) {
            // Named where the region is its own (for the paper's, where it is the only
            // inclined plane), if there is room there.
            let poly = if r.label_poly.len() >= 3 && area_of(&r.label_poly) >= 0.02 * view_area {
                &r.label_poly
            } else {
                &r.poly
            };
            if poly.len() < 3 || area_of(poly) < 0.02 * view_area {
                continue;
            }
            let Some((spot, clear)) = free_spot(poly, obstacles, self.view) else {
                continue;
            };
            if clear < label_room {
                continue;
            }
            let style = ("sans-serif", NAME)
                .into_font()
                .color(&r.color)
                .pos(Pos::new(HPos::Center, VPos::Bottom));
            chart.draw_series(std::iter::once(Text::new(r.name.clone(), spot, style)))?;
            if let Some(d) = r.down {
                // Centred just under the name (Z grows down the page).
                let len = 36.0 * scale;
                let centre = (spot.0, spot.1 + 22.0 * scale);
                let from = (centre.0 - 0.5 * len * d.0, centre.1 - 0.5 * len * d.1);
                for part in arrow(from, d, len) {
                    chart.draw_series(std::iter::once(PathElement::new(
                        part,
                        r.color.stroke_width(2),
                    )))?;
                }
            }
            obstacles.extend(along(
                (spot.0 - label_room, spot.1),
                (spot.0 + label_room, spot.1),
                8,
            ));
        }
        Ok(())
    }

    /// A route short beside the view (and no fan): its extent boxed here, to be drawn enlarged
    /// in the panel; whether it is.
    fn box_short_route(&self, chart: &mut Chart) -> Result<bool, Drawing> {
        let cm: Vec<P> = self
            .tracks
            .iter()
            .flat_map(|t| t.rows.iter().map(|r| (r.x_m, r.z_m)))
            .collect();
        let span = |f: fn(&P) -> f64| {
            cm.iter().map(f).fold(f64::NEG_INFINITY, f64::max)
                - cm.iter().map(f).fold(f64::INFINITY, f64::min)
        };
        let cm_span = span(|p| p.0).max(span(|p| p.1));
        let View { x0, x1, z0, z1 } = self.view;
        let inset = self.fan.is_none() && cm_span > 0.0 && cm_span < 0.12 * (x1 - x0).min(z1 - z0);
        if inset {
            let (ix0, ix1) = sheet::ranges(cm.iter().map(|p| p.0));
            let (iz0, iz1) = sheet::ranges(cm.iter().map(|p| p.1));
            chart.draw_series(std::iter::once(Rectangle::new(
                [(ix0, iz0), (ix1, iz1)],
                BLACK.mix(0.6).stroke_width(1),
            )))?;
        }
        Ok(inset)
    }
}
