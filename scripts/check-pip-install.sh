#!/usr/bin/env bash
# `pip install .` as a user runs it (docs/python.md, "Getting it"), then the installed package
# checked from outside the repository: it imports from the virtual environment, not from build/,
# runs a cantilever against its closed form, and raises the engine's warnings as BeamfeaWarning.
# Too slow for the test suite (pip builds the engine once more, in build-pip/); run by CI after
# the suite (.ci/run). Needs the Debian packages of scripts/install-deps.sh and PyPI (scikit-build-core).
# Usage: scripts/check-pip-install.sh [VENV]     (default build-pip-venv/, kept for the next run)
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
venv=${1:-build-pip-venv}
# --system-site-packages: Debian's numpy (the package's one dependency) instead of a download.
[ -x "$venv/bin/python" ] || /usr/bin/python3 -m venv --system-site-packages "$venv"
CMAKE_BUILD_PARALLEL_LEVEL=${CMAKE_BUILD_PARALLEL_LEVEL:-$(nproc)} "$venv/bin/pip" install --quiet "$repo"
python=$(cd "$venv" && pwd)/bin/python
cd "$(mktemp -d)"
"$python" - "$repo" <<'PY'
import os, sys, warnings
import beamfea
repo = sys.argv[1]
where = os.path.dirname(beamfea.__file__)
assert where.startswith(sys.prefix + os.sep) and not where.startswith(os.path.join(repo, "build", "")), where
L, P, E, Iz = 2.0, -1000.0, 2.1e11, 3e-6
model = {
    "nodes": [{"id": "A", "xyz": [0, 0, 0]}, {"id": "B", "xyz": [L, 0, 0]}],
    "materials": [{"id": "m", "E": E, "G": 8.1e10}, {"id": "unused", "E": E, "G": 8.1e10}],
    "sections": [{"id": "s", "A": 1e-3, "Iy": 2e-6, "Iz": Iz, "J": 1e-6}],
    "elements": [{"id": "e", "type": "beam", "nodes": ["A", "B"], "material": "m", "section": "s"}],
    "supports": [{"node": "A", "fix": "all"}],
    "loads": [{"node": "B", "force": [0, P, 0]}],
    "analyses": [{"id": "lin", "type": "linear_static"}],
}
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    res = beamfea.run(model)
uy = res["analyses"]["lin"]["nodes"]["B"]["displacement"][1]
exact = P * L**3 / (3 * E * Iz)  # Euler-Bernoulli cantilever, tip load
assert abs(uy - exact) <= 1e-9 * abs(exact), (uy, exact)
assert [w.category for w in caught] == [beamfea.BeamfeaWarning], caught
print(f"pip install: beamfea {beamfea.__version__} from {where}: tip deflection {uy:.9g} (exact {exact:.9g}), warning raised")
PY
