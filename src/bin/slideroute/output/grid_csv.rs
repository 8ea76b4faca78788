//! Batch poses for `slideroute roots --grid`: read `x_m,z_m,theta_deg` rows one at a time,
//! write one result row per pose, in order.

use crate::output::roots_report::RootsReport;
use slideroute::Displacement;
use slideroute::internals::scene::input::{CsvLine, CsvLineError, CsvLines, MAX_CSV_LINE_BYTES};
use std::io::{BufReader, Read, Write};

/// A grid file that cannot be used: names the file, the line and the reason.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}: {place}: {reason}")]
pub struct GridError {
    pub file: String,
    pub place: String,
    pub reason: String,
}

/// One pose of a grid file, as written there (degrees).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridPose {
    pub x_m: f64,
    pub z_m: f64,
    pub theta_deg: f64,
}

impl GridPose {
    pub fn displacement(&self) -> Displacement {
        Displacement::new(self.x_m, self.z_m, self.theta_deg.to_radians())
    }
}

/// The longest line a grid file may have (bytes): a pose is three numbers.
pub const MAX_LINE_BYTES: usize = MAX_CSV_LINE_BYTES;

/// The poses of a grid file (CSV with the header `x_m,z_m,theta_deg`), one at a time, so that
/// memory does not grow with the file: only a line longer than [`MAX_LINE_BYTES`] is refused.
/// Every fault names its line as the file has it, blank lines counted.
pub struct PoseRows<R: Read> {
    lines: CsvLines<BufReader<R>>,
    file: String,
    failed: bool,
}

const COLUMNS: [&str; 3] = ["x_m", "z_m", "theta_deg"];

impl<R: Read> PoseRows<R> {
    /// The reader of `input` (named `file` in errors), its header checked.
    pub fn new(input: R, file: &str) -> Result<PoseRows<R>, GridError> {
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
        Ok(PoseRows {
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

impl<R: Read> Iterator for PoseRows<R> {
    type Item = Result<GridPose, GridError>;

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
        Some(item)
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
pub const HEADER: [&str; 12] = [
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

/// The batch output: the header, then rows as they come.
pub struct RowWriter<W: Write> {
    w: csv::Writer<W>,
}

impl<W: Write> RowWriter<W> {
    /// Writes the header.
    pub fn new(out: W) -> Result<RowWriter<W>, csv::Error> {
        let mut w = csv::Writer::from_writer(out);
        w.write_record(HEADER)?;
        Ok(RowWriter { w })
    }

    /// One row per pose (echoed as read) with its report; a pose with no selected root says
    /// so in `status` and `note`.
    pub fn rows(&mut self, poses: &[GridPose], reports: &[RootsReport]) -> Result<(), csv::Error> {
        for (p, r) in poses.iter().zip(reports) {
            self.w.write_record(row(p, r))?;
        }
        Ok(())
    }

    /// Flushes what is written.
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
