//! Batch poses for `slideroute roots --grid`: read `x_m,z_m,theta_deg` rows one at a time,
//! write one result row per pose, in order.

use crate::output::roots_report::RootsReport;
use slideroute::Displacement;
use std::io::{Read, Write};

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
pub const MAX_LINE_BYTES: usize = 4096;

/// The poses of a grid file (CSV with the header `x_m,z_m,theta_deg`), one at a time, so that
/// memory does not grow with the file: only a line longer than [`MAX_LINE_BYTES`] is refused.
pub struct PoseRows<R: Read> {
    rdr: csv::Reader<LineLimit<R>>,
    file: String,
    record: csv::StringRecord,
    failed: bool,
}

const COLUMNS: [&str; 3] = ["x_m", "z_m", "theta_deg"];

impl<R: Read> PoseRows<R> {
    /// The reader of `input` (named `file` in errors), its header checked.
    pub fn new(input: R, file: &str) -> Result<PoseRows<R>, GridError> {
        let mut rdr = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .from_reader(LineLimit::new(input));
        let err = |reason: String| GridError {
            file: file.to_string(),
            place: "line 1".into(),
            reason,
        };
        let headers = match rdr.headers() {
            Ok(h) => h.clone(),
            Err(e) => {
                return Err(match too_long(&e) {
                    Some(t) => t.error(file),
                    None => err(format!("cannot read the header: {e}")),
                });
            }
        };
        if headers.iter().collect::<Vec<_>>() != COLUMNS {
            return Err(err(format!(
                "line 1 must be exactly the header `x_m,z_m,theta_deg`; it is not (it has {} \
                 comma-separated fields)",
                headers.len()
            )));
        }
        Ok(PoseRows {
            rdr,
            file: file.to_string(),
            record: csv::StringRecord::new(),
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

    fn pose(&self) -> Result<GridPose, GridError> {
        let line = self.record.position().map_or(0, |p| p.line());
        let mut v = [0.0; 3];
        for (k, name) in COLUMNS.iter().enumerate() {
            let text = self.record.get(k).unwrap_or("");
            let x: f64 = text.parse().map_err(|_| {
                self.err(
                    format!("line {line}, column {name}"),
                    format!("`{text}` is not a number"),
                )
            })?;
            if !x.is_finite() {
                return Err(self.err(
                    format!("line {line}, column {name}"),
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
        let item = match self.rdr.read_record(&mut self.record) {
            Ok(false) => return None,
            Ok(true) => self.pose(),
            Err(e) => Err(match too_long(&e) {
                Some(t) => t.error(&self.file),
                None => {
                    let line = e.position().map_or(0, |p| p.line());
                    self.err(format!("line {line}"), e.to_string())
                }
            }),
        };
        self.failed = item.is_err();
        Some(item)
    }
}

/// A line over [`MAX_LINE_BYTES`]: its number (from 1).
#[derive(Debug)]
struct TooLong {
    line: u64,
}

impl std::fmt::Display for TooLong {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "line {} is longer than {MAX_LINE_BYTES} bytes",
            self.line
        )
    }
}

impl std::error::Error for TooLong {}

impl TooLong {
    fn error(&self, file: &str) -> GridError {
        GridError {
            file: file.to_string(),
            place: format!("line {}", self.line),
            reason: format!("longer than {MAX_LINE_BYTES} bytes (a pose is three numbers)"),
        }
    }
}

/// The over-long line a CSV error comes from, if it does.
fn too_long(e: &csv::Error) -> Option<&TooLong> {
    match e.kind() {
        csv::ErrorKind::Io(io) => io.get_ref()?.downcast_ref::<TooLong>(),
        _ => None,
    }
}

/// A reader that fails (`InvalidData`) on a line longer than [`MAX_LINE_BYTES`].
struct LineLimit<R> {
    inner: R,
    run: usize,
    lines: u64,
}

impl<R> LineLimit<R> {
    fn new(inner: R) -> Self {
        LineLimit {
            inner,
            run: 0,
            lines: 0,
        }
    }
}

impl<R: Read> Read for LineLimit<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let n = self.inner.read(buf)?;
        for &b in &buf[..n] {
            if b == b'\n' {
                self.run = 0;
                self.lines += 1;
            } else {
                self.run += 1;
                if self.run > MAX_LINE_BYTES {
                    return Err(std::io::Error::new(
                        std::io::ErrorKind::InvalidData,
                        TooLong {
                            line: self.lines + 1,
                        },
                    ));
                }
            }
        }
        Ok(n)
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
