"""slideroute from Python: the three-dimensional failure route of a rigid block (a concrete
gravity-dam monolith) sliding on a three-plane foundation with three-point contact.

    >>> import slideroute
    >>> scene = slideroute.Scene.default().with_keys({"friction.mu_k": 0.35})
    >>> route = scene.route()
    >>> route.reason, round(route.travel_m, 3)            # doctest: +SKIP
    >>> route.to_pandas()                                 # with pandas installed

Units are SI; angles are in degrees wherever a person reads or writes them. Scene keys are the
scene file's own (``friction.mu_k``, ``foundation.zeta_deg``, ``loads.eccentricity_m``; see
``slideroute scene --print-default``). Every error is a :class:`SlideRouteError`; a scene's
names the key it is about (``err.key``).

The computations run in Rust (``slideroute._native``), on every core where there are many
(sweeps, grids of poses, samples), without holding the interpreter's lock.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native
from ._errors import InputError, RouteError, SceneError, SlideRouteError

__all__ = [
    "Scene",
    "Route",
    "Samples",
    "Probabilistic",
    "probabilistic",
    "sample_values",
    "run_samples",
    "summarise",
    "distributions",
    "SlideRouteError",
    "SceneError",
    "InputError",
    "RouteError",
    "__version__",
]

__version__: str = _native.version()

Value = Union[float, int, bool, str]
Distributions = Union[Mapping[str, str], Sequence[Tuple[str, str]], None]
#: Called with (done, total) as a sweep or an analysis goes on (about four times a second, and
#: once at the end); an exception it raises stops the work and is raised to the caller.
Progress = Optional[Callable[[int, int], Any]]


def _frame(columns: Mapping[str, Any]) -> Any:
    """Columns as a pandas DataFrame (pandas is needed for this only)."""
    try:
        import pandas as pd
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError("to_pandas() needs pandas: pip install pandas") from e
    return pd.DataFrame(dict(columns))


class Scene:
    """A scene: the contact frame, the foundation, the block, its loads and friction, the
    solver. Immutable: :meth:`with_keys` gives a new scene."""

    __slots__ = ("_s",)

    def __init__(self, native: "_native.Scene") -> None:
        self._s = native

    # Loading -------------------------------------------------------------------------------
    @classmethod
    def default(cls) -> "Scene":
        """The embedded default scene (paper-like)."""
        return cls(_native.Scene.default())

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"]) -> "Scene":
        """A scene file (TOML); files it names are found beside it."""
        return cls(_native.Scene.from_file(os.fspath(path)))

    @classmethod
    def from_toml(cls, text: str, origin: str = "<string>") -> "Scene":
        """A scene from its TOML text."""
        return cls(_native.Scene.from_toml(text, origin))

    @classmethod
    def from_dict(
        cls,
        document: Mapping[str, Any],
        origin: str = "<dict>",
        folder: Union[str, "os.PathLike[str]"] = ".",
    ) -> "Scene":
        """A scene from a dict of its tables and keys, as a scene file writes them
        (``{"frame": {"l1x": 6.0, ...}, "foundation": {...}, ...}``); files it names (a
        surface, a record) are found from ``folder``."""
        try:
            text = json.dumps(document, allow_nan=False)
        except (TypeError, ValueError) as e:
            raise InputError(f"{origin}: not a scene's tables and keys: {e}", "scene") from e
        return cls(_native.Scene.from_json(text, origin, os.fspath(folder)))

    # Changing ------------------------------------------------------------------------------
    def with_keys(self, keys: Mapping[str, Value]) -> "Scene":
        """The same scene with keys set, in the file's own keys and units
        (``{"friction.mu_k": 0.3, "foundation.xi_deg": 18}``), validated as a file is: a key
        that does not exist, or a value it cannot take, raises :class:`SceneError` naming it."""
        if not isinstance(keys, Mapping):
            raise InputError("give the keys as a dict: with_keys({'friction.mu_k': 0.3})", "keys")
        return Scene(self._s.with_keys(dict(keys)))

    def with_key(self, key: str, value: Value) -> "Scene":
        """The same scene with one key set (see :meth:`with_keys`)."""
        return self.with_keys({key: value})

    # Reading -------------------------------------------------------------------------------
    @property
    def name(self) -> str:
        """The scene's name."""
        return self._s.name

    @property
    def origin(self) -> str:
        """Where the scene came from: a path, ``<embedded default scene>``, ``<dict>``."""
        return self._s.origin

    def to_dict(self) -> Dict[str, Any]:
        """The document as read, in the file's own keys and units (defaults not filled in)."""
        return self._s.document()

    @property
    def uncertain(self) -> List[Tuple[str, str]]:
        """The scene's ``[uncertain]`` table: (key, distribution) pairs, by key name."""
        return list(self._s.uncertain)

    def __repr__(self) -> str:
        return f"Scene(name={self.name!r}, origin={self.origin!r})"

    def __reduce__(self) -> Tuple[Any, Tuple[Any, ...]]:
        # Pickled as its document (a Dask worker, a process pool): rebuilt and validated where
        # it lands; files it names are read there from the same folder.
        return (_from_state, (self.to_dict(), self.origin, self._s.folder))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Scene) and self.to_dict() == other.to_dict()

    __hash__ = None  # type: ignore[assignment]

    # Computing -----------------------------------------------------------------------------
    def route(self, dynamics: Optional[str] = None) -> "Route":
        """The route (``dynamics``: ``"rigid-body"`` or ``"paper"``, the scene's own by
        default): the rows ``route.csv`` has, as NumPy arrays, and its summary."""
        columns, summary = self._s.route(dynamics)
        return Route(columns=columns, summary=summary)

    def roots(
        self, x_m: float, z_m: float, theta_deg: float, mode: Optional[str] = None
    ) -> Dict[str, Any]:
        """Every root of the pose system at one displacement (``mode``: ``"exact"`` or
        ``"small-angle"``): the counts, each root (complex angles as (re, im) in degrees,
        residual, admissibility) and the selected pose (alpha, beta, gamma, psi in degrees,
        cm_y in m), or ``None`` with ``selection_error``."""
        return self._s.roots(float(x_m), float(z_m), float(theta_deg), mode)

    def roots_grid(
        self,
        x_m: "np.typing.ArrayLike",
        z_m: "np.typing.ArrayLike",
        theta_deg: "np.typing.ArrayLike",
        mode: Optional[str] = None,
    ) -> Dict[str, np.ndarray]:
        """The selected pose at many displacements, on every core: arrays ``alpha_deg``,
        ``beta_deg``, ``gamma_deg``, ``cm_y_m`` (NaN where no root is admissible) and
        ``finite_roots``."""
        as_f64 = lambda a: np.ascontiguousarray(np.asarray(a, dtype=np.float64).ravel())
        return self._s.roots_grid(as_f64(x_m), as_f64(z_m), as_f64(theta_deg), mode)

    def pose(self, x_m: float, z_m: float, theta_deg: float) -> Dict[str, Any]:
        """The pose by the direct solver (Newton on the contact conditions, independent of the
        polynomial systems): ``tilt_deg``, ``roll_deg``, ``cm_y_m``, ``vertices_m`` and
        ``residual_m``."""
        return self._s.pose(float(x_m), float(z_m), float(theta_deg))

    def sweep(
        self,
        values: Mapping[str, Iterable[float]],
        dynamics: Optional[str] = None,
        progress: Progress = None,
    ) -> "Samples":
        """Every combination of the values given (``{"friction.mu_k": [0.3, 0.35, 0.4]}``),
        each route on its own core, by the runner ``slideroute sweep`` uses: one row per
        combination, in order (the last key varies fastest), the rows ``sweep.csv`` has.
        ``progress(done, total)`` is told how far it is; Ctrl-C stops it with
        ``KeyboardInterrupt``."""
        given = [(k, [float(v) for v in vs]) for k, vs in values.items()]
        return Samples(self._s.sweep(given, dynamics, progress))


