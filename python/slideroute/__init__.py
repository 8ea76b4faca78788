"""slideroute from Python: the three-dimensional failure route of a rigid block (a concrete
gravity-dam monolith) sliding on a three-plane foundation with three-point contact.

    >>> import slideroute
    >>> scene = slideroute.Scene.default().with_keys({"friction.mu_k": 0.35})
    >>> route = scene.route()
    >>> route.reason, route.reason_text, round(route.travel_m, 3)   # doctest: +SKIP
    >>> scene.factor_of_safety(), scene.check()           # doctest: +SKIP
    >>> route.to_pandas()                                 # with pandas installed

Units are SI; angles are in degrees wherever a person reads or writes them. Scene keys are the
scene file's own (``friction.mu_k``, ``foundation.zeta_deg``, ``loads.eccentricity_m``; see
``slideroute scene --print-default``). Every error is a :class:`SlideRouteError`; a scene's
names the key it is about (``err.key``). Each is also the built-in a Python user expects: a
file that does not exist raises :class:`SceneFileNotFoundError` (a ``FileNotFoundError``), a
value of the wrong type :class:`SceneTypeError` or :class:`InputTypeError` (``TypeError``s
whose message names Python's types), a value that cannot be used :class:`SceneError` or
:class:`InputError` (``ValueError``s).

How a route ends has two spellings, everywhere the same: ``reason``, a machine name
(``contact0-reached-inclined-plane``), and ``reason_text``, a sentence (``contact 0 reached an
inclined plane``); :data:`REASONS` lists them.

The computations run in Rust (``slideroute._native``), on every core where there are many
(sweeps, grids of poses, samples), without holding the interpreter's lock. The long ones
(:meth:`Scene.route`, :meth:`Scene.sweep`, :meth:`Scene.roots_grid`, :meth:`Scene.check`,
:func:`probabilistic`) take ``progress=``: a callable told (done, total), or ``True`` for a
bar (tqdm's where tqdm is installed, else a line on stderr).
"""

from __future__ import annotations

import collections as _collections
import collections.abc as _abc
import contextlib as _contextlib
import json as _json
import os as _os
import sys as _sys
import types as _types
import typing as _t
from dataclasses import dataclass as _dataclass
from dataclasses import field as _field

import numpy as _np

from . import _native
from ._errors import (
    InputError,
    InputTypeError,
    OutputError,
    RouteError,
    SceneError,
    SceneFileNotFoundError,
    SceneTypeError,
    SlideRouteError,
)

if _t.TYPE_CHECKING:  # names for the annotations only: not the package's
    import os

    import numpy as np
    import numpy.typing
    from typing import Any, Callable, Dict, Iterable, Iterator, List, Mapping, Optional
    from typing import Sequence, Tuple, Union

__all__ = [
    "Scene",
    "Route",
    "RouteChunks",
    "Samples",
    "Check",
    "Probabilistic",
    "probabilistic",
    "sample_values",
    "run_samples",
    "summarise",
    "distributions",
    "REASONS",
    "Value",
    "Distributions",
    "Progress",
    "SlideRouteError",
    "SceneError",
    "SceneTypeError",
    "SceneFileNotFoundError",
    "InputError",
    "InputTypeError",
    "RouteError",
    "OutputError",
    "__version__",
]

__version__: str = _native.version()

#: A scene value: what a scene file's key takes.
Value = _t.Union[float, int, bool, str]
#: Uncertain keys' distributions: ``{"friction.mu_k": "normal:0.40:0.05"}`` or pairs.
Distributions = _t.Union[_t.Mapping[str, str], _t.Sequence[_t.Tuple[str, str]], None]
#: ``progress(done, total)``, called as a long computation goes on (about four times a second,
#: and once at the end; an exception it raises stops the work and is raised to the caller);
#: ``True`` for a bar (tqdm's where tqdm is installed, else a line on stderr); ``None`` or
#: ``False`` for nothing.
Progress = _t.Union[_t.Callable[[int, int], _t.Any], bool, None]

#: How a route (or a row of many) ends: machine name → sentence. The machine name is what
#: ``Route.reason`` and every table's ``reason`` column hold (``summary.json``'s
#: ``termination.reason``: ``contact0-reached-inclined-plane``, ``time-limit``,
#: ``invalid-scene``, ``not-run``); the sentence is ``Route.reason_text`` and the
#: ``reason_text`` column (the command line's CSV tables' words: ``contact 0 reached an
#: inclined plane``).
REASONS: "Mapping[str, str]" = _types.MappingProxyType(dict(_native.reasons()))


