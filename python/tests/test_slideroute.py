"""The Python package against the command line and against independent results."""

from __future__ import annotations

import csv
import json
import math
import os
import pathlib
import pickle
import subprocess

import numpy as np
import pytest

import slideroute

ROOT = pathlib.Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"


def cli() -> str:
    """The command-line tool: $SLIDEROUTE_BIN, or the repository's build (CI builds it with
    `cargo test` before pytest runs)."""
    given = os.environ.get("SLIDEROUTE_BIN")
    if given:
        return given
    built = [ROOT / "target" / p / "slideroute" for p in ("release", "debug")]
    built = [p for p in built if p.exists()]
    if built:
        return str(max(built, key=lambda p: p.stat().st_mtime))
    raise RuntimeError("no slideroute binary: build it (cargo build) or set SLIDEROUTE_BIN")


def read_csv(path: pathlib.Path) -> tuple[list[str], list[list[str]]]:
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def as_float(text: str) -> float:
    return float(text) if text != "" else math.nan


def same(a: float, b: float) -> bool:
    return (math.isnan(a) and math.isnan(b)) or a == b


def short(scene_file: pathlib.Path, tmp: pathlib.Path, t_end: str) -> pathlib.Path:
    text = scene_file.read_text(encoding="utf-8").replace("t_end_s = 20.0", f"t_end_s = {t_end}")
    out = tmp / scene_file.name
    out.write_text(text, encoding="utf-8")
    return out


@pytest.mark.parametrize("dynamics", ["rigid-body", "paper"])
def test_a_route_equals_the_command_lines_row_for_row(tmp_path, dynamics):
    scene_file = short(SCENES / "paper-like.toml", tmp_path, "3.0")
    out = tmp_path / "run"
    subprocess.run(
        [cli(), "run", "--scene", str(scene_file), "--dynamics", dynamics, "--out", str(out),
         "--quiet", "--no-plots"],
        check=True,
    )
    header, rows = read_csv(out / "route.csv")
    route = slideroute.Scene.from_file(scene_file).route(dynamics)
    assert list(route.columns) == header
    assert len(route) == len(rows) > 100
    for k, name in enumerate(header):
        got = route.columns[name]
        for j, row in enumerate(rows):
            assert same(float(got[j]), as_float(row[k])), (name, j, got[j], row[k])
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert route.reason == summary["termination"]["reason"]
    assert route.travel_m == summary["travel_m"]


def test_a_route_as_a_dataframe_has_the_rows_and_columns_of_the_arrays():
    pd = pytest.importorskip("pandas")
    r = slideroute.Scene.default().with_keys({"solver.t_end_s": 1.0}).route()
    df = r.to_pandas()
    assert isinstance(df, pd.DataFrame)
    assert df.shape == (len(r), 26)
    np.testing.assert_array_equal(df["x_m"].to_numpy(), r.columns["x_m"])


def test_every_row_of_a_one_block_route_is_of_body_0_in_the_first_column():
    r = slideroute.Scene.default().with_keys({"solver.t_end_s": 0.2}).route()
    assert list(r.columns)[0] == "body"
    assert len(r) > 10 and np.all(r.columns["body"] == 0)
    chunks = list(slideroute.Scene.default().with_keys({"solver.t_end_s": 0.2}).route_chunks(rows=50))
    assert all(list(c)[0] == "body" and np.all(c["body"] == 0) for c in chunks)


def test_a_block_on_its_base_says_where_it_rested_and_how_deep_its_base_went():
    r = slideroute.Scene.from_file(SCENES / "ramp-faces.toml").with_keys({"solver.t_end_s": 0.5}).route()
    base = r.base
    assert base is not None
    assert base["max_penetration_m"] <= 1e-6 * 10.0
    rest = base["resting"]
    shares = sum(c["share"] for c in rest["carrying"])
    assert shares > 0.99
    assert len(base["outline_m"]) == 4
    carrying = r.columns["corners_carrying"]
    assert np.all((carrying >= 0) & (carrying < 16))
    # On its three-point frame there is no base.
    frame = slideroute.Scene.from_file(SCENES / "ramp-faces.toml").with_keys(
        {"solver.t_end_s": 0.1, "solver.contacts": "frame"}).route()
    assert frame.base is None
    assert np.all(np.isnan(frame.columns["corners_carrying"]))


