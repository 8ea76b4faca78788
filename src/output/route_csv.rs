//! `route.csv`: a route's rows, one line each, written as they come.

use crate::Row;
use std::io::Write;

/// `route.csv` written row by row as the route computes them (memory does not grow with the
/// route's length): the header ([`Row::COLUMNS`], the fields of a [`Row`] in its order with their
/// units), then one line per [`RouteCsv::push`]; reactions that could not be had are empty, and
/// so is any value that is not a finite number (none should be: the file never holds one). Each
/// number is written straight into the buffered output, with no allocation a row: a whole number
/// below 2⁵³ in magnitude as an integer, any other as its shortest decimal that reads back the
/// same (an exponent past 10¹⁶ or below 10⁻⁵, as `1.5e-7` or `2.5e+17`); no number needs
/// quoting. The first write error is kept and returned by [`RouteCsv::finish`].
///
/// ```
/// use slideroute::output::RouteCsv;
/// let scene = slideroute::Scene::default_scene().with("solver.t_end_s", 0.01)?;
/// let route = slideroute::run(&scene)?;
/// let mut csv = RouteCsv::new(Vec::new())?;
/// for row in &route.rows {
///     csv.push(row);
/// }
/// let text = String::from_utf8(csv.finish()?)?;
/// assert!(text.starts_with("body,t_s,x_m,"));
/// assert_eq!(text.lines().count(), route.rows.len() + 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct RouteCsv<W: Write> {
    w: std::io::BufWriter<W>,
    error: Option<std::io::Error>,
}

impl<W: Write> RouteCsv<W> {
    /// The file on `out`, its header written.
    pub fn new(out: W) -> std::io::Result<Self> {
        let mut w = std::io::BufWriter::with_capacity(1 << 16, out);
        writeln!(w, "{}", Row::COLUMNS.join(","))?;
        Ok(RouteCsv { w, error: None })
    }

    /// The line of row `r`.
    pub fn push(&mut self, r: &Row) {
        if self.error.is_some() {
            return;
        }
        // Reactions that could not be had, and the second face of a contact on no crease, are
        // empty.
        let (mut decimal, mut integer) = (zmij::Buffer::new(), itoa::Buffer::new());
        let mut line = || -> std::io::Result<()> {
            for (k, v) in r.values().iter().enumerate() {
                if k > 0 {
                    self.w.write_all(b",")?;
                }
                // Not a number or infinite: empty, as a value that could not be had (a file
                // holds numbers only).
                if let Some(x) = *v
                    && x.is_finite()
                {
                    write_number(&mut self.w, (&mut decimal, &mut integer), x)?;
                }
            }
            self.w.write_all(b"\n")
        };
        if let Err(e) = line() {
            self.error = Some(e);
        }
    }

    /// The line of a row given as its values in [`Row::COLUMNS`]' order ([`Row::values`]), a
    /// value that could not be had as NaN: the same line [`RouteCsv::push`] writes of the row (a
    /// route kept as columns, as Python keeps it).
    pub fn push_values(&mut self, values: impl IntoIterator<Item = f64>) {
        if self.error.is_some() {
            return;
        }
        let (mut decimal, mut integer) = (zmij::Buffer::new(), itoa::Buffer::new());
        let line = || -> std::io::Result<()> {
            for (k, x) in values.into_iter().enumerate() {
                if k > 0 {
                    self.w.write_all(b",")?;
                }
                if x.is_finite() {
                    write_number(&mut self.w, (&mut decimal, &mut integer), x)?;
                }
            }
            self.w.write_all(b"\n")
        };
        if let Err(e) = line() {
            self.error = Some(e);
        }
    }

    /// Everything written out; the output back, or the first error met.
    pub fn finish(self) -> std::io::Result<W> {
        if let Some(e) = self.error {
            return Err(e);
        }
        self.w.into_inner().map_err(|e| e.into_error())
    }
}

/// Writes `x` as route.csv has it: a whole number below 2⁵³ in magnitude as an integer (a face's
/// number, a zero; as Rust's `Display` writes it), any other by `zmij`.
fn write_number(
    w: &mut impl Write,
    (decimal, integer): (&mut zmij::Buffer, &mut itoa::Buffer),
    x: f64,
) -> std::io::Result<()> {
    const WHOLE: f64 = 9_007_199_254_740_992.0;
    // Whole: |x| < 2⁵³ converts to an i64 and back exactly (the conversion truncates, so only a
    // whole x comes back equal); NaN fails the bound.
    if x.abs() < WHOLE && (x as i64) as f64 == x && !(x == 0.0 && x.is_sign_negative()) {
        w.write_all(integer.format(x as i64).as_bytes())
    } else {
        w.write_all(decimal.format(x).as_bytes())
    }
}