class _Bar:
    """``progress=True``: tqdm's bar where tqdm is installed, else one line on stderr written
    over as the count moves."""

    def __init__(self, what: str) -> None:
        self._what = what
        self._bar: "Any" = None
        self._shown = False
        try:
            from tqdm.auto import tqdm
        except ImportError:
            tqdm = None
        self._tqdm = tqdm

    def __call__(self, done: int, total: int) -> None:
        if self._tqdm is not None:
            if self._bar is None:
                self._bar = self._tqdm(total=total, desc=self._what)
            self._bar.update(done - self._bar.n)
        else:
            pct = 100.0 * done / total if total else 100.0
            _sys.stderr.write(f"\r{self._what}: {done} of {total} ({pct:.0f} %)")
            _sys.stderr.flush()
            self._shown = True

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
        elif self._shown:
            _sys.stderr.write("\n")
            _sys.stderr.flush()


@_contextlib.contextmanager
def _progress(progress: Progress, what: str) -> "Iterator[Optional[Callable[[int, int], Any]]]":
    """The callable a computation is given for ``progress``, the bar closed at its end."""
    if progress is None or progress is False:
        yield None
    elif progress is True:
        bar = _Bar(what)
        try:
            yield bar
        finally:
            bar.close()
    elif callable(progress):
        yield progress
    else:
        raise InputTypeError(
            f"progress: expected a callable(done, total), True or None, got {type(progress).__name__}",
            "progress",
        )


def _factor(fs: "Optional[Dict[str, Any]]") -> "Optional[float]":
    """A factor of safety as a number: +inf unbounded, -inf not holdable, None for none."""
    if fs is None:
        return None
    if fs["kind"] == "finite":
        return float(fs["value"])
    return float("inf") if fs["kind"] == "unbounded" else float("-inf")