def test_a_scene_from_a_file_a_dict_and_its_pickle_are_the_same_scene():
    s = slideroute.Scene.from_file(SCENES / "paper-like.toml")
    d = s.to_dict()
    t = slideroute.Scene.from_dict(d, folder=SCENES)
    assert t == s
    assert pickle.loads(pickle.dumps(s)) == s
    d["friction"]["mu_k"] = 0.3
    assert slideroute.Scene.from_dict(d) != s
    assert slideroute.Scene.from_dict(d) == s.with_keys({"friction.mu_k": 0.3})


@pytest.mark.parametrize(
    "keys, key",
    [
        ({"friction.mu_q": 0.3}, "friction.mu_q"),
        ({"friction.mu_k": -0.3}, "friction.mu_k"),
        ({"foundation.xi_deg": "steep"}, "foundation.xi_deg"),
        ({"solver.dynamics": "quantum"}, "solver.dynamics"),
    ],
)
def test_a_key_a_scene_cannot_take_is_named_by_the_exception(keys, key):
    with pytest.raises(slideroute.SceneError) as e:
        slideroute.Scene.default().with_keys(keys)
    assert e.value.key == key
    assert key.split(".")[1] in str(e.value)
    assert isinstance(e.value, ValueError)


def test_inputs_that_are_no_scene_are_named():
    with pytest.raises(slideroute.SceneError) as e:
        slideroute.Scene.from_file(SCENES / "no-such-scene.toml")
    assert "no-such-scene.toml" in str(e.value)
    with pytest.raises(slideroute.SceneError) as e:
        slideroute.Scene.from_toml("[frame]\nl1x = 'six'\n", "bad.toml")
    assert e.value.key == "frame.l1x"
    with pytest.raises(slideroute.InputError) as e:
        slideroute.Scene.default().route(dynamics="fast")
    assert e.value.name == "dynamics"
    with pytest.raises(slideroute.InputError) as e:
        slideroute.Scene.from_dict({"frame": {"l1x": float("nan")}})
    with pytest.raises(slideroute.InputError) as e:
        slideroute.probabilistic(
            slideroute.Scene.default(), {"friction.mu_k": "gauss:0:1"}, samples=4
        )
    assert e.value.name == "friction.mu_k"
    with pytest.raises(slideroute.SceneError) as e:
        slideroute.probabilistic(
            slideroute.Scene.default(), {"friction.mu_q": "normal:0.4:0.05"}, samples=4
        )
    assert e.value.key == "friction.mu_q"
    with pytest.raises(slideroute.InputError):
        slideroute.probabilistic(slideroute.Scene.default(), samples=4)


def test_the_selected_root_is_the_direct_solvers_pose():
    s = slideroute.Scene.default()
    for x, z, t in [(0.1, 0.05, 1.0), (0.4, -0.1, -2.0), (0.0, 0.0, 0.0)]:
        roots = s.roots(x, z, t)
        pose = s.pose(x, z, t)
        assert pose["residual_m"] < 1e-12
        sel = roots["selected"]
        assert abs(sel["alpha_deg"] - pose["tilt_deg"]) < 1e-9
        assert abs(sel["psi_deg"] - pose["roll_deg"]) < 1e-9
        assert abs(sel["cm_y_m"] - pose["cm_y_m"]) < 1e-12
        assert roots["finite_roots"] + roots["roots_at_infinity"] == 8


def test_a_grid_of_poses_gives_what_each_pose_gives_alone():
    s = slideroute.Scene.default()
    rng = np.random.default_rng(4)
    x, z, t = rng.uniform(0, 0.5, 50), rng.uniform(-0.2, 0.2, 50), rng.uniform(-3, 3, 50)
    g = s.roots_grid(x, z, t)
    for k in range(50):
        one = s.roots(x[k], z[k], t[k])["selected"]
        if one is None:
            assert math.isnan(g["alpha_deg"][k])
        else:
            assert g["alpha_deg"][k] == one["alpha_deg"]
            assert g["gamma_deg"][k] == one["gamma_deg"]
    with pytest.raises(slideroute.InputError):
        s.roots_grid([0.1, 0.2], [0.0], [1.0, 2.0])


def test_a_sweep_row_is_the_route_of_its_combination():
    s = slideroute.Scene.default().with_keys({"solver.t_end_s": 1.0})
    sw = s.sweep({"friction.mu_k": [0.3, 0.45], "loads.eccentricity_m": [0.0, 1.0]})
    assert list(sw["friction.mu_k"]) == [0.3, 0.3, 0.45, 0.45]
    assert list(sw["loads.eccentricity_m"]) == [0.0, 1.0, 0.0, 1.0]
    for k in range(4):
        r = s.with_keys(
            {"friction.mu_k": sw["friction.mu_k"][k], "loads.eccentricity_m": sw["loads.eccentricity_m"][k]}
        ).route()
        assert sw["travel_m"][k] == r.travel_m
        assert sw["factor_of_safety"][k] == r.factor_of_safety


