//! The short summaries `run` and `run --compare-dynamics` print: how the route ended, where, at
//! what factor of safety, at what cost, and what was written. Numbers at a precision for people
//! (the files keep every digit).

use crate::compare::Comparison;
use crate::numeric::{fixed, seconds};
use crate::{Computed, Route};
use std::fmt;
use std::path::PathBuf;

impl Computed {
    /// What `slideroute run` prints of the route, the files written for it named last: how
    /// it ended, where, the factor of safety, the record's intensity under shaking, the cost
    /// and the energy balance, numbers at a precision for people (the files keep every digit).
    ///
    /// ```
    /// let sim = slideroute::Scene::default_scene().simulation()?;
    /// let computed = slideroute::Runner::new(&sim).run();
    /// let text = computed.summary(&["out/route.csv".into()]).to_string();
    /// assert!(text.starts_with("scene paper-like: ") && text.ends_with("wrote out/route.csv\n"));
    /// # Ok::<(), slideroute::SceneError>(())
    /// ```
    pub fn summary<'a>(&'a self, files: &'a [PathBuf]) -> impl fmt::Display + 'a {
        RouteSummary {
            computed: self,
            files,
        }
    }
}

impl Comparison {
    /// What `slideroute run --compare-dynamics` prints: both routes' ends, where they part,
    /// and the files written.
    pub fn summary<'a>(&'a self, files: &'a [PathBuf]) -> impl fmt::Display + 'a {
        CompareSummary {
            comparison: self,
            files,
        }
    }
}

/// The files written, as one line.
fn written(files: &[PathBuf]) -> String {
    let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
    names.join(", ")
}

/// The summary of one route, how long it took, and the files written for it.
struct RouteSummary<'a> {
    computed: &'a Computed,
    files: &'a [PathBuf],
}

impl fmt::Display for RouteSummary<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let r = &self.computed.route;
        let t = &r.termination;
        writeln!(
            f,
            "scene {}: {} at t = {} s",
            r.scene,
            t.reason,
            seconds(t.t_s)
        )?;
        writeln!(f, "  {}", t.detail)?;
        if let Some(last) = r.rows.last() {
            writeln!(
                f,
                "  travel {} m; final yaw θ = {}°, tilts α = {}°, β = {}°, γ = {}°",
                fixed(r.travel_m, 3),
                fixed(last.theta_deg, 3),
                fixed(last.alpha_deg, 3),
                fixed(last.beta_deg, 3),
                fixed(last.gamma_deg, 3)
            )?;
        }
        for b in &r.anchors_broken {
            writeln!(
                f,
                "  anchor {} broke at its capacity at t = {} s",
                b.anchor,
                seconds(b.t_s)
            )?;
        }
        shaking(f, r)?;
        if let Some(fs) = r.factor_of_safety {
            writeln!(f, "  factor of safety {fs} (friction cones at the start)")?;
        }
        if let Some(ratio) = r.paper_ratio() {
            writeln!(
                f,
                "  the paper's resisting/driving ratio along x' at the start {ratio:.4}"
            )?;
        }
        writeln!(
            f,
            "  {} increments ({} dynamics, {} mode, {} integrator) in {} s",
            r.increments,
            r.dynamics.as_str(),
            r.mode.as_str(),
            r.integrator.as_str(),
            fixed(self.computed.diagnostics.wall_s, 3),
        )?;
        energy(f, r)?;
        writeln!(f, "  wrote {}", written(self.files))
    }
}

/// Under a ground-motion record: the permanent displacement and rotation, both polarities, the
/// yield acceleration and the record's intensity.
fn shaking(f: &mut fmt::Formatter<'_>, r: &Route) -> fmt::Result {
    if let (Some(d), Some(rot)) = (r.permanent_displacement_m, r.permanent_rotation_deg) {
        let xz = r.permanent_displacement_xz_m.unwrap_or([0.0; 2]);
        writeln!(
            f,
            "  permanent displacement {} m (X {} m, Z {} m), rotation {}° (relative to the \
             shaken foundation)",
            fixed(d, 3),
            fixed(xz[0], 3),
            fixed(xz[1], 3),
            fixed(rot, 3)
        )?;
    }
    if let Some(p) = &r.polarities {
        let length = |d: [f64; 2]| fixed(d[0].hypot(d[1]), 3);
        writeln!(
            f,
            "  both polarities: {} m as recorded, {} m reversed; this route is the {} one",
            length(p.normal_xz_m),
            length(p.reversed_xz_m),
            p.reported
        )?;
    }
    if let Some(y) = &r.yield_acceleration {
        writeln!(
            f,
            "  yield acceleration ky {} g at the start (the block pushed along {}° from X \
             towards Z, the ground accelerating the other way)",
            fixed(y.ky_g, 4),
            fixed(y.push_deg, 1)
        )?;
    }
    if let Some(m) = &r.record_intensity {
        // A component without shaking (none given, or all zero) is a dash, not a duration
        // of 0 s.
        let three = |v: [f64; 3], places: usize| {
            (0..3)
                .map(|c| match m.pga_g[c] > 0.0 {
                    true => fixed(v[c], places).to_string(),
                    false => "—".to_string(),
                })
                .collect::<Vec<_>>()
                .join(" / ")
        };
        writeln!(
            f,
            "  record (X / Y / Z): PGA {} g, PGV {} m/s, Arias intensity {} m/s, D5–95 {} s",
            three(m.pga_g, 3),
            three(m.pgv_m_s, 3),
            three(m.arias_m_s, 3),
            three(m.d5_95_s, 2)
        )?;
    }
    Ok(())
}

