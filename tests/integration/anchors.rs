//! Post-tensioned anchors (`derivations/11-dam-loads.md` §10): in the route, a tendon that
//! stretches with the block's motion and breaks at its capacity, against the one-dimensional
//! equation of a monolith sliding straight on a level base, integrated here independently.

use slideroute::Scene;

/// A monolith 20 × 10 m, 15 m high with a 5 m crest, under 14 m of water, on a level base with
/// μ = 0.25 on three contacts symmetric about its line of motion (no turning), held by one
/// vertical anchor from the crest above its centre of mass (x = x̄ from the heel), 20 m free.
fn scene(prestress: f64, capacity: f64, contacts: &str) -> String {
    format!(
        r#"name = "anchored"
[frame]
contacts_m = [[-6.0, 0.0], [4.0, 5.0], [4.0, -5.0]]
[foundation]
[[foundation.plane]]
dip_deg = 0.0
dip_direction_deg = 0.0
point_m = [0.0, 0.0, 0.0]
[monolith]
base_length_m = 20.0
width_m = 10.0
height_m = 15.0
crest_length_m = 5.0
density_kg_m3 = 2400.0
[water]
headwater_m = 14.0
tailwater_m = 0.0
density_kg_m3 = 1000.0
[loads]
eccentricity_m = 0.0
gravity_m_s2 = 9.81
[friction]
model = "coulomb"
mu_k = 0.25
[solver]
mode = "exact"
dynamics = "rigid-body"
contacts = "{contacts}"
dt_s = 1.0e-3
t_end_s = 4.0
[[anchor]]
x_m = {x_bar}
y_m = 0.0
prestress_n = {prestress}
capacity_n = {capacity}
free_length_m = 20.0
steel_area_m2 = 5.0e-3
modulus_pa = 195.0e9
"#,
        x_bar = 8.0 + 1.0 / 3.0
    )
}

/// The block's X(t) by the one-dimensional equation, RK4 at `h`:
/// m Ẍ = H − μ (W − U + T L/ℓ) − T X/ℓ, ℓ = √(X² + L²), T = P + k (ℓ − L), until T reaches the
/// capacity; then m Ẍ = H − μ (W − U). Returns X at each of `times` and the break's time.
fn by_hand(prestress: f64, capacity: f64, times: &[f64], h: f64) -> (Vec<f64>, Option<f64>) {
    let g = 9.81;
    let gamma = 1000.0 * g;
    let mass = 2400.0 * 10.0 * (5.0 * 15.0 + 0.5 * 15.0 * 15.0);
    let (w, hw, u) = (
        mass * g,
        0.5 * gamma * 14.0 * 14.0 * 10.0,
        0.5 * gamma * 14.0 * 20.0 * 10.0,
    );
    let (mu, l, k) = (0.25, 20.0, 195.0e9 * 5.0e-3 / 20.0);
    let tension = |x: f64| prestress + k * ((x * x + l * l).sqrt() - l);
    let acc = |x: f64, broken: bool| {
        if broken {
            return (hw - mu * (w - u)) / mass;
        }
        let ell = (x * x + l * l).sqrt();
        let t = tension(x);
        (hw - mu * (w - u + t * l / ell) - t * x / ell) / mass
    };
    let (mut x, mut v, mut t) = (0.0f64, 0.0f64, 0.0f64);
    let mut broken = false;
    let mut broke_at = None;
    let mut out = Vec::new();
    for &target in times {
        while t < target - 1e-12 {
            let dt = h.min(target - t);
            let f = |x: f64, v: f64| (v, acc(x, broken));
            let (k1x, k1v) = f(x, v);
            let (k2x, k2v) = f(x + 0.5 * dt * k1x, v + 0.5 * dt * k1v);
            let (k3x, k3v) = f(x + 0.5 * dt * k2x, v + 0.5 * dt * k2v);
            let (k4x, k4v) = f(x + dt * k3x, v + dt * k3v);
            let (nx, nv) = (
                x + dt / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x),
                v + dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v),
            );
            if !broken && tension(nx) > capacity {
                // Where the tension reaches the capacity, by the stretch: X = √(ℓ² − L²).
                let ell = l + (capacity - prestress) / k;
                let xb = (ell * ell - l * l).sqrt();
                // The time there, linearly within this tiny step.
                let frac = (xb - x) / (nx - x);
                let tb = t + frac * dt;
                let vb = v + frac * (nv - v);
                broke_at = Some(tb);
                broken = true;
                (x, v, t) = (xb, vb, tb);
                continue;
            }
            (x, v, t) = (nx, nv, t + dt);
        }
        out.push(x);
    }
    (out, broke_at)
}

/// X at the rows nearest each of `times` (every row is recorded at dt).
fn route_x(text: &str, times: &[f64]) -> (Vec<f64>, slideroute::Route) {
    let s = Scene::from_toml(text, "anchored").unwrap();
    let r = slideroute::run(&s).unwrap();
    let xs = times
        .iter()
        .map(|&t| {
            let row = r
                .rows
                .iter()
                .min_by(|a, b| (a.t_s - t).abs().total_cmp(&(b.t_s - t).abs()))
                .unwrap();
            assert!((row.t_s - t).abs() < 1e-9, "no row at {t}");
            assert!(
                row.theta_deg.abs() < 1e-6,
                "the block turned: {}",
                row.theta_deg
            );
            row.x_m
        })
        .collect();
    (xs, r)
}

