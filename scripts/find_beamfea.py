"""import_beamfea(): the beamfea Python module, for the scripts and examples of this repository.

Which one: the folder named by BEAMFEA_PYTHON (the test suite sets it to its build's); else the
one built in this checkout, <repository>/build/python, so that a script runs the code beside it
even when an older beamfea is installed; else an installed one (cmake --install, pip install .)
or one on PYTHONPATH."""
import importlib
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def import_beamfea(required=True):
    folder = os.environ.get("BEAMFEA_PYTHON", os.path.join(ROOT, "build", "python"))
    if os.path.isdir(os.path.join(folder, "beamfea")) and folder not in sys.path:
        sys.path.insert(0, folder)
    try:
        return importlib.import_module("beamfea")
    except ImportError:
        if required:
            sys.exit("cannot import beamfea: build it (scripts/build.sh), install it, or set BEAMFEA_PYTHON "
                     "to <build>/python")
        return None
