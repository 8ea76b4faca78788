//! One component of a ground-motion record as strong-motion files come
//! (`seismic.record_x`, `record_y`, `record_z`; `derivations/11-dam-loads.md` §7): a PEER NGA
//! `.AT2` file, two columns (time, acceleration) or one column of accelerations at a step
//! `seismic.dt_s`; and the three components put together on one time line.
//!
//! * `.AT2` (PEER NGA-West2 and the older PEER form): four header lines, the third naming the
//!   units ("… IN UNITS OF G"), the fourth the count and the step, `NPTS= 4000, DT= .0050 SEC`
//!   (or `4000 .0050 NPTS, DT`); then the NPTS accelerations, any number to a line. Sample k
//!   is at t = k·DT, the first at t = 0.
//! * Columns: numbers separated by spaces, tabs, commas or semicolons, a sample a line; lines
//!   starting with `#` and text lines before the first sample (a header) are skipped.

use super::files::MAX_RECORD_BYTES;
use super::input::read_bounded;
use crate::model::bracket;
use std::path::Path;

/// The units of a record's accelerations.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Units {
    /// Fractions of g.
    G,
    /// m/s².
    MetresPerSecondSquared,
    /// cm/s² (gal).
    CentimetresPerSecondSquared,
}

impl Units {
    /// From the scene's `seismic.units`: `g`, `m/s2` or `cm/s2`.
    pub fn parse(text: &str) -> Result<Units, String> {
        match text {
            "g" => Ok(Units::G),
            "m/s2" => Ok(Units::MetresPerSecondSquared),
            "cm/s2" => Ok(Units::CentimetresPerSecondSquared),
            other => Err(format!(
                "`{other}` is not a unit of acceleration here: `g`, `m/s2` or `cm/s2`"
            )),
        }
    }

    /// The factor that takes these units to fractions of g, with gravity `gravity` (m/s²).
    pub fn to_g(self, gravity: f64) -> f64 {
        match self {
            Units::G => 1.0,
            Units::MetresPerSecondSquared => 1.0 / gravity,
            Units::CentimetresPerSecondSquared => 0.01 / gravity,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Units::G => "g",
            Units::MetresPerSecondSquared => "m/s2",
            Units::CentimetresPerSecondSquared => "cm/s2",
        }
    }
}

/// One component: its times (s, strictly increasing) and accelerations (in its file's units),
/// and the units the file itself states (an `.AT2` header), if any.
#[derive(Debug, Clone, PartialEq)]
pub struct Component {
    pub t: Vec<f64>,
    pub a: Vec<f64>,
    pub stated: Option<Units>,
}

impl Component {
    /// The acceleration at `t`, linear between samples, zero outside them.
    fn at(&self, t: f64) -> f64 {
        bracket(&self.t, t).map_or(0.0, |(k, f)| {
            self.a[k - 1] + f * (self.a[k] - self.a[k - 1])
        })
    }

    /// The same component in fractions of g: `units` the scene gives, checked against what
    /// the file states, with gravity `gravity` (m/s²).
    pub fn in_g(mut self, units: Option<Units>, gravity: f64) -> Result<Component, String> {
        let units = match (self.stated, units) {
            (Some(file), Some(scene)) if file != scene => {
                return Err(format!(
                    "the file is in {}, the scene says seismic.units = \"{}\"",
                    file.name(),
                    scene.name()
                ));
            }
            (Some(u), _) | (None, Some(u)) => u,
            (None, None) => Units::G,
        };
        let k = units.to_g(gravity);
        for a in &mut self.a {
            *a *= k;
        }
        self.stated = Some(Units::G);
        Ok(self)
    }
}

/// The component in the file at `path`, one column's samples a step `dt` (s) apart.
pub fn read_component(path: &Path, dt: Option<f64>) -> Result<Component, String> {
    let text = read_bounded(path, MAX_RECORD_BYTES)?;
    let lines: Vec<&str> = text.lines().take(4).collect();
    if lines.len() == 4 && lines[3].to_ascii_uppercase().contains("NPTS") {
        if dt.is_some() {
            return Err("an .AT2 file gives its own step (DT): leave out seismic.dt_s".into());
        }
        at2(&text)
    } else {
        columns(&text, dt)
    }
}