def _frame(columns: "Mapping[str, Any]") -> "Any":
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
    def from_file(cls, path: "Union[str, os.PathLike[str]]") -> "Scene":
        """A scene file (TOML); files it names are found beside it. A file that does not exist
        (the scene's, or one it names) raises :class:`SceneFileNotFoundError`, a
        ``FileNotFoundError``; a value of the wrong type :class:`SceneTypeError`, a
        ``TypeError``; a value it cannot take :class:`SceneError`, a ``ValueError``."""
        return cls(_native.Scene.from_file(_os.fspath(path)))

    @classmethod
    def from_toml(cls, text: str, origin: str = "<string>") -> "Scene":
        """A scene from its TOML text."""
        return cls(_native.Scene.from_toml(text, origin))

    @classmethod
    def from_dict(
        cls,
        document: "Mapping[str, Any]",
        origin: str = "<dict>",
        folder: "Union[str, os.PathLike[str]]" = ".",
    ) -> "Scene":
        """A scene from a dict of its tables and keys, as a scene file writes them
        (``{"frame": {"l1x": 6.0, ...}, "foundation": {...}, ...}``); files it names (a
        surface, a record) are found from ``folder``."""
        missing = _none_at(document)
        if missing is not None:
            raise InputError(
                f"{origin}: {missing}: None is no value a scene can hold (leave the key out for "
                "its default)",
                missing,
            )
        try:
            text = _json.dumps(document, allow_nan=False)
        except TypeError as e:
            raise InputTypeError(f"{origin}: not a scene's tables and keys: {e}", "scene") from e
        except ValueError as e:
            raise InputError(f"{origin}: not a scene's tables and keys: {e}", "scene") from e
        return cls(_native.Scene.from_json(text, origin, _os.fspath(folder)))

    # Changing ------------------------------------------------------------------------------
    def with_keys(self, keys: "Mapping[str, Value]") -> "Scene":
        """The same scene with keys set, in the file's own keys and units
        (``{"friction.mu_k": 0.3, "foundation.xi_deg": 18}``), validated as a file is: a key
        that does not exist, or a value it cannot take, raises :class:`SceneError` naming it
        (:class:`SceneTypeError` for a value of the wrong type)."""
        if not isinstance(keys, _t.Mapping):
            raise InputTypeError(
                "keys: expected a dict like {'friction.mu_k': 0.3}, "
                f"got {type(keys).__name__}",
                "keys",
            )
        return Scene(self._s.with_keys(dict(keys)))

    def with_key(self, key: str, value: "Value") -> "Scene":
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

    def to_dict(self) -> "Dict[str, Any]":
        """The document as read, in the file's own keys and units (defaults not filled in)."""
        return self._s.document()

    @property
    def uncertain(self) -> "List[Tuple[str, str]]":
        """The scene's ``[uncertain]`` table: (key, distribution) pairs, by key name."""
        return list(self._s.uncertain)

    def __repr__(self) -> str:
        return f"<Scene {self.name} from {self.origin}>"

    def __reduce__(self) -> "Tuple[Any, Tuple[Any, ...]]":
        # Pickled as its document (a Dask worker, a process pool): rebuilt and validated where
        # it lands; files it names are read there from the same folder.
        return (_from_state, (self.to_dict(), self.origin, self._s.folder))

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Scene) and self.to_dict() == other.to_dict()

    __hash__ = None  # type: ignore[assignment]

    # Computing -----------------------------------------------------------------------------
    def route(
        self,
        dynamics: "Optional[str]" = None,
        progress: "Progress" = None,
        max_rows: int = 1_000_000,
    ) -> "Route":
        """The route (``dynamics``: ``"rigid-body"`` or ``"paper"``, the scene's own by
        default): the rows ``route.csv`` has, as NumPy arrays, and its summary.
        ``progress(done, total)`` is told how many increments of dt are done (``True``: a
        bar); Ctrl-C stops it with ``KeyboardInterrupt``. The arrays take 200 bytes a row: a
        route that may record more than ``max_rows`` rows (t_end_s / dt_s / stride) is refused
        before it starts with :class:`InputError`; :meth:`route_chunks` reads any length."""
        limit = _whole("max_rows", max_rows, 1, 2**62)
        with _progress(progress, f"route of {self.name}") as tell:
            columns, summary, files = self._s.route(dynamics, tell, limit)
        return Route(columns=columns, summary=summary, _files=files)

    def route_chunks(
        self, rows: int = 16_384, dynamics: "Optional[str]" = None
    ) -> "RouteChunks":
        """The route read in chunks: an iterator of dicts of NumPy arrays (the columns
        :meth:`route` gives) of at most ``rows`` rows each, computed a chunk or two ahead of the
        reader, so that a route of any length is read in bounded memory. Its ``summary`` is
        there once the last chunk is read. Ctrl-C stops it with ``KeyboardInterrupt``; leaving
        the loop early stops the route."""
        return RouteChunks(self._s.route_chunks(dynamics, _whole("rows", rows, 1, 2**32)))

    def factor_of_safety(self, dynamics: "Optional[str]" = None) -> "Optional[float]":
        """The factor of safety at the start, without the route after it (the largest multiple
        of the driving loads the contacts' friction holds; below 1 the loads start the block):
        the number :attr:`Route.factor_of_safety` gives — ``inf`` where no multiple of the
        driving loads starts the block (unbounded), ``-inf`` where the weight alone does (not
        holdable), ``None`` where the start has no pose."""
        return _factor(self._s.factor_of_safety(dynamics))

    def check(self, progress: "Progress" = None) -> "Check":
        """The load cases (``[[case]]``; without any, the scene as written as one usual case)
        checked by their guideline, as ``slideroute check`` does: per case the gravity
        method's sliding factor, the resultant and base pressures on a monolith with its
        water, the load multiple (the factor of safety), the requirement and whether it
        passes — ``check.json``'s ``cases`` and, by :meth:`Check.to_pandas`, ``check.csv``'s
        rows. Each case's route runs (a case that fails shows where the monolith would go).
        ``progress(done, total)`` is told how many cases are done."""
        with _progress(progress, f"check of {self.name}") as tell:
            guideline, cases, columns, files = self._s.check(tell)
        return Check(
            scene=self.name, guideline=guideline, cases=cases, columns=columns, _files=files
        )

    def roots(
        self, x_m: float, z_m: float, theta_deg: float, mode: "Optional[str]" = None
    ) -> "Dict[str, Any]":
        """Every root of the pose system at one displacement (``mode``: ``"exact"`` or
        ``"small-angle"``): the counts, each root (complex angles as (re, im) in degrees,
        residual, admissibility) and the selected pose (alpha, beta, gamma, psi in degrees,
        cm_y in m), or ``None`` with ``selection_error``."""
        return self._s.roots(float(x_m), float(z_m), float(theta_deg), mode)

    def roots_grid(
        self,
        x_m: "numpy.typing.ArrayLike",
        z_m: "numpy.typing.ArrayLike",
        theta_deg: "numpy.typing.ArrayLike",
        mode: "Optional[str]" = None,
        progress: "Progress" = None,
    ) -> "Dict[str, np.ndarray]":
        """The selected pose at many displacements (arrays of one length, flattened), on
        every core: arrays ``alpha_deg``, ``beta_deg``, ``gamma_deg``, ``cm_y_m`` (NaN where
        no root is admissible) and ``finite_roots``. ``progress(done, total)`` is told how
        many poses are done; Ctrl-C stops it with ``KeyboardInterrupt``."""

        def as_f64(a: "numpy.typing.ArrayLike") -> "np.ndarray":
            return _np.ascontiguousarray(_np.asarray(a, dtype=_np.float64).ravel())

        with _progress(progress, "poses") as tell:
            return self._s.roots_grid(as_f64(x_m), as_f64(z_m), as_f64(theta_deg), mode, tell)

    def pose(self, x_m: float, z_m: float, theta_deg: float) -> "Dict[str, Any]":
        """The pose by the direct solver (Newton on the contact conditions, independent of the
        polynomial systems): ``tilt_deg``, ``roll_deg``, ``cm_y_m``, ``vertices_m`` and
        ``residual_m``."""
        return self._s.pose(float(x_m), float(z_m), float(theta_deg))

    def sweep(
        self,
        values: "Mapping[str, Iterable[float]]",
        dynamics: "Optional[str]" = None,
        progress: "Progress" = None,
        max_combinations: int = 100_000,
    ) -> "Samples":
        """Every combination of the values given (``{"friction.mu_k": [0.3, 0.35, 0.4]}``),
        each route on its own core, by the runner ``slideroute sweep`` uses: one row per
        combination, in order (the last key varies fastest), the rows ``sweep.csv`` has (see
        :class:`Samples`). ``progress(done, total)`` is told how far it is (``True``: a bar);
        Ctrl-C stops it with ``KeyboardInterrupt``. Every row is held (about 1.1 kB a
        combination at the peak): more than ``max_combinations`` are refused before any runs
        with :class:`InputError`; raise it, sweep in parts, or use the command line, which
        holds none."""
        given = [(k, [float(v) for v in vs]) for k, vs in values.items()]
        limit = _whole("max_combinations", max_combinations, 1, 2**62)
        count = 1
        for _, vs in given:
            count *= len(vs)
        if count > limit:
            raise InputError(
                f"values: {count} combinations, more than max_combinations = {limit}; every "
                "row is held (about 1.1 kB each): raise max_combinations, sweep in parts, or use "
                "the command line's sweep, which holds none",
                "values",
            )
        with _progress(progress, "sweep") as tell:
            return Samples(self._s.sweep(given, dynamics, tell))


