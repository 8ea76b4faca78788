//! The paper's dynamics (§5–7; `[solver] dynamics = "paper"`): translation along x' and
//! turning about y', with the paper's frictional reactions (`mechanics::reactions_paper`), the
//! paper's update (33)–(38) or RK4 (`step.rs`; over an increment in substeps chosen against the
//! tolerance, `substeps.rs`), its right-hand side (`rhs.rs`). A dynamics model
//! (`route/dynamics.rs`) the driver (`driver.rs`) runs; it stops and rests through the route's
//! event and rest layers (`route/events.rs`, `route/rest.rs`), on the three-point frame's room
//! (`route/three_point.rs`).

mod rhs;
mod state;
mod step;
mod substeps;

pub use rhs::{Evaluation, evaluate, velocity};
pub use state::State;
pub use step::{paper_step, rk4_step};

use super::Steps;
use super::dynamics::{Dynamics, Flow, Start};
use super::logbook::Logbook;
use super::pose_finder::PoseFinder;
use super::rest::AtRest;
use super::row::Row;
use super::termination::{Reason, Stop};
use super::three_point::{
    faces_of, factor_of_safety_at_start, frame_row, yield_acceleration_at_start,
};
use crate::geometry::Pose;
use crate::mechanics::loads::Applied;
use crate::mechanics::onset::factor_of_safety;
use crate::model::{Body, Integrator, Simulation};
use serde::Serialize;

/// What the paper's dynamics adds to its route.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct PaperReport {
    /// Its resisting capacity over driving force along x' at the start (`mechanics::onset`), a
    /// quantity other than the factor of safety every route has (absent where nothing drives
    /// the block along x').
    #[serde(skip_serializing_if = "Option::is_none")]
    pub paper_ratio: Option<f64>,
    /// How often the followed friction solution was lost and chosen afresh by the rule
    /// (summary.json writes it with the computation's numbers, `Report::friction_switches`).
    #[serde(skip)]
    pub friction_switches: usize,
    /// RK4's substeps, chosen against the tolerance (none with the paper's own update; written
    /// with the computation's numbers, `Report::steps`).
    #[serde(skip)]
    pub steps: Steps,
}

/// The paper's logbook.
type Log<'s> = Logbook<'s, PaperReport>;

/// The row of state `s` at `pose`, with the reactions of `ev` where it was evaluated.
fn row(s: &State, ev: Option<&Evaluation>, pose: &Pose, faces: [u32; 3]) -> Row {
    let reactions = ev.map(|e| {
        let r = &e.reaction;
        (r.normal.map(|v| v.norm()), r.shear.map(|v| v.norm()))
    });
    let state = [s.x, s.z, s.theta, s.vx, s.vz, s.omega];
    frame_row(s.t, state, pose, (faces, [None; 3]), reactions)
}

/// The paper's dynamics under way: the state and the evaluation (pose, reactions,
/// accelerations) at it; with RK4, how many substeps the last increment took.
pub(super) struct Paper<'a> {
    sim: &'a Simulation,
    /// The body it follows.
    body: &'a Body,
    state: State,
    ev: Evaluation,
    pieces: usize,
}

/// An increment taken: the state and the evaluation at its end, how often the friction solution
/// was chosen afresh on the way, the CM's travel (chords at the substeps' ends), and where the
/// velocity along the increment's first acceleration passed through zero, if it did.
struct Stepped<'f> {
    next: State,
    ev: Evaluation,
    switches: usize,
    travel: f64,
    crossing: Option<Crossing<'f>>,
}

/// The (sub)step over which the velocity along the increment's first acceleration passed from
/// below zero to zero or above: its start, the evaluation there, its length, and the travel up
/// to its start, and the pose finder there (RK4's substeps; else the increment's end's).
#[derive(Clone)]
struct Crossing<'f> {
    from: State,
    ev: Evaluation,
    h: f64,
    travel: f64,
    at: Option<PoseFinder<'f>>,
}