/// A PEER `.AT2` file.
fn at2(text: &str) -> Result<Component, String> {
    let mut lines = text.lines();
    let header: Vec<&str> = lines.by_ref().take(4).collect();
    let units = header[2].to_ascii_uppercase();
    if units.contains("VELOCITY") || units.contains("DISPLACEMENT") {
        return Err(format!(
            "line 3: `{}`: a record is the ground's acceleration (an .AT2 file, not .VT2 or .DT2)",
            header[2].trim()
        ));
    }
    let stated = if units.contains("UNITS OF G") {
        Some(Units::G)
    } else if units.contains("CM/S") {
        Some(Units::CentimetresPerSecondSquared)
    } else {
        None
    };
    let (npts, dt) = npts_dt(header[3])?;
    if !(dt > 0.0 && dt.is_finite()) {
        return Err(format!(
            "line 4: the step DT = {dt} s is not a positive number"
        ));
    }
    let mut a = Vec::with_capacity(npts.min(1 << 24));
    for (k, line) in lines.enumerate() {
        for token in line.split_whitespace() {
            let v: f64 = token
                .parse()
                .ok()
                .filter(|v: &f64| v.is_finite())
                .ok_or_else(|| format!("line {}: `{token}` is not a finite number", k + 5))?;
            a.push(v);
        }
    }
    if a.len() != npts {
        return Err(format!(
            "line 4 says NPTS = {npts}, the file has {} values",
            a.len()
        ));
    }
    if npts < 2 {
        return Err("a record needs at least two samples".into());
    }
    let t = (0..npts).map(|k| k as f64 * dt).collect();
    Ok(Component { t, a, stated })
}

/// The count and the step of an `.AT2` file's fourth line: `NPTS= 4000, DT= .0050 SEC` or
/// `4000 .0050 NPTS, DT`.
fn npts_dt(line: &str) -> Result<(usize, f64), String> {
    let upper = line.to_ascii_uppercase();
    let tokens: Vec<&str> = upper
        .split(|c: char| c.is_whitespace() || c == ',' || c == '=')
        .filter(|s| !s.is_empty())
        .collect();
    let after = |key: &str| {
        tokens
            .iter()
            .position(|t| *t == key)
            .and_then(|k| tokens.get(k + 1))
            .and_then(|v| v.parse::<f64>().ok())
    };
    let numbers: Vec<f64> = tokens.iter().filter_map(|t| t.parse().ok()).collect();
    let (n, dt) = match (after("NPTS"), after("DT")) {
        (Some(n), Some(dt)) => (n, dt),
        _ if numbers.len() >= 2 => (numbers[0], numbers[1]),
        _ => {
            // What the line says is not echoed: the file may be any file (a scene names it).
            return Err(format!(
                "line 4 must give the count and the step (`NPTS= 4000, DT= .0050 SEC`); it \
                 does not (it has {} words, {} of them numbers)",
                tokens.len(),
                numbers.len()
            ));
        }
    };
    if !(n >= 0.0 && n.fract() == 0.0 && n <= 1e8) {
        return Err(format!("line 4: NPTS = {n} is not a count of samples"));
    }
    Ok((n as usize, dt))
}

