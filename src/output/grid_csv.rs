//! Poses in bulk, as `slideroute roots --grid` reads and writes them: a grid file's
//! `x_m,z_m,theta_deg` rows read one at a time, and one result row per pose written in order.

use super::OutputError;
use super::roots_report::RootsReport;
use crate::Displacement;
use crate::scene::input::{CsvLine, CsvLineError, CsvLines, MAX_CSV_LINE_BYTES, open_bounded};
use std::io::{BufReader, Read, Write};
use std::path::Path;

/// A grid file that cannot be used: names the file, the line and the reason.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}: {place}: {reason}")]
struct GridError {
    file: String,
    place: String,
    reason: String,
}

impl From<GridError> for OutputError {
    fn from(e: GridError) -> OutputError {
        OutputError::Input(e.to_string())
    }
}

/// One pose of a grid file, as written there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridPose {
    /// X: the CM's displacement along X (m).
    pub x_m: f64,
    /// Z: the CM's displacement along Z (m).
    pub z_m: f64,
    /// θ: the yaw (degrees).
    pub theta_deg: f64,
}

impl GridPose {
    /// The displacement (X, Z, θ in radians).
    pub fn displacement(&self) -> Displacement {
        Displacement::new(self.x_m, self.z_m, self.theta_deg.to_radians())
    }
}

/// The longest line a grid file may have (bytes): a pose is three numbers.
const MAX_LINE_BYTES: usize = MAX_CSV_LINE_BYTES;

/// The poses of a grid file (CSV with the header `x_m,z_m,theta_deg`), one at a time, so that
/// memory does not grow with the file: only a line longer than 4096 bytes is refused. Every
/// fault ([`OutputError::Input`]) names the file and its line as the file has it, blank lines
/// counted; after one, the poses end.
///
/// ```
/// use slideroute::output::GridPoses;
/// let text = "x_m,z_m,theta_deg\n0.1,0,0.5\n0.2,0.05,1\n";
/// let poses: Vec<_> = GridPoses::from_reader(text.as_bytes(), "grid.csv")?.collect::<Result<_, _>>()?;
/// assert_eq!(poses.len(), 2);
/// assert_eq!(poses[1].theta_deg, 1.0);
/// # Ok::<(), slideroute::output::OutputError>(())
/// ```
pub struct GridPoses<R: Read> {
    lines: CsvLines<BufReader<R>>,
    file: String,
    failed: bool,
}

const COLUMNS: [&str; 3] = ["x_m", "z_m", "theta_deg"];

impl GridPoses<Box<dyn Read>> {
    /// The poses of the file at `path`: a regular file of any length (a line is bounded
    /// instead), its header checked; the error names the file.
    pub fn open(path: &Path) -> Result<GridPoses<Box<dyn Read>>, OutputError> {
        let name = path.display().to_string();
        let file = open_bounded(path, u64::MAX - 1)
            .map_err(|e| OutputError::Input(format!("{name}: {e}")))?;
        GridPoses::from_reader(Box::new(file) as Box<dyn Read>, &name)
    }
}

impl<R: Read> GridPoses<R> {
    /// The poses `input` holds (named `file` in errors), its header checked.
    pub fn from_reader(input: R, file: &str) -> Result<GridPoses<R>, OutputError> {
        Ok(GridPoses::new(input, file)?)
    }

    /// [`GridPoses::from_reader`], its error the grid's own.
    fn new(input: R, file: &str) -> Result<GridPoses<R>, GridError> {
        let mut lines = CsvLines::new(BufReader::new(input));
        let err = |line: u64, reason: String| GridError {
            file: file.to_string(),
            place: format!("line {line}"),
            reason,
        };
        let header = match lines.next().transpose() {
            Ok(h) => h,
            Err(e) => return Err(line_error(file, &e)),
        };
        match header {
            Some(h) if h.cells == COLUMNS => {}
            Some(h) => {
                return Err(err(
                    h.number,
                    format!(
                        "line {} must be exactly the header `x_m,z_m,theta_deg`; it is not (it \
                         has {} comma-separated fields)",
                        h.number,
                        h.cells.len()
                    ),
                ));
            }
            None => {
                return Err(err(
                    1,
                    "the file is empty; its first line must be the header `x_m,z_m,theta_deg`"
                        .into(),
                ));
            }
        }
        Ok(GridPoses {
            lines,
            file: file.to_string(),
            failed: false,
        })
    }

    fn err(&self, place: String, reason: String) -> GridError {
        GridError {
            file: self.file.clone(),
            place,
            reason,
        }
    }