/// The paper's resisting-over-driving ratio (`mechanics::onset`) at evaluation `ev`, with the
/// driving and resisting forces: at the start, and at a stop to tell whether the block stays.
fn paper_ratio((sim, body): (&Simulation, &Body), ev: &Evaluation) -> (f64, f64, f64) {
    let applied = Applied::new(body.loads(), body.block(), &ev.geom.frame);
    let strength = body.frame_strength(sim.strengths(), faces_of(body.site()), false);
    factor_of_safety(&ev.geom, &applied, &ev.statics, &strength)
}

impl<'f> Stepped<'f> {
    /// The (sub)step of length `h` from the state so far, its stages from the finder `base`, to
    /// `next`, evaluated there as `end`, taken: the crossing kept if it is the first of the
    /// increment (the velocity along the increment's first acceleration `first_acc` through
    /// zero), the friction solutions chosen afresh counted, the chord travelled.
    fn take(
        &mut self,
        (next, end): (State, Evaluation),
        h: f64,
        first_acc: &[f64; 3],
        base: &PoseFinder<'f>,
    ) {
        let chord = (end.pose.cm - self.ev.pose.cm).norm();
        if self.crossing.is_none() && crosses(first_acc, &self.next, &next) {
            self.crossing = Some(Crossing {
                from: self.next,
                ev: self.ev,
                h,
                travel: self.travel,
                at: Some(base.clone()),
            });
        }
        self.switches += usize::from(end.fresh);
        self.travel += chord;
        (self.next, self.ev) = (next, end);
    }
}

/// Whether the velocity along `a` passes from below zero to zero or above between `s` and `n`.
fn crosses(a: &[f64; 3], s: &State, n: &State) -> bool {
    let along = |w: [f64; 2]| w[0] * a[0] + w[1] * a[1];
    along([s.vx, s.vz]) < 0.0 && along([n.vx, n.vz]) >= 0.0
}

