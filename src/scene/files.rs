//! The files a scene names — a triangulated surface (`foundation.surface`, Wavefront OBJ) and a
//! ground-motion record (`seismic.record`, CSV) — read with bounds, and what was read from
//! them kept by name: a scene edited by key ([`Scene::with`]) keeps them rather than reading
//! them again.

use super::Scene;
use super::input::{CsvLines, open_bounded};
use super::obj::{ObjError, ObjSurface, face_line, read_obj};
use crate::geometry::Ground;
use crate::model::Record;
use std::path::Path;
use std::sync::Arc;

/// The largest surface file (bytes): some 1.5 million triangles on a grid of shared vertices
/// (fewer where each triangle has corners of its own).
pub const MAX_SURFACE_BYTES: u64 = 64 << 20;

/// The largest record file (bytes): some million samples.
pub const MAX_RECORD_BYTES: u64 = 64 << 20;

/// The columns a record file has, in this order: seconds, then fractions of g along the scene's
/// X, Y, Z.
pub const RECORD_COLUMNS: [&str; 4] = ["t_s", "ax_g", "ay_g", "az_g"];

/// Where a scene's named files come from: the folder a relative name is found in, and the
/// files already read (one the scene still names is not read again).
#[derive(Clone, Copy)]
pub(super) struct Sources<'a> {
    pub folder: &'a Path,
    pub files: &'a Files,
}

/// The files a scene named and what was read from them, by the name the scene gave.
#[derive(Default)]
pub(super) struct Files {
    surface: Option<(String, Arc<Ground>)>,
    record: Option<(String, Arc<Record>)>,
}

impl Files {
    /// What `scene` read.
    pub fn of(scene: &Scene) -> Files {
        let named = |section: &str, key: &str| {
            scene
                .source
                .get(section)
                .and_then(|s| s.get(key))
                .and_then(|v| v.as_str())
                .map(str::to_string)
        };
        // The scene's record is the file's unless it was scaled or reversed; then the file is
        // read again.
        let adjusted = ["scale", "target_pga_g", "polarity"]
            .iter()
            .any(|k| scene.source.get("seismic").and_then(|s| s.get(k)).is_some());
        Files {
            surface: named("foundation", "surface").zip(scene.site.shared_ground().cloned()),
            record: named("seismic", "record")
                .filter(|_| !adjusted)
                .zip(scene.record.clone()),
        }
    }

    /// The surface named `name`, found from `folder`: the one read before under that name, or
    /// read now. The error, for people, names the file.
    pub fn surface(&self, folder: &Path, name: &str) -> Result<Arc<Ground>, String> {
        match &self.surface {
            Some((read, ground)) if read == name => Ok(ground.clone()),
            _ => {
                let path = folder.join(name);
                read_surface(&path)
                    .map(Arc::new)
                    .map_err(|why| format!("{}: {why}", path.display()))
            }
        }
    }

    /// The record named `name`, found from `folder`: the one read before under that name, or
    /// read now. The error, for people, names the file.
    pub fn record(&self, folder: &Path, name: &str) -> Result<Arc<Record>, String> {
        match &self.record {
            Some((read, record)) if read == name => Ok(record.clone()),
            _ => {
                let path = folder.join(name);
                read_record(&path)
                    .map(Arc::new)
                    .map_err(|why| format!("{}: {why}", path.display()))
            }
        }
    }
}

/// A Wavefront OBJ file of triangles (faces of more corners are split into triangles), Y up,
/// in scene coordinates: its vertices and triangles read as they are kept (`obj.rs`), moved
/// into the ground. A triangle the ground cannot take is named by the line of its face (the
/// file read again to find it).
fn read_surface(path: &Path) -> Result<Ground, String> {
    let open = || {
        open_bounded(path, MAX_SURFACE_BYTES)
            .map(|file| std::io::BufReader::with_capacity(1 << 16, file))
    };
    let ObjSurface {
        vertices,
        triangles,
    } = read_obj(open()?, MAX_SURFACE_BYTES).map_err(|e| e.to_string())?;
    Ground::mesh(vertices, triangles).map_err(|error| {
        let line = error.triangle().and_then(|k| face_line(open().ok()?, k));
        match line {
            Some(line) => ObjError::Face { line, error },
            None => ObjError::Surface(error),
        }
        .to_string()
    })
}

/// A record file: CSV with the header `t_s,ax_g,ay_g,az_g`, then a sample a line; every fault
/// named by its line in the file, blank lines counted ([`CsvLines`]).
fn read_record(path: &Path) -> Result<Record, String> {
    let file = open_bounded(path, MAX_RECORD_BYTES)?;
    let mut lines = CsvLines::new(std::io::BufReader::new(file));
    let header = lines.next().transpose().map_err(|e| e.to_string())?;
    match header {
        Some(h) if h.cells == RECORD_COLUMNS => {}
        // What the line says is not echoed: the file may be any file (a scene names it).
        Some(h) => {
            return Err(format!(
                "line {} must be the header `{}`; it is not (it has {} comma-separated fields)",
                h.number,
                RECORD_COLUMNS.join(","),
                h.cells.len()
            ));
        }
        None => {
            return Err(format!(
                "the file is empty; its first line must be the header `{}`",
                RECORD_COLUMNS.join(",")
            ));
        }
    }
    let (mut samples, mut numbers) = (Vec::new(), Vec::new());
    for line in lines {
        let line = line.map_err(|e| e.to_string())?;
        if line.cells.len() != RECORD_COLUMNS.len() {
            return Err(format!(
                "line {}: {} comma-separated fields where the header has {}",
                line.number,
                line.cells.len(),
                RECORD_COLUMNS.len()
            ));
        }
        let mut v = [0.0; 4];
        for (c, (cell, text)) in v.iter_mut().zip(&line.cells).enumerate() {
            *cell = text.parse().map_err(|_| {
                format!(
                    "line {}: `{text}` in {} is not a number",
                    line.number, RECORD_COLUMNS[c]
                )
            })?;
        }
        samples.push((v[0], [v[1], v[2], v[3]]));
        numbers.push(line.number);
    }
    Record::from_lines(samples, &numbers).map_err(|e| e.reason)
}
