//! A route read in chunks (`Scene.route_chunks`): the route computes on a thread of its own,
//! its rows handed over a few chunks at a time, so that a route of any length is read in
//! bounded memory — the chunks the caller keeps are the caller's.

use crate::columns::RouteColumns;
use crate::errors::{route_error, scene_error};
use pyo3::exceptions::PyStopIteration;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use slideroute::{Computed, Row, Runner};
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError, SyncSender, sync_channel};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::Duration;

/// Chunks computed ahead of the caller: the route waits when this many are unread.
const AHEAD: usize = 2;

/// What the route's thread hands over: rows, or the end.
enum Message {
    Rows(Vec<Row>),
    Done(Box<Computed>),
    Invalid(slideroute::SceneError),
}

/// The chunks of one route, in order; then its summary.
#[pyclass(module = "slideroute._native", name = "RouteChunks")]
pub struct PyRouteChunks {
    /// In a mutex for Python's threads (one reads at a time).
    rows: Option<Mutex<Receiver<Message>>>,
    stop: Arc<AtomicBool>,
    worker: Option<JoinHandle<()>>,
    /// The route's summary (as summary.json has it) once the last chunk is read.
    summary: Option<Py<PyAny>>,
}

impl PyRouteChunks {
    /// Starts `scene`'s route, its rows in chunks of `rows` rows.
    pub fn start(scene: slideroute::Scene, rows: usize) -> PyRouteChunks {
        let (tx, rx) = sync_channel::<Message>(AHEAD);
        let stop = Arc::new(AtomicBool::new(false));
        let halt = Arc::clone(&stop);
        let worker = std::thread::spawn(move || compute(&scene, rows, &tx, &halt));
        PyRouteChunks {
            rows: Some(Mutex::new(rx)),
            stop,
            worker: Some(worker),
            summary: None,
        }
    }

    /// Ends the route's thread: told to stop, the channel closed, joined.
    fn end(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        self.rows = None; // a send waiting on a full channel fails at once
        if let Some(w) = self.worker.take() {
            let _ = w.join();
        }
    }
}

/// The route's thread: the route of `scene`, every row into chunks of `size` sent down `tx`
/// (waiting while [`AHEAD`] are unread), then its summary; stops at `halt` or when the
/// receiver has gone.
fn compute(scene: &slideroute::Scene, size: usize, tx: &SyncSender<Message>, halt: &AtomicBool) {
    let sim = match scene.simulation() {
        Ok(s) => s,
        Err(e) => {
            let _ = tx.send(Message::Invalid(e));
            return;
        }
    };
    let gone = AtomicBool::new(false);
    let mut chunk = Vec::with_capacity(size);
    let computed = Runner::new(&sim)
        .progress(|_| {
            if halt.load(Ordering::Relaxed) || gone.load(Ordering::Relaxed) {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        })
        .stream(1, |r| {
            chunk.push(*r);
            if chunk.len() == size {
                let full = std::mem::replace(&mut chunk, Vec::with_capacity(size));
                if tx.send(Message::Rows(full)).is_err() {
                    gone.store(true, Ordering::Relaxed);
                }
            }
        })
        .keep_at_most(slideroute::KEPT_ROWS)
        .run();
    if !chunk.is_empty() && tx.send(Message::Rows(chunk)).is_err() {
        return;
    }
    let _ = tx.send(Message::Done(Box::new(computed)));
}

/// `rows` as `route.csv`'s columns ([`RouteColumns`]).
pub fn columns<'py>(py: Python<'py>, rows: &[Row]) -> PyResult<Bound<'py, PyDict>> {
    let mut cols = RouteColumns::with_capacity(rows.len());
    for row in rows {
        cols.push(row);
    }
    cols.into_dict(py)
}

#[pymethods]
impl PyRouteChunks {
    fn __iter__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    /// The next chunk's columns; `StopIteration` after the last. Ctrl-C stops the route with
    /// `KeyboardInterrupt` (the interpreter is checked every 50 ms while the route computes).
    fn __next__<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        loop {
            let Some(rx) = &self.rows else {
                return Err(PyStopIteration::new_err(()));
            };
            let got = py.detach(|| match rx.lock() {
                Ok(r) => r.recv_timeout(Duration::from_millis(50)),
                Err(_) => Err(RecvTimeoutError::Disconnected),
            });
            match got {
                Ok(Message::Rows(rows)) => return columns(py, &rows),
                Ok(Message::Done(computed)) => {
                    self.summary = Some(crate::json(py, &*computed)?.unbind());
                    self.end();
                    return Err(PyStopIteration::new_err(()));
                }
                Ok(Message::Invalid(e)) => {
                    self.end();
                    return Err(scene_error(py, &e));
                }
                Err(RecvTimeoutError::Timeout) => {
                    if let Err(e) = py.check_signals() {
                        self.end();
                        return Err(e);
                    }
                }
                Err(RecvTimeoutError::Disconnected) => {
                    self.end();
                    return Err(route_error(py, "the computation failed unexpectedly"));
                }
            }
        }
    }

    /// The route's summary (as summary.json has it) once every chunk was read, else None.
    #[getter]
    fn summary(&self, py: Python<'_>) -> Option<Py<PyAny>> {
        self.summary.as_ref().map(|s| s.clone_ref(py))
    }

    /// Stops the route (the chunks not read are dropped).
    fn close(&mut self) {
        self.end();
    }
}

impl Drop for PyRouteChunks {
    fn drop(&mut self) {
        self.end();
    }
}