def _from_state(document: Dict[str, Any], origin: str, folder: str) -> Scene:
    return Scene(_native.Scene.from_json(json.dumps(document), origin, folder))


@dataclass(frozen=True)
class Route:
    """A route: ``columns`` (``t_s``, ``x_m``, ``z_m``, ``theta_deg``, … as ``route.csv`` has
    them; NaN where a value could not be had) and ``summary`` (as ``summary.json`` has it)."""

    columns: Dict[str, np.ndarray]
    summary: Dict[str, Any]

    @property
    def reason(self) -> str:
        """How the route ended (``time-limit``, ``stopped``, …)."""
        return self.summary["termination"]["reason"]

    @property
    def t_end_s(self) -> float:
        """When it ended (s)."""
        return self.summary["termination"]["t_s"]

    @property
    def travel_m(self) -> float:
        """The length of the centre of mass's path (m)."""
        return self.summary["travel_m"]

    @property
    def factor_of_safety(self) -> Optional[float]:
        """The factor of safety at the start (+inf where no multiple of the driving loads
        starts the block, -inf where the weight alone does; None if its program failed)."""
        fs = self.summary.get("factor_of_safety")
        if fs is None:
            return None
        if fs["kind"] == "finite":
            return float(fs["value"])
        return float("inf") if fs["kind"] == "unbounded" else float("-inf")

    @property
    def base(self) -> Optional[Dict[str, Any]]:
        """A block on its base (``contacts = "base"``): ``resting`` (where it rested before any
        load: the CM, yaw, tilt, rotation and the points that carried it with their shares),
        ``max_penetration_m`` (the deepest its base went into the ground) and ``outline_m``
        (its corners, numbered as the ``corners_carrying`` column's bits); None on the paper's
        three-point frame."""
        return self.summary.get("base")

    def __len__(self) -> int:
        return len(self.columns["t_s"])

    def to_pandas(self) -> Any:
        """The rows as a pandas DataFrame."""
        return _frame(self.columns)