def _none_at(value: Any, at: str = "") -> "Optional[str]":
    """The key (``friction.mu_k``, ``case[2].name``) of the first None in a scene's dict."""
    if value is None:
        return at or "scene"
    if isinstance(value, _abc.Mapping):
        for k, v in value.items():
            found = _none_at(v, f"{at}.{k}" if at else str(k))
            if found is not None:
                return found
    elif isinstance(value, (list, tuple)):
        for i, v in enumerate(value):
            found = _none_at(v, f"{at}[{i}]")
            if found is not None:
                return found
    return None


def _from_state(document: "Dict[str, Any]", origin: str, folder: str) -> Scene:
    return Scene(_native.Scene.from_json(_json.dumps(document), origin, folder))


class RouteChunks:
    """A route read in chunks (:meth:`Scene.route_chunks`): iterate for dicts of NumPy arrays;
    ``summary`` (as ``summary.json`` has it) once the last is read, else None."""

    def __init__(self, native: "Any") -> None:
        self._native = native

    def __iter__(self) -> "RouteChunks":
        return self

    def __next__(self) -> "Dict[str, Any]":
        return self._native.__next__()

    @property
    def summary(self) -> "Optional[Dict[str, Any]]":
        return self._native.summary

    def close(self) -> None:
        """Stops the route; the chunks not read are dropped."""
        self._native.close()

    def __enter__(self) -> "RouteChunks":
        return self

    def __exit__(self, *exc: "Any") -> None:
        self.close()

    def __repr__(self) -> str:
        done = "done" if self.summary is not None else "under way"
        return f"<RouteChunks: {done}>"


