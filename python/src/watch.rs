//! Long computations on a thread of their own while the interpreter's thread watches: for
//! Ctrl-C (a `KeyboardInterrupt` stops the work at its next item) and to tell a progress
//! callable how far the work is.

use crate::errors::route_error;
use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

/// What a long computation and the thread watching it share: whether to stop, and how many
/// samples, combinations, poses, cases or increments are done.
pub struct Watch {
    stop: AtomicBool,
    done: AtomicUsize,
}

impl Watch {
    /// Whether the caller asked the work to stop.
    pub fn stopped(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
    }

    /// One more item done.
    pub fn tick(&self) {
        self.done.fetch_add(1, Ordering::Relaxed);
    }

    /// `done` items done (a route's increments).
    pub fn set(&self, done: usize) {
        self.done.store(done, Ordering::Relaxed);
    }
}

/// Runs `work` on a thread of its own while this one watches it, holding the interpreter only
/// for a moment now and then: a `KeyboardInterrupt` (or an exception of `progress`) raises
/// `stop`, the work ends at its next sample or combination, and the exception is raised here
/// (what was computed is dropped, as Python drops a loop's work when it is interrupted).
/// `progress`, a callable and the total, is called with (done, total) as the count moves (at
/// most about four times a second) and once at the end.
pub fn interruptible<T: Send>(
    py: Python<'_>,
    progress: Option<(&Bound<'_, PyAny>, usize)>,
    work: impl FnOnce(&Watch) -> T + Send,
) -> PyResult<T> {
    let watch = Watch {
        stop: AtomicBool::new(false),
        done: AtomicUsize::new(0),
    };
    let mut failed: Option<PyErr> = None;
    let mut told = (usize::MAX, std::time::Instant::now());
    let mut tell = |failed: &mut Option<PyErr>, last: bool| {
        let Some((f, total)) = progress else {
            return;
        };
        let done = watch.done.load(Ordering::Relaxed);
        let due = told.1.elapsed() >= Duration::from_millis(250);
        if failed.is_none() && done != told.0 && (due || last) {
            told = (done, std::time::Instant::now());
            if let Err(e) = f.call1((done, total)) {
                *failed = Some(e);
                watch.stop.store(true, Ordering::Relaxed);
            }
        }
    };
    let result = std::thread::scope(|s| {
        let handle = s.spawn(|| work(&watch));
        let mut nap = Duration::from_micros(200);
        while !handle.is_finished() {
            py.detach(|| std::thread::sleep(nap));
            nap = (nap * 2).min(Duration::from_millis(25));
            if failed.is_none()
                && let Err(e) = py.check_signals()
            {
                failed = Some(e);
                watch.stop.store(true, Ordering::Relaxed);
            }
            tell(&mut failed, false);
        }
        handle.join()
    });
    tell(&mut failed, true);
    if let Some(e) = failed {
        return Err(e);
    }
    result.map_err(|_| route_error(py, "the computation failed unexpectedly"))
}