impl<'a> Dynamics<'a> for Paper<'a> {
    type Report = PaperReport;

    fn start<'s>(
        sim: &'a Simulation,
        finder: &mut PoseFinder<'_>,
        mut o: Log<'s>,
    ) -> Start<'s, Self, PaperReport> {
        let body = sim.first_body();
        let init = body.initial();
        // At rest, or moving as the scene's [initial] says.
        let state = State {
            vx: init.vx,
            vz: init.vz,
            omega: init.omega,
            ..State::default()
        };
        // The start: pose, statics and whether the block slides at all (a block that starts
        // moving goes on until it stops, whatever the factor of safety).
        let Some(start_pose) = finder.pose() else {
            return Start::Ended(o.end(
                Reason::NoAdmissibleRoot,
                0.0,
                "the flat start pose has no root to follow".into(),
            ));
        };
        let pair = (sim, body);
        let ev = match evaluate(pair, finder, state.displacement(), None, velocity(&state)) {
            Ok(ev) => ev,
            Err(Stop { reason, detail, .. }) => {
                o.push(row(&state, None, &start_pose, faces_of(body.site())));
                return Start::Ended(o.end(reason, 0.0, detail));
            }
        };
        let (fs, driving, resisting) = paper_ratio(pair, &ev);
        o.report.paper_ratio = fs.is_finite().then_some(fs);
        o.push(row(&state, Some(&ev), &ev.pose, faces_of(body.site())));
        if init.at_rest() && (fs >= 1.0 || ev.reaction.accel <= 0.0) {
            let detail = if driving <= 0.0 {
                format!("nothing drives the block: net driving force along x' is {driving:.6e} N")
            } else if fs >= 1.0 {
                format!(
                    "factor of safety {fs:.4} ≥ 1: resisting capacity {resisting:.6e} N against driving {driving:.6e} N"
                )
            } else {
                format!(
                    "the paper's reactions give no forward acceleration ({:.6e} m/s²)",
                    ev.reaction.accel
                )
            };
            let (reason, detail) = AtRest::NeverSlid(detail).words(sim.foundation());
            return Start::Ended(o.end(reason, 0.0, detail));
        }
        Start::Moving(
            Paper {
                sim,
                body,
                state,
                ev,
                pieces: 1,
            },
            o,
        )
    }

    fn advance<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        t_to: f64,
        mut o: Log<'s>,
    ) -> Flow<'s, PaperReport> {
        let sim = (self.sim, self.body);
        let (state, ev) = (self.state, self.ev);
        // The increment ends at t_to (exactly t_end for the last one).
        let settings = self.sim.settings();
        let dt = t_to - (k - 1) as f64 * settings.dt;
        let stepped = match settings.integrator {
            Integrator::Paper => {
                // Time as k·dt (t_end at the last), not a running sum.
                let next = State {
                    t: t_to,
                    ..paper_step(&state, &ev.acc, dt)
                };
                let at = next.displacement();
                evaluate(sim, finder, at, Some(&ev.reaction), velocity(&next))
                    .map(|e| Stepped {
                        next,
                        ev: e,
                        switches: usize::from(e.fresh),
                        travel: (e.pose.cm - ev.pose.cm).norm(),
                        crossing: crosses(&ev.acc, &state, &next).then_some(Crossing {
                            from: state,
                            ev,
                            h: dt,
                            travel: 0.0,
                            at: None,
                        }),
                    })
                    .map_err(|stop| (stop, None))
            }
            Integrator::Rk4 => self.rk4_within(finder, (t_to, dt), &mut o),
        };
        let Stepped {
            next,
            ev: new_ev,
            switches,
            travel,
            crossing,
        } = match stepped {
            Ok(x) => x,
            Err((Stop { reason, detail, .. }, taken)) => {
                // The block stopped before the substep that could not be, and friction holds
                // it: the route ends there, stopped.
                if let Some(c) = taken.as_ref().and_then(|t| t.crossing.clone()) {
                    o = match self.stop_in(finder, c, state.t, o) {
                        Ok(ended) => return ended,
                        Err(o) => o,
                    };
                }
                // The substeps taken before the one that could not be: the route ends there.
                if let Some(t) = taken {
                    o.report.friction_switches += t.switches;
                    o.travel += t.travel;
                    (self.state, self.ev) = (t.next, t.ev);
                }
                return Flow::Ended(o.finish(self.row(), reason, self.state.t, detail));
            }
        };
        o.report.friction_switches += switches;
        o.increments = k;
        // Stopped where the velocity along the acceleration passes through zero and friction
        // holds (`stop_in`).
        if let Some(c) = crossing {
            o = match self.stop_in(finder, c, state.t, o) {
                Ok(ended) => return ended,
                Err(o) => o,
            };
        }
        o.travel += travel;
        self.state = next;
        self.ev = new_ev;
        Flow::Go(o)
    }

    fn row(&self) -> Row {
        row(
            &self.state,
            Some(&self.ev),
            &self.ev.pose,
            faces_of(self.body.site()),
        )
    }

    /// The frame's factor of safety at the start and, under a record, its yield acceleration.
    fn at_start(sim: &'a Simulation, start: Option<&Pose>, o: &mut Log<'_>) {
        factor_of_safety_at_start(sim, start, o);
        yield_acceleration_at_start(sim, start, o);
    }

    /// Where the paper's dynamics cannot start or continue the block, the detail says so and names
    /// the rigid body's: its kinematics hold only where its frictional system has a
    /// solution and its contacts stay on their planes, which is not physics ending the route.
    fn explain_end(o: &mut Log<'_>) {
        let fs = o.fs;
        let t = &mut o.termination;
        let hint = match t.reason {
            Reason::DoesNotSlide if fs.is_some_and(|f| !f.at_least_one()) => Some(format!(
                "the paper's dynamics cannot start this block, yet the friction cones cannot hold \
                 it (factor of safety {}): run it with --dynamics rigid-body",
                fs.map(|f| f.to_string()).unwrap_or_default()
            )),
            Reason::NoFrictionSolution
            | Reason::NoAdmissibleRoot
            | Reason::ContactLeftPlane
            | Reason::ContactLiftedOff => Some(
                "the paper's dynamics cannot continue here (its kinematics, translation along x' and \
                 turning about y', hold only where its frictional system has a solution that keeps \
                 the contacts on their planes); --dynamics rigid-body follows the block by Newton's \
                 laws"
                    .to_string(),
            ),
            _ => None,
        };
        if let Some(h) = hint {
            t.detail = format!("{}; {h}", t.detail);
        }
    }
}

