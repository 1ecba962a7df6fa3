#!/usr/bin/env python3
"""Writes the generated space frame of opensees_compare.py (and bench_frame_solve) as a beamfea model.

    python3 benchmarks/cube_frame.py 31x32x32 /tmp/cube.json     # 202,752 free DOFs
    python3 benchmarks/cube_frame.py 25x25x24 /tmp/cube.json     #  97,344
    python3 benchmarks/cube_frame.py 15x15x14 /tmp/cube.json     #  21,504

One linear_static analysis; used for timing `beamfea check` and `beamfea run` (reading,
validating, writing results.json) at sizes where anything quadratic shows.
"""
import json, os, sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from opensees_compare import beamfea_model, frame, parse_size  # noqa: E402

if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    nx, ny, nz = parse_size(sys.argv[1])
    with open(sys.argv[2], "w") as f:
        json.dump(beamfea_model(*frame(nx, ny, nz)), f)
    print(f"{sys.argv[2]}: {nx}x{ny}x{nz} bays, {6 * (nx + 1) * (ny + 1) * nz} free DOFs")
