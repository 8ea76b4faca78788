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
