//! What the browser tests share: the browser and the screenshot's pixels.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The browser: `SLIDEROUTE_CHROMIUM`, else the first of the usual names on the PATH.
pub fn chromium() -> PathBuf {
    if let Some(p) = std::env::var_os("SLIDEROUTE_CHROMIUM") {
        return PathBuf::from(p);
    }
    for name in ["chromium", "chromium-browser", "google-chrome"] {
        if let Ok(o) = Command::new(name).arg("--version").output()
            && o.status.success()
        {
            return PathBuf::from(name);
        }
    }
    panic!("no Chromium on the PATH (apt-get install chromium, or set SLIDEROUTE_CHROMIUM)");
}

/// The screenshot's pixels: width, height and RGBA.
pub fn pixels(png_file: &Path) -> (u32, u32, Vec<[u8; 4]>) {
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(png_file).expect("the screenshot was written"),
    ));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = info.color_type.samples();
    let px = buf[..info.buffer_size()]
        .chunks(channels)
        .map(|c| match channels {
            4 => [c[0], c[1], c[2], c[3]],
            3 => [c[0], c[1], c[2], 255],
            _ => [c[0], c[0], c[0], 255],
        })
        .collect();
    (info.width, info.height, px)
}
