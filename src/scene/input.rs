//! Reading an input file with bounds: only a regular file, at most a stated size,
//! so that `/dev/zero`, a FIFO with no writer or a runaway file gets one clear error instead of
//! growing memory without end, an abort or a hang.

use std::io::{BufRead, Read};
use std::path::Path;

/// The largest scene file (bytes): a scene is a few kilobytes.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// Opens `path` for reading if it is a regular file of at most `limit` bytes; the error, for
/// people, says why not (without the path: the caller names the file).
pub fn open_bounded(path: &Path, limit: u64) -> Result<impl Read + use<>, String> {
    // The kind is asked before opening: opening a FIFO with no writer blocks.
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read the file: {e}"))?;
    if !meta.is_file() {
        return Err(
            "not a regular file (a device, a pipe or a folder cannot be read as input)".to_string(),
        );
    }
    if meta.len() > limit {
        return Err(format!(
            "the file has {} bytes, more than the {limit} an input may have",
            meta.len()
        ));
    }
    let file = std::fs::File::open(path).map_err(|e| format!("cannot read the file: {e}"))?;
    // A file that grows while it is read stops at the limit (and fails to parse there).
    Ok(file.take(limit + 1))
}

/// The text of a regular file of at most `limit` bytes.
pub fn read_bounded(path: &Path, limit: u64) -> Result<String, String> {
    let mut text = String::new();
    open_bounded(path, limit)?
        .read_to_string(&mut text)
        .map_err(|e| format!("cannot read the file: {e}"))?;
    if text.len() as u64 > limit {
        return Err(format!(
            "the file grew past the {limit} bytes an input may have"
        ));
    }
    Ok(text)
}

/// The longest line a comma-separated input may have (bytes): a line is a few numbers.
pub const MAX_CSV_LINE_BYTES: usize = 4096;

/// One line of a comma-separated file: its number in the file (from 1) and its cells, each
/// trimmed, a quoted cell (`"0.5"`, `""` for a quote inside) without its quotes.
#[derive(Debug, Clone, PartialEq)]
pub struct CsvLine {
    /// The line's number, every line of the file counted (blank ones too).
    pub number: u64,
    /// The cells.
    pub cells: Vec<String>,
}

/// Why a comma-separated file could not be read: each names the line (from 1), never its text.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CsvLineError {
    /// A line longer than [`MAX_CSV_LINE_BYTES`].
    #[error("line {0} is longer than {MAX_CSV_LINE_BYTES} bytes")]
    TooLong(u64),
    /// A line that is not UTF-8 text.
    #[error("line {0} is not UTF-8 text")]
    NotText(u64),
    /// A line with a quoted cell not closed on it.
    #[error("line {0} has a quoted cell that is not closed on the line")]
    OpenQuote(u64),
    /// The file could not be read at a line (the system's reason).
    #[error("line {0}: cannot read the file: {1}")]
    Read(u64, String),
}

/// The lines of a comma-separated file (a record, a grid of poses) one at a time, each
/// counted as the file has it: a fault is reported at its own line whatever blank lines come
/// before it (the `csv` crate leaves blank lines out of its count). Blank lines (or of spaces
/// alone) are passed over, a byte-order mark before the first line is dropped, `\r\n` ends a
/// line as `\n` does. Memory is one line's, at most [`MAX_CSV_LINE_BYTES`]; after an error,
/// nothing more.
pub struct CsvLines<R> {
    reader: R,
    number: u64,
    line: Vec<u8>,
    failed: bool,
}

impl<R: BufRead> CsvLines<R> {
    /// The lines of `reader`.
    pub fn new(reader: R) -> CsvLines<R> {
        CsvLines {
            reader,
            number: 0,
            line: Vec::with_capacity(128),
            failed: false,
        }
    }

    /// The next line that is not blank, or none at the end.
    fn next_line(&mut self) -> Result<Option<CsvLine>, CsvLineError> {
        loop {
            self.line.clear();
            let limit = MAX_CSV_LINE_BYTES as u64 + 2;
            let got = (&mut self.reader)
                .take(limit)
                .read_until(b'\n', &mut self.line)
                .map_err(|e| CsvLineError::Read(self.number + 1, e.to_string()))?;
            if got == 0 {
                return Ok(None);
            }
            self.number += 1;
            let n = self.number;
            let mut bytes = &self.line[..];
            if n == 1 {
                bytes = bytes.strip_prefix("\u{feff}".as_bytes()).unwrap_or(bytes);
            }
            let ended = bytes.last() == Some(&b'\n');
            let bytes = bytes.strip_suffix(b"\n").unwrap_or(bytes);
            let bytes = bytes.strip_suffix(b"\r").unwrap_or(bytes);
            if bytes.len() > MAX_CSV_LINE_BYTES || (!ended && got as u64 == limit) {
                return Err(CsvLineError::TooLong(n));
            }
            let text = std::str::from_utf8(bytes).map_err(|_| CsvLineError::NotText(n))?;
            if text.trim().is_empty() {
                continue;
            }
            let cells = cells(text).ok_or(CsvLineError::OpenQuote(n))?;
            return Ok(Some(CsvLine { number: n, cells }));
        }
    }
}