def test_a_sweep_equals_the_command_lines_row_for_row(tmp_path):
    # The command line and Python run a sweep through the library's one runner: the same rows.
    scene_file = short(SCENES / "paper-like.toml", tmp_path, "1.0")
    out = tmp_path / "sweep"
    subprocess.run(
        [cli(), "sweep", "--scene", str(scene_file), "--vary", "friction.mu_k=0.3,0.45,-1",
         "--vary", "loads.eccentricity_m=0:1:2", "--out", str(out), "--quiet"],
        check=True,
    )
    header, rows = read_csv(out / "sweep.csv")
    sw = slideroute.Scene.from_file(scene_file).sweep(
        {"friction.mu_k": [0.3, 0.45, -1.0], "loads.eccentricity_m": [0.0, 1.0]}
    )
    assert len(rows) == len(sw["sample"]) == 6
    # The command line's `reason` column is the sentence: Python's `reason_text`.
    names = {"final_theta_deg": "final_yaw_deg", "reason": "reason_text"}
    words = {"unbounded": math.inf, "not-holdable": -math.inf}
    for k, name in enumerate(header):
        col = sw[names.get(name, name)]
        for j, row in enumerate(rows):
            if name in ("reason", "detail"):
                assert col[j] == row[k], (name, j)
            else:
                want = words.get(row[k], None) if name == "factor_of_safety" else None
                want = as_float(row[k]) if want is None else want
                assert same(float(col[j]), want), (name, j, col[j], row[k])
    assert list(sw["reason"]).count("invalid-scene") == 2


def cli_probabilistic(scene_file, out, args):
    """`slideroute probabilistic` on `scene_file` into `out` with `args`: its summary
    (probabilistic.json without the manifest)."""
    subprocess.run(
        [cli(), "probabilistic", "--scene", str(scene_file), *args,
         "--out", str(out), "--quiet", "--no-plots"],
        check=True,
    )
    want = json.loads((out / "probabilistic.json").read_text(encoding="utf-8"))
    want.pop("manifest")
    return want


def test_the_probabilistic_analysis_equals_the_command_lines(tmp_path):
    scene_file = short(SCENES / "paper-like-uncertain.toml", tmp_path, "0.5")
    out = tmp_path / "prob"
    want = cli_probabilistic(
        scene_file, out, ["--samples", "40", "--seed", "5", "--dist",
                          "block.mass_kg=uniform:0.9e6:1.1e6", "--travel-limit-m", "0.1"]
    )
    header, rows = read_csv(out / "samples.csv")
    p = slideroute.probabilistic(
        slideroute.Scene.from_file(scene_file),
        {"block.mass_kg": "uniform:0.9e6:1.1e6"},
        samples=40,
        seed=5,
        travel_limit_m=0.1,
    )
    names = {"reason": "reason_text"}
    for k, name in enumerate(header):
        col = p.samples[names.get(name, name)]
        for j, row in enumerate(rows):
            if name in ("reason", "detail"):
                assert col[j] == row[k]
            else:
                assert same(float(col[j]), as_float(row[k])), (name, j)
    assert p.summary == want


def test_under_a_record_the_probabilistic_analysis_names_a_displacement_limit_as_the_command_line(
    tmp_path,
):
    scene_file = SCENES / "shaken.toml"
    want = cli_probabilistic(
        scene_file, tmp_path / "prob", ["--samples", "6", "--seed", "3", "--dist",
                                        "friction.mu_k=uniform:0.38:0.42",
                                        "--displacement-limit-m", "0.5"]
    )
    p = slideroute.probabilistic(
        slideroute.Scene.from_file(scene_file),
        {"friction.mu_k": "uniform:0.38:0.42"},
        samples=6,
        seed=3,
        displacement_limit_m=0.5,
    )
    assert p.summary == want
    assert p.summary["shaken"] is True
    assert p.summary["displacement_limit_m"] == 0.5
    assert p.probability_of_sliding == 1.0
    assert not math.isnan(p.samples["permanent_x_m"][0])


