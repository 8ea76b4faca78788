//! Running a simulation: [`simulate`] for the route alone, or a [`Runner`] that also picks the
//! pose method, reports progress (and may be told to stop), streams the rows as they are
//! computed, and says how the computation went ([`Diagnostics`]).

use super::models;
use super::pose_finder::{PoseFinder, PoseMethod};
use super::row::Row;
use super::{Computed, Diagnostics, Polarities, Route};
use crate::model::{Intensity, Simulation};
use std::ops::ControlFlow;
use std::time::Instant;

/// The route of a simulation, checked when it was built: nothing here can fail, every end is a
/// [`Reason`](super::Reason).
pub fn simulate(sim: &Simulation) -> Route {
    Runner::new(sim).run().route
}

/// Where a streamed route's kept rows go, as they are made.
type RowSink<'a> = Box<dyn FnMut(&Row) + 'a>;

/// The rows a long route keeps in memory for its pictures and summaries where every row goes
/// to a file as it is computed, or is not needed: the command line's routes, a check's cases,
/// a comparison's two routes ([`Runner::keep_at_most`]).
pub const KEPT_ROWS: usize = 4000;

/// How a simulation is run, apart from what is simulated: the pose method, who is told of the
/// progress (and may stop the route), and where rows go as they are computed.
///
/// ```
/// # let sim = slideroute::Scene::default_scene().simulation()?;
/// let mut rows = 0;
/// let run = slideroute::Runner::new(&sim)
///     .progress(|done| if done < 0.01 { std::ops::ControlFlow::Continue(()) } else { std::ops::ControlFlow::Break(()) })
///     .stream(100, |_row| rows += 1)
///     .run();
/// assert_eq!(run.route.termination.reason, slideroute::Reason::Interrupted);
/// # assert!(rows > 0 && run.route.rows.len() < rows);
/// # Ok::<(), slideroute::SceneError>(())
/// ```
#[must_use]
pub struct Runner<'a> {
    sim: &'a Simulation,
    method: PoseMethod,
    progress: Box<dyn FnMut(f64) -> ControlFlow<()> + 'a>,
    sink: Option<RowSink<'a>>,
    keep_every: usize,
}

impl<'a> Runner<'a> {
    /// `sim` by continuation, keeping every row, told of nothing.
    pub fn new(sim: &'a Simulation) -> Self {
        Runner {
            sim,
            method: PoseMethod::Continuation,
            progress: Box::new(|_| ControlFlow::Continue(())),
            sink: None,
            keep_every: 1,
        }
    }

    /// The method that gives the pose at each increment.
    pub fn pose_method(mut self, method: PoseMethod) -> Self {
        self.method = method;
        self
    }

    /// `progress(t / t_end)` after every increment (for progress bars); when it answers
    /// `ControlFlow::Break`, the route stops there with
    /// [`Reason::Interrupted`](super::Reason::Interrupted), its last state the last row, so that
    /// an interrupted run keeps what it computed.
    pub fn progress(mut self, progress: impl FnMut(f64) -> ControlFlow<()> + 'a) -> Self {
        self.progress = Box::new(progress);
        self
    }

    /// Every row to `sink` as it is computed (to be written out), the route keeping only every
    /// `keep_every`-th row and the last (for pictures and summaries): a route of any length in
    /// bounded memory.
    pub fn stream(mut self, keep_every: usize, sink: impl FnMut(&Row) + 'a) -> Self {
        self.sink = Some(Box::new(sink));
        self.keep_every = keep_every.max(1);
        self
    }

    /// The route keeping at most about `rows` of its recorded rows in memory (every k-th and the
    /// last, k from the rows the settings record: t_end / dt / stride), whether or not they are
    /// also streamed ([`Runner::stream`], which sets k itself; call this after it): a route of
    /// any length in bounded memory, its result the same.
    pub fn keep_at_most(mut self, rows: usize) -> Self {
        let s = self.sim.settings();
        let recorded = (s.t_end / s.dt).ceil() / s.stride as f64;
        let k = (recorded / rows.max(1) as f64).ceil();
        self.keep_every = if k.is_finite() && k >= 1.0 {
            // Beyond any count of rows: the first and the last only.
            k.min(usize::MAX as f64) as usize
        } else {
            1
        };
        self
    }