impl<R: BufRead> Iterator for CsvLines<R> {
    type Item = Result<CsvLine, CsvLineError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        let item = self.next_line().transpose();
        self.failed = matches!(item, Some(Err(_)));
        item
    }
}

/// The cells of one line: split at commas outside quotes, each trimmed, a quoted one without
/// its quotes (`""` inside for a quote); `None` where a quote is not closed.
fn cells(line: &str) -> Option<Vec<String>> {
    let mut out = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        while chars.next_if(|c| *c != '\n' && c.is_whitespace()).is_some() {}
        let mut cell = String::new();
        if chars.next_if_eq(&'"').is_some() {
            loop {
                match chars.next()? {
                    '"' if chars.next_if_eq(&'"').is_some() => cell.push('"'),
                    '"' => break,
                    c => cell.push(c),
                }
            }
            // Anything after the closing quote up to the comma belongs to the cell.
            while let Some(c) = chars.next_if(|c| *c != ',') {
                cell.push(c);
            }
            out.push(cell.trim().to_string());
        } else {
            while let Some(c) = chars.next_if(|c| *c != ',') {
                cell.push(c);
            }
            out.push(cell.trim().to_string());
        }
        if chars.next().is_none() {
            return Some(out);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lines(text: &str) -> Vec<Result<CsvLine, CsvLineError>> {
        CsvLines::new(text.as_bytes()).collect()
    }

    #[test]
    fn csv_lines_are_numbered_as_the_file_has_them_blank_ones_counted() {
        // The csv crate counted `0.2,x` here as line 3; it is the file's fifth.
        let got: Vec<(u64, Vec<String>)> = lines("\u{feff}a, b\r\n\r\n  \n0.1,2\n0.2,x\n\n")
            .into_iter()
            .map(|l| l.map(|l| (l.number, l.cells)).unwrap())
            .collect();
        let own = |v: &[&str]| v.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        assert_eq!(
            got,
            vec![
                (1, own(&["a", "b"])),
                (4, own(&["0.1", "2"])),
                (5, own(&["0.2", "x"]))
            ]
        );
    }

    #[test]
    fn quoted_cells_lose_their_quotes_and_an_open_quote_is_named_by_its_line() {
        let l = lines("\"0.5\" , \"a,b\",\"say \"\"hi\"\"\",,\n");
        assert_eq!(
            l[0].as_ref().unwrap().cells,
            vec!["0.5", "a,b", "say \"hi\"", "", ""]
        );
        assert_eq!(
            lines("x\n\n\"0.5,1\n2,3\n"),
            vec![
                Ok(CsvLine {
                    number: 1,
                    cells: vec!["x".into()]
                }),
                Err(CsvLineError::OpenQuote(3))
            ]
        );
    }

    #[test]
    fn a_line_too_long_or_not_text_ends_the_reading_at_its_number() {
        let long = format!("a\n\n{}\nb\n", "1".repeat(MAX_CSV_LINE_BYTES + 1));
        let l = lines(&long);
        assert_eq!(l.len(), 2);
        assert_eq!(l[1], Err(CsvLineError::TooLong(3)));
        let just = format!("{}\r\n", "1".repeat(MAX_CSV_LINE_BYTES));
        assert!(lines(&just)[0].is_ok());
        let l: Vec<_> = CsvLines::new(&b"a\n\xff,1\n"[..]).collect();
        assert_eq!(l[1], Err(CsvLineError::NotText(2)));
        assert_eq!(
            CsvLineError::NotText(2).to_string(),
            "line 2 is not UTF-8 text"
        );
    }

    #[test]
    fn devices_and_folders_are_refused_and_sizes_bounded() {
        assert!(
            read_bounded(Path::new("/dev/zero"), 10)
                .unwrap_err()
                .contains("regular")
        );
        assert!(
            read_bounded(Path::new("/"), 10)
                .unwrap_err()
                .contains("regular")
        );
        let p = std::env::temp_dir().join(format!("slideroute-bounded-{}", std::process::id()));
        std::fs::write(&p, "0123456789ab").unwrap();
        assert!(read_bounded(&p, 10).unwrap_err().contains("12 bytes"));
        assert_eq!(read_bounded(&p, 12).unwrap(), "0123456789ab");
        let _ = std::fs::remove_file(&p);
    }
}
