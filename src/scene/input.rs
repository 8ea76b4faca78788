//! Reading an input file with bounds: only a regular file, at most a stated size,
//! so that `/dev/zero`, a FIFO with no writer or a runaway file gets one clear error instead of
//! growing memory without end, an abort or a hang.

use std::io::Read;
use std::path::Path;

/// The largest scene file (bytes): a scene is a few kilobytes.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// Opens `path` for reading if it is a regular file of at most `limit` bytes; the error, for
/// people, says why not (without the path: the caller names the file).
pub fn open_bounded(path: &Path, limit: u64) -> Result<impl Read, String> {
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

#[cfg(test)]
mod tests {
    use super::*;

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
