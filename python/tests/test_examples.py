"""The examples as a user runs them: `examples/dask_probabilistic.py`'s command line (its own
process; with Dask hidden where it must not be needed)."""

from __future__ import annotations

import json
import pathlib
import subprocess
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "dask_probabilistic.py"

# Runs the example as `python examples/dask_probabilistic.py ARGS` with `dask` unimportable.
WITHOUT_DASK = (
    "import runpy, sys\n"
    "sys.modules['dask'] = None\n"
    "sys.modules['dask.distributed'] = None\n"
    "sys.argv = sys.argv[1:]\n"
    "runpy.run_path(sys.argv[0], run_name='__main__')\n"
)


def run(args, dask=True):
    command = [sys.executable, str(EXAMPLE), *args]
    if not dask:
        command = [sys.executable, "-c", WITHOUT_DASK, str(EXAMPLE), *args]
    return subprocess.run(command, capture_output=True, text=True, cwd=ROOT, timeout=300)


def test_the_dask_examples_help_needs_no_dask():
    r = run(["--help"], dask=False)
    assert r.returncode == 0, r.stderr
    assert "--scene" in r.stdout and "--dist" in r.stdout


def test_the_dask_example_refuses_a_scene_without_uncertain_keys_before_needing_dask():
    r = run(["--scene", "scenes/paper-like.toml"], dask=False)
    assert r.returncode == 2, (r.stdout, r.stderr)
    assert "no [uncertain] table" in r.stderr and "--dist" in r.stderr
    assert r.stdout == ""
    r = run([], dask=False)  # the embedded default scene has no [uncertain] table either
    assert r.returncode == 2 and "no [uncertain] table" in r.stderr


def test_the_dask_example_takes_the_scenes_uncertain_table_and_nothing_else(tmp_path):
    pytest.importorskip("dask.distributed")
    text = (ROOT / "scenes" / "paper-like.toml").read_text(encoding="utf-8")
    text = text.replace("t_end_s = 20.0", "t_end_s = 0.2")
    text += '\n[uncertain]\n"friction.mu_k" = "uniform:0.35:0.45"\n'
    scene = tmp_path / "one-uncertain.toml"
    scene.write_text(text, encoding="utf-8")
    r = run(["--scene", str(scene), "--samples", "6", "--chunk", "3", "--workers", "1"])
    assert r.returncode == 0, r.stderr
    summary = json.loads(r.stdout)
    assert summary["distributions"] == [
        {"key": "friction.mu_k", "distribution": "uniform:0.35:0.45"}
    ]
    # --dist adds to the table.
    r = run(["--scene", str(scene), "--samples", "4", "--chunk", "2", "--workers", "1",
             "--dist", "loads.eccentricity_m=uniform:0:2"])
    assert r.returncode == 0, r.stderr
    keys = [d["key"] for d in json.loads(r.stdout)["distributions"]]
    assert sorted(keys) == ["friction.mu_k", "loads.eccentricity_m"]
