"""The probabilistic analysis over a Dask cluster: the samples in chunks on the workers, the
same numbers as the in-process run (``slideroute.probabilistic``) for the same seed.

Why the numbers are the same: the design (every sample's values) is drawn whole from the seed
here, before any route runs; each chunk's rows depend on its values alone; the chunks are
joined in sample order and summarised here.

The uncertain keys are the scene's ``[uncertain]`` table and the ``--dist`` given (a key of
both takes ``--dist``'s); a scene with neither is refused — nothing is assumed uncertain.

Run it on a local cluster of two workers:

    python examples/dask_probabilistic.py --scene scenes/paper-like-uncertain.toml --samples 400 --seed 7

or on a real cluster, by the address of its scheduler (every worker needs slideroute installed,
`pip install "./python[dask]"` from a checkout, and the scene's files if it names any):

    python examples/dask_probabilistic.py --scheduler tcp://scheduler.example:8786 \
        --scene dam.toml --samples 100000

`--help` needs no Dask: it is imported once the arguments are read.
"""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any, Dict, List, Mapping, NoReturn, Optional, Sequence, Tuple, Union

import numpy as np

import slideroute


def _chunk(scene: slideroute.Scene, dists: list, values: np.ndarray, first: int) -> Dict[str, Any]:
    """One chunk on a worker (the scene crosses the network as its document): the chunk's
    routes on the worker's cores."""
    return dict(slideroute.run_samples(scene, dists, values, first))


def probabilistic_on_dask(
    client: Any,
    scene: slideroute.Scene,
    dists: Union[Mapping[str, str], Sequence[Tuple[str, str]], None] = None,
    samples: int = 1000,
    seed: int = 1,
    sampling: str = "lhs",
    chunk: int = 100,
    travel_limit_m: Optional[float] = None,
    rotation_limit_deg: Optional[float] = None,
) -> slideroute.Probabilistic:
    """``slideroute.probabilistic`` with the routes on the workers of ``client`` (a
    ``dask.distributed.Client``), ``chunk`` samples a task."""
    dist = slideroute.distributions(scene, dists)
    values = slideroute.sample_values(scene, dist, samples, seed, sampling)
    futures = [
        client.submit(_chunk, scene, dist, values[k : k + chunk], k, pure=False)
        for k in range(0, samples, chunk)
    ]
    rows = slideroute.Samples.concat(client.gather(futures))
    summary = slideroute.summarise(
        scene, dist, samples, seed, sampling, rows, travel_limit_m, rotation_limit_deg
    )
    return slideroute.Probabilistic(samples=rows, summary=summary)


def arguments(argv: Optional[Sequence[str]] = None) -> argparse.Namespace:
    """The command line's arguments."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--scene", help="a scene file (default: the embedded default scene)")
    ap.add_argument("--scheduler", help="a Dask scheduler's address (default: a local cluster)")
    ap.add_argument("--workers", type=int, default=2, help="local cluster's workers")
    ap.add_argument("--samples", type=int, default=400)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--sampling", choices=["lhs", "mc"], default="lhs")
    ap.add_argument("--chunk", type=int, default=50)
    ap.add_argument(
        "--dist",
        action="append",
        default=[],
        metavar="KEY=DISTRIBUTION",
        help="e.g. friction.mu_k=normal:0.40:0.05 (repeat); with the scene's [uncertain] "
        "table, a key of both taking this one",
    )
    return ap.parse_args(argv)


def design(a: argparse.Namespace) -> Tuple[slideroute.Scene, List[Tuple[str, str]]]:
    """The scene and its uncertain keys with their distributions: the scene's ``[uncertain]``
    table and ``--dist``, nothing else. ``SystemExit`` (status 2) saying what to give where
    there are none, or where a ``--dist`` is not ``KEY=DISTRIBUTION``."""
    scene = slideroute.Scene.from_file(a.scene) if a.scene else slideroute.Scene.default()
    given = []
    for d in a.dist:
        key, eq, dist = d.partition("=")
        if not eq or not key or not dist:
            refuse(f"--dist {d!r}: give KEY=DISTRIBUTION (e.g. friction.mu_k=normal:0.40:0.05)")
        given.append((key, dist))
    try:
        return scene, slideroute.distributions(scene, given)
    except slideroute.InputError as e:
        if e.name != "dists":
            raise
        refuse(
            f"{scene.origin} has no [uncertain] table and no --dist was given: give --dist "
            "KEY=DISTRIBUTION (e.g. --dist friction.mu_k=normal:0.40:0.05) or a scene with an "
            "[uncertain] table"
        )


def refuse(message: str) -> NoReturn:
    """Ends the program with status 2, saying why on stderr."""
    print(f"error: {message}", file=sys.stderr)
    raise SystemExit(2)


def main(argv: Optional[Sequence[str]] = None) -> None:
    a = arguments(argv)
    scene, dists = design(a)
    print("uncertain: " + ", ".join(f"{k} {d}" for k, d in dists), file=sys.stderr)
    # Dask only now: --help and a refused design need none.
    from dask.distributed import Client, LocalCluster

    if a.scheduler:
        client = Client(a.scheduler)
    else:
        client = Client(
            LocalCluster(
                n_workers=a.workers, threads_per_worker=1, processes=True, dashboard_address=None
            )
        )
    with client:
        p = probabilistic_on_dask(client, scene, dists, a.samples, a.seed, a.sampling, a.chunk)
    shown = ("probability_of_sliding", "travel_m", "distributions")
    print(json.dumps({k: p.summary[k] for k in shown}, indent=2))


if __name__ == "__main__":
    main()
