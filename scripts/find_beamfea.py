"""import_beamfea(): the beamfea Python module, for the scripts and examples of this repository.

An installed module (cmake --install, pip install .) or one on PYTHONPATH comes first; else the
one built in this checkout, <repository>/build/python (or the folder BEAMFEA_PYTHON names)."""
import importlib
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def import_beamfea(required=True):
    try:
        return importlib.import_module("beamfea")
    except ImportError:
        pass
    folder = os.environ.get("BEAMFEA_PYTHON", os.path.join(ROOT, "build", "python"))
    if os.path.isdir(os.path.join(folder, "beamfea")):
        sys.path.insert(0, folder)
        try:
            return importlib.import_module("beamfea")
        except ImportError:
            sys.path.remove(folder)
    if required:
        sys.exit("cannot import beamfea: build it (scripts/build.sh) or put <build>/python on PYTHONPATH")
    return None