/// A file of one or two columns.
fn columns(text: &str, dt: Option<f64>) -> Result<Component, String> {
    let (mut t, mut a) = (Vec::new(), Vec::new());
    let mut width = None;
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let cells: Vec<&str> = line
            .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
            .filter(|s| !s.is_empty())
            .collect();
        let numbers: Result<Vec<f64>, &str> = cells
            .iter()
            .map(|c| c.parse::<f64>().ok().filter(|v| v.is_finite()).ok_or(*c))
            .collect();
        let numbers = match numbers {
            Ok(n) => n,
            Err(_) if width.is_none() => continue,
            Err(cell) => return Err(format!("line {}: `{cell}` is not a finite number", k + 1)),
        };
        let w = *width.get_or_insert(numbers.len());
        if numbers.len() != w {
            return Err(format!(
                "line {}: {} numbers where the first sample had {w}",
                k + 1,
                numbers.len()
            ));
        }
        match w {
            1 => a.push(numbers[0]),
            2 => {
                if let Some(&last) = t.last()
                    && numbers[0] <= last
                {
                    return Err(format!(
                        "line {}: time {} s does not come after {last} s",
                        k + 1,
                        numbers[0]
                    ));
                }
                t.push(numbers[0]);
                a.push(numbers[1]);
            }
            _ => {
                return Err(format!(
                    "line {}: {w} numbers; a component has one (acceleration, with \
                     seismic.dt_s) or two (time, acceleration); three components with times \
                     go in seismic.record as t_s,ax_g,ay_g,az_g",
                    k + 1
                ));
            }
        }
    }
    if a.len() < 2 {
        return Err("a record needs at least two samples".into());
    }
    match (width, dt) {
        (Some(1), None) => {
            Err("one column of accelerations: give the step between them as seismic.dt_s".into())
        }
        (Some(1), Some(dt)) => {
            if !(dt > 0.0 && dt.is_finite()) {
                return Err(format!("seismic.dt_s = {dt} is not a positive step"));
            }
            t = (0..a.len()).map(|k| k as f64 * dt).collect();
            Ok(Component { t, a, stated: None })
        }
        (_, Some(_)) => Err("the file gives its times: leave out seismic.dt_s".into()),
        _ => Ok(Component { t, a, stated: None }),
    }
}

