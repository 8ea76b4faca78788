//! The recorded rows within a long step (`derivations/08-rigid-body.md` §4a, "Rows interpolated
//! within a long step"): the model evaluated at a few of them, spread like Chebyshev–Lobatto
//! points, and at one more where the interpolant's error is largest; the rest interpolated
//! through those and the step's two ends, when that one more row says the interpolant is within
//! 10⁻⁴ of the tolerance (never below the model's round-off). In a step that holds no contact
//! their state (X, Z, θ and the rates) is the step's dense output either way, and what is
//! interpolated is what the model adds to it: the CM's height, the tilts and the reactions; in
//! a step that holds a sticking contact where it stuck, the hold moves the state as well, and
//! every value is interpolated.

use crate::numeric::barycentric::{Nodes, combine};
use crate::route::row::Row;
use crate::route::termination::Stop;

/// The fewest rows inside a step that are interpolated: below it each is evaluated (the
/// interpolation evaluates `INSIDE + 1` of them).
pub(super) const FEWEST: usize = 12;

/// The rows evaluated as nodes inside the step; with the step's two ends, the interpolant's
/// degree is `INSIDE + 1`, one above the step's own order.
const INSIDE: usize = 4;

/// The nodes: the step's two ends and those inside.
const N: usize = INSIDE + 2;

/// The rows of an interpolated step that are evaluated: the nodes inside and the check.
pub(super) const EVALUATED: usize = INSIDE + 1;

/// The largest error of an interpolated value, as a fraction of the tolerance times the
/// value's scale (the block's size L for the CM's height, one radian for the tilts, the largest
/// normal reaction at the nodes for the reactions).
const SHARE: f64 = 1e-4;

/// The least bound, as a fraction of the value's scale: the model's own round-off (on the
/// default scene, interpolated and evaluated forces differ by up to 8·10⁻¹⁴ of the largest
/// normal reaction; at τ below 10⁻⁹ the bound `SHARE` τ would refuse every step on round-off).
const ROUND_OFF: f64 = 1e-13;

/// A row's numbers but its time: X, Y, Z, θ, α, β, γ, Ẋ, Ż, θ̇, the normal reactions and the
/// shears.
const FIELDS: usize = 16;

/// Which of a row's numbers are interpolated.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Values {
    /// What the model adds to the step's state: the CM's height Y, the tilts, the reactions.
    Model,
    /// Every number (a held contact's projection moves the state too).
    All,
}

impl Values {
    /// The fields interpolated (indices into `fields`).
    fn which(self) -> &'static [usize] {
        match self {
            Values::Model => &[1, 4, 5, 6, 10, 11, 12, 13, 14, 15],
            Values::All => &[0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15],
        }
    }
}

/// What became of the rows within a step.
#[derive(Debug)]
pub(super) enum Interpolated {
    /// The rows are interpolated (in time order).
    Done,
    /// The interpolant is not close enough at the check (or a value there is not a number),
    /// the rows are of different kinds (faces, creases, a reaction missing), or an
    /// interpolated normal reaction is below zero: each row is to be evaluated.
    Evaluate,
}

/// A row's numbers but its body and its time (`FIELDS`: `Row::values` after those two, in its
/// order), if it has its reactions.
fn fields(r: &Row) -> Option<[f64; FIELDS]> {
    let values = r.values();
    let mut f = [0.0; FIELDS];
    for (f, v) in f.iter_mut().zip(&values[2..2 + FIELDS]) {
        *f = (*v)?;
    }
    Some(f)
}

/// Row `r` with the fields `which` set from `v`.
fn with_fields(mut r: Row, v: &[f64; FIELDS], which: &[usize]) -> Row {
    let (mut n, mut s) = (r.n_n.unwrap_or_default(), r.s_n.unwrap_or_default());
    for &i in which {
        let x = v[i];
        match i {
            0 => r.x_m = x,
            1 => r.y_m = x,
            2 => r.z_m = x,
            3 => r.theta_deg = x,
            4 => r.alpha_deg = x,
            5 => r.beta_deg = x,
            6 => r.gamma_deg = x,
            7 => r.vx_m_s = x,
            8 => r.vz_m_s = x,
            9 => r.omega_deg_s = x,
            10..13 => n[i - 10] = x,
            _ => s[i - 13] = x,
        }
    }
    r.n_n = Some(n);
    r.s_n = Some(s);
    r
}

