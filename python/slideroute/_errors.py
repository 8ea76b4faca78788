"""The exceptions of slideroute: each names what it is about."""

from __future__ import annotations


class SlideRouteError(Exception):
    """Every error slideroute raises."""


class SceneError(SlideRouteError, ValueError):
    """A scene that cannot be used: ``key`` is the key it is about (``friction.mu_k``),
    ``origin`` where the scene came from (a path, ``<dict>``)."""

    def __init__(self, message: str, key: str = "", origin: str = "") -> None:
        super().__init__(message)
        self.key = key
        self.origin = origin


class InputError(SlideRouteError, ValueError):
    """An argument that cannot be used: ``name`` is the argument, or the key, it is about."""

    def __init__(self, message: str, name: str = "") -> None:
        super().__init__(message)
        self.name = name
        self.key = name


class RouteError(SlideRouteError, RuntimeError):
    """A computation that failed for a reason other than its inputs."""
