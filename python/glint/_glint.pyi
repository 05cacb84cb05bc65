# Type stubs of glint._glint, the C++ half of the glint package (python/src/). The public API is
# glint/__init__.py's, which carries its own annotations; this is what it calls.
from typing import Any, Callable, Optional, Sequence

import numpy as np
import numpy.typing as npt

__version__: str

class SceneError(ValueError):
    file: Optional[str]
    line: int
    column: int
    message: str

class RenderError(RuntimeError): ...
class SceneWarning(UserWarning): ...

class Frame:
    """A rendered image at the film's full precision (kept beside the float32 array)."""

class Mesh:
    """A triangle mesh made of arrays, in its own space (glint.Scene.mesh places it)."""

    vertices: int
    triangles: int
    def __init__(
        self,
        positions: npt.NDArray[np.floating[Any]],
        indices: npt.NDArray[np.integer[Any]],
        normals: Optional[npt.NDArray[np.floating[Any]]] = None,
        uvs: Optional[npt.NDArray[np.floating[Any]]] = None,
        name: str = "mesh",
    ) -> None: ...

class LoadedScene:
    size: tuple[int, int]
    camera: Optional[dict[str, Any]]
    @property
    def integrator(self) -> str: ...
    @property
    def spp(self) -> int: ...
    @property
    def model(self) -> bool: ...
    @property
    def note(self) -> str: ...
    @property
    def output(self) -> str: ...
    @property
    def display(self) -> dict[str, Any]: ...
    @property
    def lights(self) -> int: ...
    @property
    def triangles(self) -> int: ...
    @property
    def extensions(self) -> dict[str, str]: ...
    @property
    def animations(self) -> list[dict[str, Any]]: ...
    def render(
        self, args: Sequence[str], progress: Optional[Callable[[float, float], Any]] = None
    ) -> tuple[npt.NDArray[np.float32], dict[str, npt.NDArray[np.float32]], dict[str, Any], Frame]: ...

def load(path: str, args: Sequence[str]) -> LoadedScene: ...
def from_text(
    text: str, name: str, meshes: dict[str, Mesh], args: Sequence[str]
) -> LoadedScene: ...
def option_names() -> list[str]: ...
def set_environment(
    scene: LoadedScene, rgb: Optional[npt.NDArray[np.floating[Any]]], scale: float = 1.0,
    rotation: float = 0.0,
) -> None: ...
def encode(
    format: str, image: npt.NDArray[Any], passes: dict[str, npt.NDArray[Any]], exposure: float,
    srgb: bool, tonemap: str, frame: Optional[Frame] = None,
) -> bytes: ...
def denoise(
    image: npt.NDArray[Any], passes: dict[str, npt.NDArray[Any]], denoiser: str, quality: str,
    threads: int,
) -> tuple[npt.NDArray[np.float32], str]: ...
def write(
    path: str, image: npt.NDArray[Any], passes: dict[str, npt.NDArray[Any]], exposure: float,
    srgb: bool, tonemap: str, frame: Optional[Frame] = None,
) -> None: ...
