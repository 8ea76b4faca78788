"""Type stubs of the Rust extension (python/src/lib.rs)."""

from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple

import numpy as np

class Scene:
    @staticmethod
    def default() -> Scene: ...
    @staticmethod
    def from_file(path: str) -> Scene: ...
    @staticmethod
    def from_toml(text: str, origin: str = ...) -> Scene: ...
    @staticmethod
    def from_json(text: str, origin: str = ..., folder: str = ...) -> Scene: ...
    def with_keys(self, keys: Dict[str, Any]) -> Scene: ...
    @property
    def name(self) -> str: ...
    @property
    def origin(self) -> str: ...
    @property
    def folder(self) -> str: ...
    def document(self) -> Dict[str, Any]: ...
    @property
    def uncertain(self) -> List[Tuple[str, str]]: ...
    def route(
        self, dynamics: Optional[str] = ...
    ) -> Tuple[Dict[str, np.ndarray], Dict[str, Any]]: ...
    def roots(
        self, x_m: float, z_m: float, theta_deg: float, mode: Optional[str] = ...
    ) -> Dict[str, Any]: ...
    def roots_grid(
        self,
        x_m: np.ndarray,
        z_m: np.ndarray,
        theta_deg: np.ndarray,
        mode: Optional[str] = ...,
    ) -> Dict[str, np.ndarray]: ...
    def pose(self, x_m: float, z_m: float, theta_deg: float) -> Dict[str, Any]: ...
    def sweep(
        self,
        values: Sequence[Tuple[str, Sequence[float]]],
        dynamics: Optional[str] = ...,
        progress: Optional[Callable[[int, int], Any]] = ...,
    ) -> Dict[str, Any]: ...

def sample_values(
    scene: Scene,
    uncertain: Sequence[Tuple[str, str]],
    samples: int,
    seed: int,
    sampling: str,
) -> np.ndarray: ...
def run_samples(
    scene: Scene,
    uncertain: Sequence[Tuple[str, str]],
    values: np.ndarray,
    first: int = ...,
    progress: Optional[Callable[[int, int], Any]] = ...,
) -> Dict[str, Any]: ...
def summarise_samples(
    scene: Scene,
    uncertain: Sequence[Tuple[str, str]],
    samples: int,
    seed: int,
    sampling: str,
    columns: Dict[str, Any],
    travel_limit_m: Optional[float] = ...,
    rotation_limit_deg: Optional[float] = ...,
) -> Dict[str, Any]: ...
def version() -> str: ...