    /// The route and how its computation went. A record to be run under both polarities
    /// (`seismic.polarity = "both"`) is run as it is and reversed, each keeping no rows, then
    /// the one of the longer permanent displacement again as asked (three routes; progress
    /// counts a third for each).
    pub fn run(self) -> Computed {
        if self.sim.foundation().both_polarities() {
            self.both()
        } else {
            self.one()
        }
    }

    /// [`Runner::run`] under both polarities.
    fn both(self) -> Computed {
        let Runner {
            sim,
            method,
            mut progress,
            sink,
            keep_every,
        } = self;
        let (Ok(normal), Ok(reversed)) = (sim.one_polarity(false), sim.one_polarity(true)) else {
            // A record that cannot be reversed was refused when read: run it as it is.
            return Runner {
                sim,
                method,
                progress,
                sink,
                keep_every,
            }
            .one();
        };
        let mut measured = Vec::with_capacity(2);
        for (k, s) in [&normal, &reversed].into_iter().enumerate() {
            let share = k as f64 / 3.0;
            let done = Runner::new(s)
                .pose_method(method)
                .progress(|f| progress(share + f / 3.0))
                .stream(usize::MAX, |_| {})
                .run();
            if done.route.termination.reason == super::Reason::Interrupted {
                return done;
            }
            measured.push(done.route.permanent_displacement_xz_m.unwrap_or([0.0; 2]));
        }
        let length = |d: [f64; 2]| d[0].hypot(d[1]);
        let back = length(measured[1]) > length(measured[0]);
        let chosen = if back { &reversed } else { &normal };
        let mut done = Runner {
            sim: chosen,
            method,
            progress: Box::new(|f| progress(2.0 / 3.0 + f / 3.0)),
            sink,
            keep_every,
        }
        .one();
        done.route.polarities = Some(Polarities {
            reported: if back { "reversed" } else { "normal" },
            normal_xz_m: measured[0],
            reversed_xz_m: measured[1],
        });
        done
    }

    /// One route.
    fn one(mut self) -> Computed {
        let started = Instant::now();
        let sim = self.sim;
        let settings = *sim.settings();
        let mut finder = PoseFinder::new(sim.first_body().site(), settings.mode, self.method);
        let sink = self.sink.as_deref_mut().map(|s| s as &mut dyn FnMut(&Row));
        // One driver; the model, picked by the settings, is the only difference.
        let mut o = models::drive(sim, &mut finder, &mut self.progress, sink, self.keep_every);
        // Newmark's permanent displacement and rotation, when the foundation was shaken.
        let start = o.first_row().map_or((0.0, 0.0), |r| (r.x_m, r.z_m));
        let record = sim.foundation().record();
        let permanent = o
            .last_row()
            .filter(|_| record.is_some())
            .map(|r| ([r.x_m - start.0, r.z_m - start.1], r.theta_deg));
        let gravity = sim.first_body().loads().gravity;
        let intensity = record.map(|r| Intensity::of(r, gravity));
        let route = Route {
            scene: sim.name().to_string(),
            mode: settings.mode,
            integrator: settings.integrator,
            dynamics: settings.dynamics,
            pose_method: self.method,
            rows: o.take_rows(),
            termination: o.termination.clone(),
            factor_of_safety: o.fs,
            factor_of_safety_limit: o.fs_limit,
            travel_m: o.travel,
            increments: o.increments,
            report: o.report.clone(),
            permanent_displacement_m: permanent.map(|p| p.0[0].hypot(p.0[1])),
            permanent_rotation_deg: permanent.map(|p| p.1),
            permanent_displacement_xz_m: permanent.map(|p| p.0),
            record_intensity: intensity,
            yield_acceleration: o.yield_acceleration,
            polarities: None,
            anchors_broken: std::mem::take(&mut o.anchors_broken),
        };
        Computed {
            route,
            diagnostics: Diagnostics {
                tracker: finder.stats(),
                end_jacobian_condition: finder.jacobian_condition(),
                wall_s: started.elapsed().as_secs_f64(),
            },
        }
    }
}
