"""The Dask example gives the in-process run's numbers."""

from __future__ import annotations

import importlib.util
import pathlib

import numpy as np
import pytest

import slideroute

distributed = pytest.importorskip("dask.distributed")

ROOT = pathlib.Path(__file__).resolve().parents[2]


def example():
    spec = importlib.util.spec_from_file_location(
        "dask_probabilistic", ROOT / "examples" / "dask_probabilistic.py"
    )
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_the_dask_example_on_two_workers_gives_the_in_process_results():
    scene = slideroute.Scene.from_file(ROOT / "scenes" / "paper-like-uncertain.toml").with_keys(
        {"solver.t_end_s": 1.0}
    )
    args = dict(samples=60, seed=7, sampling="lhs", travel_limit_m=0.5)
    here = slideroute.probabilistic(scene, None, **args)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        there = example().probabilistic_on_dask(client, scene, None, chunk=8, **args)
    assert there.summary == here.summary
    assert list(there.samples) == list(here.samples)
    for name, col in here.samples.items():
        if isinstance(col, np.ndarray):
            np.testing.assert_array_equal(col, there.samples[name])
        else:
            assert col == there.samples[name]


def test_a_seed_gives_the_same_samples_from_a_file_flags_a_dict_and_dask(tmp_path):
    # The [uncertain] table, --dist, Python dicts and Dask must draw alike whatever the order
    # the keys are given in. Here: the same three distributions from the scene's
    # table, from --dist flags in another order, from a Python dict in a third, and over Dask.
    import csv
    import os
    import subprocess

    from test_slideroute import cli

    dists = {
        "loads.eccentricity_m": "truncnormal:1.0:0.5:0:2",
        "friction.mu_k": "normal:0.40:0.05",
        "foundation.zeta_deg": "uniform:22:28",
    }
    base = (ROOT / "scenes" / "paper-like.toml").read_text()
    table = "\n[uncertain]\n" + "".join(f'"{k}" = "{v}"\n' for k, v in dists.items())
    scene_file = tmp_path / "uncertain.toml"
    scene_file.write_text(base + table)
    common = ["--samples", "16", "--seed", "11", "--set", "solver.t_end_s=0.05", "--quiet", "--no-plots"]

    def cli_values(out, *extra):
        subprocess.run([cli(), "probabilistic", *extra, *common, "--out", str(out)], check=True)
        with open(out / "samples.csv", newline="") as f:
            rows = list(csv.DictReader(f))
        return {k: [float(r[k]) for r in rows] for k in dists}

    from_file = cli_values(tmp_path / "file", "--scene", str(scene_file))
    flags = [a for k in reversed(list(dists)) for a in ("--dist", f"{k}={dists[k]}")]
    from_flags = cli_values(tmp_path / "flags", *flags)
    scene = slideroute.Scene.from_file(ROOT / "scenes" / "paper-like.toml").with_keys({"solver.t_end_s": 0.05})
    shuffled = {k: dists[k] for k in sorted(dists, key=lambda k: k[::-1])}
    here = slideroute.probabilistic(scene, shuffled, samples=16, seed=11)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        there = example().probabilistic_on_dask(
            client, slideroute.Scene.from_file(scene_file).with_keys({"solver.t_end_s": 0.05}), None, samples=16, seed=11, chunk=4
        )
    for key in dists:
        # samples.csv writes each value to round-trip: the same floats, bit for bit.
        np.testing.assert_array_equal(from_file[key], from_flags[key], err_msg=key)
        np.testing.assert_array_equal(from_file[key], here.samples[key], err_msg=key)
        np.testing.assert_array_equal(from_file[key], there.samples[key], err_msg=key)