impl Paper<'_> {
    /// The stop in the (sub)step `c` where the velocity along the increment's first
    /// acceleration passes through zero: the route ends "stopped" there if friction holds the
    /// block (`Ok`, or ended where the stop is off the model, at `start_t`, the increment's
    /// start); else the logbook back (`Err`) and the block goes on.
    ///
    /// Stopped: the CM velocity along the acceleration — along i', the direction the paper's
    /// dynamics drive (eqs. 30–35) — passes through zero in the increment (with RK4, in the
    /// substep `crossing` is), and friction holds there. The paper's model has no friction
    /// against the velocity across i' (a drift of a fraction of a per cent of the speed where
    /// we measured it), so the speed itself only passes through a minimum; the stop sets it
    /// to zero.
    // The logbook comes back by value where the route goes on, as the driver passes it along
    // (`Flow`); boxing it for this one call an increment with a stop would gain nothing.
    #[allow(clippy::result_large_err)]
    fn stop_in<'s>(
        &self,
        finder: &PoseFinder<'_>,
        c: Crossing<'_>,
        start_t: f64,
        mut o: Log<'s>,
    ) -> Result<Flow<'s, PaperReport>, Log<'s>> {
        let sim = (self.sim, self.body);
        // Where the paper's update (accelerations frozen over the (sub)step) brings it to
        // zero: (v + a τ)·a = 0 (with RK4, to first order in τ).
        let (v, a) = ([c.from.vx, c.from.vz], [c.ev.acc[0], c.ev.acc[1]]);
        let along = |w: [f64; 2]| w[0] * a[0] + w[1] * a[1];
        let tau = (-along(v) / along(a)).clamp(0.0, c.h);
        let mut stop = paper_step(&c.from, &c.ev.acc, tau);
        stop.vx = 0.0;
        stop.vz = 0.0;
        stop.omega = 0.0;
        // The finder where the (sub)step started, near the stop (an increment may go on well
        // past it before a later substep fails).
        let mut at_stop = c.at.clone().unwrap_or_else(|| finder.clone());
        let stop_ev = match evaluate(
            sim,
            &mut at_stop,
            stop.displacement(),
            Some(&c.ev.reaction),
            None,
        ) {
            Ok(e) => e,
            Err(Stop { reason, detail, .. }) => {
                return Ok(Flow::Ended(o.finish(self.row(), reason, start_t, detail)));
            }
        };
        let (fs_here, _, _) = paper_ratio(sim, &stop_ev);
        if fs_here < 1.0 {
            return Err(o);
        }
        o.travel += c.travel + (stop_ev.pose.cm - c.ev.pose.cm).norm();
        o.push(row(
            &stop,
            Some(&stop_ev),
            &stop_ev.pose,
            faces_of(self.body.site()),
        ));
        let detail = format!(
            "speed reached zero at t = {:.6} s; factor of safety there {fs_here:.4}",
            stop.t
        );
        let (reason, detail) = AtRest::Stopped(detail).words(self.sim.foundation());
        Ok(Flow::Ended(o.end(reason, stop.t, detail)))
    }
}