/// Whether two rows are of one kind: of the same body, on the same faces, creases and carrying
/// points.
fn same_kind(a: &Row, b: &Row) -> bool {
    a.body == b.body
        && a.faces == b.faces
        && a.crease == b.crease
        && a.corners_carrying == b.corners_carrying
        && a.points_carrying == b.points_carrying
}

/// The rows at `times` (increasing, strictly inside the step from `t0` to `t1`, at least
/// `FEWEST` of them) into `out`, the `values` interpolated: `first` and `last` the rows at the
/// step's ends, `exact` the model's row at a time (called in increasing time), `state` the row
/// of the step's dense state at a time (its other values as they come; those interpolated are
/// set over them). `l` the block's size, `tolerance` the route's. An error is a node's row off
/// the model.
#[allow(clippy::too_many_arguments)]
pub(super) fn interpolate(
    times: &[f64],
    (t0, first): (f64, &Row),
    (t1, last): (f64, &Row),
    (l, tolerance): (f64, f64),
    values: Values,
    mut exact: impl FnMut(f64) -> Result<Row, Stop>,
    state: impl Fn(f64, &Row) -> Row,
    out: &mut Vec<Row>,
) -> Result<Interpolated, Stop> {
    out.clear();
    let h = t1 - t0;
    let (Some((picked, nodes, check)), Some(ends)) =
        (nodes_in(times, t0, h), fields(first).zip(fields(last)))
    else {
        return Ok(Interpolated::Evaluate);
    };
    let mut evaluated: [(usize, Row); INSIDE + 1] = [(0, Row::default()); INSIDE + 1];
    let mut order = [picked[0], picked[1], picked[2], picked[3], check];
    order.sort_unstable();
    for (slot, &k) in evaluated.iter_mut().zip(&order) {
        *slot = (k, exact(times[k])?);
    }
    let Some((nodal, checked)) = nodal_values(&evaluated, &picked, ends, (first, last)) else {
        return Ok(Interpolated::Evaluate);
    };
    let which = values.which();
    let bounds = bounds(&nodal, l, SHARE * tolerance);
    let at = |t: f64| -> [f64; FIELDS] {
        let basis = nodes.basis((t - t0) / h);
        std::array::from_fn(|i| combine(&basis, &nodal[i]))
    };
    let guess = at(times[check]);
    // (Not `>`: a value that is not a number is no agreement.)
    if !which
        .iter()
        .all(|&i| (guess[i] - checked[i]).abs() <= bounds[i])
    {
        return Ok(Interpolated::Evaluate);
    }
    let row = |t: f64, v: &[f64; FIELDS]| with_fields(state(t, first), v, which);
    Ok(fill(times, &evaluated, at, row, out))
}

/// The nodes inside a step from `t0` of length `h` among the rows at `times`: the rows picked
/// near the Chebyshev–Lobatto points, the nodes (with the step's two ends) in the step's
/// fraction s, and the row where the nodal polynomial is largest, where the interpolant is
/// checked; none where the rows are too few or the nodes do not make an interpolant.
fn nodes_in(times: &[f64], t0: f64, h: f64) -> Option<([usize; INSIDE], Nodes<N>, usize)> {
    let picked = pick(times, t0, h)?;
    let s_of = |t: f64| (t - t0) / h;
    let mut s = [0.0; N];
    s[N - 1] = 1.0;
    for (j, &k) in picked.iter().enumerate() {
        s[j + 1] = s_of(times[k]);
    }
    let nodes = Nodes::new(s)?;
    let check = (0..times.len())
        .filter(|k| !picked.contains(k))
        .max_by(|&a, &b| {
            let w = |k: usize| nodes.nodal(s_of(times[k])).abs();
            w(a).total_cmp(&w(b))
        })?;
    Some((picked, nodes, check))
}