#[test]
fn a_vertical_anchor_stretches_as_the_monolith_slides_and_holds_it_back_as_the_1d_equation_says() {
    let times = [0.5, 1.0, 2.0, 3.0, 4.0];
    let (want, broke) = by_hand(1.0e6, 1.0e9, &times, 1e-5);
    assert!(broke.is_none());
    let (got, r) = route_x(&scene(1.0e6, 1.0e9, "frame"), &times);
    assert!(r.anchors_broken.is_empty());
    // The tendon's work is booked with the loads': the energy balance closes, to the step
    // control's tolerance (a tendon's work left out would be of the order of its 1e6 J).
    let e = r.energy().unwrap();
    assert!(
        e.residual_j.abs() < 1e-8 * e.work_hydraulic_j.abs(),
        "{e:?}"
    );
    // Unanchored it would have gone further: the anchor matters here.
    let free = by_hand(0.0, 1.0e9, &times, 1e-5).0;
    assert!(
        free[4] - want[4] > 0.05 * want[4],
        "{free:?} against {want:?}"
    );
    for ((t, g), w) in times.iter().zip(&got).zip(&want) {
        assert!(
            (g - w).abs() < 1e-6 * w.abs().max(1.0),
            "X({t}) = {g} against {w} by hand"
        );
    }
}

#[test]
fn a_tendon_breaks_where_its_force_reaches_its_capacity_and_the_block_runs_free_after() {
    let (p, c) = (1.0e6, 3.0e6);
    let times = [0.5, 1.0, 2.0, 3.0, 4.0];
    let (want, broke) = by_hand(p, c, &times, 1e-5);
    let broke = broke.expect("by hand the tendon breaks");
    assert!(broke > 1.0 && broke < 3.5, "{broke}");
    let (got, r) = route_x(&scene(p, c, "frame"), &times);
    assert_eq!(r.anchors_broken.len(), 1, "{:?}", r.anchors_broken);
    let at = r.anchors_broken[0].t_s;
    assert!(
        (at - broke).abs() < 1e-5,
        "broke at {at} s against {broke} s by hand"
    );
    for ((t, g), w) in times.iter().zip(&got).zip(&want) {
        assert!(
            (g - w).abs() < 1e-6 * w.abs().max(1.0),
            "X({t}) = {g} against {w} by hand"
        );
    }
}

#[test]
fn an_anchor_strong_enough_holds_the_monolith_where_it_would_slide_without() {
    // Without the anchor the block slides (H > μ (W − U)); a prestress of 10 MN holds it.
    let (_, r) = route_x(&scene(0.0, 1.0e9, "frame"), &[0.0]);
    assert!(r.travel_m > 0.1);
    let s = Scene::from_toml(&scene(10.0e6, 2.0e7, "frame"), "anchored").unwrap();
    let r = slideroute::run(&s).unwrap();
    assert_eq!(r.termination.reason, slideroute::Reason::DoesNotSlide);
    // The load multiple by hand: (μ (W − U + P))/H on a level base with no couple.
    let g = 9.81;
    let mass = 2400.0 * 10.0 * 187.5;
    let (hw, u) = (0.5 * 9810.0 * 196.0 * 10.0, 0.5 * 9810.0 * 14.0 * 200.0);
    let want = 0.25 * (mass * g - u + 10.0e6) / hw;
    let fs = r.factor_of_safety.and_then(|f| f.value()).unwrap();
    assert!((fs - want).abs() < 1e-6 * want, "{fs} against {want}");
}

#[test]
fn on_its_whole_base_the_anchored_monolith_slides_as_the_1d_equation_says_to_the_step() {
    // The block on its base steps at dt by impulses (first order): X within 0.1 % of the
    // equation's, the break located to the step.
    let times = [1.0, 2.0, 3.0, 4.0];
    for (p, c) in [(1.0e6, 1.0e9), (1.0e6, 3.0e6)] {
        let (want, broke) = by_hand(p, c, &times, 1e-5);
        let (got, r) = route_x(&scene(p, c, "base"), &times);
        assert_eq!(r.anchors_broken.len(), usize::from(broke.is_some()));
        if let (Some(b), Some(at)) = (broke, r.anchors_broken.first()) {
            assert!((at.t_s - b).abs() <= 1e-3 + 1e-9, "{} against {b}", at.t_s);
        }
        for ((t, g), w) in times.iter().zip(&got).zip(&want) {
            assert!((g - w).abs() < 1e-3 * w, "X({t}) = {g} against {w} by hand");
        }
    }
}