def _written_by(files: "Any", what: str) -> "Any":
    """What writes the files of a result: the extension's, or an error saying why there is
    none (a result made by hand or unpickled holds only its numbers)."""
    if files is None:
        raise InputError(
            f"this {what} holds its numbers only (made by hand or unpickled): compute it again "
            "to write its files",
            what,
        )
    return files


@_dataclass(frozen=True, repr=False)
class Route:
    """A route: ``columns`` (``body``, ``t_s``, ``x_m``, ``z_m``, ``theta_deg``, … as
    ``route.csv`` has them; NaN where a value could not be had) and ``summary`` (as
    ``summary.json`` has it). ``body`` is the number of the body a row is of, from 0: a scene of
    one block has 0 in every row. :meth:`write` writes its files as ``slideroute run`` does,
    :meth:`plot_plan` its plan view."""

    columns: "Dict[str, np.ndarray]"
    summary: "Dict[str, Any]"
    _files: "Any" = _field(default=None, compare=False)

    def __reduce__(self) -> "Tuple[Any, ...]":
        # Pickled as its numbers (a Dask worker's result): its files are written where it
        # was computed.
        return (Route, (self.columns, self.summary))

    def write(
        self, folder: "Union[str, os.PathLike[str]]", pictures: bool = True, view: bool = True
    ) -> "List[str]":
        """Writes the route's files into ``folder`` as ``slideroute run`` does, the same bytes:
        ``route.csv`` (every row), the route in 3-D (``route.html``, ``route.glb``; unless
        ``view=False``), the pictures (``plan.svg``, ``profile.svg``, ``angles.svg``,
        ``reactions.svg``; unless ``pictures=False``) and ``summary.json`` with its manifest,
        last. Each file appears whole or not at all; the folder is locked while it is written,
        and the files an earlier run wrote there and this one did not are removed. Gives the
        paths written; what was left out (a route with nothing to show in 3-D) is a warning. A
        folder that cannot be written raises :class:`OutputError` (an ``OSError``)."""
        files = _written_by(self._files, "route")
        return files.write(_os.fspath(folder), self.columns, bool(pictures), bool(view))

    def plot_plan(self, path: "Union[str, os.PathLike[str]]") -> None:
        """Draws the plan view from above (``plan.svg``, like the paper's Figure 12: the
        foundation shaded and named, the CM's path, the block's outline as it goes, the water's
        push) to ``path`` (SVG), whole or not at all."""
        _written_by(self._files, "route").plot_plan(_os.fspath(path))

    @property
    def reason(self) -> str:
        """How the route ended, as a machine name (``summary.json``'s ``termination.reason``:
        ``contact0-reached-inclined-plane``, ``time-limit``, ``does-not-slide``, …; every one
        in :data:`REASONS`)."""
        return self.summary["termination"]["reason"]

    @property
    def reason_text(self) -> str:
        """How the route ended, as a sentence (``contact 0 reached an inclined plane``): the
        words of the command line's tables and of the ``reason_text`` column."""
        return REASONS.get(self.reason, self.reason)

    @property
    def detail(self) -> str:
        """What exactly ended it, for people."""
        return self.summary["termination"]["detail"]

    @property
    def t_end_s(self) -> float:
        """When it ended (s)."""
        return self.summary["termination"]["t_s"]

    @property
    def travel_m(self) -> float:
        """The length of the centre of mass's path (m)."""
        return self.summary["travel_m"]

    @property
    def factor_of_safety(self) -> "Optional[float]":
        """The factor of safety at the start (+inf where no multiple of the driving loads
        starts the block, -inf where the weight alone does; None if its program failed);
        :meth:`Scene.factor_of_safety` gives it without the route."""
        return _factor(self.summary.get("factor_of_safety"))

    @property
    def base(self) -> "Optional[Dict[str, Any]]":
        """A block on its base (``contacts = "base"``): ``resting`` (where it rested before any
        load: the CM, yaw, tilt, rotation and the points that carried it with their shares),
        ``max_penetration_m`` (the deepest its base went into the ground) and ``outline_m``
        (its corners, numbered as the ``corners_carrying`` column's bits); None on the paper's
        three-point frame."""
        return self.summary.get("base")

    def __len__(self) -> int:
        return len(self.columns["t_s"])

    def __repr__(self) -> str:
        scene = self.summary.get("scene")
        name = scene.get("name") if isinstance(scene, dict) else scene
        named = f" {name}" if name else ""
        return (
            f"<Route{named}: {self.reason_text} at t = {self.t_end_s:.3f} s, "
            f"travel {self.travel_m:.3f} m, {len(self)} rows>"
        )

    def to_pandas(self) -> "Any":
        """The rows as a pandas DataFrame."""
        return _frame(self.columns)