    fn pose(&self, line: &CsvLine) -> Result<GridPose, GridError> {
        let n = line.number;
        if line.cells.len() != COLUMNS.len() {
            return Err(self.err(
                format!("line {n}"),
                format!(
                    "{} comma-separated fields where the header has {}",
                    line.cells.len(),
                    COLUMNS.len()
                ),
            ));
        }
        let mut v = [0.0; 3];
        for (k, (name, text)) in COLUMNS.iter().zip(&line.cells).enumerate() {
            let x: f64 = text.parse().map_err(|_| {
                self.err(
                    format!("line {n}, column {name}"),
                    format!("`{text}` is not a number"),
                )
            })?;
            if !x.is_finite() {
                return Err(self.err(
                    format!("line {n}, column {name}"),
                    format!("must be a finite number, got {text}"),
                ));
            }
            v[k] = x;
        }
        Ok(GridPose {
            x_m: v[0],
            z_m: v[1],
            theta_deg: v[2],
        })
    }
}

impl<R: Read> Iterator for GridPoses<R> {
    type Item = Result<GridPose, OutputError>;

    /// The next pose; after an error, nothing.
    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        let item = match self.lines.next()? {
            Ok(line) => self.pose(&line),
            Err(e) => Err(line_error(&self.file, &e)),
        };
        self.failed = item.is_err();
        Some(item.map_err(OutputError::from))
    }
}

/// The grid error of a line that could not be read.
fn line_error(file: &str, e: &CsvLineError) -> GridError {
    let (line, reason) = match e {
        CsvLineError::TooLong(n) => (
            *n,
            format!("longer than {MAX_LINE_BYTES} bytes (a pose is three numbers)"),
        ),
        CsvLineError::NotText(n) => (*n, "not UTF-8 text".into()),
        CsvLineError::OpenQuote(n) => (*n, "a quoted cell is not closed on the line".into()),
        CsvLineError::Read(n, why) => (*n, format!("cannot read the file: {why}")),
    };
    GridError {
        file: file.to_string(),
        place: format!("line {line}"),
        reason,
    }
}

/// The columns of the batch output.
const HEADER: [&str; 12] = [
    "x_m",
    "z_m",
    "theta_deg",
    "status",
    "alpha_deg",
    "beta_deg",
    "gamma_deg",
    "cm_y_m",
    "finite_roots",
    "roots_at_infinity",
    "admissible_roots",
    "note",
];

/// The result rows of a grid of poses, as `slideroute roots --grid` writes them: the header
/// (`x_m,z_m,theta_deg,status,alpha_deg,beta_deg,gamma_deg,cm_y_m,finite_roots,…`), then one
/// row per pose as they come, the pose echoed as read and its selected root (or why none is).
pub struct GridRows<W: Write> {
    w: csv::Writer<W>,
}

impl<W: Write> GridRows<W> {
    /// The rows on `out`, the header written.
    pub fn new(out: W) -> Result<GridRows<W>, csv::Error> {
        let mut w = csv::Writer::from_writer(out);
        w.write_record(HEADER)?;
        Ok(GridRows { w })
    }

    /// One row per pose (echoed as read) with its report; a pose with no selected root says
    /// so in `status` and `note`.
    pub fn rows(&mut self, poses: &[GridPose], reports: &[RootsReport]) -> Result<(), csv::Error> {
        for (p, r) in poses.iter().zip(reports) {
            self.w.write_record(row(p, r))?;
        }
        Ok(())
    }

    /// Everything written out; the output back.
    pub fn finish(mut self) -> Result<W, csv::Error> {
        self.w.flush()?;
        self.w
            .into_inner()
            .map_err(|e| csv::Error::from(std::io::Error::other(e.to_string())))
    }
}

/// The output row of pose `p` and its report `r`.
fn row(p: &GridPose, r: &RootsReport) -> Vec<String> {
    let admissible = r.roots.iter().filter(|x| x.admissible).count();
    let (status, vals, note) = match (&r.selected, &r.selection_error) {
        (Some(s), _) => (
            "selected",
            [s.alpha_deg, s.beta_deg, s.gamma_deg, s.cm_y_m].map(|v| v.to_string()),
            String::new(),
        ),
        (None, e) => (
            "no admissible root",
            [(); 4].map(|_| String::new()),
            e.clone().unwrap_or_default(),
        ),
    };
    let mut row = vec![
        p.x_m.to_string(),
        p.z_m.to_string(),
        p.theta_deg.to_string(),
        status.to_string(),
    ];
    row.extend(vals);
    row.extend([
        r.finite_roots.to_string(),
        r.roots_at_infinity.to_string(),
        admissible.to_string(),
        note,
    ]);
    row
}