#[test]
fn the_dam_templates_commented_anchor_is_a_valid_one_once_its_marks_are_taken_off() {
    let text = Scene::DAM_TOML;
    let start = text
        .find("# [[anchor]]")
        .expect("the template shows an anchor");
    let uncommented: String = text[..start].to_string()
        + &text[start..]
            .lines()
            .map(|l| l.strip_prefix("# ").unwrap_or(l))
            .collect::<Vec<_>>()
            .join("\n");
    let s = Scene::from_toml(&uncommented, "dam").unwrap();
    assert_eq!(s.anchors().len(), 1);
    assert_eq!(s.anchors()[0].prestress, 2.0e6);
    assert_eq!(s.anchors()[0].modulus, slideroute::STRAND_MODULUS_PA);
    // It runs, and the verdicts count it.
    let bare =
        slideroute::check::check_cases(&Scene::from_toml(text, "dam").unwrap(), |_| ()).unwrap();
    let with = slideroute::check::check_cases(&s, |_| ()).unwrap();
    let n = |r: &[slideroute::check::CaseResult]| r[0].gravity.unwrap().normal_n;
    assert!((n(&with) - n(&bare) - 2.0e6).abs() < 1e-6);
}

#[test]
fn anchors_are_refused_without_a_monolith_and_under_the_papers_dynamics_on_three_contacts() {
    let text = scene(1.0e6, 2.0e6, "frame");
    let paper = text.replace("dynamics = \"rigid-body\"", "dynamics = \"paper\"");
    let e = Scene::from_toml(&paper, "anchored").unwrap_err();
    assert_eq!(e.key, "anchor", "{e}");
    let outside = text.replace("y_m = 0.0", "y_m = 16.0");
    let e = Scene::from_toml(&outside, "anchored").unwrap_err();
    assert_eq!(e.key, "anchor[0].y_m", "{e}");
    let block = format!(
        "{}\n[[anchor]]\nx_m = 1.0\nprestress_n = 1.0\ncapacity_n = 2.0\nfree_length_m = 1.0\n\
         steel_area_m2 = 1.0e-3\n",
        Scene::DEFAULT_TOML
    );
    let e = Scene::from_toml(&block, "block").unwrap_err();
    assert!(e.key == "anchor" && e.reason.contains("[monolith]"), "{e}");
    let unknown = text.replace("y_m = 0.0", "y_m = 0.0\nlength_m = 3.0");
    let e = Scene::from_toml(&unknown, "anchored").unwrap_err();
    assert!(e.to_string().contains("length_m"), "{e}");
}

#[test]
fn an_anchors_keys_are_changed_by_its_number_as_any_scene_key_and_swept() {
    let s = Scene::from_toml(&scene(1.0e6, 3.0e6, "frame"), "anchored").unwrap();
    let t = s.with("anchor[0].prestress_n", 2.0e6).unwrap();
    assert_eq!(t.anchors()[0].prestress, 2.0e6);
    // A key the file left to its default, and a number the scene does not have.
    assert_eq!(
        s.with("anchor[0].plunge_deg", 60.0).unwrap().anchors()[0].plunge,
        60f64.to_radians()
    );
    let e = s.with("anchor[1].prestress_n", 2.0e6).unwrap_err();
    assert_eq!(e.key, "anchor[1]", "{e}");
    // Checked as the file's own: a prestress over the capacity names the key.
    let e = s.with("anchor[0].prestress_n", 4.0e6).unwrap_err();
    assert_eq!(e.key, "anchor[0].capacity_n", "{e}");
    use slideroute::sweep::check_key;
    assert!(check_key(&s, "anchor[0].prestress_n", false, &[1.0, 2.0]).is_ok());
    assert!(check_key(&s, "anchor[0].trend_deg", false, &[0.0, 180.0]).is_ok());
    let e = check_key(&s, "anchor[2].prestress_n", false, &[1.0]).unwrap_err();
    assert!(e.to_string().contains("has 1 [[anchor]]"), "{e}");
}

#[test]
fn a_tendon_whose_force_reaches_its_capacity_as_the_block_stops_breaks_there() {
    // Kicked at 1 m/s under 10 m of water (held by friction alone), the block slides about half
    // a metre and stops, the tendon's force greatest there. A capacity just under that force
    // breaks the tendon as the block stops; one just over it does not.
    let kicked = |capacity: f64| {
        let text = scene(1.0e6, capacity, "frame")
            .replace("headwater_m = 14.0", "headwater_m = 10.0")
            + "[initial]\nvx_m_s = 1.0\n";
        slideroute::run(&Scene::from_toml(&text, "kicked").unwrap()).unwrap()
    };
    let whole = kicked(1.0e9);
    assert_eq!(whole.termination.reason, slideroute::Reason::Stopped);
    let last = whole.rows.last().unwrap();
    let (l, k) = (20.0, 195.0e9 * 5.0e-3 / 20.0);
    let at_stop = 1.0e6 + k * ((last.x_m * last.x_m + l * l).sqrt() - l);
    assert!(at_stop > 1.2e6, "{at_stop}");
    let r = kicked(at_stop * (1.0 - 1e-7));
    assert_eq!(r.anchors_broken.len(), 1, "{:?}", r.termination);
    assert!((r.anchors_broken[0].t_s - whole.termination.t_s).abs() < 1e-3);
    assert!(kicked(at_stop * (1.0 + 1e-6)).anchors_broken.is_empty());
}