class Samples(dict):
    """Rows of samples (or of a sweep's combinations) as columns: ``sample``, each key's values,
    ``factor_of_safety`` (±inf where no multiple of the loads starts the block, or the weight
    alone does), ``t_end_s``, ``travel_m``, ``final_yaw_deg``, ``final_x_m``, ``final_z_m``,
    ``max_alpha_deg``, ``max_beta_deg``, ``permanent_x_m``, ``permanent_z_m``, ``reason`` (how
    the route ended, a machine name as :attr:`Route.reason`: ``time-limit``,
    ``invalid-scene`` where a sample's values made no valid scene, ``not-run`` where a stopped
    run did not start it), ``reason_text`` (the same as a sentence, as the command line's
    ``samples.csv`` and ``sweep.csv`` write their ``reason`` column) and ``detail`` (what ended
    the route, or why the values made no valid scene) — the command line's columns, from the
    same runner."""

    def to_pandas(self) -> "Any":
        """The rows as a pandas DataFrame."""
        return _frame(self)

    def keys_varied(self) -> "List[str]":
        """The scene keys whose values the rows take (the columns after ``sample``)."""
        names = list(self)
        end = names.index("factor_of_safety") if "factor_of_safety" in names else len(names)
        return [n for n in names[:end] if n != "sample"]

    def __repr__(self) -> str:
        n = len(self.get("sample", ()))
        keys = ", ".join(self.keys_varied()) or "no keys"
        ends = _collections.Counter(self.get("reason", ()))
        told = ", ".join(f"{count} {code}" for code, count in ends.most_common(3))
        more = ", …" if len(ends) > 3 else ""
        return f"<Samples: {n} rows of {keys}; {told}{more}>"

    @staticmethod
    def concat(parts: "Sequence[Mapping[str, Any]]") -> "Samples":
        """Chunks of one design's samples (from :func:`run_samples`) joined in sample order."""
        if not parts:
            raise InputError("no chunks to join", "parts")
        parts = sorted(
            parts, key=lambda p: int(_np.asarray(p["sample"])[0]) if len(p["sample"]) else 0
        )
        out = Samples()
        for name in parts[0]:
            first = parts[0][name]
            if isinstance(first, _np.ndarray):
                out[name] = _np.concatenate([_np.asarray(p[name]) for p in parts])
            else:
                out[name] = [x for p in parts for x in p[name]]
        return out