class Samples(dict):
    """Rows of samples (or of a sweep's combinations) as columns: ``sample``, each key's values,
    ``factor_of_safety`` (±inf where no multiple of the loads starts the block, or the weight
    alone does), ``reason``, ``t_end_s``, ``travel_m``, ``final_yaw_deg``, ``final_x_m``,
    ``final_z_m``, ``max_alpha_deg``, ``max_beta_deg`` and ``detail`` (what ended the route, or
    why a sample's values made no valid scene) — the command line's ``samples.csv`` and
    ``sweep.csv`` columns, from the same runner."""

    def to_pandas(self) -> Any:
        """The rows as a pandas DataFrame."""
        return _frame(self)

    @staticmethod
    def concat(parts: Sequence[Mapping[str, Any]]) -> "Samples":
        """Chunks of one design's samples (from :func:`run_samples`) joined in sample order."""
        if not parts:
            raise InputError("no chunks to join", "parts")
        parts = sorted(parts, key=lambda p: int(np.asarray(p["sample"])[0]) if len(p["sample"]) else 0)
        out = Samples()
        for name in parts[0]:
            first = parts[0][name]
            if isinstance(first, np.ndarray):
                out[name] = np.concatenate([np.asarray(p[name]) for p in parts])
            else:
                out[name] = [x for p in parts for x in p[name]]
        return out


def distributions(scene: Scene, dists: Distributions) -> List[Tuple[str, str]]:
    """The uncertain keys of an analysis and their distributions: the scene's ``[uncertain]``
    table, then ``dists`` (``{key: "name:p1:p2…"}`` or pairs; a key of both takes ``dists``)."""
    given: List[Tuple[str, str]]
    if dists is None:
        given = []
    elif isinstance(dists, Mapping):
        given = [(str(k), str(v)) for k, v in dists.items()]
    else:
        given = [(str(k), str(v)) for k, v in dists]
    merged = _native.distributions(scene._s, given)
    if not merged:
        raise InputError(
            f"{scene.origin}: nothing is uncertain: give dists={{key: distribution}} or an "
            "[uncertain] table in the scene",
            "dists",
        )
    return merged