/// Each field's values at the nodes — the step's ends' `ends` and those of the rows `evaluated`
/// at the `picked` rows — and the check row's; none where an evaluated row has no reactions,
/// is of another kind than the step's ends (`first`, `last`), or the check is missing.
fn nodal_values(
    evaluated: &[(usize, Row); INSIDE + 1],
    picked: &[usize; INSIDE],
    ends: ([f64; FIELDS], [f64; FIELDS]),
    (first, last): (&Row, &Row),
) -> Option<([[f64; N]; FIELDS], [f64; FIELDS])> {
    let mut nodal = [[0.0; N]; FIELDS];
    for (i, v) in nodal.iter_mut().enumerate() {
        v[0] = ends.0[i];
        v[N - 1] = ends.1[i];
    }
    let mut checked = None;
    for (k, row) in evaluated {
        let d = fields(row).filter(|_| same_kind(row, first) && same_kind(row, last))?;
        match picked.iter().position(|p| p == k) {
            Some(j) => nodal.iter_mut().zip(d).for_each(|(v, x)| v[j + 1] = x),
            None => checked = Some(d),
        }
    }
    Some((nodal, checked?))
}

/// The rows at `times` into `out`: the rows `evaluated` as they are, the others the
/// interpolant's values `at` their time set over the dense state's `row`; none, and `Evaluate`,
/// where an interpolated normal reaction is below zero (a lift-off between the nodes is the
/// model's to tell).
fn fill(
    times: &[f64],
    evaluated: &[(usize, Row); INSIDE + 1],
    at: impl Fn(f64) -> [f64; FIELDS],
    row: impl Fn(f64, &[f64; FIELDS]) -> Row,
    out: &mut Vec<Row>,
) -> Interpolated {
    let mut next = evaluated.iter().peekable();
    for (k, &t) in times.iter().enumerate() {
        if let Some((_, r)) = next.next_if(|(j, _)| *j == k) {
            out.push(*r);
            continue;
        }
        let v = at(t);
        if v[10..13].iter().any(|n| *n < 0.0) {
            out.clear();
            return Interpolated::Evaluate;
        }
        out.push(row(t, &v));
    }
    Interpolated::Done
}

/// Each field's bound from its values at the nodes: `share` (10⁻⁴ of the tolerance, not below
/// `ROUND_OFF`) of its scale — the block's size `l` for X, Y, Z, one radian for the angles, the
/// largest speed at the nodes (of the CM, or of a point at `l` from it by the yaw rate) for the
/// rates, the largest normal reaction at the nodes for the forces.
fn bounds(nodal: &[[f64; N]; FIELDS], l: f64, share: f64) -> [f64; FIELDS] {
    let largest = |range: std::ops::Range<usize>, by: f64| {
        nodal[range]
            .iter()
            .flatten()
            .fold(0.0_f64, |m, x| m.max(by * x.abs()))
    };
    let reactions = largest(10..13, 1.0);
    let speed = largest(7..9, 1.0).max(largest(9..10, l.to_radians()));
    let degree = 1f64.to_degrees();
    let yaw_rate = (speed / l).to_degrees();
    let share = share.max(ROUND_OFF);
    let mut scale = [reactions; FIELDS];
    scale[..10].copy_from_slice(&[
        l, l, l, degree, degree, degree, degree, speed, speed, yaw_rate,
    ]);
    scale.map(|x| share * x)
}