@_dataclass(frozen=True, repr=False)
class Check:
    """The load cases of a scene checked by their guideline (:meth:`Scene.check`):
    ``guideline`` and ``cases`` as ``check.json`` has them — per case ``factor_of_safety`` (the
    load multiple), ``load_multiple_limit``, ``required_fs``, on a monolith with its water the
    gravity method's ``sliding_fs``, ``resultant_from_heel_m``, ``base_in_compression_pct``,
    ``heel_pressure_pa``, ``toe_pressure_pa``, ``crack_length_m``, …, ``passes`` and ``loads``
    — and ``columns``, ``check.csv``'s rows (numbers as floats, NaN where a case has none,
    ``sliding_fs`` and ``load_multiple`` +inf where unbounded and -inf where not holdable; the
    route's end as ``reason`` and ``reason_text``, as :class:`Samples` has them).
    :meth:`write_report` writes its files as ``slideroute check`` does, :meth:`table` gives
    the tables it prints."""

    scene: str
    guideline: "Dict[str, Any]"
    cases: "List[Dict[str, Any]]"
    columns: "Dict[str, Any]"
    _files: "Any" = _field(default=None, compare=False)

    def __reduce__(self) -> "Tuple[Any, ...]":
        return (Check, (self.scene, self.guideline, self.cases, self.columns))

    def write_report(
        self, folder: "Union[str, os.PathLike[str]]", pictures: bool = True, view: bool = True
    ) -> "List[str]":
        """Writes the check's files into ``folder`` as ``slideroute check`` does, the same
        bytes: each failing case's route in ``case-N/`` (with its pictures and 3-D view unless
        turned off), ``check.csv``, ``report.html`` (a page to hand in: each case's section
        drawn with its water, loads and resultant, the loads and verdicts with the guideline
        each comes from) and ``check.json`` with its manifest, last; each whole or not at all.
        Gives the paths written. Ctrl-C stops it with ``KeyboardInterrupt`` (the check's own
        files not written); a folder that cannot be written raises :class:`OutputError`."""
        files = _written_by(self._files, "check")
        return files.write_report(_os.fspath(folder), bool(pictures), bool(view))

    def table(self) -> str:
        """The check's tables as ``slideroute check`` prints them."""
        return _written_by(self._files, "check").table()

    @property
    def passes(self) -> bool:
        """Whether every case meets its guideline."""
        return all(c["passes"] for c in self.cases)

    @property
    def failing(self) -> "List[str]":
        """The names of the cases that fail."""
        return [c["case"]["name"] for c in self.cases if not c["passes"]]

    def __len__(self) -> int:
        return len(self.cases)

    def __repr__(self) -> str:
        n, failing = len(self.cases), self.failing
        verdict = f"{n - len(failing)} pass"
        if failing:
            verdict += f", {len(failing)} fail{'s' if len(failing) == 1 else ''}: " + ", ".join(
                failing
            )
        return f"<Check {self.scene}: {n} load case{'s' if n != 1 else ''}, {verdict}>"

    def to_pandas(self) -> "Any":
        """The cases as a pandas DataFrame, one row each (``check.csv``'s columns)."""
        return _frame(self.columns)


def distributions(scene: Scene, dists: "Distributions") -> "List[Tuple[str, str]]":
    """The uncertain keys of an analysis and their distributions: the scene's ``[uncertain]``
    table, then ``dists`` (``{key: "name:p1:p2…"}`` or pairs; a key of both takes ``dists``).
    Nothing uncertain raises :class:`InputError`."""
    given: "List[Tuple[str, str]]"
    if dists is None:
        given = []
    elif isinstance(dists, _t.Mapping):
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


def _whole(name: str, value: Any, lo: int, hi: int) -> int:
    """``value`` as a whole number from ``lo`` to ``hi``; else :class:`InputError` naming
    ``name`` (Python's OverflowError named nothing, and a wrapped number ran silently)."""
    if isinstance(value, bool) or not isinstance(value, (int, _np.integer)):
        raise InputTypeError(f"{name}: a whole number, got {value!r}", name)
    v = int(value)
    if not lo <= v <= hi:
        raise InputError(f"{name} {v}: a whole number from {lo} to {hi}", name)
    return v


_MAX_SAMPLES = 10_000_000
_MAX_SEED = 2**64 - 1
_MAX_SAMPLE_NUMBER = 2**53 - 1


def sample_values(
    scene: Scene,
    dists: "Distributions" = None,
    samples: int = 1000,
    seed: int = 1,
    sampling: str = "lhs",
) -> "np.ndarray":
    """The values of every sample of a design (rows) of each uncertain key (columns), drawn
    whole from ``seed``: the same on any machine. ``dists`` as for :func:`probabilistic`."""
    return _native.sample_values(
        scene._s,
        distributions(scene, dists),
        _whole("samples", samples, 1, _MAX_SAMPLES),
        _whole("seed", seed, 0, _MAX_SEED),
        sampling,
    )