def test_the_probability_of_sliding_is_phi_of_the_margin():
    # Dips of 0.01°, the push through the centre of mass: it slides when μ W < H.
    s = slideroute.Scene.default().with_keys(
        {
            "foundation.xi_deg": 0.01,
            "foundation.zeta_deg": 0.01,
            "foundation.kappa_deg": 0.0,
            "loads.eccentricity_m": 0.0,
            "solver.t_end_s": 0.001,
        }
    )
    m, sd, n = 0.8, 0.05, 300
    want = 0.5 * (1 + math.erf(((8e6 / 9.81e6) - m) / sd / math.sqrt(2)))
    se = math.sqrt(want * (1 - want) / n)
    for sampling in ("mc", "lhs"):
        p = slideroute.probabilistic(
            s, {"friction.mu_k": f"normal:{m}:{sd}"}, samples=n, seed=9, sampling=sampling
        )
        assert abs(p.probability_of_sliding - want) < 3 * se, (sampling, p.probability_of_sliding, want)


def test_chunks_of_a_design_joined_give_the_whole_run():
    s = slideroute.Scene.from_file(SCENES / "paper-like-uncertain.toml").with_keys(
        {"solver.t_end_s": 0.3}
    )
    d = slideroute.distributions(s, None)
    values = slideroute.sample_values(s, d, 30, 2, "mc")
    whole = slideroute.run_samples(s, d, values)
    parts = [slideroute.run_samples(s, d, values[k : k + 7], k) for k in range(0, 30, 7)]
    joined = slideroute.Samples.concat(parts[::-1])
    for name in whole:
        a, b = whole[name], joined[name]
        if isinstance(a, np.ndarray):
            np.testing.assert_array_equal(a, b)
        else:
            assert a == b


def test_every_function_of_the_extension_has_a_stub():
    stub = (pathlib.Path(slideroute.__file__).parent / "_native.pyi").read_text(encoding="utf-8")
    native = slideroute._native
    public = [n for n in dir(native) if not n.startswith("_")]
    for name in public:
        assert f"def {name}(" in stub or f"class {name}" in stub, name
    for name in [n for n in dir(native.Scene) if not n.startswith("_")]:
        assert f"def {name}(" in stub, f"Scene.{name}"


def test_the_notebook_example_runs():
    import runpy

    os.environ["SLIDEROUTE_SAMPLES"] = "12"
    try:
        runpy.run_path(str(ROOT / "examples" / "probabilistic.py"), run_name="__main__")
    finally:
        del os.environ["SLIDEROUTE_SAMPLES"]


@pytest.mark.parametrize(
    "call, name",
    [
        (lambda s: slideroute.probabilistic(s, {"friction.mu_k": "normal:0.4:0.05"}, samples=0), "samples"),
        (lambda s: slideroute.probabilistic(s, {"friction.mu_k": "normal:0.4:0.05"}, sampling="sobol"), "sampling"),
        (lambda s: slideroute.probabilistic(s, {"friction.mu_k": "normal:0.4:0.05"}, samples=4, travel_limit_m=-1.0), "travel_limit_m"),
        (lambda s: slideroute.run_samples(s, {"friction.mu_k": "normal:0.4:0.05"}, [[0.4, 1.0]]), "values"),
        (lambda s: slideroute.run_samples(s, {"friction.mu_k": "normal:0.4:0.05"}, [0.4]), "values"),
        (lambda s: s.with_keys({"friction.mu_k": [0.3]}), "friction.mu_k"),
        (lambda s: s.roots(0.1, 0.0, 1.0, mode="approximate"), "mode"),
        (lambda s: s.sweep({"friction.mu_k": []}), "friction.mu_k"),
        (lambda s: s.with_keys("friction.mu_k=0.3"), "keys"),
    ],
)
def test_arguments_it_cannot_use_raise_an_input_error_naming_them(call, name):
    with pytest.raises(slideroute.InputError) as e:
        call(slideroute.Scene.default())
    assert e.value.name == name, str(e.value)


def test_a_sample_whose_values_make_no_scene_is_a_row_that_says_why():
    s = slideroute.Scene.default().with_keys({"solver.t_end_s": 0.01})
    rows = slideroute.run_samples(s, {"friction.mu_k": "uniform:-1:1"}, [[-0.5], [0.4], [math.nan]])
    assert list(rows["reason"][:1]) == ["invalid-scene"]
    assert rows["reason_text"][0] == "invalid scene"
    assert "friction.mu_k" in rows["detail"][0]
    assert rows["reason"][1] != "invalid-scene"
    assert rows["reason"][2] == "invalid-scene"
    summary = slideroute.summarise(s, {"friction.mu_k": "uniform:-1:1"}, 3, 1, "mc", rows)
    assert summary["invalid_samples"] == 2 and summary["routes"] == 1


