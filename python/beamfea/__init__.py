"""beamfea: matrix structural analysis of 3-D frames of Euler-Bernoulli beams, in process.

    import beamfea
    res = beamfea.run(model)            # model: a dict in the JSON format, or a path
    res["analyses"]["lin"]["nodes"]["tip"]["displacement"]   # a float64 ndarray

The model format is the program's (docs/input-format.md); results have the structure of
results.json (docs/python.md says how arrays become NumPy arrays). Errors:
InputError(ValueError) with .pointer and .entity, ModelError with .entity. A failed analysis
(a mechanism, no convergence) is not an exception: its result says so in "status". The engine's
warnings are raised as BeamfeaWarning (a UserWarning) through the warnings module. Ctrl-C stops
a run or a sweep (KeyboardInterrupt); progress=callable reports where it stands.
"""
import json
import os
import warnings
from typing import Any, Callable, Dict, Iterable, Mapping, Optional, Union

from . import _beamfea
from ._errors import BeamfeaWarning, Error, InputError, ModelError

__version__: str = _beamfea.__version__
__all__ = ["run", "check", "lump", "sweep", "blas", "section_properties", "section_shapes", "from_urdf", "Error", "InputError",
           "ModelError", "BeamfeaWarning", "__version__"]

Model = Union[Mapping[str, Any], str, "os.PathLike[str]"]
Progress = Optional[Callable[[int, int, str], Any]]


def _is_path(x: Any) -> bool:
    return isinstance(x, (str, os.PathLike))


def run(model: Model, analyses: Union[None, str, Iterable[Any]] = None,
        out: Union[None, str, "os.PathLike[str]"] = None, *, vtk: bool = True,
        progress: Progress = None) -> Dict[str, Any]:
    """Run the analyses of a model and return its results.

    Args:
        model: the model, as a dict in beamfea's JSON format (docs/input-format.md; NumPy
            arrays and scalars are accepted anywhere a list or a number is) or the path of a
            model file.
        analyses: which analyses to run. None: all of the model's "analyses". A string or a
            list of strings: only the analyses with these ids. A list of dicts: these analysis
            specs, in place of the model's "analyses" (their errors point into "/analyses").
        out: a folder. When given, results.json and each analysis's files (VTK for ParaView)
            are written there, as `beamfea run model.json --out DIR` does. When None, nothing
            at all is written.
        vtk: with `out`, also write the VTK files (False: as `--no-vtk`).
        progress: None, or a callable called as progress(done, total, message) while the run
            goes on: done of total analyses finished, and the engine's last progress line
            ("[p] path p: step 12: load factor 0.37, ..."). Called from the calling thread when
            the progress changes (at most five times a second), at least once a second, and once
            at the end. An exception it raises stops the run and is raised here.

    Returns:
        dict: the structure of results.json: {"beamfea": version, "model": {...counts},
        "analyses": {id: result}, "warnings": [...]}. Every array of numbers is a float64 numpy.ndarray, an array
        of equal-length arrays a 2-D one (stiffness and compliance matrices, Jacobians; deeper
        nesting gives more dimensions); null inside such an array is NaN. Other arrays are
        lists, objects dicts, a non-finite number None (as in results.json). Each analysis
        result has its "status" ("ok" or what failed, with a "message"): a failed analysis is
        returned, not raised.

    Raises:
        InputError: bad input (.pointer is the JSON pointer of the field at fault, .entity the
            node, element, analysis... it belongs to).
        ModelError: a model that cannot be analysed as given (.entity names what).
        KeyboardInterrupt: Ctrl-C; the run stops within a second or so (at the next step of a
            path, between analyses) and nothing is written to `out`.

    Warns:
        BeamfeaWarning: each of the run's warnings (also in the result's "warnings").

    The engine runs with the GIL released: cases run on a ThreadPoolExecutor run in parallel.
    """
    only: list = []
    specs: Any = None
    if isinstance(analyses, str):
        only = [analyses]
    elif analyses is not None:
        items = list(analyses)
        if all(isinstance(a, str) for a in items):
            only = items
        elif all(isinstance(a, Mapping) for a in items):
            specs = items
        else:
            raise TypeError("analyses: a list of analysis ids (str) or of analysis specs (dict), not a mix")
    if out is not None:
        out = os.fspath(out)
    result = _beamfea.run(model if _is_path(model) else _as_dict(model), only, specs, out, bool(vtk), progress)
    for message in result.get("warnings", ()):
        warnings.warn(message, BeamfeaWarning, stacklevel=2)
    return result


def check(model: Model) -> Dict[str, int]:
    """Validate a model (and its analysis specs) without analysing it.

    Args:
        model: a dict in beamfea's JSON format, or the path of a model file.

    Returns:
        dict: the counts {"nodes", "elements", "members", "joints"} of the model as meshed.

    Raises:
        InputError, ModelError: as run() does.
    """
    return _beamfea.check(model if _is_path(model) else _as_dict(model))