def run_samples(
    scene: Scene,
    dists: "Distributions",
    values: "numpy.typing.ArrayLike",
    first: int = 0,
    progress: "Progress" = None,
) -> Samples:
    """The samples numbered ``first``, ``first + 1``, … with ``values`` (rows of
    :func:`sample_values`), on every core. A chunk run anywhere gives the rows the whole run
    gives for it: this is what a Dask worker runs (see ``examples/dask_probabilistic.py``).
    ``progress`` as for :func:`probabilistic`."""
    v = _np.ascontiguousarray(_np.asarray(values, dtype=_np.float64))
    if v.ndim != 2:
        raise InputError("values: a 2-D array, one row per sample", "values")
    with _progress(progress, "samples") as tell:
        return Samples(
            _native.run_samples(
                scene._s,
                distributions(scene, dists),
                v,
                _whole("first", first, 0, _MAX_SAMPLE_NUMBER - len(v)),
                tell,
            )
        )


def summarise(
    scene: Scene,
    dists: "Distributions",
    samples: int,
    seed: int,
    sampling: str,
    rows: "Mapping[str, Any]",
    travel_limit_m: "Optional[float]" = None,
    rotation_limit_deg: "Optional[float]" = None,
    displacement_limit_m: "Optional[float]" = None,
) -> "Dict[str, Any]":
    """What the rows of one design come to: the summary ``probabilistic.json`` has (the
    probability of sliding with its 95 % interval — under a ground-motion record, that the
    record displaces the block —, exceedance probabilities, percentiles, rank correlations)."""
    return _native.summarise_samples(
        scene._s,
        distributions(scene, dists),
        _whole("samples", samples, 1, _MAX_SAMPLES),
        _whole("seed", seed, 0, _MAX_SEED),
        sampling,
        dict(rows),
        travel_limit_m,
        rotation_limit_deg,
        displacement_limit_m,
    )


@_dataclass(frozen=True, repr=False)
class Probabilistic:
    """A probabilistic analysis's result: ``samples`` (one row per sample, a
    :class:`Samples`) and ``summary`` (as ``probabilistic.json`` has it)."""

    samples: Samples
    summary: "Dict[str, Any]"

    @property
    def probability_of_sliding(self) -> float:
        """The fraction of samples whose factor of safety is below 1 (under a ground-motion
        record, whose block the record displaces)."""
        return self.summary["probability_of_sliding"]["value"]

    def __repr__(self) -> str:
        p = self.summary.get("probability_of_sliding", {})
        ci = p.get("ci95")
        interval = f" (95 % interval {ci[0]:.3f} to {ci[1]:.3f})" if ci else ""
        n = len(self.samples.get("sample", ()))
        keys = ", ".join(self.samples.keys_varied())
        return (
            f"<Probabilistic: {n} samples of {keys}; probability of sliding "
            f"{p.get('value', float('nan')):.3f}{interval}>"
        )


def probabilistic(
    scene: Scene,
    dists: "Distributions" = None,
    samples: int = 1000,
    seed: int = 1,
    sampling: str = "lhs",
    travel_limit_m: "Optional[float]" = None,
    rotation_limit_deg: "Optional[float]" = None,
    progress: "Progress" = None,
    displacement_limit_m: "Optional[float]" = None,
    max_samples: int = 100_000,
) -> Probabilistic:
    """The probabilistic analysis, as ``slideroute probabilistic`` runs it: each uncertain
    key's distribution (``{"friction.mu_k": "normal:0.40:0.05"}``; the scene's
    ``[uncertain]`` table too), ``samples`` samples from ``seed`` by ``sampling`` (``"lhs"``
    or ``"mc"``), every route on every core; the same numbers as the command line's.
    ``progress(done, total)`` is told how many samples are done; ``progress=True`` shows a bar
    (tqdm's where it is installed, else a line on stderr). Ctrl-C stops it at its next route
    with ``KeyboardInterrupt``. Under a ground-motion record, ``displacement_limit_m`` asks
    for the probability that the permanent displacement exceeds it. Every sample's row is held
    (about 1.5 kB a sample at the peak): more than ``max_samples`` samples are refused before
    any runs with :class:`InputError`; raise it, run the design in ranges with
    :func:`run_samples` keeping what you need, or use the command line, which holds none."""
    limit = _whole("max_samples", max_samples, 1, _MAX_SAMPLES)
    if _whole("samples", samples, 1, _MAX_SAMPLES) > limit:
        raise InputError(
            f"samples {samples}: more than max_samples = {limit}; every sample's row is held "
            "(about 1.5 kB each): raise max_samples, run ranges with run_samples, or use the "
            "command line's probabilistic, which holds none",
            "samples",
        )
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


del annotations  # the __future__ import's name: not the package's
