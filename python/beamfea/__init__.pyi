# Type stubs of the beamfea package (docstrings in __init__.py, docs/python.md).
import os
from typing import Any, Callable, Dict, Iterable, List, Mapping, Optional, Union

import numpy as np
import numpy.typing as npt

__version__: str

Model = Union[Mapping[str, Any], str, os.PathLike[str]]
# Results mirror results.json: dicts, lists, str, int, float, bool, None, and float64 arrays.
Result = Dict[str, Any]
FloatArray = npt.NDArray[np.float64]
# progress(done, total, message)
Progress = Optional[Callable[[int, int, str], Any]]

class Error(Exception): ...

class InputError(Error, ValueError):
    pointer: Optional[str]
    entity: Optional[str]
    def __init__(self, message: str, pointer: Optional[str] = ..., entity: Optional[str] = ...) -> None: ...

class BeamfeaWarning(UserWarning): ...

class ModelError(Error):
    entity: Optional[str]
    def __init__(self, message: str, entity: Optional[str] = ...) -> None: ...

def run(model: Model, analyses: Union[None, str, Iterable[str], Iterable[Mapping[str, Any]]] = ...,
        out: Union[None, str, os.PathLike[str]] = ..., *, vtk: bool = ..., progress: Progress = ...) -> Result: ...
def check(model: Model) -> Dict[str, int]: ...
def lump(model: Model, links: Union[Mapping[str, Any], str, os.PathLike[str]],
         out: Union[None, str, os.PathLike[str]] = ...) -> Dict[str, Any]: ...
# A pandas.DataFrame when pandas is importable, else a dict of columns.
def sweep(spec: Union[Mapping[str, Any], str, os.PathLike[str]],
          jobs: Optional[int] = ..., progress: Progress = ...) -> Union[Dict[str, Union[FloatArray, list]], Any]: ...
def blas() -> Dict[str, Any]: ...
def section_properties(shape: str, **dimensions: float) -> Dict[str, float]: ...
def section_shapes() -> List[Dict[str, Any]]: ...
def from_urdf(path: Union[str, os.PathLike[str]],
              sidecar: Union[None, Mapping[str, Any], str, os.PathLike[str]] = ...) -> Dict[str, Any]: ...
