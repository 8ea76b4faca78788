//! What the browser tests share: the browser.

use std::path::PathBuf;
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