def sample_values(
    scene: Scene,
    dists: Distributions = None,
    samples: int = 1000,
    seed: int = 1,
    sampling: str = "lhs",
) -> np.ndarray:
    """The values of every sample of a design (rows) of each uncertain key (columns), drawn
    whole from ``seed``: the same on any machine. ``dists`` as for :func:`probabilistic`."""
    return _native.sample_values(scene._s, distributions(scene, dists), int(samples), int(seed), sampling)


def run_samples(
    scene: Scene,
    dists: Distributions,
    values: "np.typing.ArrayLike",
    first: int = 0,
    progress: Progress = None,
) -> Samples:
    """The samples numbered ``first``, ``first + 1``, … with ``values`` (rows of
    :func:`sample_values`), on every core. A chunk run anywhere gives the rows the whole run
    gives for it: this is what a Dask worker runs (see ``examples/dask_probabilistic.py``)."""
    v = np.ascontiguousarray(np.asarray(values, dtype=np.float64))
    if v.ndim != 2:
        raise InputError("values: a 2-D array, one row per sample", "values")
    return Samples(
        _native.run_samples(scene._s, distributions(scene, dists), v, int(first), progress)
    )


def summarise(
    scene: Scene,
    dists: Distributions,
    samples: int,
    seed: int,
    sampling: str,
    rows: Mapping[str, Any],
    travel_limit_m: Optional[float] = None,
    rotation_limit_deg: Optional[float] = None,
    displacement_limit_m: Optional[float] = None,
) -> Dict[str, Any]:
    """What the rows of one design come to: the summary ``probabilistic.json`` has (the
    probability of sliding with its 95 % interval — under a ground-motion record, that the
    record displaces the block —, exceedance probabilities, percentiles, rank correlations)."""
    return _native.summarise_samples(
        scene._s,
        distributions(scene, dists),
        int(samples),
        int(seed),
        sampling,
        dict(rows),
        travel_limit_m,
        rotation_limit_deg,
        displacement_limit_m,
    )


@dataclass(frozen=True)
class Probabilistic:
    """A probabilistic analysis's result: ``samples`` (one row per sample) and ``summary``."""

    samples: Samples
    summary: Dict[str, Any] = field(repr=False)

    @property
    def probability_of_sliding(self) -> float:
        """The fraction of samples whose factor of safety is below 1 (under a ground-motion
        record, whose block the record displaces)."""
        return self.summary["probability_of_sliding"]["value"]


def probabilistic(
    scene: Scene,
    dists: Distributions = None,
    samples: int = 1000,
    seed: int = 1,
    sampling: str = "lhs",
    travel_limit_m: Optional[float] = None,
    rotation_limit_deg: Optional[float] = None,
    progress: Progress = None,
    displacement_limit_m: Optional[float] = None,
) -> Probabilistic:
    """The probabilistic analysis, as ``slideroute probabilistic`` runs it: each uncertain
    key's distribution (``{"friction.mu_k": "normal:0.40:0.05"}``; the scene's
    ``[uncertain]`` table too), ``samples`` samples from ``seed`` by ``sampling`` (``"lhs"``
    or ``"mc"``), every route on every core; the same numbers as the command line's.
    ``progress(done, total)`` is told how many samples are done (``tqdm``'s ``update`` fits);
    Ctrl-C stops it at its next route with ``KeyboardInterrupt``. Under a ground-motion
    record, ``displacement_limit_m`` asks for the probability that the permanent displacement
    exceeds it."""
    dist = distributions(scene, dists)
    values = sample_values(scene, dist, samples, seed, sampling)
    rows = run_samples(scene, dist, values, progress=progress)
    summary = summarise(
        scene,
        dist,
        samples,
        seed,
        sampling,
        rows,
        travel_limit_m,
        rotation_limit_deg,
        displacement_limit_m,
    )
    return Probabilistic(samples=rows, summary=summary)