/// The energy balance of a block that moved (one that never moved has none to account for).
fn energy(f: &mut fmt::Formatter<'_>, r: &Route) -> fmt::Result {
    // A block that never moved has no energy to account for.
    if let Some(e) = r.energy().filter(|_| r.increments > 0) {
        let kinetic = if e.kinetic_initial_j != 0.0 {
            format!(
                "kinetic {:.6e} J (from {:.6e} J)",
                e.kinetic_j, e.kinetic_initial_j
            )
        } else {
            format!("kinetic {:.6e} J", e.kinetic_j)
        };
        writeln!(
            f,
            "  energy: hydraulic work {:.6e} J, friction work {:.6e} J, {kinetic}, \
             potential change {:.6e} J, balance residual {:.3e} J",
            e.work_hydraulic_j, e.work_friction_j, e.potential_change_j, e.residual_j
        )?;
    }
    let (first, unmet) = r.report.not_held();
    if let Some(p) = first {
        writeln!(
            f,
            "  first order (the time-stepping scheme alone): {} steps, {} s of the route \
             between t = {} and {} s: the route and its energy balance there are not held to \
             the tolerance",
            p.steps,
            fixed(p.duration_s, 3),
            seconds(p.from_s),
            seconds(p.to_s)
        )?;
    }
    if let Some(u) = unmet {
        writeln!(
            f,
            "  over the tolerance: {} steps at the shortest step between t = {} and {} s, \
             at worst {} times it",
            u.steps,
            seconds(u.from_s),
            seconds(u.to_s),
            fixed(u.worst_ratio, 1)
        )?;
    }
    Ok(())
}

/// The summary of both dynamics' routes of one scene, where they part, and the files written.
struct CompareSummary<'a> {
    comparison: &'a Comparison,
    files: &'a [PathBuf],
}

impl fmt::Display for CompareSummary<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = self.comparison;
        for (name, r) in [
            ("paper's dynamics", &c.paper.route),
            ("rigid body", &c.rigid_body.route),
        ] {
            writeln!(
                f,
                "{name}: {} at t = {} s; travel {} m, final yaw θ = {}°",
                r.termination.reason,
                seconds(r.termination.t_s),
                fixed(r.travel_m, 3),
                fixed(r.rows.last().map_or(0.0, |l| l.theta_deg), 3)
            )?;
        }
        let p = &c.parting;
        match p.parted_at_s {
            Some(t) => writeln!(
                f,
                "  the routes part (CM {} m apart, 1% of L) at t = {} s, near X = {} m, Z = {} m",
                fixed(p.threshold_m, 3),
                fixed(t, 3),
                fixed(p.parted_at_x_m.unwrap_or(f64::NAN), 3),
                fixed(p.parted_at_z_m.unwrap_or(f64::NAN), 3)
            )?,
            None => writeln!(
                f,
                "  the routes stay within {} m (1% of L) while both run",
                fixed(p.threshold_m, 3)
            )?,
        }
        writeln!(
            f,
            "  until t = {} s: largest separation {} m (at {} s); at the end {} m apart, yaw \
             rigid − paper {:+.3}°",
            fixed(p.common_until_s, 3),
            fixed(p.max_separation_m, 3),
            fixed(p.max_separation_at_s, 3),
            fixed(p.separation_at_end_m, 3),
            p.yaw_difference_at_end_deg
        )?;
        writeln!(f, "  wrote {}", written(self.files))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_still_block_has_no_energy_line_and_numbers_are_short() {
        let sim = crate::Scene::default_scene().simulation().unwrap();
        let mut computed = crate::Runner::new(&sim).run();
        computed.diagnostics.wall_s = 0.123456789;
        let s = RouteSummary {
            computed: &computed,
            files: &[PathBuf::from("out/route.csv")],
        }
        .to_string();
        assert!(s.contains("in 0.123 s"), "{s}");
        assert!(
            s.contains("energy:"),
            "a moving rigid body has its balance: {s}"
        );
        assert!(s.ends_with("wrote out/route.csv\n"), "{s}");
        computed.route.increments = 0;
        let still = RouteSummary {
            computed: &computed,
            files: &[],
        }
        .to_string();
        assert!(!still.contains("energy:"), "{still}");
    }
}