/// The rows (indices into `times`) nearest the Chebyshev–Lobatto points inside the step from
/// `t0` of length `h`, distinct and in time order; `None` if the rows are too few for them.
fn pick(times: &[f64], t0: f64, h: f64) -> Option<[usize; INSIDE]> {
    if times.len() < FEWEST {
        return None;
    }
    let mut picked = [0; INSIDE];
    for j in 0..INSIDE {
        let angle = std::f64::consts::PI * (j + 1) as f64 / (N - 1) as f64;
        let target = t0 + h * 0.5 * (1.0 - angle.cos());
        let k = times.partition_point(|&t| t < target);
        // The nearer of the rows either side of the target.
        let k = match k {
            0 => 0,
            k if k == times.len() => k - 1,
            k if target - times[k - 1] <= times[k] - target => k - 1,
            k => k,
        };
        picked[j] = if j > 0 { k.max(picked[j - 1] + 1) } else { k };
    }
    (picked[INSIDE - 1] < times.len()).then_some(picked)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::route::termination::Reason;

    /// A row whose values are smooth functions of time, X the time itself.
    fn model(t: f64) -> Row {
        let v: [f64; FIELDS] = std::array::from_fn(|i| {
            let k = i as f64;
            match i {
                0 => t,
                10.. => 1e6 * (2.0 + (0.7 * t + 0.1 * k).sin()),
                _ => (1.3 * t + k).cos(),
            }
        });
        let at = Row {
            t_s: t,
            ..Row::default()
        };
        with_fields(at, &v, Values::All.which())
    }

    fn state(t: f64, template: &Row) -> Row {
        Row {
            t_s: t,
            x_m: t,
            ..*template
        }
    }

    fn times(t0: f64, h: f64, n: usize) -> Vec<f64> {
        (1..=n)
            .map(|k| t0 + h * k as f64 / (n + 1) as f64)
            .collect()
    }

    /// The rows of a step from 0.5 s to 0.54 s with `n` rows inside, the model `m` (its ends
    /// too), τ = 10⁻⁹ and L = 1 m, the model's values interpolated: what became of them, and
    /// the rows.
    fn step(
        n: usize,
        m: impl FnMut(f64) -> Result<Row, Stop>,
        ends: impl Fn(f64) -> Row,
    ) -> (Result<Interpolated, Stop>, Vec<Row>) {
        step_of(Values::Model, n, m, ends, state)
    }

    /// `step` with `values` interpolated and the dense state `state`.
    fn step_of(
        values: Values,
        n: usize,
        m: impl FnMut(f64) -> Result<Row, Stop>,
        ends: impl Fn(f64) -> Row,
        state: impl Fn(f64, &Row) -> Row,
    ) -> (Result<Interpolated, Stop>, Vec<Row>) {
        let (t0, h) = (0.5, 0.04);
        let mut out = Vec::new();
        let (first, last) = (ends(t0), ends(t0 + h));
        let got = interpolate(
            &times(t0, h, n),
            (t0, &first),
            (t0 + h, &last),
            (1.0, 1e-9),
            values,
            m,
            state,
            &mut out,
        );
        (got, out)
    }

    #[test]
    fn rows_of_a_smooth_model_are_interpolated_within_the_bound_from_five_evaluations() {
        let ts = times(0.5, 0.04, 39);
        let mut calls = Vec::new();
        let record = |t| {
            calls.push(t);
            Ok(model(t))
        };
        let (got, out) = step(39, record, model);
        assert!(matches!(got, Ok(Interpolated::Done)));
        assert_eq!(calls.len(), EVALUATED);
        // In time order: the tracker behind the model follows the rows.
        assert!(calls.windows(2).all(|w| w[0] < w[1]), "{calls:?}");
        assert_eq!(out.len(), ts.len());
        for (r, &t) in out.iter().zip(&ts) {
            let (a, b) = (fields(r).unwrap(), fields(&model(t)).unwrap());
            assert_eq!(r.t_s, t);
            // The state is the step's own at the row's time, whether interpolated or not.
            assert_eq!(r.x_m, t);
            for &i in Values::Model.which() {
                let scale = if i >= 10 { 3e6 } else { 1.0 };
                assert!(
                    (a[i] - b[i]).abs() <= 1e-12 * scale,
                    "{t} {i}: {}",
                    a[i] - b[i]
                );
            }
        }
    }

    #[test]
    fn in_a_step_that_holds_a_contact_every_value_is_interpolated() {
        // The hold moves the state off the dense output: the state is interpolated too (the
        // dense state gives the time alone here).
        let ts = times(0.5, 0.04, 39);
        let time_only = |t: f64, like: &Row| Row { t_s: t, ..*like };
        let (got, out) = step_of(Values::All, 39, |t| Ok(model(t)), model, time_only);
        assert!(matches!(got, Ok(Interpolated::Done)));
        for (r, &t) in out.iter().zip(&ts) {
            let (a, b) = (fields(r).unwrap(), fields(&model(t)).unwrap());
            for i in 0..FIELDS {
                let scale = if i >= 10 { 3e6 } else { 1.0 };
                assert!(
                    (a[i] - b[i]).abs() <= 1e-12 * scale,
                    "{t} {i}: {}",
                    a[i] - b[i]
                );
            }
        }
        // The model's values alone, the state left as it came.
        let (_, out) = step_of(Values::Model, 39, |t| Ok(model(t)), model, time_only);
        let moved = out.iter().zip(&ts).filter(|(r, t)| r.x_m != **t).count();
        assert!(moved > 30, "{moved} rows keep the state they came with");
    }

    #[test]
    fn a_model_the_interpolant_does_not_follow_is_evaluated_row_by_row() {
        // A kink in the middle of the step: no polynomial follows it to 10⁻⁴ of 1e-9.
        let kinked = |t: f64| {
            let mut r = model(t);
            r.alpha_deg += (t - 0.52).abs();
            r
        };
        let (got, out) = step(39, |t| Ok(kinked(t)), kinked);
        assert!(matches!(got, Ok(Interpolated::Evaluate)));
        assert!(out.is_empty());
    }

    #[test]
    fn rows_on_another_face_without_reactions_or_not_numbers_are_evaluated_row_by_row() {
        let changes: [fn(&mut Row); 3] = [
            |r| r.faces = [0, 1, 5],
            |r| r.n_n = None,
            |r| r.alpha_deg = f64::NAN,
        ];
        for change in changes {
            let changed = |t: f64| {
                let mut r = model(t);
                if t > 0.52 {
                    change(&mut r);
                }
                Ok(r)
            };
            let (got, _) = step(20, changed, model);
            assert!(matches!(got, Ok(Interpolated::Evaluate)));
        }
    }

    #[test]
    fn a_normal_reaction_below_zero_between_the_nodes_is_the_models_to_tell() {
        let mut evaluated = Vec::new();
        let record = |t| {
            evaluated.push(t);
            Ok(model(t))
        };
        let _ = step(39, record, model);
        // Contact 0's normal reaction a parabola below zero only about one row the
        // interpolation does not evaluate: the parabola is followed exactly, so it is the sign
        // alone that sends the step back to the model.
        let ts = times(0.5, 0.04, 39);
        let c = *ts.iter().find(|t| !evaluated.contains(t)).unwrap();
        let dipping = |t: f64| {
            let mut r = model(t);
            let mut n = r.n_n.unwrap();
            n[0] = 1e9 * ((t - c).powi(2) - 1.6e-7);
            r.n_n = Some(n);
            r
        };
        let (got, out) = step(39, |t| Ok(dipping(t)), dipping);
        assert!(matches!(got, Ok(Interpolated::Evaluate)));
        assert!(out.is_empty());
    }

    #[test]
    fn a_node_off_the_model_is_the_steps_failure() {
        let lifting = |t| {
            if t > 0.53 {
                Err(Stop {
                    reason: Reason::ContactLiftedOff,
                    detail: String::new(),
                    contact: Some(1),
                })
            } else {
                Ok(model(t))
            }
        };
        let (got, _) = step(20, lifting, model);
        assert!(got.is_err());
    }

    #[test]
    fn the_nodes_are_distinct_rows_near_the_lobatto_points_and_too_few_rows_are_none() {
        let ts = times(0.0, 1.0, 12);
        let p = pick(&ts, 0.0, 1.0).unwrap();
        assert!(p.windows(2).all(|w| w[0] < w[1]), "{p:?}");
        // Lobatto points 0.095, 0.345, 0.655, 0.905 of rows at k/13.
        assert_eq!(p, [0, 3, 8, 11]);
        assert!(pick(&times(0.0, 1.0, FEWEST - 1), 0.0, 1.0).is_none());
    }
}
