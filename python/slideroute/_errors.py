"""The exceptions of slideroute: each names what it is about, and each is also the built-in
exception a Python user expects — a missing file a :class:`FileNotFoundError`, a value of the
wrong type a :class:`TypeError`, a value that cannot be used a :class:`ValueError`.

    SlideRouteError
    ├── SceneError (ValueError)                  .key, .origin
    │   ├── SceneTypeError (TypeError)
    │   └── SceneFileNotFoundError (FileNotFoundError)   .filename
    ├── InputError (ValueError)                  .name (also .key)
    │   └── InputTypeError (TypeError)
    ├── RouteError (RuntimeError)
    └── OutputError (OSError)
"""

from __future__ import annotations

import errno as _errno
from typing import Any, Tuple


class SlideRouteError(Exception):
    """Every error slideroute raises."""


class SceneError(SlideRouteError, ValueError):
    """A scene that cannot be used: ``key`` is the key it is about (``friction.mu_k``; empty
    for the file as a whole), ``origin`` where the scene came from (a path, ``<dict>``)."""

    def __init__(self, message: str, key: str = "", origin: str = "") -> None:
        super().__init__(message)
        self.key = key
        self.origin = origin

    def __reduce__(self) -> Tuple[Any, ...]:
        return (type(self), (str(self), self.key, self.origin))


class SceneTypeError(SceneError, TypeError):
    """A scene value of the wrong type (a word where a number belongs): the message says, in
    Python's names of types, what the key expects and what it got (``expected a number
    (float), got str "steep"``)."""


class SceneFileNotFoundError(SceneError, FileNotFoundError):
    """A file that does not exist: the scene file itself (``key`` empty) or one it names
    (``foundation.surface``, ``seismic.record``: ``key`` names it). ``filename`` is its path;
    ``errno`` is ``ENOENT``."""

    def __init__(self, message: str, key: str = "", origin: str = "", filename: str = "") -> None:
        FileNotFoundError.__init__(self, _errno.ENOENT, message, filename)
        self.args = (message,)
        self.key = key
        self.origin = origin

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""

    def __reduce__(self) -> Tuple[Any, ...]:
        return (type(self), (str(self), self.key, self.origin, self.filename))


class InputError(SlideRouteError, ValueError):
    """An argument that cannot be used: ``name`` is the argument, or the key, it is about
    (``key`` too)."""

    def __init__(self, message: str, name: str = "") -> None:
        super().__init__(message)
        self.name = name
        self.key = name

    def __reduce__(self) -> Tuple[Any, ...]:
        return (type(self), (str(self), self.name))


class InputTypeError(InputError, TypeError):
    """An argument of the wrong type (a list where a scene value belongs, keys not in a
    dict): the message says what was expected and what was given, in Python's names."""


class RouteError(SlideRouteError, RuntimeError):
    """A computation that failed for a reason other than its inputs."""


class OutputError(SlideRouteError, OSError):
    """A file or folder the outputs could not be written to, named in the message: a full disk,
    a file where the folder goes, a link where an output goes (never followed), a folder another
    run is writing into."""
