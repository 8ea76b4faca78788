//! The plan view's legend: the foundation's regions, the water force, the routes and their
//! marks, in the engineer's words.

use super::regions::Region;
use super::route::Force;
use super::{FACE_CHANGE, FAN, FORCE, HORIZONTAL, PLANE_1, PLANE_2, PlanView, TOUCH};
use crate::Scene;
use crate::output::plots::sheet::{self, Entry, Mark};
use plotters::prelude::*;

/// What the legend describes beyond the view itself: the regions drawn, the force at the
/// start, and where a contact changed face.
pub(super) struct Drawn<'a> {
    pub regions: &'a [Region],
    pub surface: bool,
    pub force: Option<Force>,
    pub changes: &'a [(super::P, String)],
    /// The first route is a block on its base: its base's outline is drawn, its corners
    /// numbered.
    pub on_base: bool,
    /// The first route rides its frame under a block with a footprint of its own: the
    /// footprint is drawn about the frame's contacts.
    pub footprint: bool,
    /// The corners that carried a block on its base are marked.
    pub touches: bool,
    /// What else carried a block on its base at rest is marked.
    pub resting: bool,
}

/// The legend's entries, in order: the foundation, the force, each route and the fan, the
/// marks of the contacts and the CM.
pub(super) fn entries(scene: &Scene, shown: &PlanView, drawn: &Drawn) -> Vec<Entry> {
    let mut entries = foundation(scene, drawn);
    if let Some(force) = drawn.force {
        entries.push(Entry::new(
            Mark::Line(FORCE),
            format!(
                "hydraulic force F = {} at the start, its line of action {} m from the CM",
                sheet::force(force.size),
                sheet::short(force.eccentricity.abs())
            ),
        ));
    }
    for t in shown.tracks {
        entries.push(Entry::new(Mark::Line(t.color), t.name.clone()));
    }
    if let Some(f) = shown.fan {
        entries.push(Entry::new(Mark::Line(FAN), f.name.clone()));
        entries.push(Entry::new(Mark::Dot(FAN), "where each sampled route ended"));
    }
    let several = shown.tracks.len() > 1;
    let outline = match (drawn.on_base, drawn.footprint, several) {
        (true, _, false) => {
            "corners of the base at the start (numbered as route.csv's corners_carrying); thick \
             outline: start and end, thin: every 1/8 of the route"
        }
        (false, true, false) => {
            "contacts 0, 1, 2 at the start; the base's outline (the block's footprint) about \
             them, thick: start and end, thin: every 1/8 of the route"
        }
        (false, false, false) => {
            "contacts 0, 1, 2 at the start; thick frame: start and end, thin: every 1/8 of the \
             route"
        }
        (true, _, true) => "corners of the base at the start",
        (false, _, true) => "contacts 0, 1, 2 at the start",
    };
    entries.push(Entry::new(Mark::Dot(BLACK), outline));
    if several {
        // Each route's frames in its own ink, and the one they start from over them.
        let shape = if drawn.on_base || drawn.footprint {
            "the base's outline"
        } else {
            "the frame"
        };
        entries.push(Entry::new(
            Mark::Thick(BLACK),
            format!("{shape} at the start, where the routes begin (drawn over the others)"),
        ));
        for (k, t) in shown.tracks.iter().enumerate() {
            let ink = if k == 0 { BLACK } else { t.color };
            entries.push(Entry::new(
                Mark::Line(ink),
                format!(
                    "{}: its frame at its end (thick) and every 1/8 of its route (thin)",
                    t.who
                ),
            ));
        }
    }
    if drawn.touches {
        entries.push(Entry::new(
            Mark::Dot(TOUCH),
            "corners carrying the block at those poses (where the base touched the ground)",
        ));
    }
    if drawn.resting {
        entries.push(Entry::new(
            Mark::Ring(TOUCH),
            "at rest before the load, a ground vertex or edge under the base carrying it too",
        ));
    }
    if shown
        .tracks
        .iter()
        .any(|t| t.rows.len() > 1 && t.rows.first() != t.rows.last())
    {
        let end = if drawn.on_base {
            "corners at the end"
        } else {
            "contacts at the end"
        };
        entries.push(Entry::new(Mark::Cross(BLACK), end));
        if !drawn.changes.is_empty() {
            let said: Vec<&str> = drawn.changes.iter().map(|(_, s)| s.as_str()).collect();
            entries.push(Entry::new(
                Mark::Square(FACE_CHANGE),
                format!("where a contact changed face: {}", said.join("; ")),
            ));
        }
        entries.push(Entry::new(
            Mark::Ring(BLACK),
            "CM at the end (filled dot: at the start)",
        ));
    }
    entries
}

/// The foundation's entries: the paper's planes with their dips and strikes, a surface's
/// shading, or a general site's planes or faces (at most eight named).
fn foundation(scene: &Scene, drawn: &Drawn) -> Vec<Entry> {
    if let Some(paper) = scene.site().as_paper() {
        let g = paper.foundation;
        return vec![
            Entry::new(Mark::Swatch(HORIZONTAL), "horizontal plane (contact 0)"),
            Entry::new(
                Mark::Swatch(PLANE_1),
                format!(
                    "plane 1 (contact 1), dip ξ = {}°; solid line: its strike",
                    sheet::short(g.xi.to_degrees())
                ),
            ),
            Entry::new(
                Mark::Swatch(PLANE_2),
                format!(
                    "plane 2 (contact 2), dip ζ = {}°; solid line: its strike",
                    sheet::short(g.zeta.to_degrees())
                ),
            ),
            Entry::new(Mark::None, "arrows on the planes point down-dip"),
        ];
    }
    if drawn.surface {
        return vec![Entry::new(
            Mark::None,
            format!(
                "foundation: a surface of {} triangles, shaded by dip (darker: steeper, \
                     60° and more darkest); grey lines: its edges",
                scene.site().ground().map_or(0, |(g, _)| g.faces().len())
            ),
        )];
    }
    let regions = drawn.regions;
    let mut e: Vec<Entry> = regions
        .iter()
        .take(8)
        .map(|r| Entry::new(Mark::Swatch(r.color), r.name.clone()))
        .collect();
    if regions.len() > 8 {
        e.push(Entry::new(
            Mark::None,
            format!("… {} faces in all", regions.len()),
        ));
    }
    e.push(Entry::new(
        Mark::None,
        match scene.site().ground() {
            Some(_) => "the ground is the highest face; grey lines: its creases",
            None => "each contact on its own plane (the paper's model); grey: region edges",
        },
    ));
    e.push(Entry::new(Mark::None, "arrows point down-dip"));
    e
}