/// The components along X, Y and Z (any may be missing) as samples of the three at once: at
/// every time any of them has a sample (within 1e-9 s), each linear between its own samples
/// and zero outside them.
pub fn combine(parts: &[Option<Component>; 3]) -> Vec<(f64, [f64; 3])> {
    let mut times: Vec<f64> = parts.iter().flatten().flat_map(|c| c.t.clone()).collect();
    times.sort_by(f64::total_cmp);
    times.dedup_by(|b, a| (*b - *a).abs() <= 1e-9);
    times
        .into_iter()
        .map(|t| {
            let at = |c: &Option<Component>| c.as_ref().map_or(0.0, |c| c.at(t));
            (t, [at(&parts[0]), at(&parts[1]), at(&parts[2])])
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The head of an NGA-West2 file as the PEER database writes it.
    const AT2: &str = "PEER NGA STRONG MOTION DATABASE RECORD
Imperial Valley-06, 10/15/1979, El Centro Array #6, 140
ACCELERATION TIME SERIES IN UNITS OF G
NPTS=    7, DT=   .0100 SEC
  .1234567E-02  -.2000000E-01   .3000000E+00  0.0000000E+00 -.5000000E-02
  .6000000E-02   -.7000000E-02
";

    fn write(name: &str, text: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("slideroute-rec-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path
    }

    #[test]
    fn an_at2_file_gives_its_samples_at_k_dt_in_g_as_its_header_says() {
        let c = read_component(&write("a.AT2", AT2), None).unwrap();
        assert_eq!(c.stated, Some(Units::G));
        assert_eq!(c.a.len(), 7);
        assert_eq!(c.a[0], 1.234567e-3);
        assert_eq!(c.a[6], -7e-3);
        assert!((c.t[6] - 0.06).abs() < 1e-15 && c.t[0] == 0.0);
        // The older PEER form of the fourth line.
        let old = AT2.replace("NPTS=    7, DT=   .0100 SEC", "    7    .01000    NPTS, DT");
        let o = read_component(&write("old.at2", &old), None).unwrap();
        assert_eq!(o, c);
    }

    #[test]
    fn an_at2_file_whose_count_or_values_are_wrong_is_refused_naming_the_line() {
        let short = AT2.replace("NPTS=    7", "NPTS=    8");
        let e = read_component(&write("s.AT2", &short), None).unwrap_err();
        assert!(e.contains("NPTS = 8") && e.contains("7 values"), "{e}");
        let bad = AT2.replace("-.7000000E-02", "-.70000x0E-02");
        let e = read_component(&write("b.AT2", &bad), None).unwrap_err();
        assert!(e.starts_with("line 6:"), "{e}");
        let e = read_component(&write("d.AT2", AT2), Some(0.01)).unwrap_err();
        assert!(e.contains("DT"), "{e}");
        let velocity = AT2.replace(
            "ACCELERATION TIME SERIES IN UNITS OF G",
            "VELOCITY TIME SERIES IN UNITS OF CM/SEC",
        );
        let e = read_component(&write("v.VT2", &velocity), None).unwrap_err();
        assert!(
            e.starts_with("line 3:") && e.contains("acceleration"),
            "{e}"
        );
        // NPTS and DT without the comma, a comma after SEC, as some writers put them.
        let loose = AT2.replace(
            "NPTS=    7, DT=   .0100 SEC",
            "NPTS=      7  DT=  0.0100 SEC,",
        );
        assert_eq!(
            read_component(&write("l.AT2", &loose), None).unwrap(),
            read_component(&write("l0.AT2", AT2), None).unwrap()
        );
    }

    #[test]
    fn two_columns_give_times_and_one_column_takes_its_step_from_the_scene() {
        let two = "time_s, acc_g\n0.0, 0.0\n0.02, 0.1\n# a comment\n0.04 -0.2\n";
        let c = read_component(&write("two.csv", two), None).unwrap();
        assert_eq!(c.t, vec![0.0, 0.02, 0.04]);
        assert_eq!(c.a, vec![0.0, 0.1, -0.2]);
        let one = "0.0\n0.1\n-0.2\n";
        let c1 = read_component(&write("one.txt", one), Some(0.02)).unwrap();
        assert_eq!(c1.a, c.a);
        assert!(c1.t.iter().zip(&c.t).all(|(a, b)| (a - b).abs() < 1e-15));
        let e = read_component(&write("one.txt", one), None).unwrap_err();
        assert!(e.contains("seismic.dt_s"), "{e}");
        let e = read_component(&write("back.csv", "0 0\n0.1 1\n0.05 2\n"), None).unwrap_err();
        assert!(e.starts_with("line 3:"), "{e}");
        let e = read_component(&write("three.csv", "0 0 0\n1 1 1\n"), None).unwrap_err();
        assert!(e.contains("seismic.record"), "{e}");
        let e = read_component(&write("mixed.csv", "0 0\n1 1\n2 x\n"), None).unwrap_err();
        assert!(e.starts_with("line 3:"), "{e}");
    }

    #[test]
    fn units_convert_to_fractions_of_g_and_a_file_that_states_its_own_must_agree() {
        let c = Component {
            t: vec![0.0, 1.0],
            a: vec![981.0, -490.5],
            stated: None,
        };
        let g = c
            .clone()
            .in_g(Some(Units::CentimetresPerSecondSquared), 9.81)
            .unwrap();
        assert!((g.a[0] - 1.0).abs() < 1e-15 && (g.a[1] + 0.5).abs() < 1e-15);
        let stated = Component {
            stated: Some(Units::G),
            ..c
        };
        assert!(
            stated
                .in_g(Some(Units::MetresPerSecondSquared), 9.81)
                .unwrap_err()
                .contains("the file is in g")
        );
        assert!(Units::parse("ft/s2").is_err());
    }

    #[test]
    fn components_sampled_apart_are_put_on_one_time_line_each_linear_between_its_samples() {
        let x = Component {
            t: vec![0.0, 0.02, 0.04],
            a: vec![0.0, 0.2, 0.0],
            stated: None,
        };
        let z = Component {
            t: vec![0.0, 0.01, 0.02, 0.03],
            a: vec![0.1, 0.1, 0.3, 0.3],
            stated: None,
        };
        let s = combine(&[Some(x), None, Some(z)]);
        let t: Vec<f64> = s.iter().map(|p| p.0).collect();
        assert_eq!(t, vec![0.0, 0.01, 0.02, 0.03, 0.04]);
        assert!((s[1].1[0] - 0.1).abs() < 1e-15);
        assert_eq!(s[1].1[2], 0.1);
        assert!((s[3].1[0] - 0.1).abs() < 1e-15);
        // Z ends at 0.03 s: still after it; no Y.
        assert_eq!(s[4].1, [0.0, 0.0, 0.0]);
    }
}