# 20 000 rigid-body routes in a child: minutes of work, which says whether Ctrl-C ended it.
_LONG_ANALYSIS = (
    "import slideroute\n"
    "s = slideroute.Scene.default()\n"
    "print('started', flush=True)\n"
    "try:\n"
    "    slideroute.probabilistic(s, {'friction.mu_k': 'normal:0.4:0.05'}, samples=20000)\n"
    "    print('finished')\n"
    "except KeyboardInterrupt:\n"
    "    print('interrupted')\n"
)


def _ctrl_c_heard():
    """In the child, before it starts: Ctrl-C as a terminal delivers it. A shell running these
    tests in the background (`cmd &` without job control) hands its children SIGINT ignored,
    and Python then installs no KeyboardInterrupt."""
    import signal

    signal.signal(signal.SIGINT, signal.SIG_DFL)


def test_ctrl_c_at_the_first_call_of_an_analysis_is_a_keyboard_interrupt_not_a_panic():
    import signal
    import sys
    import time

    # The first array a call makes used to import NumPy's modules then: a Ctrl-C landing in
    # that import became a PanicException, or was lost and the analysis ran on.
    script = _LONG_ANALYSIS
    for delay in (0.0, 0.01, 0.03, 0.1):
        p = subprocess.Popen(
            [sys.executable, "-c", script],
            stdout=subprocess.PIPE,
            stderr=subprocess.PIPE,
            text=True,
            preexec_fn=_ctrl_c_heard,
        )
        assert p.stdout.readline().strip() == "started"
        time.sleep(delay)
        p.send_signal(signal.SIGINT)
        out, err = p.communicate(timeout=60)
        assert out.strip() == "interrupted", (delay, out, err)
        assert "Panic" not in err, (delay, err)


def test_ctrl_c_stops_a_long_analysis_with_keyboard_interrupt():
    import signal
    import sys
    import time

    # 20 000 rigid-body routes: minutes of work; the interrupt must end it long before.
    script = _LONG_ANALYSIS
    p = subprocess.Popen(
        [sys.executable, "-c", script], stdout=subprocess.PIPE, text=True, preexec_fn=_ctrl_c_heard
    )
    assert p.stdout.readline().strip() == "started"
    time.sleep(1.0)
    p.send_signal(signal.SIGINT)
    out, _ = p.communicate(timeout=60)
    assert out.strip() == "interrupted"
    assert p.returncode == 0


def test_progress_is_told_how_far_the_work_is_and_may_stop_it():
    s = slideroute.Scene.default().with_keys({"solver.t_end_s": 0.5})
    seen = []
    p = slideroute.probabilistic(
        s, {"friction.mu_k": "normal:0.4:0.05"}, samples=24, progress=lambda d, t: seen.append((d, t))
    )
    assert seen and seen[-1] == (24, 24)
    assert all(t == 24 for _, t in seen) and [d for d, _ in seen] == sorted(d for d, _ in seen)
    assert p.summary["routes"] == 24
    swept = []
    s.sweep({"friction.mu_k": [0.3, 0.4, 0.5]}, progress=lambda d, t: swept.append((d, t)))
    assert swept[-1] == (3, 3)

    class Enough(Exception):
        pass

    def give_up(done, total):
        raise Enough(done)

    slow = slideroute.Scene.default()
    with pytest.raises(Enough):
        slideroute.probabilistic(slow, {"friction.mu_k": "normal:0.4:0.05"}, samples=2000, progress=give_up)


def test_a_seed_gives_each_key_the_same_values_whatever_order_the_dict_gives_them():
    # The scene's table and a dict in another order draw the same samples.
    s = slideroute.Scene.from_file(SCENES / "paper-like.toml")
    a = {"loads.eccentricity_m": "uniform:0:2", "friction.mu_k": "uniform:0.3:0.5"}
    b = dict(reversed(list(a.items())))
    pa = slideroute.probabilistic(s.with_keys({"solver.t_end_s": 0.05}), a, samples=12, seed=3)
    pb = slideroute.probabilistic(s.with_keys({"solver.t_end_s": 0.05}), b, samples=12, seed=3)
    for key in a:
        np.testing.assert_array_equal(pa.samples[key], pb.samples[key])
    # The same summary, its lists by key in the order given.
    by_key = lambda rows: {r["key"]: r for r in rows}
    for listed in ("distributions", "rank_correlations"):
        assert by_key(pa.summary[listed]) == by_key(pb.summary[listed])
    rest = lambda p: {k: v for k, v in p.summary.items() if k not in ("distributions", "rank_correlations")}
    assert rest(pa) == rest(pb)
