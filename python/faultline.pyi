"""Faultline: find, name and follow faults in Discrete Element Models (type stubs)."""
from typing import Any, List, Optional, Sequence, Union

import numpy as np
import numpy.typing as npt

__version__: str

class InputError(ValueError):
    """A file that cannot be read: path, line or byte offset, what was expected."""

class CommandError(RuntimeError):
    """A journal op refused (nothing was changed)."""

class Frame:
    """One timestep's spheres; arrays are read-only views of the frame's memory."""
    def __len__(self) -> int: ...
    @property
    def ids(self) -> npt.NDArray[np.int64]: ...
    @property
    def x(self) -> npt.NDArray[np.float32]: ...
    @property
    def y(self) -> npt.NDArray[np.float32]: ...
    @property
    def z(self) -> npt.NDArray[np.float32]: ...
    @property
    def radius(self) -> npt.NDArray[np.float32]: ...
    @property
    def positions(self) -> npt.NDArray[np.float32]:
        """N x 3 centres: a copy (the frame keeps x, y, z apart)."""
    @property
    def columns(self) -> list[str]: ...
    @property
    def box(self) -> dict[str, Any]: ...
    def __getitem__(self, name: str) -> npt.NDArray[Any]:
        """A variable (float32 or int32), or x, y, z, radius, id: a view."""
    def __contains__(self, name: str) -> bool: ...

class Dataset:
    """Frames of a DEM run, loaded lazily."""
    def __len__(self) -> int: ...
    def frame(self, index: int) -> Frame: ...
    def timestep(self, index: int) -> int: ...
    @property
    def notes(self) -> List[str]:
        """A file that ends inside a frame keeps its complete frames; a note names the one left out."""

def open(paths: Union[str, Sequence[str]]) -> Dataset:
    """Open DEM output (a path, a glob or a list); raises InputError."""

class generate:
    @staticmethod
    def demo() -> str:
        """The demo model's dump, generated once per user (one to two minutes)."""
    @staticmethod
    def planes(size: str = "small", path: str = "planes.dump.gz", seed: int = -1) -> tuple[str, dict[str, Any]]:
        """Planted planar faults written as a LAMMPS dump; returns (path, truth)."""

class Session:
    """A Faultline session: the journal's ops (JOURNAL.md) as dicts."""
    def __init__(self, paths: Union[None, str, Sequence[str]] = None) -> None: ...
    @staticmethod
    def load(path: str) -> "Session": ...
    def run(self, command: dict[str, Any]) -> None:
        """Run one journal op; Ctrl+C stops a long one (KeyboardInterrupt, nothing changed).
        An expectation ({"expect": "visible_count", "equals": 12}) raises AssertionError when
        it does not hold."""
    def undo(self) -> bool: ...
    def redo(self) -> bool: ...
    def save(self, path: str) -> None: ...
    @property
    def can_undo(self) -> bool: ...
    @property
    def can_redo(self) -> bool: ...
    @property
    def undo_label(self) -> str: ...
    @property
    def state(self) -> dict[str, Any]: ...
    @property
    def dataset(self) -> Optional[Dataset]: ...
    @property
    def frame(self) -> Optional[Frame]: ...
    @property
    def visible(self) -> npt.NDArray[np.bool_]: ...
    @property
    def faults(self) -> dict[str, npt.NDArray[np.int64]]: ...
    def render(self, view: str = "main", size: tuple[int, int] = (1280, 720), frame: Optional[int] = None,
               transparent: bool = False) -> npt.NDArray[np.uint8]:
        """The view drawn offscreen: H x W x 4 RGBA."""
    def fault_metrics(self, pandas: bool = False) -> Any:
        """Every fault's metrics in every frame, a structured array (export.csv fault_metrics);
        pandas=True: a pandas DataFrame."""
    def fault_growth(self, pandas: bool = False) -> Any: ...
    def fault_events(self, pandas: bool = False) -> Any: ...
    def spheres(self, variables: Optional[Sequence[str]] = None, only_visible: bool = False,
                pandas: bool = False) -> Any: ...
    def surface(self, fault: str) -> dict[str, Any]:
        """A fault's surface in the current frame as export.gltf builds it: {"vertices": N x 3
        float32, "triangles": M x 3 uint32, "colours": N x 3 float32, "normals": N x 3 float32,
        "iso": float}."""
