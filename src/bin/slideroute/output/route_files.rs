//! `route.csv` and `summary.json` for a computed route.

use super::folder::Folder;
use slideroute::Row;
use std::io::Write;
use std::path::PathBuf;

/// The header of `route.csv`: the fields of a [`Row`], in its order, with their units.
pub const ROUTE_HEADER: [&str; 25] = Row::COLUMNS;

/// route.csv written row by row as the route computes them (memory does not grow
/// with the route's length): the header [`ROUTE_HEADER`], then one record per [`CsvRows::push`];
/// reactions that could not be had are empty. The first write error is kept and returned by
/// [`CsvRows::finish`].
pub struct CsvRows<W: Write> {
    w: csv::Writer<W>,
    error: Option<csv::Error>,
}

impl<W: Write> CsvRows<W> {
    pub fn new(out: W) -> Result<Self, csv::Error> {
        let mut w = csv::Writer::from_writer(out);
        w.write_record(ROUTE_HEADER)?;
        Ok(CsvRows { w, error: None })
    }

    pub fn push(&mut self, r: &Row) {
        if self.error.is_some() {
            return;
        }
        // Reactions that could not be had, and the second face of a contact on no crease, are
        // empty.
        let rec = r
            .values()
            .map(|v| v.map_or(String::new(), |x| x.to_string()));
        if let Err(e) = self.w.write_record(&rec) {
            self.error = Some(e);
        }
    }

    pub fn finish(mut self) -> Result<(), csv::Error> {
        if let Some(e) = self.error {
            return Err(e);
        }
        self.w.flush()?;
        Ok(())
    }
}

/// Writes the rows with the header [`ROUTE_HEADER`]; reactions that could not be had are empty.
pub fn write_csv(out: impl Write, rows: &[Row]) -> Result<(), csv::Error> {
    let mut w = CsvRows::new(out)?;
    for r in rows {
        w.push(r);
    }
    w.finish()
}

/// What produced an output folder: `summary.json` carries it, so that anyone
/// holding the folder can tell.
#[derive(Debug, Clone, serde::Serialize)]
pub struct Manifest {
    /// The slideroute version.
    pub slideroute_version: &'static str,
    /// The command line, word for word.
    pub command_line: Vec<String>,
    /// The scene exactly as used: every value, defaults filled in, in the file's keys and units
    /// (`Scene::as_used`).
    pub scene: toml::Table,
    /// The loads the route used, in the engineer's terms (`Scene::loads_used`): weight, the
    /// water's net push and its couples, the uplift, the pseudo-static coefficients, and from
    /// `[water]` each water load with where it acts.
    pub loads: Option<slideroute::LoadsUsed>,
    /// The other files this run wrote into the folder, with their sizes.
    pub files: Vec<FileEntry>,
}

/// One file of an output folder.
#[derive(Debug, Clone, serde::Serialize)]
pub struct FileEntry {
    pub name: String,
    pub bytes: u64,
}

impl Manifest {
    /// For this process's command line, `scene`, and the files `folder` holds so far.
    pub fn new(scene: &slideroute::Scene, folder: &Folder) -> Manifest {
        Manifest {
            slideroute_version: env!("CARGO_PKG_VERSION"),
            command_line: std::env::args().collect(),
            scene: scene.as_used(),
            loads: scene.loads_used(),
            files: folder
                .written()
                .iter()
                .map(|(name, bytes)| FileEntry {
                    name: name.clone(),
                    bytes: *bytes,
                })
                .collect(),
        }
    }
}

/// Writes the rows as `name` (CSV) into `folder`, whole or not at all.
pub fn write_route_csv(folder: &mut Folder, name: &str, rows: &[Row]) -> Result<PathBuf, String> {
    folder.write_with(name, |tmp| {
        let file = std::fs::File::create(tmp)
            .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
        write_csv(std::io::BufWriter::new(file), rows).map_err(|e| format!("{name}: {e}"))
    })
}

/// `value` with the manifest, as pretty JSON, written as `name` into `folder`.
pub fn write_json_with_manifest(
    folder: &mut Folder,
    name: &str,
    value: &impl serde::Serialize,
    manifest: &Manifest,
) -> Result<PathBuf, String> {
    #[derive(serde::Serialize)]
    struct WithManifest<'a, T: serde::Serialize> {
        #[serde(flatten)]
        value: &'a T,
        manifest: &'a Manifest,
    }
    let text = serde_json::to_string_pretty(&WithManifest { value, manifest })
        .map_err(|e| format!("{name}: {e}"))?;
    folder.write_bytes(name, (text + "\n").as_bytes())
}