/// Writes the rows with the header; reactions that could not be had are empty.
#[cfg(test)]
fn write_csv(out: impl Write, rows: &[Row]) -> std::io::Result<()> {
    let mut w = RouteCsv::new(out)?;
    for r in rows {
        w.push(r);
    }
    w.finish().map(drop)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn route_csv_reads_back_as_the_same_values_by_a_csv_reader() {
        // The rows are written by hand for speed; a CSV reader, parsing each cell by Rust's own
        // float parser, must give back every value bit for bit, and an empty cell where none.
        let scene = crate::Scene::default_scene()
            .with("solver.t_end_s", 0.05)
            .unwrap();
        let mut rows = crate::analysis::run(&scene).unwrap().rows;
        let mut gap = rows[1];
        gap.n_n = None;
        gap.s_n = Some([-0.0, 1e-300, f64::MAX]);
        gap.crease = [None, Some(2), None];
        gap.x_m = 1e21;
        // 2⁵³ is past the integers written as such; 2⁵³ − 1 is not.
        gap.z_m = 9_007_199_254_740_992.0;
        gap.vx_m_s = -9_007_199_254_740_991.0;
        gap.vz_m_s = 0.5;
        rows.push(gap);
        // A value that is not a number is written empty, never `NaN` or `inf`.
        let mut odd = rows[1];
        odd.n_n = Some([f64::NAN, f64::INFINITY, 1.0]);
        let mut ours = Vec::new();
        write_csv(&mut ours, &rows).unwrap();
        let mut back = csv::Reader::from_reader(ours.as_slice());
        assert_eq!(back.headers().unwrap(), Row::COLUMNS.as_slice());
        let mut n = 0;
        for (line, r) in back.records().zip(&rows) {
            let line = line.unwrap();
            let cells: Vec<Option<f64>> = line
                .iter()
                .map(|c| (!c.is_empty()).then(|| c.parse::<f64>().unwrap()))
                .collect();
            let written: Vec<Option<u64>> =
                r.values().iter().map(|v| v.map(f64::to_bits)).collect();
            let read: Vec<Option<u64>> = cells.iter().map(|v| v.map(f64::to_bits)).collect();
            assert_eq!(read, written, "row {n}: {line:?}");
            n += 1;
        }
        assert_eq!(n, rows.len());
        // Faces and zeros as integers, as people write them; other numbers shortest.
        let text = String::from_utf8(ours).unwrap();
        let first = text.lines().nth(1).unwrap();
        assert!(first.starts_with("0,0,0,0,0,0,0,0,0,0,0,"), "{first}");
        assert!(first.contains(",0,1,2,"), "{first}");
        let last = text.lines().last().unwrap();
        assert!(
            last.contains(",-0.0,1e-300,1.7976931348623157e+308,"),
            "{last}"
        );
        assert!(last.starts_with(&format!("0,{},1e+21,", gap.t_s)), "{last}");
        assert!(
            last.contains(",9007199254740992.0,") && last.contains(",-9007199254740991,0.5,"),
            "{last}"
        );
        let mut one = Vec::new();
        write_csv(&mut one, &[odd]).unwrap();
        let one = String::from_utf8(one).unwrap();
        let line = one.lines().nth(1).unwrap();
        assert!(!line.contains("NaN") && !line.contains("inf"), "{line}");
        assert!(line.contains(",,,1,"), "{line}");
    }

    #[test]
    fn a_row_given_as_its_values_is_written_as_the_row_is() {
        // Python holds a route as columns, a value that could not be had NaN: its route.csv
        // must be the bytes of the rows'.
        let scene = crate::Scene::default_scene()
            .with("solver.t_end_s", 0.3)
            .unwrap();
        let mut rows = crate::analysis::run(&scene).unwrap().rows;
        let mut odd = rows[1];
        odd.n_n = None;
        odd.crease = [None, Some(2), None];
        odd.x_m = -0.0;
        odd.z_m = 1e-300;
        rows.push(odd);
        let (mut by_row, mut by_values) = (Vec::new(), RouteCsv::new(Vec::new()).unwrap());
        write_csv(&mut by_row, &rows).unwrap();
        for r in &rows {
            by_values.push_values(r.values().map(|v| v.unwrap_or(f64::NAN)));
        }
        let by_values = by_values.finish().unwrap();
        assert!(by_row.len() > 1000);
        assert_eq!(
            String::from_utf8(by_values).unwrap(),
            String::from_utf8(by_row).unwrap()
        );
    }
}