def lump(model: Model, links: Union[Mapping[str, Any], str, "os.PathLike[str]"],
         out: Union[None, str, "os.PathLike[str]"] = None) -> Dict[str, Any]:
    """The lumped (VJM) model of a beam model, as `beamfea lump model.json --links links.json -o out` writes it.

    Each link (its elements, clamped at its base node) becomes a rigid link from the base to a node
    "<link>_spring" at the tip and a 6-D virtual spring "<link>_spring" from there to the tip, whose
    6x6 stiffness is the link's condensed tip stiffness; joints, actuators, supports, loads and
    analyses are kept (docs/analyses/superelement.md, "Generated lumped models").

    Args:
        model: the beam model, a dict or the path of a model file.
        links: {"links": [{"id": ..., "elements": [...], "base": node, "tip": node}, ...]}, a dict
            or the path of a JSON file.
        out: when given, the lumped model is also written there (JSON).

    Returns:
        dict: the lumped model in beamfea's JSON format (plain lists and dicts), ready for run().

    Raises:
        InputError: bad input (an unknown element or node, a link whose inside is named elsewhere;
            .pointer is "/links/..." for the links document).
        ModelError: as run() does.
    """
    text = _beamfea.lump(model if _is_path(model) else _as_dict(model), links if _is_path(links) else _as_dict(links))
    result = json.loads(text)
    if out is not None:
        with open(os.fspath(out), "w", encoding="utf-8") as f:
            f.write(json.dumps(result, indent=2) + "\n")
    return result


def blas() -> Dict[str, Any]:
    """The OpenBLAS kernels the engine runs on.

    At import, beamfea replaces OpenBLAS's generic "Prescott" kernels with those the CPU supports
    (AVX2: "Haswell", AVX-512: "SkylakeX") when OpenBLAS did not recognise the CPU (versions before
    0.3.25 on recent Intel models) and OPENBLAS_CORETYPE is not set, as the program does
    (docs/performance.md, "The BLAS"). This is process-wide: NumPy on the same OpenBLAS gains too.

    Returns:
        dict: {"openblas": whether the BLAS is OpenBLAS with runtime kernel selection,
        "core": its kernels now, "replaced": the kernels OpenBLAS had chosen when beamfea replaced
        them, else ""}.
    """
    return dict(_beamfea.blas())


def section_properties(shape: str, **dimensions: float) -> Dict[str, float]:
    """The properties of a section shape, as a model's section with "shape" gets them.

    Example: ``beamfea.section_properties("i", h=0.3, b=0.15, tw=0.0071, tf=0.0107, r=0.015)``.
    The shapes and their dimensions are those of ``section_shapes()`` (docs/input-format.md,
    "sections"); b is along local y, h along local z; any consistent units.

    Returns:
        dict: A, Iy, Iz, J, ky, kz, Iyz (product of inertia about the centroidal y and z: nonzero for
        an angle, neglected by the beam element), I1 >= I2 (principal second moments) and
        principal_angle (radians from local y towards local z, the axis of I1).

    Raises:
        InputError: an unknown shape, a missing, unknown or non-positive dimension, or dimensions
        that do not make the shape (the message names the dimension).
    """
    return dict(_beamfea.section_properties(shape, [(k, float(v)) for k, v in dimensions.items()]))


def section_shapes() -> list:
    """The section shapes: a list of dicts {"shape", "dimensions", "optional", "description", "formulas"}."""
    return [dict(s) for s in _beamfea.section_shapes()]


def from_urdf(path: Union[str, "os.PathLike[str]"],
              sidecar: Union[None, Mapping[str, Any], str, "os.PathLike[str]"] = None) -> Dict[str, Any]:
    """A URDF robot description as a model dict (docs/urdf.md), as `beamfea urdf` writes it.

    Args:
        path: the URDF file.
        sidecar: what URDF lacks, as a dict or the path of a JSON file: {"joints": {name:
            {"stiffness": [k]}}, "links": {name: {"beam": {...}}}, "materials", "sections",
            "inertials"}; None: rigid links, passive joints.

    Returns:
        dict: the model (plain lists and numbers), ready for run() once analyses (and gravity
        or loads) are added.

    Raises:
        InputError: a URDF the parser refuses (the element named), an unsupported joint type, or
            a side-car field at fault (its JSON pointer).
    """
    car = None if sidecar is None else (os.fspath(sidecar) if _is_path(sidecar) else _as_dict(sidecar))
    return json.loads(_beamfea.urdf_model(os.fspath(path), car))


def sweep(spec: Union[Mapping[str, Any], str, "os.PathLike[str]"], jobs: Optional[int] = None,
          progress: Progress = None) -> Any:
    """Run a sweep (docs/sweep.md): many cases of one base model, in process, into one table.

    Args:
        spec: a sweep document as a dict (a relative "base" path is taken from the current
            folder) or the path of a sweep file (relative to the file's folder).
        jobs: worker threads; None or 0: all cores.
        progress: None, or a callable called as progress(done, total, message): done of total
            cases finished (as run()'s: from the calling thread, at least once a second).

    Returns:
        The table of `beamfea sweep` (DIR/cases.csv) as columns, in its order: "case", the
        parameters, the outputs flattened ("K[0][0]"...), "status" ("ok", "analysis failed",
        "bad input"), "message", "wall_time_s". A pandas.DataFrame when pandas can be
        imported, else a dict of columns: numeric columns are float64 numpy.ndarrays (NaN
        where a case has no value), the others lists.

    Raises:
        InputError: a bad sweep document (a bad case is a row with status "bad input").
        KeyboardInterrupt: Ctrl-C; the sweep stops after the cases running then.
    """
    if jobs is None:
        jobs = 0
    if int(jobs) < 0:
        raise ValueError("jobs must be at least 1 (or 0/None for all cores)")
    columns = _beamfea.sweep(spec if _is_path(spec) else _as_dict(spec), int(jobs), progress)
    try:
        import pandas
    except ImportError:
        return columns
    return pandas.DataFrame(columns)


def _as_dict(x: Any) -> Any:
    """A Mapping that is not a dict is copied into one (the engine reads dicts)."""
    if isinstance(x, Mapping) and not isinstance(x, dict):
        return dict(x)
    return x
